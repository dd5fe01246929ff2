//! Prints one JSON line per workload (W1–W8, see `benches/workloads/mod.rs`): the
//! figures `tools/compare_perf.py` compares with dm_control and MjSpec; then the
//! performance issue's table (each goal with ours, the floor measured in the same run
//! on the same bytes, the ratio, and whether the goal is met).
//!
//! ```text
//! cargo bench --bench figures                       # everything
//! cargo bench --bench figures -- --only issue       # the issue's table only (W1 N=1000, W2-W7)
//! cargo bench --bench figures -- --sizes 1,10,100   # W1 on these fleet sizes only
//! cargo bench --bench figures -- --only w1,w4       # some workloads
//! cargo bench --bench figures -- --only growth      # the README's growth table
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

/// W8: `examples/compose.rs` itself (its `main` is not used here).
#[allow(dead_code)]
#[path = "../examples/compose.rs"]
mod compose;

use std::io::Write;
use std::path::PathBuf;
use std::time::Duration;

use serde_json::{Value, json};
use workloads::*;

/// The issue's table, filled as the workloads are measured, printed at the end.
#[derive(Default)]
struct Table {
    rows: Vec<[String; 6]>,
}

impl Table {
    /// A row: the workload, ours, the floor, the ratio, the goal, and whether it is met.
    fn row(&mut self, cells: [&str; 5], met: Option<bool>) {
        let met = match met {
            Some(true) => "met",
            Some(false) => "NOT MET",
            None => "-",
        };
        let [a, b, c, d, e] = cells.map(str::to_string);
        self.rows.push([a, b, c, d, e, met.to_string()]);
    }

    fn print(&self) {
        if self.rows.is_empty() {
            return;
        }
        let head = ["workload", "ours", "floor", "ratio", "goal", ""];
        let mut width = head.map(str::len);
        for r in &self.rows {
            for (w, c) in width.iter_mut().zip(r) {
                *w = (*w).max(c.chars().count());
            }
        }
        let mut out = std::io::stdout().lock();
        let line = |cells: &[String; 6]| {
            let mut l = String::from("|");
            for (c, w) in cells.iter().zip(width) {
                l.push_str(&format!(" {c:<w$} |"));
            }
            l
        };
        let _ = writeln!(out, "\nissue 13 (ratio = ours / floor, both measured in this run):\n");
        let _ = writeln!(out, "{}", line(&head.map(str::to_string)));
        let _ = writeln!(out, "{}", line(&width.map(|w| "-".repeat(w))));
        for r in &self.rows {
            let _ = writeln!(out, "{}", line(r));
        }
    }
}

/// A duration for the table: `16.2 ms`, `8.1 µs`, `1.20 s`.
fn time(s: f64) -> String {
    if s >= 1.0 {
        format!("{s:.2} s")
    } else if s >= 1e-3 {
        format!("{:.1} ms", s * 1e3)
    } else {
        format!("{:.1} µs", s * 1e6)
    }
}

