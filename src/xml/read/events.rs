//! The XML events of one file's text, with every position a byte offset into that
//! whole text: the offsets the source records (`xml::source`) and errors report.
//!
//! quick-xml drops a leading byte-order mark before it reads, and counts its
//! positions from after it; every position read through [`Events`] adds it back, so
//! that no caller measures in the text quick-xml saw instead of the text kept.

use quick_xml::events::Event;

/// The UTF-8 byte-order mark (U+FEFF), as quick-xml drops it at the start of its input.
const BOM: &str = "\u{feff}";

/// quick-xml's reader over a file's text, its positions in that text (see the module
/// documentation).
pub(super) struct Events<'t> {
    xml: quick_xml::Reader<&'t [u8]>,
    /// How many bytes quick-xml drops before its position 0 (a byte-order mark's 3,
    /// or 0): it drops one mark, once, at the start of what it is given.
    skipped: usize,
}

impl<'t> Events<'t> {
    /// The events of `text`.
    ///
    /// Time: O(1).
    pub(super) fn new(text: &'t str) -> Events<'t> {
        let skipped = if text.starts_with(BOM) { BOM.len() } else { 0 };
        Events { xml: quick_xml::Reader::from_str(text), skipped }
    }

    /// The next event.
    ///
    /// Time: O(length of the event's text).
    pub(super) fn read_event(&mut self) -> Result<Event<'t>, quick_xml::Error> {
        self.xml.read_event()
    }

    /// The offset in the text just after the last event read (before the first one:
    /// where the document starts, after a byte-order mark).
    ///
    /// Time: O(1).
    pub(super) fn position(&self) -> usize {
        self.skipped + self.xml.buffer_position() as usize
    }

    /// The offset in the text of the last error.
    ///
    /// Time: O(1).
    pub(super) fn error_position(&self) -> usize {
        self.skipped + self.xml.error_position() as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The offset of every start tag, as (tag name, offset): what the source records.
    fn starts(text: &str) -> Vec<(String, usize)> {
        let mut ev = Events::new(text);
        let mut out = Vec::new();
        loop {
            let at = ev.position();
            match ev.read_event().unwrap() {
                Event::Start(t) | Event::Empty(t) => {
                    let qname = t.name();
                    let name: &str = qname.as_ref();
                    out.push((name.to_string(), at));
                }
                Event::Eof => return out,
                _ => {}
            }
        }
    }

    #[test]
    fn positions_after_a_byte_order_mark_count_the_mark() {
        for prefix in ["", BOM, "\u{feff}<?xml version=\"1.0\"?>\r\n<!-- é -->\r"] {
            let text = format!("{prefix}<mujoco>\n\t<worldbody/></mujoco>");
            let found = starts(&text);
            let want: Vec<(String, usize)> = ["mujoco", "worldbody"]
                .iter()
                .map(|n| (n.to_string(), text.find(&format!("<{n}")).unwrap()))
                .collect();
            assert_eq!(found, want, "{text:?}");
        }
    }

    #[test]
    fn a_second_byte_order_mark_is_text_at_its_own_offset() {
        let text = "\u{feff}\u{feff}<mujoco/>";
        let mut ev = Events::new(text);
        assert_eq!(ev.position(), 3);
        assert!(matches!(ev.read_event().unwrap(), Event::Text(_)));
        assert_eq!(ev.position(), 6);
        assert!(matches!(ev.read_event().unwrap(), Event::Empty(_)));
        assert_eq!(ev.position(), text.len());
    }

    /// The position of the first error, if any.
    fn error_at(text: &str) -> Option<usize> {
        let mut ev = Events::new(text);
        loop {
            match ev.read_event() {
                Err(_) => return Some(ev.error_position()),
                Ok(Event::Eof) => return None,
                Ok(_) => {}
            }
        }
    }

    #[test]
    fn error_positions_count_the_mark() {
        let text = "<mujoco>\n  <worldbody></body>";
        let plain = error_at(text).unwrap();
        assert!(plain > text.find("<worldbody>").unwrap(), "{plain}");
        assert_eq!(error_at(&format!("{BOM}{text}")), Some(BOM.len() + plain));
    }
}
