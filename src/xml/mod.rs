//! MJCF text: reading and writing.

mod export;
mod read;
mod write;

pub use read::ReadOptions;
pub use write::{WriteOptions, Written, WrittenElement};