/// Bytes for the table: `2.6 KiB`, `3.1 MiB`.
fn size(b: f64) -> String {
    if b >= 1024.0 * 1024.0 {
        format!("{:.1} MiB", b / 1024.0 / 1024.0)
    } else {
        format!("{:.1} KiB", b / 1024.0)
    }
}

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
    // `issue`: the workloads of the issue's table; W1 at N = 1000 unless sizes are given.
    if let Some(only) = &mut a.only {
        if only.iter().any(|w| w == "issue") {
            only.extend(["w1", "w2", "w3", "w4", "w5", "w6", "w7", "w8"].map(String::from));
            if !std::env::args().any(|x| x == "--sizes") {
                a.sizes = vec![1000];
            }
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
    RECORDS.with(|r| r.borrow_mut().push(line));
}

thread_local! {
    /// Every line emitted, for the issue's table at the end.
    static RECORDS: std::cell::RefCell<Vec<Value>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// A field of the record `key`, if it was measured.
fn got(key: &str, field: &str) -> Option<f64> {
    RECORDS
        .with(|r| r.borrow().iter().rev().find(|l| l["key"] == key).and_then(|l| l[field].as_f64()))
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
            // The same with inputs read without their source (`keep_source(false)`): the
            // text and tag records a lossless save needs are what the two differ by.
            let bare = mjcf::ReadOptions::default().keep_source(false);
            let l1 = live_bytes();
            let inputs = (bare.read_str(&arena_xml(n)), bare.read_path(robot_path()));
            let bare_live = live_bytes() - l1;
            if inputs.0.is_ok() && inputs.1.is_ok() {
                l["live_bytes_with_inputs_without_source"] =
                    json!(b.live_bytes + bare_live as isize);
            }
            drop(inputs);
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
            ("w3_rtree", "W3 10,000-body tree, realistic attributes", &realistic_tree_xml()),
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
            ("w5_chain", "W5 quick-xml, W3 chain", &chain_10k_xml()),
            ("w5_rtree", "W5 quick-xml, W3 realistic tree", &realistic_tree_xml()),
        ] {
            let rt = measure(3, 200, budget, || quickxml_roundtrip(xml));
            let mut l = line(&format!("{key}_roundtrip"), &format!("{name}: read+write"), &rt);
            l["bytes"] = json!(xml.len());
            emit(l);
            let r = measure(3, 200, budget, || quickxml_read(xml));
            let mut l = line(&format!("{key}_read"), &format!("{name}: read"), &r);
            l["bytes"] = json!(xml.len());
            emit(l);
            let r = measure(3, 200, budget, || quickxml_read_attrs(xml));
            let mut l = line(
                &format!("{key}_read_attrs"),
                &format!("{name}: read, attributes decoded"),
                &r,
            );
            l["bytes"] = json!(xml.len());
            emit(l);
        }
    }

    // W6 nested default classes: read, and the floor on the same bytes.
    if wants("w6") {
        for n in NESTED_DEFAULTS {
            let xml = nested_defaults_xml(n);
            let r = measure(1, 20, budget, || mjcf::Model::from_xml_str(&xml));
            match &r.value {
                Ok(_) => {
                    let mut l = line(
                        &format!("w6_nested_{n}_read"),
                        &format!("W6 read {n} nested default classes"),
                        &r,
                    );
                    l["bytes"] = json!(xml.len());
                    emit(l);
                }
                Err(e) => error(&format!("w6_nested_{n}_read"), "W6 nested defaults", e),
            }
            drop(r);
            let f = measure(3, 200, budget, || quickxml_read_attrs(&xml));
            let mut l = line(
                &format!("w5_nested_{n}_read_attrs"),
                &format!("W5 quick-xml, W6 {n} nested defaults: read, attributes decoded"),
                &f,
            );
            l["bytes"] = json!(xml.len());
            emit(l);
        }
    }

    // W7 attach growth: one more robot (attach + freejoint) onto a fleet of N.
    if wants("w7") {
        for n in ATTACH_GROWTH {
            let (fleet, site) = fleet_with_free_site(&robot, n);
            let m = measure(20, 100_000, budget, || attach_one(&fleet, &site, &robot));
            let mut l = line(
                &format!("w7_attach_{n}"),
                &format!("W7 attach + freejoint of one more robot, fleet of {n}"),
                &m,
            );
            l["fleet"] = json!(n);
            emit(l);
        }
    }

    // W8 the real job: examples/compose.rs, its models read, the scene composed, 200
    // variants built and exported with their meshes into a fresh folder.
    if wants("w8") {
        let case = models_dir().join("../../tests/conformance/cases/real_02_jaco_arm_with_hand");
        let out = std::env::temp_dir().join(format!("mjcf-w8-{}", std::process::id()));
        let m = measure(3, 20, budget, || {
            let _ = std::fs::remove_dir_all(&out);
            compose::compose(&case, &out)
        });
        match &m.value {
            Ok(()) => {
                let mut l =
                    line("w8_compose", "W8 compose.rs: read, compose, 200 variants exported", &m);
                l["files"] = json!(std::fs::read_dir(&out).map_or(0, Iterator::count));
                emit(l);
            }
            Err(e) => error("w8_compose", "W8 compose.rs", e),
        }
        let _ = std::fs::remove_dir_all(&out);
    }

    issue_table().print();
}

