//! The options of writing a model as MJCF ([`WriteOptions`]): a leaf module, so that
//! what reads them beside the writer ([`Model::check_with`](crate::Model::check_with),
//! the composed keyframes of `model::keys`) names no writer.

/// Options for [`Model::to_xml_string_with`](crate::Model::to_xml_string_with).
#[derive(Clone, Debug, PartialEq)]
pub struct WriteOptions {
    /// `None` (the default): floats print as the shortest text that reads back exactly
    /// (`0.1`). `Some(p)`: C `%.{p}g`, as the reference prints them (`Some(17)` gives
    /// its exact output, `0.10000000000000001`).
    pub precision: Option<u32>,
    /// Floats whose magnitude is below this print as `0`.
    pub zero_threshold: f64,
    /// Indent with two spaces per level and end with a newline (default `true`);
    /// otherwise one line. Indentation stops growing at 100 levels, so that the output
    /// of a very deep model stays linear in its size.
    pub pretty_print: bool,
    /// Name files `stem-<sha1>.ext` (default `true`) or `stem.ext`.
    pub filename_with_hash: bool,
    /// Write one key per key name over the whole composed model (default `false`,
    /// as the reference, which keeps each attached model's keys as separate keys that
    /// no longer fit the composed model): the model's key and the attached models'
    /// keys of that name laid out in the composed `qpos`, `qvel`, `act`, `ctrl`,
    /// `mpos` and `mquat` order, MuJoCo's defaults where a model has no key of that
    /// name. Joint types follow default classes; a class's `ref` and activation
    /// settings do not (the element's own are read).
    pub merge_keyframes: bool,
}

impl Default for WriteOptions {
    fn default() -> Self {
        WriteOptions {
            precision: None,
            zero_threshold: 0.0,
            pretty_print: true,
            filename_with_hash: true,
            merge_keyframes: false,
        }
    }
}
