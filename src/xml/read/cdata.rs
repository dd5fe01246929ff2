//! The CDATA section of a `<text>` of `<custom>` ([`Role::TextField`]): MuJoCo 4.0.0
//! takes it, as it is, for the text's data, so it is read into `data`. MuJoCo
//! refuses a second section ([`ErrorKind::TextCdataTwice`]) and a section beside a
//! `data` attribute, even an empty one ([`ErrorKind::TextDataTwice`]); CDATA in any
//! other element, and plain text, are ignored (as MuJoCo ignores them).

use std::collections::HashMap;

use quick_xml::events::BytesStart;

use crate::error::{ErrorKind, ReadError};
use crate::model::tree::{Attr, take_attrs};
use crate::schema::{ElementKind, Role};

use super::{Input, Open, Reader, ValueCtx};

/// What the tag of a `<text>` being read gave: whether it has a `data` attribute, and
/// whether a CDATA section was read into it.
#[derive(Clone, Copy, Default)]
pub(super) struct TextField {
    attribute: bool,
    cdata: bool,
}

/// The `<text>`s read, by arena entry.
#[derive(Default)]
pub(super) struct TextFields(HashMap<usize, TextField>);

impl TextFields {
    /// Notes the text field at arena entry `entry`, read from `tag`.
    ///
    /// Time: O(attributes of the tag).
    pub(super) fn opened(&mut self, entry: usize, tag: &BytesStart<'_>) {
        let attribute = tag.attributes().flatten().any(|a| a.key.as_ref() == "data");
        self.0.insert(entry, TextField { attribute, cdata: false });
    }

    /// Whether a CDATA section inside the element at arena entry `entry`, of kind
    /// `kind`, is its data: a text field's first section (MuJoCo refuses a second,
    /// and one beside a `data` attribute); any other element's is ignored.
    fn takes(&mut self, entry: usize, kind: ElementKind) -> Result<bool, ErrorKind> {
        if !kind.is(Role::TextField) {
            return Ok(false);
        }
        let field = self.0.entry(entry).or_default();
        if field.cdata {
            return Err(ErrorKind::TextCdataTwice);
        }
        if field.attribute {
            return Err(ErrorKind::TextDataTwice);
        }
        field.cdata = true;
        Ok(true)
    }
}

/// Reads the CDATA section `text` (at `offset`) inside the open element `open`: a
/// text field's data, read as its `data` attribute is (an empty section leaves it
/// without data, which MuJoCo refuses as an empty text: `check()` says so).
pub(super) fn read(
    r: &mut Reader<'_>,
    open: Option<&Open>,
    text: &str,
    offset: usize,
) -> Result<(), ReadError> {
    let Some(entry) = open.map(|o| o.entry).filter(|e| *e != usize::MAX) else { return Ok(()) };
    let kind = r.arena[entry].kind;
    if !r.text_fields.takes(entry, kind).map_err(|k| r.err(k, offset))? {
        return Ok(());
    }
    let Some(index) = kind.attr_index("data") else { return Ok(()) };
    let ctx = ValueCtx { files: &r.ctx, basepaths: &r.basepaths, model_files: r.model_files };
    let value =
        ctx.assign_at(kind, index, Some(Input::Text(text))).map_err(|k| r.err(k, offset))?;
    let mut attrs: Vec<Attr> = r.arena[entry].attrs.iter().cloned().collect();
    let i = index as u16;
    attrs.retain(|(k, _)| *k != i);
    if let Some(v) = value {
        attrs.push((i, v));
        attrs.sort_unstable_by_key(|(k, _)| *k);
    }
    r.arena[entry].attrs = take_attrs(&mut attrs);
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::error::ErrorKind;
    use crate::model::Model;

    fn custom(text: &str) -> String {
        format!("<mujoco><custom>{text}</custom></mujoco>")
    }

    /// MuJoCo 4.0.0 reads this text's data as `" a\n b&amp;<x> "` (the section's
    /// characters as they are), and the written `data` attribute as the same.
    #[test]
    fn a_text_s_cdata_is_its_data_as_it_is() {
        let text = "<text name=\"t\">\n <![CDATA[ a\n b&amp;<x> ]]> </text>";
        let m = Model::from_xml_str(&custom(text)).unwrap();
        let xml = m.to_xml_string().unwrap();
        assert!(xml.contains(r#"<text name="t" data=" a&#10; b&amp;amp;&lt;x&gt; "/>"#), "{xml}");
        // CDATA elsewhere is ignored, as MuJoCo ignores it.
        let m = Model::from_xml_str("<mujoco><worldbody><![CDATA[x]]></worldbody></mujoco>");
        assert!(m.is_ok());
    }

    /// Each refused by MuJoCo 4.0.0 with the message the error quotes.
    #[test]
    fn a_second_cdata_section_or_one_beside_data_is_refused_where_it_is() {
        let cases = [
            (r#"<text name="t"><![CDATA[a]]><![CDATA[b]]></text>"#, ErrorKind::TextCdataTwice, 45),
            (r#"<text name="t"><![CDATA[a]]>x<![CDATA[b]]></text>"#, ErrorKind::TextCdataTwice, 46),
            (r#"<text name="t" data="a"><![CDATA[b]]></text>"#, ErrorKind::TextDataTwice, 41),
            (r#"<text name="t" data=""><![CDATA[b]]></text>"#, ErrorKind::TextDataTwice, 40),
        ];
        for (text, kind, column) in cases {
            let e = Model::from_xml_str(&custom(text)).unwrap_err();
            assert_eq!(e.kind(), &kind, "{text}");
            assert_eq!(e.pos().map(|p| (p.line, p.column)), Some((1, column)), "{text}");
        }
        let e = ErrorKind::TextCdataTwice.to_string();
        assert!(e.contains("text field cannot have multiple CDATA sections"), "{e}");
        let e = ErrorKind::TextDataTwice.to_string();
        assert!(
            e.contains("text field data cannot be specified as both attribute and CDATA"),
            "{e}"
        );
    }
}
