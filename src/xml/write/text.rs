//! The text as it is written: indentation, line ends, attribute syntax, and escaping
//! as lxml does it (the reference's output). What is written where is decided
//! elsewhere (`super` and its rules); this only spells it.

use std::fmt::Write as _;

use crate::value::{FloatStyle, Value, is_clean};

/// The deepest indentation, in levels (deeper elements are indented as much).
const MAX_INDENT: usize = 100;

/// The output and what spelling it needs.
pub(super) struct Text {
    pub(super) out: String,
    /// A value spelt here first, then escaped into `out` (one buffer for all).
    pub(super) value: String,
    pub(super) style: FloatStyle,
    /// Indent and end lines ([`super::WriteOptions::pretty_print`]).
    pretty: bool,
    /// The first character XML cannot hold: (tag, attribute, character).
    pub(super) bad_char: Option<(&'static str, &'static str, char)>,
}

impl Text {
    pub(super) fn new(style: FloatStyle, pretty: bool) -> Text {
        Text {
            out: String::with_capacity(4096),
            value: String::new(),
            style,
            pretty,
            bad_char: None,
        }
    }

    /// Indents for an element at `depth`.
    #[inline]
    pub(super) fn indent(&mut self, depth: usize) {
        if self.pretty {
            // One copy from a line of spaces (two a level), not one per level.
            const SPACES: &str = match std::str::from_utf8(&[b' '; 2 * MAX_INDENT]) {
                Ok(s) => s,
                Err(_) => "",
            };
            self.out.push_str(&SPACES[..2 * depth.min(MAX_INDENT)]);
        }
    }

    /// Ends a line.
    #[inline]
    pub(super) fn newline(&mut self) {
        if self.pretty {
            self.out.push('\n');
        }
    }

    /// Writes `line` (a tag with nothing to escape) on a line of its own at `depth`.
    pub(super) fn line(&mut self, depth: usize, line: &str) {
        self.indent(depth);
        self.out.push_str(line);
        self.newline();
    }

    /// Appends ` name="v"` for a value with nothing to escape (a number or a schema
    /// keyword), written straight into the output.
    #[inline]
    pub(super) fn plain_attr(&mut self, name: &str, v: &Value) {
        self.out.push(' ');
        self.out.push_str(name);
        self.out.push_str("=\"");
        v.write_plain(&mut self.out, self.style);
        self.out.push('"');
    }

    /// Appends ` name="<escaped self.value>"`.
    #[inline]
    pub(super) fn value_attr(&mut self, tag: &'static str, name: &'static str) {
        let value = std::mem::take(&mut self.value);
        self.parts_attr(tag, name, [&value, ""], false);
        self.value = value;
    }

    /// Appends ` name="<escaped parts[0] + parts[1]>"` (a prefix and a name, escaped
    /// one after the other: escaping goes character by character) and records the
    /// first character XML cannot hold. `first_clean`: `parts[0]` is known to need no
    /// escaping (a scope prefix, checked once per instance).
    #[inline]
    pub(super) fn parts_attr(
        &mut self,
        tag: &'static str,
        name: &'static str,
        parts: [&str; 2],
        first_clean: bool,
    ) {
        let out = &mut self.out;
        out.reserve(name.len() + parts[0].len() + parts[1].len() + 4);
        out.push(' ');
        out.push_str(name);
        out.push_str("=\"");
        for (k, p) in parts.into_iter().enumerate() {
            if k == 0 && first_clean {
                out.push_str(p);
            } else if let Some(c) = escape_into(out, p) {
                self.bad_char.get_or_insert((tag, name, c));
            }
        }
        out.push('"');
    }
}

/// Escapes an attribute value as lxml does: `& < > "` as entities, tab, newline and
/// carriage return as character references, and every non-ASCII character as a
/// numeric character reference.
///
/// Returns the first character that XML 1.0 cannot hold at all (most control
/// characters, U+FFFE, U+FFFF), if any; it is written as a reference all the same.
pub(crate) fn escape_into(out: &mut String, s: &str) -> Option<char> {
    if is_clean(s.as_bytes()) {
        out.push_str(s);
        return None;
    }
    let bad = s.chars().find(|c| !crate::value::is_xml_char(*c));
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            ' '..='~' => out.push(c),
            _ => {
                let _ = write!(out, "&#{};", c as u32);
            }
        }
    }
    bad
}
