//! Recording the source while reading (`model::source` holds the data the model keeps).

use std::path::PathBuf;
use std::sync::Arc;

use crate::files::write::Fingerprint;
use crate::model::Model;
use crate::model::tree::ElementId;

pub(crate) use crate::model::source::{NO_RECORD, RecordKind, Source};
use crate::model::source::{Record, SourceFile};

/// The source being recorded while reading.
#[derive(Default)]
pub(crate) struct SourceBuilder {
    pub(crate) files: Vec<SourceFile>,
    pub(crate) records: Vec<Record>,
    /// Each record's last child so far.
    last_child: Vec<u32>,
    /// The main model before reopening, when reopening changed it ([`Source::literal`]).
    pub(crate) literal: Option<Model>,
}

impl SourceBuilder {
    /// Adds a file; returns its index, or `None` when its text is too long to be
    /// recorded (over 4 GiB: no source is kept then).
    pub(crate) fn file(
        &mut self,
        rel: Option<PathBuf>,
        disk: Option<PathBuf>,
        read: Option<Fingerprint>,
        text: &str,
    ) -> Option<u32> {
        u32::try_from(text.len()).ok()?;
        let i = u32::try_from(self.files.len()).ok()?;
        // Room for the records of a text of about 40 bytes a tag, or fewer tags (given
        // back at the end): grown by doubling from empty, the records were copied once
        // more in all (a megabyte for a 10,000-body tree).
        self.records.reserve(text.len() / 40);
        self.files.push(SourceFile { rel, disk, read, text: Arc::from(text), root: NO_RECORD });
        Some(i)
    }

    /// Records a tag whose start tag is `start..start_end` in `file`, under `parent`;
    /// returns its index. The end tag is set by [`SourceBuilder::close`].
    pub(crate) fn open(
        &mut self,
        file: u32,
        kind: RecordKind,
        id: ElementId,
        parent: u32,
        start: usize,
        start_end: usize,
    ) -> u32 {
        debug_assert!(self.is_tag(file, start, start_end), "start tag at {start}..{start_end}");
        let i = self.records.len() as u32;
        // The file's length fits in u32 (`SourceBuilder::file`), so offsets do.
        let (start, start_end) = (start as u32, start_end as u32);
        self.records.push(Record {
            id,
            kind,
            file,
            parent,
            first_child: NO_RECORD,
            next_sibling: NO_RECORD,
            start,
            start_end,
            end: start_end,
            end_end: start_end,
        });
        self.last_child.push(NO_RECORD);
        if parent == NO_RECORD {
            if let Some(f) = self.files.get_mut(file as usize) {
                f.root = i;
            }
        } else {
            match self.last_child[parent as usize] {
                NO_RECORD => self.records[parent as usize].first_child = i,
                p => self.records[p as usize].next_sibling = i,
            }
            self.last_child[parent as usize] = i;
        }
        i
    }

    /// Sets the end tag span of the record `r`.
    pub(crate) fn close(&mut self, r: u32, end: usize, end_end: usize) {
        if let Some(rec) = self.records.get_mut(r as usize) {
            debug_assert!(
                self.files.get(rec.file as usize).is_none_or(|f| f.text[end..].starts_with("</")),
                "end tag at {end}..{end_end}"
            );
            rec.end = end as u32;
            rec.end_end = end_end as u32;
        }
    }

    /// Whether `start..end` of `file` is a tag as read (`<` to `>`): the offsets are
    /// into the whole text, a byte-order mark included (checked in debug builds).
    fn is_tag(&self, file: u32, start: usize, end: usize) -> bool {
        self.files.get(file as usize).is_none_or(|f| {
            let b = f.text.as_bytes();
            b.get(start) == Some(&b'<') && end > start && b.get(end - 1) == Some(&b'>')
        })
    }

    /// Gives every record from `from` on whose element is a key of `ids` the element
    /// it maps to (an include merged into the model: its elements are copies).
    pub(crate) fn remap(
        &mut self,
        from: usize,
        ids: &std::collections::HashMap<ElementId, ElementId>,
    ) {
        for r in self.records.iter_mut().skip(from) {
            if let Some(new) = ids.get(&r.id) {
                r.id = *new;
            }
        }
    }

    /// The source, for the model `read` as read.
    pub(crate) fn finish(self, read: Model) -> Source {
        Source::new(self.files, self.records, read, self.literal)
    }
}
