//! MJCF text: reading and writing.

mod export;
mod open;
mod read;
pub(crate) mod rules;
mod save;
mod scene;
mod source;
mod write;

pub use read::ReadOptions;
pub(crate) use rules::{FrameTags, frame_keeps_bodies_top_level};
pub use save::{SaveError, SaveOptions, SourceText};
pub use scene::{SavedScene, Scene, ScenePart};
pub use write::{WriteOptions, Written, WrittenElement};
