//! The performance workloads W1–W5, shared by the divan benchmarks (`benches/perf.rs`)
//! and the figures binary (`benches/figures.rs`, one JSON line per workload, which
//! `tools/compare_perf.py` reads).
//!
//! - W1 fleet: an arena with N sites `spawn_i`; N attaches of one robot value, each at
//!   its own site, with a freejoint on the attachment frame; then `to_xml_string`.
//! - W2 undo: 1000 small edits of the 100-robot fleet, every version kept.
//! - W3 read: a generated 10,000-body tree (100 chains of 100 nested bodies), the same
//!   bodies as one 10,000-deep chain, the CMU humanoid, and a 10,000-body tree with
//!   realistic attributes (quat, inertial mass, joint range and damping, geom rgba and
//!   mass on every body, joint and geom).
//! - W4 detach: one robot out of the 1000-robot fleet.
//! - W5 floor: quick-xml reading a document into events and writing them back, or
//!   reading it into events and decoding every attribute value.
//! - W6 nested default classes: `<default class>` nested 100,000 / 200,000 / 400,000
//!   levels deep, read.
//! - W7 attach growth: one more robot (attach + freejoint) onto a fleet of N robots,
//!   N = 10 / 100 / 1,000 / 10,000.
//! - W8 the real job: `examples/compose.rs` (the jaco arm and hand read, the scene
//!   composed, 200 variants built and exported with their meshes, one after another as
//!   compose.py does), run by
//!   `benches/figures.rs` through that file itself; `tools/compare_perf.py` runs
//!   dm_control's `benches/dm_control/compose.py` beside it.
//!
//! The models are in `benches/models` (see its README.md).
#![allow(dead_code)]

use std::path::PathBuf;
use std::time::{Duration, Instant};

use mjcf::{Element, Error, Model, Namespace};

/// The global allocator of every binary that includes this module: `cap` keeps the
/// live, total and peak heap bytes (read with [`live_bytes`], [`total_bytes`]), and
/// divan's profiler inside it counts allocations per benchmark iteration.
#[global_allocator]
static ALLOC: cap::Cap<divan::AllocProfiler> =
    cap::Cap::new(divan::AllocProfiler::system(), usize::MAX);

/// Heap bytes allocated and not yet freed, over the whole process.
pub(crate) fn live_bytes() -> usize {
    ALLOC.allocated()
}

/// Heap bytes allocated since the process started, including freed ones.
pub(crate) fn total_bytes() -> usize {
    ALLOC.total_allocated()
}

/// The fleet sizes of W1.
pub(crate) const FLEET_SIZES: [usize; 4] = [1, 10, 100, 1000];
/// W2: the fleet size and the number of edits (= extra versions).
pub(crate) const UNDO_ROBOTS: usize = 100;
pub(crate) const UNDO_EDITS: usize = 1000;
/// W3: 100 chains of 100 bodies.
pub(crate) const TREE_CHAINS: usize = 100;
pub(crate) const TREE_DEPTH: usize = 100;
/// W4: the fleet size.
pub(crate) const DETACH_ROBOTS: usize = 1000;

/// `benches/models`.
pub(crate) fn models_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("models")
}

/// The quadruped, read from `benches/models/quadruped_robot.xml` (with its includes).
pub(crate) fn read_robot() -> Model {
    Model::from_path(robot_path()).expect("benches/models/quadruped_robot.xml reads")
}

/// The robot's file.
pub(crate) fn robot_path() -> std::path::PathBuf {
    models_dir().join("quadruped_robot.xml")
}

/// The arena with `n` spawn sites: `benches/models/arena_{100,1000}.xml`, or generated
/// the same way for other sizes.
pub(crate) fn arena_xml(n: usize) -> String {
    let file = models_dir().join(format!("arena_{n}.xml"));
    if n == 100 || n == 1000 {
        std::fs::read_to_string(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display()))
    } else {
        generate_arena_xml(n)
    }
}

/// An arena as in `benches/models`: a ground plane, a light and `n` sites `spawn_i` on
/// a 2 m grid (ceil(sqrt(n)) per row) centred on the origin at z = 0.6.
pub(crate) fn generate_arena_xml(n: usize) -> String {
    use std::fmt::Write;
    let side = (1..).find(|s| s * s >= n).unwrap_or(1);
    let half = side as i64 - 1;
    let mut s = String::from("<mujoco model=\"arena\">\n");
    if n >= 1000 {
        s.push_str("  <size memory=\"2G\"/>\n");
    }
    s.push_str("  <option timestep=\"0.005\"/>\n  <visual>\n    <map znear=\"0.005\" zfar=\"20\"/>\n  </visual>\n");
    s.push_str("  <worldbody>\n    <light name=\"top\" pos=\"0 0 20\" directional=\"true\"/>\n");
    s.push_str("    <geom name=\"floor\" type=\"plane\" size=\"0 0 0.1\" rgba=\".2 .3 .4 1\"/>\n");
    for i in 0..n {
        let x = 2 * (i % side) as i64 - half;
        let y = 2 * (i / side) as i64 - half;
        let _ = writeln!(s, "    <site name=\"spawn_{i}\" pos=\"{x} {y} 0.6\" size=\"0.05\"/>");
    }
    s.push_str("  </worldbody>\n</mujoco>\n");
    s
}

