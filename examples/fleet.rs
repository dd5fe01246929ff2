//! A fleet of robots and many randomized variants of it, built in parallel from one
//! shared base.
//!
//! ```text
//! cargo run --release --example fleet -- [ROBOTS] [VARIANTS] [THREADS] [WRITE_EVERY]
//! ```
//!
//! ROBOTS copies (default 1000) of the quadruped of `benches/models` are attached at
//! the sites of an arena, each with a freejoint on its attachment frame. Then VARIANTS
//! variants (default 1000) are built on THREADS threads (default: the available
//! parallelism), each from the same base value: a few robots recolored, two moved, one
//! removed and an extra one attached. Every variant is kept; all of them share the
//! base's unchanged parts, so holding a thousand 1000-robot scenes costs little more
//! than one. Every WRITE_EVERY-th variant (default 1000: one) is written as MJCF.
//!
//! Memory is the process's resident set from `/proc/self/status` (Linux).

use std::path::PathBuf;
use std::time::Instant;

use mjcf::{Element, Error, Model, Namespace};

fn arg(i: usize, default: usize) -> usize {
    std::env::args().nth(i).and_then(|s| s.parse().ok()).unwrap_or(default)
}

/// `VmRSS` and `VmHWM` (peak) of this process in MiB, if `/proc` has them.
fn rss_mib() -> (f64, f64) {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let field = |name: &str| {
        status
            .lines()
            .find(|l| l.starts_with(name))
            .and_then(|l| l.split_whitespace().nth(1))
            .and_then(|kb| kb.parse::<f64>().ok())
            .map_or(f64::NAN, |kb| kb / 1024.0)
    };
    (field("VmRSS:"), field("VmHWM:"))
}

/// A small deterministic generator (splitmix64), so every run builds the same variants.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// An arena: a ground plane, a light and `n` sites `spawn_i` on a 2 m grid centred on
/// the origin at z = 0.6 (as `benches/models/arena_*.xml`).
fn arena(n: usize) -> Result<Model, Error> {
    let side = (1..).find(|s| s * s >= n).unwrap_or(1);
    let half = side as f64 - 1.0;
    let m = Model::new("arena");
    let (m, _) = m.add(
        &m.worldbody(),
        Element::new("light")
            .attr("name", "top")
            .attr("pos", [0.0, 0.0, 20.0])
            .attr("directional", true),
    )?;
    let (mut m, _) = m.add(
        &m.worldbody(),
        Element::new("geom")
            .attr("name", "floor")
            .attr("type", "plane")
            .attr("size", [0.0, 0.0, 0.1]),
    )?;
    for i in 0..n {
        let pos = [2.0 * (i % side) as f64 - half, 2.0 * (i / side) as f64 - half, 0.6];
        let site = Element::new("site")
            .attr("name", format!("spawn_{i}"))
            .attr("pos", pos)
            .attr("size", [0.05]);
        m = m.add(&m.worldbody(), site)?.0;
    }
    Ok(m)
}

/// `base` with a few random changes: three robots recolored, two moved, an extra robot
/// attached at the worldbody with a freejoint, and one of the base's robots removed.
fn variant(base: &Model, robot: &Model, scopes: &[String], seed: u64) -> Result<Model, Error> {
    let mut rng = Rng(seed);
    let mut m = base.clone();
    for _ in 0..3 {
        let scope = &scopes[rng.below(scopes.len())];
        if let Some(torso) = m.find(Namespace::Geom, &format!("{scope}/torso")) {
            m = m.set_attr(&torso, "rgba", [rng.unit(), rng.unit(), rng.unit(), 1.0])?;
        }
    }
    for _ in 0..2 {
        let scope = &scopes[rng.below(scopes.len())];
        if let Ok(frame) = m.frame(scope) {
            m = m.set_attr(
                &frame,
                "pos",
                [40.0 * rng.unit() - 20.0, 40.0 * rng.unit() - 20.0, 0.6],
            )?;
        }
    }
    // Attach first, then detach: the attach reuses the merged global settings the base
    // has cached, which a detach would make it recompute over every attachment.
    let (next, frame) = m.attach_to_world(robot)?;
    let (next, _) = next.add(frame.frame(), Element::new("freejoint"))?;
    let next = next.set_attr(frame.frame(), "pos", [0.0, 0.0, 1.5 + rng.unit()])?;
    Ok(next.detach(&scopes[rng.below(scopes.len())])?)
}

