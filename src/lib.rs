#![forbid(unsafe_code)]
mod schema;
pub use schema::*;