/// The arena with `n` sites, read.
pub(crate) fn read_arena(n: usize) -> Model {
    Model::from_xml_str(&arena_xml(n)).expect("the arena reads")
}

/// W1: attaches `robot` at each of the `n` sites `spawn_i` of `arena` (found by name),
/// each with a freejoint on its frame; in place, as the README's quickstart builds
/// (`attach_mut`, `add_mut`: the nodes the fleet owns alone are edited in place).
pub(crate) fn build_fleet(arena: &Model, robot: &Model, n: usize) -> Result<Model, Error> {
    let mut m = arena.clone();
    for i in 0..n {
        let site = m.find(Namespace::Site, &format!("spawn_{i}")).expect("the arena has the site");
        let a = m.attach_mut(&site, robot)?;
        m.add_mut(a.frame(), Element::new("freejoint"))?;
    }
    Ok(m)
}

/// The geoms and bodies of the quadruped that W2 edits.
pub(crate) const ROBOT_GEOMS: [&str; 6] =
    ["torso", "eye_r", "thigh_front_left", "shin_back_right", "foot_front_right", "toe_back_left"];
pub(crate) const ROBOT_BODIES: [&str; 5] =
    ["torso", "hip_front_left", "knee_back_right", "ankle_front_right", "toe_back_left"];

/// W2, edit `k` of `m` (whose attachment scopes are `scopes`): even `k` sets the rgba of
/// a geom inside some robot, odd `k` the pos of a body inside some robot, both found by
/// scoped name.
pub(crate) fn undo_edit(m: &Model, scopes: &[String], k: usize) -> Result<Model, Error> {
    let scope = &scopes[(k * 37) % scopes.len()];
    let t = k as f64 / UNDO_EDITS as f64;
    if k % 2 == 0 {
        let name = format!("{scope}/{}", ROBOT_GEOMS[(k / 2) % ROBOT_GEOMS.len()]);
        let loc = m.find(Namespace::Geom, &name).expect("the geom exists");
        Ok(m.set_attr(&loc, "rgba", [t, 1.0 - t, 0.5, 1.0])?)
    } else {
        let name = format!("{scope}/{}", ROBOT_BODIES[(k / 2) % ROBOT_BODIES.len()]);
        let loc = m.find(Namespace::Body, &name).expect("the body exists");
        Ok(m.set_attr(&loc, "pos", [0.1 * t, 0.0, 0.57 + 0.01 * t])?)
    }
}

/// The attachment scope names of a model, in attach order.
pub(crate) fn scopes_of(m: &Model) -> Vec<String> {
    m.scopes().map(str::to_string).collect()
}

/// W2: `edits` edits of `fleet`, every version kept (`versions[0]` is `fleet`).
pub(crate) fn undo_history(fleet: &Model, edits: usize) -> Result<Vec<Model>, Error> {
    let scopes = scopes_of(fleet);
    let mut versions = Vec::with_capacity(edits + 1);
    versions.push(fleet.clone());
    for k in 0..edits {
        let next = undo_edit(&versions[k], &scopes, k)?;
        versions.push(next);
    }
    Ok(versions)
}

/// W3: `chains` chains of `depth` nested bodies under the worldbody, each body with a
/// hinge joint and a capsule geom. One element per line, no indentation (indenting a
/// 10,000-deep chain would make the file mostly spaces).
pub(crate) fn tree_xml(chains: usize, depth: usize) -> String {
    use std::fmt::Write;
    let mut s = String::with_capacity(chains * depth * 170 + 100);
    s.push_str("<mujoco model=\"tree\">\n<worldbody>\n");
    for c in 0..chains {
        for d in 0..depth {
            let _ = writeln!(
                s,
                "<body name=\"b{c}_{d}\" pos=\"0 0 0.1\">\n<joint name=\"j{c}_{d}\" type=\"hinge\" axis=\"0 1 0\"/>\n\
                 <geom name=\"g{c}_{d}\" type=\"capsule\" size=\"0.02\" fromto=\"0 0 0 0 0 0.1\"/>"
            );
        }
        for _ in 0..depth {
            s.push_str("</body>\n");
        }
    }
    s.push_str("</worldbody>\n</mujoco>\n");
    s
}

