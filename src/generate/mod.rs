//! Generators of valid models, compositions and edit sequences, for property tests
//! and fuzzing (features `proptest` and `arbitrary`).
//!
//! A generated model is described by a plain-data **recipe**: a [`ModelRecipe`] is a
//! model name, its global settings and a list of [`Step`]s (add a body, a geom, a
//! joint, a default class, an actuator, ..., attach another recipe's model at a
//! site); an [`EditRecipe`] is a list of [`Edit`]s (add, set, rename, remove, attach,
//! detach, rename a scope, `include_copy`). Recipes hold no model and no locator:
//! every choice of "which element" is a [`Pick`], an index taken modulo what exists
//! when the step runs, and every number is a [`Unit`] mapped into the range the
//! attribute needs. **Applying** a recipe builds the model step by step and skips
//! (or repairs) any step that would make it invalid, so *every* recipe, and so every
//! recipe a shrinker or a fuzzer makes out of another, gives a valid model:
//!
//! - elements only where the schema allows them, and attribute values of the type
//!   and length the schema gives ([`ElementKind::spec`](crate::ElementKind::spec)),
//!   in ranges MuJoCo accepts (positive sizes, masses and inertias, non-zero axes,
//!   `lo < hi` ranges);
//! - names unique per namespace (a taken name gets `_2`, `_3`, ...); references that
//!   resolve (actuators, sensors, tendons, equalities and contact pairs name
//!   existing elements, of the joint types they need);
//! - what MuJoCo compiles: every body has a geom with a size (so it has mass),
//!   moving attachment frames get an inertial, freejoints only on bodies and frames
//!   directly in the worldbody (and never with other joints), planes only in the
//!   worldbody;
//! - after every step, [`Model::check`](crate::Model::check) finds no more problems than before (none,
//!   for a model built from a recipe); an edit that would add one is repaired
//!   (a remove also removes or clears what referred to the removed elements) or
//!   skipped.
//!
//! With the `proptest` feature, [`strategy`] has the proptest strategies (recipes,
//! and the models they build); with the `arbitrary` feature, every recipe type
//! implements `arbitrary::Arbitrary`, for cargo-fuzz targets.
//!
//! # Palettes
//!
//! A recipe's [`Palette`] says which models it builds (the outermost recipe's counts
//! for everything it attaches); `strategy::scene_recipe_in(palette)` gives scenes of
//! each:
//!
//! - [`Palette::Valid`] (the default, and what every other strategy and `Arbitrary`
//!   give): the valid models described above.
//! - [`Palette::Wide`]: also what MuJoCo may refuse, to judge
//!   [`Model::check`](crate::Model::check) against MuJoCo (`mjcf-mujoco`'s
//!   `tests/check.rs` compares their verdicts on 2,000 such scenes). Attachments at
//!   sites anywhere: in moving bodies, in MuJoCo `<frame>`s ([`Step::Frame`]), in
//!   attached models; attached models with free bodies and planes in their
//!   worldbody; freejoints on attachment frames wherever they are; frames with
//!   joints of mixed types. No step is skipped for what `check` finds.
//! - [`Palette::Simulates`]: valid models that simulate, for properties that step
//!   every scene. Every joint and attachment-frame joint has armature (at least 0.1)
//!   and damping (at least 1), no geom is smaller than 0.05, the integrator is
//!   `implicitfast` at MuJoCo's default timestep (0.002), and every geom's
//!   `contype`/`conaffinity` is set by what moves it: static geoms and free bodies'
//!   geoms collide with free bodies' geoms, geoms of bodies moved by other joints
//!   collide with free bodies' geoms only (randomly placed bodies that can only
//!   turn or slide about their joints start inside one another and cannot part,
//!   and the contact forces between them made most diverging scenes diverge; a
//!   light joint inertia, which armature raises, made most of the rest). The scenes
//!   keep every joint type (free, ball, slide, hinge), contacts, and attachments
//!   below moving bodies, nested. `mjcf-mujoco`'s `tests/simulates.rs` steps them
//!   1,000 steps each and requires at least 99.9% without a MuJoCo warning.
//!
//! ```
//! # #[cfg(feature = "proptest")] {
//! use mjcf::generate::{Palette, strategy};
//! use proptest::prelude::*;
//!
//! proptest!(ProptestConfig::with_cases(4), |(r in strategy::scene_recipe_in(Palette::Simulates))| {
//!     let scene = r.build();
//!     prop_assert!(scene.check().is_empty());
//!     // Compile and step it with mjcf-mujoco: MuJoCo::load()?.compile(&scene)?,
//!     // then Physics::new(&compiled)?.step(1000)? gives no warning.
//! });
//! # }
//! ```
//!
//! # A failing case prints as MJCF
//!
//! proptest prints a failing input with `{:#?}`: a [`Model`](crate::Model) then
//! prints as its MJCF text, and a [`ModelRecipe`] as its steps (picks as `#i`,
//! numbers in `[0, 1]`, names as the words they give) followed by the MJCF text of
//! the model it builds.
//!
//! # Properties to write with them
//!
//! Every generated scene (nested attachments, frames with joints and freejoints
//! included) compiles in MuJoCo. Compile each in memory with the workspace's
//! `mjcf-mujoco` crate (`MuJoCo::load()?.compile(&scene)`; its tests judge 1,325 of
//! them so), or write them out and compile them with MuJoCo from Python:
//!
//! ```no_run
//! # #[cfg(feature = "proptest")] {
//! use mjcf::generate::strategy;
//! use proptest::strategy::{Strategy, ValueTree};
//! use proptest::test_runner::TestRunner;
//!
//! let mut runner = TestRunner::deterministic();
//! for i in 0..100 {
//!     let scene = strategy::scene_recipe().new_tree(&mut runner).unwrap().current().build();
//!     assert!(scene.check().is_empty());
//!     std::fs::write(format!("/tmp/scene_{i}.xml"), scene.to_xml_string().unwrap()).unwrap();
//! }
//! # }
//! ```
//!
//! Undo after any edit sequence gives back the first version: the versions are
//! values, and the first one is the model the edits started from.
//!
//! ```
//! # #[cfg(feature = "proptest")] {
//! use mjcf::generate::strategy;
//! use proptest::prelude::*;
//!
//! proptest!(ProptestConfig::with_cases(8), |((scene, edits) in strategy::scene_and_edits())| {
//!     let base = scene.build();
//!     let before = base.to_xml_string().unwrap();
//!     let versions = edits.apply(&base);
//!     prop_assert!(versions[0] == base);
//!     for v in &versions {
//!         prop_assert!(v.check().is_empty()); // every version stays valid
//!     }
//!     prop_assert_eq!(versions[0].to_xml_string().unwrap(), before);
//! });
//! # }
//! ```
//!
//! A fuzz target takes the same recipes from bytes (feature `arbitrary`):
//!
//! ```ignore
//! fuzz_target!(|input: (mjcf::generate::ModelRecipe, mjcf::generate::EditRecipe)| {
//!     let versions = input.1.apply(&input.0.build());
//!     assert!(versions.iter().all(|v| v.check().is_empty()));
//! });
//! ```

mod builder;
mod debug;
mod edit;
mod palette;
#[cfg(test)]
mod palette_tests;
mod pick;
mod recipe;
mod repair;
mod simulate;
mod steps;
#[cfg(any(test, feature = "proptest"))]
pub mod strategy;
#[cfg(test)]
mod tests;

pub use palette::{Domain, Length, PaletteEntry, palette, value};
pub use recipe::{
    ActuatorKind, AttrDraw, DefaultTag, Edit, EditRecipe, EqualityKind, FrameJoint, FrameRecipe,
    GeomRecipe, JointKind, MAX_DEPTH, MAX_ELEMENTS, MAX_STEPS, MODEL_WORDS, ModelRecipe, ObjKind,
    Palette, Pick, SensorKind, Settings, Shape, Step, Unit, WORDS, Word,
};
