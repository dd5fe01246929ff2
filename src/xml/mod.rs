//! MJCF text: reading and writing.

mod export;
mod open;
mod read;
mod save;
mod scene;
mod source;
mod write;

pub use read::ReadOptions;
pub use save::{SaveError, SaveOptions, SourceText};
pub use scene::{SavedScene, Scene, ScenePart};
pub(crate) use write::policy::{FrameTags, frame_keeps_bodies_top_level};
pub use write::{WriteOptions, Written, WrittenElement};
