//! Composition of models: attachments, merges and copies.

mod attach;
mod include;
pub(crate) mod settings;

pub(crate) use attach::frame_settable;
