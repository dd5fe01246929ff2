//! Composition of models: attachments, merges and copies.

mod include;
