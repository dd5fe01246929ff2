//! The performance workloads W1–W5 (see `benches/workloads/mod.rs`) as divan
//! benchmarks: time per iteration, throughput (bytes read or written), and, from divan's
//! allocation profiler, the heap bytes allocated per iteration.
//!
//! ```text
//! cargo bench --bench perf              # all
//! cargo bench --bench perf -- w1        # W1 only (a filter on the benchmark path)
//! ```
//!
//! `cargo bench --bench figures` prints the same workloads as JSON lines, with live
//! bytes (memory of the fleet, memory per kept version).

mod workloads;

fn main() {
    divan::main();
}

/// W1: N copies of one robot, each attached at its own site with a freejoint on its
/// frame; `to_xml_string` of the result.
mod w1_fleet {
    use super::workloads::*;
    use divan::{Bencher, counter::BytesCount};

    #[divan::bench(args = FLEET_SIZES, sample_count = 10)]
    fn build(bencher: Bencher, n: usize) {
        let robot = read_robot();
        let arena = read_arena(n);
        bencher.bench(|| build_fleet(&arena, &robot, n).expect("the fleet builds"));
    }

    #[divan::bench(args = FLEET_SIZES, sample_count = 10)]
    fn write(bencher: Bencher, n: usize) {
        let fleet = build_fleet(&read_arena(n), &read_robot(), n).expect("the fleet builds");
        let len = fleet.to_xml_string().expect("writes").len();
        bencher.counter(BytesCount::new(len)).bench(|| fleet.to_xml_string().expect("writes"));
    }
}

/// W2: small edits of the 100-robot fleet, every version kept.
mod w2_undo {
    use super::workloads::*;
    use divan::Bencher;

    /// One more version: one edit (scoped find + set_attr) of the fleet.
    #[divan::bench]
    fn one_edit(bencher: Bencher) {
        let fleet = build_fleet(&read_arena(UNDO_ROBOTS), &read_robot(), UNDO_ROBOTS)
            .expect("the fleet builds");
        let scopes = scopes_of(&fleet);
        let mut k = 0;
        bencher.bench_local(|| {
            k += 1;
            undo_edit(&fleet, &scopes, k % UNDO_EDITS).expect("the edit applies")
        });
    }

    /// 1000 edits in a row, every version kept in a Vec.
    #[divan::bench(sample_count = 10)]
    fn history_1000(bencher: Bencher) {
        let fleet = build_fleet(&read_arena(UNDO_ROBOTS), &read_robot(), UNDO_ROBOTS)
            .expect("the fleet builds");
        bencher.bench(|| undo_history(&fleet, UNDO_EDITS).expect("the edits apply"));
    }
}

/// W3: reading (and writing back) generated deep and wide trees and the CMU humanoid.
mod w3_read {
    use super::workloads::*;
    use divan::{Bencher, counter::BytesCount};

    fn read(bencher: Bencher, xml: &str) {
        bencher
            .counter(BytesCount::new(xml.len()))
            .bench(|| mjcf::Model::from_xml_str(xml).expect("reads"));
    }

    fn write(bencher: Bencher, xml: &str) {
        let m = mjcf::Model::from_xml_str(xml).expect("reads");
        let len = m.to_xml_string().expect("writes").len();
        bencher.counter(BytesCount::new(len)).bench(|| m.to_xml_string().expect("writes"));
    }

    #[divan::bench(sample_count = 20)]
    fn tree_10k(bencher: Bencher) {
        read(bencher, &tree_10k_xml());
    }

    #[divan::bench(sample_count = 20)]
    fn realistic_tree_10k(bencher: Bencher) {
        read(bencher, &realistic_tree_xml());
    }

    #[divan::bench(sample_count = 10)]
    fn chain_10k(bencher: Bencher) {
        read(bencher, &chain_10k_xml());
    }

    #[divan::bench]
    fn humanoid_cmu(bencher: Bencher) {
        read(bencher, &humanoid_xml());
    }

    #[divan::bench(sample_count = 20)]
    fn write_tree_10k(bencher: Bencher) {
        write(bencher, &tree_10k_xml());
    }

    #[divan::bench(sample_count = 5)]
    fn write_chain_10k(bencher: Bencher) {
        write(bencher, &chain_10k_xml());
    }
}

/// W4: detaching one robot out of the 1000-robot fleet.
mod w4_detach {
    use super::workloads::*;
    use divan::Bencher;

    #[divan::bench]
    fn one_of_1000(bencher: Bencher) {
        let fleet = build_fleet(&read_arena(DETACH_ROBOTS), &read_robot(), DETACH_ROBOTS)
            .expect("the fleet builds");
        let scope = scopes_of(&fleet)[DETACH_ROBOTS / 2].clone();
        bencher.bench(|| fleet.detach(&scope).expect("detaches"));
    }
}

/// W5: the floor: quick-xml reading the same documents into events and writing them
/// back, no model.
mod w5_quick_xml {
    use super::workloads::*;
    use divan::{Bencher, counter::BytesCount};

    fn fleet_1000_xml() -> String {
        build_fleet(&read_arena(1000), &read_robot(), 1000)
            .expect("the fleet builds")
            .to_xml_string()
            .expect("writes")
    }

    #[divan::bench(sample_count = 20)]
    fn roundtrip_fleet_1000(bencher: Bencher) {
        let xml = fleet_1000_xml();
        bencher.counter(BytesCount::new(xml.len())).bench(|| quickxml_roundtrip(&xml));
    }

    #[divan::bench(sample_count = 20)]
    fn read_fleet_1000(bencher: Bencher) {
        let xml = fleet_1000_xml();
        bencher.counter(BytesCount::new(xml.len())).bench(|| quickxml_read(&xml));
    }

    #[divan::bench]
    fn roundtrip_tree_10k(bencher: Bencher) {
        let xml = tree_10k_xml();
        bencher.counter(BytesCount::new(xml.len())).bench(|| quickxml_roundtrip(&xml));
    }

    #[divan::bench]
    fn read_tree_10k(bencher: Bencher) {
        let xml = tree_10k_xml();
        bencher.counter(BytesCount::new(xml.len())).bench(|| quickxml_read(&xml));
    }
}