/// W3: the 10,000-body tree.
pub(crate) fn tree_10k_xml() -> String {
    tree_xml(TREE_CHAINS, TREE_DEPTH)
}

/// W3: the same 10,000 bodies as one chain (names `b0_0` … `b0_9999`).
pub(crate) fn chain_10k_xml() -> String {
    tree_xml(1, TREE_CHAINS * TREE_DEPTH)
}

/// W3: the 10,000-body tree with realistic attributes: 100 chains of 100 nested bodies,
/// each body with a pos, a quat and an inertial (pos, mass, diaginertia), a hinge joint
/// with an axis, a range and a damping, and a capsule geom with a size, a fromto, an
/// rgba and a mass; the numbers vary from body to body (about 3.7 MB).
pub(crate) fn realistic_tree_xml() -> String {
    use std::fmt::Write;
    let (chains, depth) = (TREE_CHAINS, TREE_DEPTH);
    let mut s = String::with_capacity(chains * depth * 400 + 100);
    s.push_str("<mujoco model=\"realistic_tree\">\n<worldbody>\n");
    for c in 0..chains {
        for d in 0..depth {
            let k = (c * depth + d) as f64;
            let a = 0.05 + 0.001 * d as f64;
            let (w, z) = ((a / 2.0).cos(), (a / 2.0).sin());
            let _ = writeln!(
                s,
                "<body name=\"b{c}_{d}\" pos=\"0 0 {len:.3}\" quat=\"{w:.7} 0 {z:.7} 0\">\n\
                 <inertial pos=\"0 0 {half:.4}\" mass=\"{mass:.4}\" diaginertia=\"{ixx:.6} {ixx:.6} {izz:.6}\"/>\n\
                 <joint name=\"j{c}_{d}\" type=\"hinge\" axis=\"0 1 0\" range=\"-{r:.1} {r:.1}\" damping=\"{damp:.3}\"/>\n\
                 <geom name=\"g{c}_{d}\" type=\"capsule\" size=\"{rad:.4}\" fromto=\"0 0 0 0 0 {len:.3}\" \
                 rgba=\"{cr:.3} {cg:.3} {cb:.3} 1\" mass=\"{mass:.4}\"/>",
                len = 0.1 + 0.0001 * d as f64,
                half = 0.05 + 0.00005 * d as f64,
                mass = 0.35 + 0.0007 * (k % 97.0),
                ixx = 0.0012 + 0.000003 * (k % 89.0),
                izz = 0.0002 + 0.000001 * (k % 83.0),
                r = 30.0 + (k % 61.0),
                damp = 0.5 + 0.01 * (k % 53.0),
                rad = 0.02 + 0.0001 * (k % 47.0),
                cr = 0.2 + 0.007 * (k % 101.0),
                cg = 0.3 + 0.005 * (k % 103.0),
                cb = 0.4 + 0.003 * (k % 107.0),
            );
        }
        for _ in 0..depth {
            s.push_str("</body>\n");
        }
    }
    s.push_str("</worldbody>\n</mujoco>\n");
    s
}

/// W6: the nesting depths of default classes read.
pub(crate) const NESTED_DEFAULTS: [usize; 3] = [100_000, 200_000, 400_000];

/// W6: default classes `c0` … `c{n-1}`, each inside the one before, the innermost
/// setting a geom size, and one geom of class `c0` in the worldbody.
pub(crate) fn nested_defaults_xml(n: usize) -> String {
    use std::fmt::Write;
    let mut s = String::with_capacity(n * 32 + 200);
    s.push_str("<mujoco model=\"nested_defaults\">\n<default>\n");
    for i in 0..n {
        let _ = writeln!(s, "<default class=\"c{i}\">");
    }
    s.push_str("<geom size=\"0.1\"/>\n");
    for _ in 0..n {
        s.push_str("</default>\n");
    }
    s.push_str(
        "</default>\n<worldbody>\n<geom class=\"c0\" size=\"1\"/>\n</worldbody>\n</mujoco>\n",
    );
    s
}

/// W7: the fleet sizes N that one more robot is attached to.
pub(crate) const ATTACH_GROWTH: [usize; 4] = [10, 100, 1000, 10_000];

/// W7: the fleet of `n` robots on an arena of `n + 1` sites, and the free site
/// `spawn_n` the next robot goes to.
pub(crate) fn fleet_with_free_site(robot: &Model, n: usize) -> (Model, mjcf::Loc) {
    let fleet = build_fleet(&read_arena(n + 1), robot, n).expect("the fleet builds");
    let site = fleet.find(Namespace::Site, &format!("spawn_{n}")).expect("the free site");
    (fleet, site)
}

