//! MJCF text: reading and writing.

mod export;
mod read;
mod save;
mod source;
mod write;

pub(crate) use read::scan;
pub(crate) use source::Source;

pub use read::ReadOptions;
pub use save::{SaveError, SourceText};
pub(crate) use write::policy::frame_keeps_bodies_top_level;
pub use write::{WriteOptions, Written, WrittenElement};
