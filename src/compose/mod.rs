//! Composition of models: attach, detach, scope renames and `include_copy`. The rules
//! they rely on (frames, scopes, merged settings) belong to the model, in `model/`.

pub(crate) mod angles;
mod attach;
mod include;
mod part;

pub use part::Part;