/// What one thread built: its variants, and the XML it wrote.
struct Batch {
    kept: Vec<Model>,
    bytes: usize,
    written: usize,
}

fn main() -> Result<(), Error> {
    let n = arg(1, 1000);
    let count = arg(2, 1000);
    let threads = arg(3, std::thread::available_parallelism().map_or(2, |p| p.get())).max(1);
    let write_every = arg(4, 1000).max(1);
    let (rss0, _) = rss_mib();

    let models =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..").join("benches").join("models");
    let t = Instant::now();
    let robot = Model::from_path(models.join("quadruped_robot.xml"))?;
    let arena = arena(n)?;
    println!(
        "read the robot and built a {n}-site arena in {:.1} ms",
        t.elapsed().as_secs_f64() * 1e3
    );

    let t = Instant::now();
    let mut base = arena;
    for i in 0..n {
        let Some(site) = base.find(Namespace::Site, &format!("spawn_{i}")) else { continue };
        let (m, frame) = base.attach(&site, &robot)?;
        base = m.add(frame.frame(), Element::new("freejoint"))?.0;
    }
    let scopes: Vec<String> = base.scopes().map(str::to_string).collect();
    let (rss1, _) = rss_mib();
    println!(
        "base: {} robots attached in {:.1} ms ({:.1} MiB resident growth)",
        scopes.len(),
        t.elapsed().as_secs_f64() * 1e3,
        rss1 - rss0
    );

    // The variants, built on `threads` threads from the one shared base.
    let t = Instant::now();
    let results: Vec<Result<Batch, Error>> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..threads)
            .map(|k| {
                let (base, robot, scopes) = (&base, &robot, &scopes);
                s.spawn(move || {
                    let mut batch = Batch { kept: Vec::new(), bytes: 0, written: 0 };
                    for v in (k..count).step_by(threads) {
                        let m = variant(base, robot, scopes, v as u64)?;
                        if v % write_every == 0 {
                            batch.bytes += m.to_xml_string()?.len();
                            batch.written += 1;
                        }
                        batch.kept.push(m);
                    }
                    Ok(batch)
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().expect("a variant thread panicked")).collect()
    });
    let elapsed = t.elapsed().as_secs_f64();
    let mut variants = Vec::with_capacity(count);
    let (mut bytes, mut written) = (0, 0);
    for r in results {
        let batch = r?;
        variants.extend(batch.kept);
        bytes += batch.bytes;
        written += batch.written;
    }
    let (rss2, hwm) = rss_mib();
    println!(
        "{} variants on {threads} threads in {:.2} s: {:.0} variants/s, {written} written ({:.1} MB of XML)",
        variants.len(),
        elapsed,
        variants.len() as f64 / elapsed,
        bytes as f64 / 1e6
    );
    println!(
        "memory: {:.1} MiB resident growth holding all {} variants ({:.1} KiB each), peak resident {:.1} MiB",
        rss2 - rss1,
        variants.len(),
        (rss2 - rss1) * 1024.0 / variants.len().max(1) as f64,
        hwm
    );

    // Every variant has as many robots as the base: one removed, one added.
    if let Some(v) = variants.first() {
        println!(
            "variant 0: {} robots, base: {} robots; the base is unchanged",
            v.scopes().count(),
            scopes.len()
        );
    }
    Ok(())
}
