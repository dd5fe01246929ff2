//! The source a model was read from: the text of every file read (the main file and
//! its `<include>`s) and, for each element read, where its tags are in that text.
//!
//! Kept by the reader in the model ([`Model`]'s `source`; the reader, `xml::read`,
//! builds it with `xml::source::SourceBuilder`), used by the lossless writer
//! (`xml::save`). The data lives here so that the model holds it without naming `xml`. Formatting is not content: a model's equality, hash and diff
//! never look at it.
//!
//! What is recorded, per tag read (a [`Record`]): the file, the byte spans of its
//! start tag and end tag (the end tag's span is empty for `<x/>`), its parent tag in
//! that file and the model element it became. The text between recorded spans
//! (whitespace, comments, processing instructions, a DOCTYPE) is not stored apart:
//! it is what lies between them. Attributes are tokenized again from the start tag
//! when needed. One model element can have several records: a singleton given twice
//! (`<asset>` in the main file and in an include), or the root class of a file written
//! as `<default><default class="/">` (both tags are the root class).
//!
//! The model as read is kept too ([`Source::read`]): a node of a later version still
//! pointer-equal to the node read is, with its whole subtree, unchanged.

use std::path::PathBuf;
use std::sync::Arc;

use crate::files::write::Fingerprint;
use crate::model::Model;
use crate::model::tree::ElementId;

/// No record (the end of a list, or no parent).
pub(crate) const NO_RECORD: u32 = u32::MAX;

/// What a recorded tag is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum RecordKind {
    /// An element: its attributes are the model element's.
    Element,
    /// The root of an included file: it stands for the element it is included in (the
    /// model's root, or the element holding an `<include>`), and supplies no attribute.
    FileRoot,
    /// An `<include>` tag (its content, if any, is ignored): kept as it is.
    Include,
}

/// One tag read, and where it is.
#[derive(Clone, Debug)]
pub(crate) struct Record {
    /// The model element it became (for an `Include`, the element holding it).
    pub(crate) id: ElementId,
    pub(crate) kind: RecordKind,
    /// Index into [`Source::files`].
    pub(crate) file: u32,
    /// The parent tag in the same file, or [`NO_RECORD`] for a file's root.
    pub(crate) parent: u32,
    /// The first child tag and the next sibling, in document order.
    pub(crate) first_child: u32,
    pub(crate) next_sibling: u32,
    /// Byte offsets into the file's whole text as read (a byte-order mark starting it
    /// counts; line endings are as written): the start tag is `start..start_end`, the
    /// end tag `end..end_end` (`start_end == end == end_end` for `<x/>`).
    pub(crate) start: u32,
    pub(crate) start_end: u32,
    pub(crate) end: u32,
    pub(crate) end_end: u32,
}

impl Record {
    /// Whether the tag is written `<x/>` (no end tag).
    pub(crate) fn self_closing(&self) -> bool {
        self.end == self.end_end
    }
}

/// One file read.
#[derive(Clone, Debug)]
pub(crate) struct SourceFile {
    /// The path relative to the model's folder (`None`: the main text, read from a
    /// string).
    pub(crate) rel: Option<PathBuf>,
    /// The path as read (joined with the folder of the file that includes it), to
    /// write it back in place; `None` for text not read from disk.
    pub(crate) disk: Option<PathBuf>,
    /// What the file on disk held when it was read, so that a save can tell whether
    /// another program changed it since.
    pub(crate) read: Option<Fingerprint>,
    pub(crate) text: Arc<str>,
    /// The file's root tag.
    pub(crate) root: u32,
}

/// The source of a model read: see the module documentation.
#[derive(Clone)]
pub(crate) struct Source {
    pub(crate) files: Vec<SourceFile>,
    /// In document order (an include's tags where the include is).
    pub(crate) records: Vec<Record>,
    /// The records sorted by element, then document order: the records of an element
    /// are one run (4 bytes a tag, the element read from its record). Empty when the
    /// records themselves are in element order, as they are in most texts (ids are
    /// handed out as tags are read; includes and reopened attachments can break it).
    by_id: Vec<u32>,
    /// The model as read (without a source of its own).
    pub(crate) read: Model,
    /// The model as the text spells it, before the reader reopened its `<attach>`es
    /// as attachments (`xml::scene::reopen`); `None` when nothing reopened (then it is
    /// `read`). Shares every subtree but the paths to the reopened frames with `read`.
    pub(crate) literal: Option<Model>,
}

