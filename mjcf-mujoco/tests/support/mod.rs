//! Shared by the binding's tests: MuJoCo, loaded from `MUJOCO_LIB`.

use mjcf_mujoco::MuJoCo;

/// MuJoCo 4.0.0, from `MUJOCO_LIB` (the tests that call this are ignored in a plain
/// `cargo test`; `.ci/run` runs them with the pinned wheel's library).
pub(crate) fn mujoco() -> MuJoCo {
    match MuJoCo::load() {
        Ok(m) => m,
        Err(e) => panic!("this test needs MuJoCo 4.0.0: {e}"),
    }
}
