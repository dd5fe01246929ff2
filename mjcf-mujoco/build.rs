//! Compiles the fatal-error guard (shim/guard.c); see its header comment.
fn main() {
    println!("cargo::rerun-if-changed=shim/guard.c");
    // The mjcf crate's tests/support files, included by this crate's tests, leave
    // their own unit tests to the mjcf crate.
    println!("cargo::rustc-check-cfg=cfg(mjcf_mujoco)");
    println!("cargo::rustc-cfg=mjcf_mujoco");
    cc::Build::new().file("shim/guard.c").std("c11").warnings(true).compile("mjcf_mujoco_guard");
}