/// The issue's table from the records measured in this run.
fn issue_table() -> Table {
    let mut t = Table::default();
    let ratio = |a: f64, b: f64| format!("{:.1}x", a / b);
    if let Some(b) = got("w1_build_1000", "seconds") {
        t.row(["build the N=1000 fleet", &time(b), "-", "-", "< 5 ms"], Some(b < 5e-3));
    }
    let attach: Vec<Option<f64>> =
        ATTACH_GROWTH.iter().map(|n| got(&format!("w7_attach_{n}"), "seconds")).collect();
    if let (Some(Some(first)), Some(Some(last))) = (attach.first(), attach.last()) {
        let ours =
            attach.iter().map(|s| s.map_or("-".into(), time)).collect::<Vec<_>>().join(" / ");
        t.row(
            [
                "attach + freejoint of one more robot, fleet of N = 10 / 100 / 1,000 / 10,000",
                &ours,
                "-",
                &format!("{} (N=10,000 / N=10)", ratio(*last, *first)),
                "N=10,000 within 1.5x of N=10",
            ],
            Some(last / first <= 1.5),
        );
    }
    if let (Some(w), Some(bytes), Some(f)) = (
        got("w1_write_1000", "seconds"),
        got("w1_write_1000", "bytes"),
        got("w5_fleet_1000_roundtrip", "seconds"),
    ) {
        t.row(
            [
                &format!("write the N=1000 fleet ({:.1} MB)", bytes / 1e6),
                &format!("{}, {:.0} MB/s", time(w), bytes / w / 1e6),
                &format!("{} (quick-xml event round trip)", time(f)),
                &ratio(w, f),
                "<= 3x the round trip (>= 300 MB/s)",
            ],
            Some(w / f <= 3.0),
        );
    }
    for (key, floor, name, goal) in [
        (
            "w3_rtree_read",
            "w5_rtree_read_attrs",
            "read a 10,000-body tree, realistic attributes",
            Some(25e-3),
        ),
        ("w3_tree_read", "w5_tree_read_attrs", "read the plain 10,000-body tree", None),
        ("w3_chain_read", "w5_chain_read_attrs", "read a 10,000-deep chain", None),
    ] {
        if let (Some(r), Some(f), Some(bytes)) =
            (got(key, "seconds"), got(floor, "seconds"), got(key, "bytes"))
        {
            let goal_text = match goal {
                Some(g) => format!("<= 3x (<= {})", time(g)),
                None => "<= 3x".into(),
            };
            let met = r / f <= 3.0 && goal.is_none_or(|g| r <= g);
            t.row(
                [
                    &format!("{name} ({:.1} MB)", bytes / 1e6),
                    &time(r),
                    &format!("{} (quick-xml events + attributes)", time(f)),
                    &ratio(r, f),
                    &goal_text,
                ],
                Some(met),
            );
        }
    }
    if let Some(d) = got("w4_detach", "seconds") {
        t.row(
            ["detach one robot from the N=1000 fleet", &time(d), "-", "-", "<= 5 µs"],
            Some(d <= 5e-6),
        );
    }
    let nested: Vec<Option<f64>> =
        NESTED_DEFAULTS.iter().map(|n| got(&format!("w6_nested_{n}_read"), "seconds")).collect();
    if let [Some(a), Some(_), Some(c)] = nested[..] {
        let ours =
            nested.iter().map(|s| s.map_or("-".into(), time)).collect::<Vec<_>>().join(" / ");
        let last = NESTED_DEFAULTS[NESTED_DEFAULTS.len() - 1];
        let floor = got(&format!("w5_nested_{last}_read_attrs"), "seconds");
        t.row(
            [
                "read 100k / 200k / 400k nested default classes",
                &ours,
                &floor.map_or("-".into(), |f| format!("{} (quick-xml, 400k)", time(f))),
                &format!(
                    "{} (400k / 100k; linear = 4x){}",
                    ratio(c, a),
                    floor.map_or(String::new(), |f| format!("; {} of the floor", ratio(c, f)))
                ),
                "linear; 400k <= 2 s",
            ],
            Some(c <= 2.0 && c / a <= 4.0 * 1.25),
        );
    }
    if let (Some(v), Some(h), Some(f)) = (
        got("w2_one_version", "seconds"),
        got("w2_history", "live_bytes_per_version"),
        got("w1_build_1000", "live_bytes_with_inputs"),
    ) {
        t.row(
            [
                "one more undo version, N=100; heap per version; fleet heap N=1000",
                &format!("{}; {}; {}", time(v), size(h), size(f)),
                "-",
                "-",
                "keep (3.0 µs; 2.6 KiB; 3.1 MiB)",
            ],
            None,
        );
    }
    if let (Some(c), Some(files)) = (got("w8_compose", "seconds"), got("w8_compose", "files")) {
        t.row(
            [
                &format!("compose.rs: read, compose, 200 variants exported ({files} files)"),
                &time(c),
                "dm_control 4.2 s (the issue; tools/compare_perf.py measures it)",
                &format!("{} faster", ratio(4.2, c)),
                "-",
            ],
            None,
        );
    }
    t
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
