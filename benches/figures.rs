//! Prints one JSON line per workload (W1–W5, see `benches/workloads/mod.rs`): the
//! figures `tools/compare_perf.py` compares with dm_control and MjSpec.
//!
//! ```text
//! cargo bench --bench figures                       # everything
//! cargo bench --bench figures -- --sizes 1,10,100   # W1 on these fleet sizes only
//! cargo bench --bench figures -- --only w1,w4       # some workloads
//! cargo bench --bench figures -- --dump-dir DIR --dump-only   # write the generated models
//! ```
//!
//! Each line: `{"key", "workload", "seconds", "min_seconds", "runs", "bytes", "mb_per_s",
//! "allocated_bytes", "live_bytes", ...}`: `seconds` is the median over `runs` runs;
//! `bytes` the XML read or written (absent otherwise); `allocated_bytes` all heap bytes
//! the run allocated, `live_bytes` those it still held when it returned (the result).
//! Lines are printed (and flushed) as soon as measured, so a crash keeps the earlier
//! ones; a failing workload prints `"error"`.

mod workloads;

use std::io::Write;
use std::path::PathBuf;
use std::time::Duration;

use serde_json::{Value, json};
use workloads::*;

struct Args {
    sizes: Vec<usize>,
    only: Option<Vec<String>>,
    dump_dir: Option<PathBuf>,
    dump_only: bool,
    budget: Duration,
}

fn parse_args() -> Args {
    let mut a = Args {
        sizes: FLEET_SIZES.to_vec(),
        only: None,
        dump_dir: None,
        dump_only: false,
        budget: Duration::from_millis(1000),
    };
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        match arg.as_str() {
            "--sizes" => {
                a.sizes = it
                    .next()
                    .unwrap_or_default()
                    .split(',')
                    .filter_map(|s| s.trim().parse().ok())
                    .collect()
            }
            "--only" => {
                a.only = Some(
                    it.next()
                        .unwrap_or_default()
                        .split(',')
                        .map(|s| s.trim().to_lowercase())
                        .collect(),
                )
            }
            "--dump-dir" => a.dump_dir = it.next().map(PathBuf::from),
            "--dump-only" => a.dump_only = true,
            "--budget-ms" => {
                a.budget =
                    Duration::from_millis(it.next().and_then(|s| s.parse().ok()).unwrap_or(1000))
            }
            // `cargo bench` passes `--bench`; ignore it and anything else.
            _ => {}
        }
    }
    a
}

fn emit(mut line: Value) {
    if let (Some(b), Some(s)) =
        (line.get("bytes").and_then(Value::as_f64), line.get("seconds").and_then(Value::as_f64))
    {
        if s > 0.0 {
            line["mb_per_s"] = json!(b / s / 1e6);
        }
    }
    let mut out = std::io::stdout().lock();
    let _ = writeln!(out, "{line}");
    let _ = out.flush();
}

fn line<T>(key: &str, workload: &str, m: &Measured<T>) -> Value {
    json!({
        "key": key,
        "workload": workload,
        "seconds": m.seconds,
        "min_seconds": m.min_seconds,
        "runs": m.runs,
        "allocated_bytes": m.allocated_bytes,
        "live_bytes": m.live_bytes,
    })
}

fn error(key: &str, workload: &str, e: impl std::fmt::Display) {
    emit(json!({"key": key, "workload": workload, "error": e.to_string()}));
}

