//! Writes generated models for MuJoCo to compile (`tools/generated_check.py`), each
//! with what it reads back as (the pairs `tools/readback_check.py` takes).
//!
//! ```text
//! cargo run --release --features proptest --example generated -- OUT [COUNT] [SEED]
//! ```
//!
//! Writes `OUT/gen_NNNN.xml` for COUNT (default 1000) models from a fixed seed: a
//! third plain models (`strategy::model_recipe`), a third composed scenes
//! (`strategy::scene_recipe`: nested attachments, frames with joints and
//! freejoints), a third scenes after a generated edit sequence (its last version).
//! Each is read back from its file and written again as `OUT/gen_NNNN.readback.xml`;
//! writing what that reads back as must give the same text (the example fails
//! otherwise), as must `Model::check` find nothing in any generated model.

use std::path::PathBuf;

use mjcf::generate::strategy;
use mjcf::{Model, Namespace};
use proptest::strategy::{Strategy, ValueTree};
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let out = PathBuf::from(args.next().ok_or("usage: generated OUT [COUNT] [SEED]")?);
    let count: usize = args.next().map_or(Ok(1000), |c| c.parse())?;
    let seed: u8 = args.next().map_or(Ok(14), |c| c.parse())?;
    std::fs::create_dir_all(&out)?;
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &[seed; 32]);
    let mut runner = TestRunner::new_with_rng(Config::default(), rng);
    let (models, scenes, edits) =
        (strategy::model_recipe(), strategy::scene_recipe(), strategy::scene_and_edits());
    let (mut composed, mut nested, mut bodies, mut bytes, mut versions) = (0, 0, 0, 0, 0);
    for i in 0..count {
        let m = match i % 3 {
            0 => models.new_tree(&mut runner).map_err(|e| e.to_string())?.current().build(),
            1 => scenes.new_tree(&mut runner).map_err(|e| e.to_string())?.current().build(),
            _ => {
                let (r, e) = edits.new_tree(&mut runner).map_err(|e| e.to_string())?.current();
                let all = e.apply(&r.build());
                versions += all.len();
                all.last().ok_or("no version")?.clone()
            }
        };
        if let Some(p) = m.check().first() {
            return Err(format!("gen_{i:04}: generated model has a problem: {p}").into());
        }
        composed += usize::from(m.scopes().next().is_some());
        let names: Vec<String> =
            m.find_all(Namespace::Body).iter().filter_map(|l| m.get(l).ok()?.full_name()).collect();
        // A frame inside an attachment: `robot/arm/`.
        nested +=
            usize::from(names.iter().any(|n| n.ends_with('/') && n.matches('/').count() >= 2));
        bodies += names.len();
        let xml = m.to_xml_string()?;
        bytes += xml.len();
        let path = out.join(format!("gen_{i:04}.xml"));
        std::fs::write(&path, &xml)?;
        let back = Model::from_path(&path)?;
        let w2 = back.to_xml_string()?;
        if Model::from_xml_str(&w2)?.to_xml_string()? != w2 {
            return Err(format!("gen_{i:04}: writing the read-back again gives other text").into());
        }
        std::fs::write(out.join(format!("gen_{i:04}.readback.xml")), w2)?;
    }
    println!(
        "{count} generated models written to {} ({composed} composed, {nested} with nested \
         attachments, {bodies} bodies, {versions} edited versions, {bytes} bytes), each read \
         back and written again",
        out.display()
    );
    Ok(())
}
