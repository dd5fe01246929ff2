//! Text helpers shared by the round-trip tests (`tests/corpus.rs`,
//! `tests/properties.rs`); include with `#[path = "support/text.rs"] mod text;`.

/// The text with the top-level `<default>…</default>` block (two-space indented, as
/// pretty printing writes it) replaced by what reading and writing it again gives:
/// the written root class `<default class="R">` is read as a class nested in an
/// unnamed root class, which is written as `<default class="/">`.
pub(crate) fn rewrapped_root_default(text: &str) -> String {
    let mut out = String::new();
    let mut inside = false;
    for line in text.lines() {
        match (inside, line) {
            (false, "  <default>") => {
                inside = true;
                out.push_str("  <default>\n    <default class=\"/\">\n");
            }
            (true, "  </default>") => {
                inside = false;
                out.push_str("    </default>\n  </default>\n");
            }
            (true, l) => {
                out.push_str("  ");
                out.push_str(l);
                out.push('\n');
            }
            (false, l) => {
                out.push_str(l);
                out.push('\n');
            }
        }
    }
    out
}