fn main() {
    let args = parse_args();
    let wants = |w: &str| args.only.as_ref().is_none_or(|o| o.iter().any(|x| x == w));
    // Growth runs only when asked for (`--only growth`): it is not a workload of the
    // comparison.
    if args.only.as_ref().is_some_and(|o| o.iter().any(|x| x == "growth")) {
        growth(args.budget);
    }

    if let Some(dir) = &args.dump_dir {
        std::fs::create_dir_all(dir).expect("create the dump dir");
        for &n in &args.sizes {
            std::fs::write(dir.join(format!("arena_{n}.xml")), arena_xml(n)).expect("write");
        }
        std::fs::write(dir.join("tree_10k.xml"), tree_10k_xml()).expect("write");
        std::fs::write(dir.join("chain_10k.xml"), chain_10k_xml()).expect("write");
        std::fs::copy(models_dir().join("humanoid_CMU.xml"), dir.join("humanoid_CMU.xml"))
            .expect("copy");
        eprintln!("wrote the generated models to {}", dir.display());
        if args.dump_only {
            return;
        }
    }
    let budget = args.budget;

    let live0 = live_bytes();
    let robot = read_robot();
    let robot_live = live_bytes() - live0;
    emit(json!({"key": "robot", "workload": "robot (quadruped) read", "live_bytes": robot_live,
                "bodies": robot.find_all(mjcf::Namespace::Body).len()}));

    // W1 fleet: build, memory, write.
    let mut fleet_1000_xml = None;
    if wants("w1") {
        for &n in &args.sizes {
            let l0 = live_bytes();
            let arena = read_arena(n);
            let arena_live = live_bytes() - l0;
            let b = measure(3, 200, budget, || build_fleet(&arena, &robot, n));
            let fleet = match &b.value {
                Ok(f) => f.clone(),
                Err(e) => {
                    error(&format!("w1_build_{n}"), &format!("W1 build N={n}"), e);
                    continue;
                }
            };
            let mut l = line(&format!("w1_build_{n}"), &format!("W1 build N={n}"), &b);
            // The fleet's own structure (`live_bytes`) plus the arena and robot it shares.
            l["live_bytes_with_inputs"] = json!(b.live_bytes + (arena_live + robot_live) as isize);
            emit(l);
            let w = measure(2, 50, budget, || fleet.to_xml_string());
            match &w.value {
                Ok(xml) => {
                    let mut l = line(&format!("w1_write_{n}"), &format!("W1 write N={n}"), &w);
                    l["bytes"] = json!(xml.len());
                    emit(l);
                    if n == 1000 {
                        fleet_1000_xml = Some(xml.clone());
                    }
                }
                Err(e) => error(&format!("w1_write_{n}"), &format!("W1 write N={n}"), e),
            }
        }
    }

    // W2 undo: 1000 edits of the 100-robot fleet, every version kept.
    if wants("w2") {
        let fleet =
            build_fleet(&read_arena(UNDO_ROBOTS), &robot, UNDO_ROBOTS).expect("the fleet builds");
        let scopes = scopes_of(&fleet);
        let h = measure(1, 10, budget, || undo_history(&fleet, UNDO_EDITS));
        match &h.value {
            Ok(versions) => {
                let mut l =
                    line("w2_history", &format!("W2 {UNDO_EDITS} edits, all versions kept"), &h);
                l["versions"] = json!(versions.len());
                l["seconds_per_edit"] = json!(h.seconds / UNDO_EDITS as f64);
                l["live_bytes_per_version"] = json!(h.live_bytes as f64 / UNDO_EDITS as f64);
                emit(l);
            }
            Err(e) => error("w2_history", "W2 history", e),
        }
        // One more version, alone: edit k of the fleet.
        let mut k = 0;
        let one = measure(20, 100_000, budget, || {
            k += 1;
            undo_edit(&fleet, &scopes, k % UNDO_EDITS)
        });
        emit(line("w2_one_version", "W2 one more version", &one));
    }

    // W3 read (and write back, which must not overflow the stack either).
    let tree = tree_10k_xml();
    if wants("w3") {
        let humanoid = humanoid_xml();
        for (key, name, xml) in [
            ("w3_tree", "W3 10,000-body tree", &tree),
            ("w3_humanoid", "W3 CMU humanoid", &humanoid),
            ("w3_chain", "W3 10,000-deep chain", &chain_10k_xml()),
        ] {
            let r = measure(3, 200, budget, || mjcf::Model::from_xml_str(xml));
            let model = match &r.value {
                Ok(m) => m.clone(),
                Err(e) => {
                    error(&format!("{key}_read"), &format!("{name} read"), e);
                    continue;
                }
            };
            let mut l = line(&format!("{key}_read"), &format!("{name} read"), &r);
            l["bytes"] = json!(xml.len());
            emit(l);
            let w = measure(2, 100, budget, || model.to_xml_string());
            match &w.value {
                Ok(out) => {
                    let mut l = line(&format!("{key}_write"), &format!("{name} write"), &w);
                    l["bytes"] = json!(out.len());
                    emit(l);
                }
                Err(e) => error(&format!("{key}_write"), &format!("{name} write"), e),
            }
        }
    }

    // W4 detach one robot out of the 1000-robot fleet.
    if wants("w4") {
        let fleet = build_fleet(&read_arena(DETACH_ROBOTS), &robot, DETACH_ROBOTS)
            .expect("the fleet builds");
        let scopes = scopes_of(&fleet);
        let scope = scopes[DETACH_ROBOTS / 2].clone();
        let d = measure(20, 100_000, budget, || fleet.detach(&scope));
        match &d.value {
            Ok(_) => {
                let mut l =
                    line("w4_detach", &format!("W4 detach {scope} (N={DETACH_ROBOTS})"), &d);
                l["scope"] = json!(scope);
                emit(l);
            }
            Err(e) => error("w4_detach", "W4 detach", e),
        }
        if fleet_1000_xml.is_none() && wants("w5") {
            fleet_1000_xml = fleet.to_xml_string().ok();
        }
    }

    // W5 floor: quick-xml events in and out, no model.
    if wants("w5") {
        let fleet_xml = match fleet_1000_xml {
            Some(x) => x,
            None => build_fleet(&read_arena(1000), &robot, 1000)
                .and_then(|f| Ok(f.to_xml_string()?))
                .expect("fleet"),
        };
        for (key, name, xml) in [
            ("w5_fleet_1000", "W5 quick-xml, W1 N=1000 output", &fleet_xml),
            ("w5_tree", "W5 quick-xml, W3 tree", &tree),
        ] {
            let rt = measure(3, 200, budget, || quickxml_roundtrip(xml));
            let mut l = line(&format!("{key}_roundtrip"), &format!("{name}: read+write"), &rt);
            l["bytes"] = json!(xml.len());
            emit(l);
            let r = measure(3, 200, budget, || quickxml_read(xml));
            let mut l = line(&format!("{key}_read"), &format!("{name}: read"), &r);
            l["bytes"] = json!(xml.len());
            emit(l);
        }
    }
}

