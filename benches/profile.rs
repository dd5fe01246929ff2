//! One workload in a loop, for a profiler: `valgrind --tool=callgrind` counts
//! instructions repeatably on this noisy machine, so this binary runs exactly one
//! workload, a given number of times, and nothing else (no timing loop, no statistics).
//!
//! ```text
//! cargo bench --bench profile --no-run          # prints the binary's path
//! valgrind --tool=callgrind target/release/deps/profile-HASH WORKLOAD [ARG] [REPS]
//! ```
//!
//! Workloads: `build N` (the W1 fleet), `write N` (writing it), `read-tree`,
//! `read-rtree`, `read-chain` (W3) and their floors `floor-tree`, `floor-rtree`,
//! `floor-chain` (quick-xml events and attributes), `nested N` (W6, N levels),
//! `attach N` (W7: one more robot onto a fleet of N), `detach` (W4), `names N` (the
//! name of every element of the W1 fleet of N robots, through handles walked from the
//! root by `children()`), `full-names N` (the same names asked one by one of the
//! model, `Model::full_name` of each element's locator), `walk N` (the preorder walk
//! of that fleet). REPS defaults
//! to 1 (the setup is counted too: compare runs that differ in REPS to subtract it).

mod workloads;

use std::time::Instant;

use workloads::*;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).filter(|a| a != "--bench").collect();
    let what = args.first().map_or("", String::as_str);
    let arg = |i: usize, d: usize| args.get(i).and_then(|s| s.parse().ok()).unwrap_or(d);
    let reps = arg(2, 1);
    let robot = read_robot();
    let t = Instant::now();
    match what {
        "build" => {
            let n = arg(1, 1000);
            let arena = read_arena(n);
            for _ in 0..reps {
                std::hint::black_box(build_fleet(&arena, &robot, n).expect("builds"));
            }
        }
        "write" => {
            let n = arg(1, 1000);
            let fleet = build_fleet(&read_arena(n), &robot, n).expect("builds");
            for _ in 0..reps {
                std::hint::black_box(fleet.to_xml_string().expect("writes"));
            }
        }
        "read-tree" | "read-rtree" | "read-chain" => {
            let xml = match what {
                "read-tree" => tree_10k_xml(),
                "read-rtree" => realistic_tree_xml(),
                _ => chain_10k_xml(),
            };
            for _ in 0..arg(1, 1) {
                std::hint::black_box(mjcf::Model::from_xml_str(&xml).expect("reads"));
            }
        }
        "floor-tree" | "floor-rtree" | "floor-chain" => {
            let xml = match what {
                "floor-tree" => tree_10k_xml(),
                "floor-rtree" => realistic_tree_xml(),
                _ => chain_10k_xml(),
            };
            for _ in 0..arg(1, 1) {
                std::hint::black_box(quickxml_read_attrs(&xml));
            }
        }
        "nested" => {
            let xml = nested_defaults_xml(arg(1, 10_000));
            for _ in 0..reps {
                std::hint::black_box(mjcf::Model::from_xml_str(&xml).expect("reads"));
            }
        }
        "attach" => {
            let (fleet, site) = fleet_with_free_site(&robot, arg(1, 1000));
            for _ in 0..reps {
                std::hint::black_box(attach_one(&fleet, &site, &robot));
            }
        }
        "detach" => {
            let fleet =
                build_fleet(&read_arena(DETACH_ROBOTS), &robot, DETACH_ROBOTS).expect("builds");
            let scope = scopes_of(&fleet)[DETACH_ROBOTS / 2].clone();
            for _ in 0..arg(1, 1) {
                std::hint::black_box(fleet.detach(&scope).expect("detaches"));
            }
        }
        "walk" => {
            let n = arg(1, 100);
            let fleet = build_fleet(&read_arena(n), &robot, n).expect("builds");
            for _ in 0..reps {
                let entered = fleet.walk().filter(|e| matches!(e, mjcf::Event::Enter(_))).count();
                eprintln!("walk: {entered} elements entered");
            }
        }
        "names" => {
            let n = arg(1, 100);
            let fleet = build_fleet(&read_arena(n), &robot, n).expect("builds");
            for _ in 0..reps {
                let (elements, chars) = names_by_handles(&fleet);
                eprintln!("names: {elements} elements, {chars} characters of names");
            }
        }
        "full-names" => {
            let n = arg(1, 100);
            let fleet = build_fleet(&read_arena(n), &robot, n).expect("builds");
            let locs: Vec<mjcf::Loc> = fleet
                .walk()
                .filter_map(|e| match e {
                    mjcf::Event::Enter(h) => Some(h.loc()),
                    mjcf::Event::Leave(_) => None,
                })
                .collect();
            for _ in 0..reps {
                let chars: usize =
                    locs.iter().filter_map(|l| fleet.full_name(l)).map(|s| s.len()).sum();
                eprintln!("full-names: {} elements, {chars} characters of names", locs.len());
            }
        }
        _ => {
            eprintln!(
                "usage: profile build|write|read-tree|read-rtree|read-chain|floor-tree|floor-rtree|floor-chain|nested|attach|detach|names|full-names|walk [N] [REPS]"
            );
            std::process::exit(2);
        }
    }
    eprintln!("{what}: {:?}", t.elapsed());
}

/// The full name of every element of `m`, through handles walked down from the root
/// with `children()`: how many elements, and the names' total length.
fn names_by_handles(m: &mjcf::Model) -> (usize, usize) {
    let mut stack = vec![m.get(&m.root()).expect("the root")];
    let (mut elements, mut chars) = (0, 0);
    while let Some(e) = stack.pop() {
        elements += 1;
        chars += std::hint::black_box(e.full_name()).map_or(0, |n| n.len());
        stack.extend(e.children());
    }
    (elements, chars)
}
