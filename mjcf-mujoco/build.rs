//! Compiles the fatal-error guard (shim/guard.c); see its header comment.
fn main() {
    println!("cargo::rerun-if-changed=shim/guard.c");
    cc::Build::new().file("shim/guard.c").std("c11").warnings(true).compile("mjcf_mujoco_guard");
}