/// W7 (and the growth table): `child` attached at `site`, with a freejoint on its frame,
/// as the quickstart does it (`attach_mut`, `add_mut`) on a new version of `parent`
/// (which is kept: the attach copies the path it shares, the freejoint then edits
/// that copy in place).
pub(crate) fn attach_one(parent: &Model, site: &mjcf::Loc, child: &Model) -> Model {
    let mut m = parent.clone();
    let a = m.attach_mut(site, child).expect("attach");
    m.add_mut(a.frame(), Element::new("freejoint")).expect("freejoint");
    m
}

/// W3: the CMU humanoid (`benches/models/humanoid_CMU.xml`, from the conformance corpus).
pub(crate) fn humanoid_xml() -> String {
    std::fs::read_to_string(models_dir().join("humanoid_CMU.xml"))
        .expect("benches/models/humanoid_CMU.xml")
}

/// W5: reads `xml` into quick-xml events and writes them back with `quick_xml::Writer`;
/// returns the bytes written.
pub(crate) fn quickxml_roundtrip(xml: &str) -> Vec<u8> {
    let mut reader = quick_xml::Reader::from_str(xml);
    let mut writer = quick_xml::Writer::new(Vec::with_capacity(xml.len()));
    loop {
        match reader.read_event() {
            Ok(quick_xml::events::Event::Eof) => break,
            Ok(e) => writer.write_event(e).expect("writing to a Vec"),
            Err(e) => panic!("quick-xml: {e}"),
        }
    }
    writer.into_inner()
}

/// W5: quick-xml reading `xml` into events only; returns the number of events.
pub(crate) fn quickxml_read(xml: &str) -> usize {
    let mut reader = quick_xml::Reader::from_str(xml);
    let mut n = 0;
    loop {
        match reader.read_event() {
            Ok(quick_xml::events::Event::Eof) => break,
            Ok(e) => {
                std::hint::black_box(e);
                n += 1;
            }
            Err(e) => panic!("quick-xml: {e}"),
        }
    }
    n
}

/// W5: quick-xml reading `xml` into events and decoding every attribute (its name and
/// its normalized, unescaped value), as a reader must; returns the number of
/// attributes. The floor of reading.
pub(crate) fn quickxml_read_attrs(xml: &str) -> usize {
    use quick_xml::events::Event;
    let mut reader = quick_xml::Reader::from_str(xml);
    let mut n = 0;
    loop {
        match reader.read_event() {
            Ok(Event::Eof) => break,
            Ok(Event::Start(t) | Event::Empty(t)) => {
                std::hint::black_box(t.name());
                for a in t.attributes() {
                    let a = a.expect("a well-formed attribute");
                    let v = a
                        .normalized_value(quick_xml::XmlVersion::default())
                        .expect("a well-formed value");
                    std::hint::black_box((a.key, v));
                    n += 1;
                }
            }
            Ok(e) => {
                std::hint::black_box(e);
            }
            Err(e) => panic!("quick-xml: {e}"),
        }
    }
    n
}

/// One measurement: the median time of `runs` runs of `f`, and the heap bytes the last
/// run allocated in total and still holds (the value it returned, before it is dropped).
#[derive(Clone, Debug)]
pub(crate) struct Measured<T> {
    pub value: T,
    pub seconds: f64,
    pub min_seconds: f64,
    pub runs: usize,
    pub allocated_bytes: usize,
    pub live_bytes: isize,
}

/// Runs `f` repeatedly (at least `min_runs` times and until about `budget` has passed,
/// at most `max_runs`), dropping each result except the last.
pub(crate) fn measure<T>(
    min_runs: usize,
    max_runs: usize,
    budget: Duration,
    mut f: impl FnMut() -> T,
) -> Measured<T> {
    let mut times = Vec::new();
    let start = Instant::now();
    let mut last = None;
    let mut alloc = 0;
    let mut live = 0;
    while times.len() < min_runs.max(1) || (times.len() < max_runs && start.elapsed() < budget) {
        drop(last.take());
        let (live0, total0) = (live_bytes(), total_bytes());
        let t = Instant::now();
        let v = std::hint::black_box(f());
        times.push(t.elapsed().as_secs_f64());
        alloc = total_bytes() - total0;
        live = live_bytes() as isize - live0 as isize;
        last = Some(v);
    }
    let runs = times.len();
    times.sort_by(f64::total_cmp);
    Measured {
        value: last.expect("ran at least once"),
        seconds: times[runs / 2],
        min_seconds: times[0],
        runs,
        allocated_bytes: alloc,
        live_bytes: live,
    }
}
