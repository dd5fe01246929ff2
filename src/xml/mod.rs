//! MJCF text: reading and writing.

mod export;
mod read;
mod write;

pub use read::ReadOptions;
pub(crate) use write::frame_keeps_bodies_top_level;
pub use write::{WriteOptions, Written, WrittenElement};
