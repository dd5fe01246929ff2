//! Start tags as text: their attributes tokenized, and rewritten with some values
//! changed, some removed and some appended, everything else kept as written.

/// One attribute of a start tag, by byte offsets into the tag's text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Token {
    /// Where the whitespace before the name starts.
    pub(crate) lead: usize,
    pub(crate) name: (usize, usize),
    /// The value, inside its quotes.
    pub(crate) value: (usize, usize),
    pub(crate) quote: u8,
}

/// A start tag's name and attributes (the text was checked by the XML reader; on
/// text that is not a start tag the tokens found so far are returned).
pub(crate) struct Tag<'t> {
    pub(crate) text: &'t str,
    pub(crate) name: (usize, usize),
    pub(crate) tokens: Vec<Token>,
    /// Just after the last attribute (or the name): where appended ones go.
    pub(crate) end: usize,
}

impl<'t> Tag<'t> {
    /// Tokenizes `text`, a start tag (`<geom name="a" pos='0 0 .5'/>`).
    ///
    /// Time: O(length of `text`).
    pub(crate) fn parse(text: &'t str) -> Tag<'t> {
        let b = text.as_bytes();
        let ws = |c: u8| matches!(c, b' ' | b'\t' | b'\n' | b'\r');
        let mut i = usize::from(b.first() == Some(&b'<'));
        let name_start = i;
        while i < b.len() && !ws(b[i]) && b[i] != b'/' && b[i] != b'>' {
            i += 1;
        }
        let mut tag = Tag { text, name: (name_start, i), tokens: Vec::new(), end: i };
        loop {
            let lead = i;
            while i < b.len() && ws(b[i]) {
                i += 1;
            }
            if i >= b.len() || b[i] == b'/' || b[i] == b'>' {
                return tag;
            }
            let n0 = i;
            while i < b.len() && b[i] != b'=' && !ws(b[i]) {
                i += 1;
            }
            let n1 = i;
            while i < b.len() && (ws(b[i]) || b[i] == b'=') {
                i += 1;
            }
            let Some(&quote) = b.get(i) else { return tag };
            if quote != b'"' && quote != b'\'' {
                return tag;
            }
            let v0 = i + 1;
            let Some(len) = b[v0..].iter().position(|&c| c == quote) else { return tag };
            i = v0 + len + 1;
            tag.tokens.push(Token { lead, name: (n0, n1), value: (v0, v0 + len), quote });
            tag.end = i;
        }
    }

    /// The tag name.
    pub(crate) fn tag_name(&self) -> &'t str {
        &self.text[self.name.0..self.name.1]
    }

    /// The name of an attribute.
    pub(crate) fn name_of(&self, t: &Token) -> &'t str {
        &self.text[t.name.0..t.name.1]
    }

    /// The tag rewritten: the attribute tokens at the positions of `set` get the
    /// new values (already escaped for their quote by `escape`), those in `remove`
    /// go with the whitespace before them, `append` (name, value) are added after
    /// the last attribute with double quotes, and, with `open`, a `<x/>` becomes
    /// `<x>`.
    pub(crate) fn rewrite(
        &self,
        set: &[(usize, String)],
        remove: &[usize],
        append: &[(&str, String)],
        open: bool,
    ) -> String {
        let mut out = String::with_capacity(self.text.len() + 32);
        let mut at = 0;
        for (k, t) in self.tokens.iter().enumerate() {
            if remove.contains(&k) {
                // With the whitespace before it, unless another attribute follows it
                // without any (`a="1"b="2"`): then the whitespace separates that one.
                let next = self.text.as_bytes().get(t.value.1 + 1);
                let glued =
                    next.is_some_and(|c| !matches!(c, b' ' | b'\t' | b'\n' | b'\r' | b'/' | b'>'));
                out.push_str(&self.text[at..if glued { t.name.0 } else { t.lead }]);
                at = t.value.1 + 1;
            } else if let Some((_, v)) = set.iter().find(|(j, _)| *j == k) {
                out.push_str(&self.text[at..t.value.0]);
                out.push_str(&escape(v, t.quote));
                at = t.value.1;
            }
        }
        out.push_str(&self.text[at..self.end.max(at)]);
        for (name, v) in append {
            out.push(' ');
            out.push_str(name);
            out.push_str("=\"");
            out.push_str(&escape(v, b'"'));
            out.push('"');
        }
        let tail = &self.text[self.end.max(at)..];
        match tail.strip_suffix("/>") {
            Some(before) if open => {
                out.push_str(before.trim_end());
                out.push('>');
            }
            _ => out.push_str(tail),
        }
        out
    }
}

/// An attribute value escaped for a value in `quote`s: as the plain writer escapes
/// (`& < > "` as entities, tab, newline, carriage return and non-ASCII characters
/// as character references), and `'` as `&apos;` inside single quotes.
pub(crate) fn escape(v: &str, quote: u8) -> String {
    let mut out = String::with_capacity(v.len());
    // Characters XML cannot hold were refused when the values were set.
    let _ = crate::xml::write::text::escape_into(&mut out, v);
    if quote == b'\'' && out.contains('\'') {
        out = out.replace('\'', "&apos;");
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn attributes_are_found_with_their_quotes_and_spacing() {
        let t = Tag::parse("<geom name=\"a\"\n   pos='0 0 .5' size = \"1\"/>");
        assert_eq!(t.tag_name(), "geom");
        let names: Vec<&str> = t.tokens.iter().map(|k| t.name_of(k)).collect();
        assert_eq!(names, ["name", "pos", "size"]);
        assert_eq!(t.tokens[1].quote, b'\'');
        assert_eq!(&t.text[t.tokens[1].value.0..t.tokens[1].value.1], "0 0 .5");
        assert_eq!(&t.text[t.end..], "/>");
    }

    #[test]
    fn a_rewrite_changes_only_what_it_is_given() {
        let t = Tag::parse("<geom name=\"a\"\n   pos='0 0 .5'  size=\"1\" />");
        assert_eq!(t.rewrite(&[], &[], &[], false), t.text);
        let s = t.rewrite(&[(1, "1 2 3".into())], &[2], &[("rgba", "1 0 0 1".into())], false);
        assert_eq!(s, "<geom name=\"a\"\n   pos='1 2 3' rgba=\"1 0 0 1\" />");
        let s = t.rewrite(&[], &[0], &[], true);
        assert_eq!(s, "<geom\n   pos='0 0 .5'  size=\"1\">");
    }

    /// An attribute removed from before another written without whitespace between
    /// them leaves the whitespace before it, so that the next one stays apart from
    /// the tag name (found by the `lossless` fuzz target).
    #[test]
    fn a_removed_attribute_glued_to_the_next_leaves_its_whitespace() {
        let t = Tag::parse("<body name=\"b \"pos=\"0 0 1\"\tmass='1'/>");
        assert_eq!(t.rewrite(&[], &[0], &[], false), "<body pos=\"0 0 1\"\tmass='1'/>");
        assert_eq!(t.rewrite(&[], &[1], &[], false), "<body name=\"b \"\tmass='1'/>");
        assert_eq!(t.rewrite(&[], &[0, 1], &[], false), "<body \tmass='1'/>");
        assert_eq!(t.rewrite(&[], &[2], &[], true), "<body name=\"b \"pos=\"0 0 1\">");
    }

    #[test]
    fn values_are_escaped_for_their_quote() {
        assert_eq!(escape("a'b\"c&", b'\''), "a&apos;b&quot;c&amp;");
        assert_eq!(escape("a'b", b'"'), "a'b");
    }
}
