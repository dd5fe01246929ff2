//! Where each element was written ([`Model::to_xml_written`]): the map from what a
//! consumer of the text (MuJoCo's compiler) reports back, by line, to the element of
//! the model.

use std::sync::Arc;

use crate::error::WriteError;
use crate::model::Model;
use crate::model::tree::{ElementId, Node};

use super::WriteOptions;

/// Where an element's start tag begins: byte offset, locator, tag.
pub(super) type Mark = (usize, crate::Loc, &'static str);

/// A [`Mark`] as the writer takes it: the frames leading to the element's model and
/// the node, made a locator at the end ([`located`]).
pub(super) type RawMark<'a> = (usize, Arc<[ElementId]>, &'a Node, &'static str);

/// The writer's marks as locators in `model`.
pub(super) fn located(model: &Model, marks: Vec<RawMark<'_>>) -> Vec<Mark> {
    marks
        .into_iter()
        .map(|(offset, frames, node, tag)| {
            (offset, crate::Loc::scoped(frames, node.id(), model.name()), tag)
        })
        .collect()
}

/// MJCF text and where each element of the model was written in it, from
/// [`Model::to_xml_written`].
#[derive(Clone, Debug)]
pub struct Written {
    xml: String,
    elements: Vec<WrittenElement>,
}

/// Where one element was written (see [`Written`]).
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct WrittenElement {
    /// The element's locator in the model written.
    pub loc: crate::Loc,
    /// The tag it was written with: its element's, or for an attachment frame `body`,
    /// or `frame` where it is written as MuJoCo's `<frame>` (decision D10), which
    /// MuJoCo's compiled model keeps no record of.
    pub tag: &'static str,
    /// The line its start tag begins on (1 for the first).
    pub line: usize,
    /// The byte offset of its `<`.
    pub offset: usize,
}

impl Model {
    /// Writes the model as [`Model::to_xml_string_with`] does, and tells where each
    /// element was written: its locator, its tag, and its line and byte offset in the
    /// text. This is the map from what a consumer of the text (MuJoCo's compiler)
    /// reports back, by line, to the element of the model.
    ///
    /// Time: as [`Model::to_xml_string_with`], plus O(E) for the E elements written.
    ///
    /// # Errors
    /// As [`Model::to_xml_string_with`].
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, WriteOptions, element};
    /// let mut m = Model::new("m");
    /// let torso = m.add_mut(&m.worldbody(), element!("body", name = "torso"))?;
    /// let written = m.to_xml_written(&WriteOptions::default())?;
    /// let line = written.elements().iter().find(|e| e.loc == torso).unwrap().line;
    /// assert_eq!(written.xml().lines().nth(line - 1), Some(r#"    <body name="torso"/>"#));
    /// assert_eq!(written.element_at_line(line).map(|e| e.tag), Some("body"));
    /// # Ok::<(), mjcf::Error>(())
    /// ```
    pub fn to_xml_written(&self, options: &WriteOptions) -> Result<Written, WriteError> {
        let (xml, marks) = self.write(options, true)?;
        let mut elements = Vec::with_capacity(marks.len());
        let (mut line, mut scanned) = (1, 0);
        for (offset, loc, tag) in marks {
            line += xml.as_bytes()[scanned..offset].iter().filter(|b| **b == b'\n').count();
            scanned = offset;
            elements.push(WrittenElement { loc, tag, line, offset });
        }
        Ok(Written { xml, elements })
    }
}

impl Written {
    /// The text.
    ///
    /// Time: O(1).
    pub fn xml(&self) -> &str {
        &self.xml
    }

    /// The text, taken out.
    ///
    /// Time: O(1).
    pub fn into_xml(self) -> String {
        self.xml
    }

    /// Every element written, in document order.
    ///
    /// Time: O(1).
    pub fn elements(&self) -> &[WrittenElement] {
        &self.elements
    }

    /// The element whose start tag begins on `line`, when exactly one does (one per
    /// line when pretty-printed).
    ///
    /// Time: O(log E).
    pub fn element_at_line(&self, line: usize) -> Option<&WrittenElement> {
        let from = self.elements.partition_point(|e| e.line < line);
        let to = self.elements.partition_point(|e| e.line <= line);
        (to == from + 1).then(|| &self.elements[from])
    }
}