/// Growth: one attach (with a freejoint on its frame) as the child grows at a fixed
/// parent, and as the parent grows (its width: sites and frames in the worldbody)
/// with a fixed child; and writing, as the output grows. One JSON line per point.
fn growth(budget: Duration) {
    let robot = read_robot();
    // A fixed parent: 100 sites, 50 robots attached.
    let parent = build_fleet(&read_arena(100), &robot, 50).expect("the fleet builds");
    let site = parent.find(mjcf::Namespace::Site, "spawn_99").expect("the site");
    for bodies in [10usize, 100, 1000, 10_000] {
        let child = mjcf::Model::from_xml_str(&tree_xml(bodies.div_ceil(100), bodies.min(100)))
            .expect("the child reads")
            .with_name("child");
        let m = measure(20, 100_000, budget, || attach_one(&parent, &site, &child));
        let mut l = line(
            &format!("growth_child_{bodies}"),
            &format!("attach a {bodies}-body child (parent: 50 robots)"),
            &m,
        );
        l["child_bodies"] = json!(bodies);
        emit(l);
    }
    for width in [10usize, 100, 1000, 10_000] {
        let arena = read_arena(width);
        let half = build_fleet(&arena, &robot, width / 2).expect("the fleet builds");
        let site =
            half.find(mjcf::Namespace::Site, &format!("spawn_{}", width - 1)).expect("the site");
        let m = measure(20, 100_000, budget, || attach_one(&half, &site, &robot));
        let mut l = line(
            &format!("growth_width_{width}"),
            &format!("attach the robot to a {width}-site arena holding {} robots", width / 2),
            &m,
        );
        l["parent_width"] = json!(width + width / 2);
        emit(l);
    }
    for n in [10usize, 100, 1000] {
        let fleet = build_fleet(&read_arena(n), &robot, n).expect("the fleet builds");
        let w = measure(2, 50, budget, || fleet.to_xml_string());
        if let Ok(xml) = &w.value {
            let mut l =
                line(&format!("growth_write_{n}"), &format!("write the {n}-robot fleet"), &w);
            l["bytes"] = json!(xml.len());
            l["ns_per_byte"] = json!(w.seconds * 1e9 / xml.len() as f64);
            emit(l);
        }
    }
}

fn attach_one(parent: &mjcf::Model, site: &mjcf::Loc, child: &mjcf::Model) -> mjcf::Model {
    let (m, frame) = parent.attach(site, child).expect("attach");
    m.add(frame.frame(), mjcf::Element::new("freejoint")).expect("freejoint").0
}