impl Source {
    /// The source of the model `read`, from its files and its records in document
    /// order; `literal`: the model before reopening, if it differs.
    ///
    /// Time: O(r log r) for `r` records.
    pub(crate) fn new(
        files: Vec<SourceFile>,
        records: Vec<Record>,
        read: Model,
        literal: Option<Model>,
    ) -> Source {
        let mut records = records;
        records.shrink_to_fit();
        let by_id = if records.is_sorted_by_key(|r| r.id) {
            Vec::new()
        } else {
            let mut by_id: Vec<u32> = (0..records.len() as u32).collect();
            // Mostly in id order already: the sort finds the runs.
            by_id.sort_unstable_by_key(|&r| (records[r as usize].id, r));
            by_id
        };
        Source { files, records, by_id, read, literal }
    }

    /// The model as its text spells it: [`Source::literal`] if the reader reopened
    /// attachments, else the model as read.
    ///
    /// Time: O(1).
    pub(crate) fn spelled(&self) -> &Model {
        self.literal.as_ref().unwrap_or(&self.read)
    }

    /// The records of the model element `id`, in document order.
    ///
    /// Time: O(log n).
    pub(crate) fn records_of(&self, id: ElementId) -> impl Iterator<Item = u32> + '_ {
        let id_of = |r: &u32| self.records[*r as usize].id;
        // Records in element order are their own list (`by_id` is empty then).
        let in_order = self.by_id.is_empty().then(|| {
            let from = self.records.partition_point(|r| r.id < id);
            let to = from + self.records[from..].iter().take_while(|r| r.id == id).count();
            from as u32..to as u32
        });
        let sorted = (!self.by_id.is_empty()).then(|| {
            let from = self.by_id.partition_point(|r| id_of(r) < id);
            self.by_id[from..].iter().take_while(move |r| id_of(r) == id).copied()
        });
        in_order.into_iter().flatten().chain(sorted.into_iter().flatten())
    }

    /// The record new children of `id` are written under: its first element record
    /// in document order that no other record of `id` is inside (for the root class
    /// written `<default><default class="/">`, the inner tag).
    pub(crate) fn primary(&self, id: ElementId) -> Option<u32> {
        let mut found = None;
        for r in self.records_of(id) {
            let rec = &self.records[r as usize];
            if rec.kind == RecordKind::Include {
                continue;
            }
            let wraps = self.children(r).any(|c| {
                let c = &self.records[c as usize];
                c.id == id && c.kind == RecordKind::Element
            });
            if !wraps && (found.is_none() || rec.kind == RecordKind::Element) {
                if rec.kind == RecordKind::Element {
                    return Some(r);
                }
                found.get_or_insert(r);
            }
        }
        found
    }

    /// The child records of `r`, in document order.
    pub(crate) fn children(&self, r: u32) -> impl Iterator<Item = u32> + '_ {
        let first = self.records[r as usize].first_child;
        std::iter::successors(Some(first).filter(|&c| c != NO_RECORD), move |&c| {
            Some(self.records[c as usize].next_sibling).filter(|&n| n != NO_RECORD)
        })
    }

    /// The text of the file of `r`.
    pub(crate) fn text_of(&self, r: u32) -> &str {
        &self.files[self.records[r as usize].file as usize].text
    }

    /// Heap bytes held besides the model as read: the texts and the records.
    ///
    /// Time: O(files).
    pub(crate) fn heap_bytes(&self) -> usize {
        self.files.iter().map(|f| f.text.len()).sum::<usize>()
            + self.records.capacity() * std::mem::size_of::<Record>()
            + self.by_id.capacity() * std::mem::size_of::<u32>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The manual (`src/guide.md`, saving) states the cost per tag: a record, and a
    /// by-element entry where the records are not in element order.
    #[test]
    fn a_tag_costs_48_or_52_bytes() {
        assert_eq!(std::mem::size_of::<Record>(), 48);
        assert_eq!(std::mem::size_of::<Record>() + std::mem::size_of::<u32>(), 52);
    }

    /// A text read in order keeps no by-element list; one whose records are out of
    /// element order does; both find every element's records.
    #[test]
    fn records_are_found_with_and_without_a_by_element_list() {
        let xml =
            r#"<mujoco><worldbody><body name="a"><geom size="1"/></body></worldbody></mujoco>"#;
        let m = Model::from_xml_str(xml).unwrap();
        let src = m.side.source.as_ref().expect("a source");
        assert!(src.by_id.is_empty());
        let mut shuffled = (**src).clone();
        shuffled.records.reverse();
        let rebuilt = Source::new(shuffled.files, shuffled.records, shuffled.read, None);
        assert!(!rebuilt.by_id.is_empty());
        for (i, rec) in src.records.iter().enumerate() {
            let found: Vec<u32> = src.records_of(rec.id).collect();
            assert!(found.contains(&(i as u32)), "record {i} of its element");
            let again: Vec<u32> = rebuilt.records_of(rec.id).collect();
            let n = src.records.len() as u32;
            // Reversed: record i is at n - 1 - i.
            assert!(again.contains(&(n - 1 - i as u32)), "record {i} reversed");
            assert_eq!(found.len(), again.len());
        }
    }
}
