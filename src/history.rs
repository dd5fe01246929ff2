//! [`History`]: the versions of an editor session, with undo, redo and diffs.

use std::collections::VecDeque;

use crate::model::Model;
use crate::model::diff::Change;

/// The versions of a model an editor keeps: each edit pushes a new version with a
/// label, [`undo`](History::undo) and [`redo`](History::redo) move a cursor, and
/// [`diff`](History::diff) compares any two entries.
///
/// Entries are numbered from 0, the oldest kept. Editing after an undo drops the
/// entries after the cursor (they can no longer be redone), as editors do. With a
/// [`limit`](History::with_limit), pushing beyond it forgets the oldest entry, so
/// every index moves down by one. Versions share what they did not change, so
/// each entry costs about what its edit changed ([`Model`]'s `clone()` is O(1)).
///
/// # Examples
/// ```
/// use mjcf::{History, Model, element};
/// let mut history = History::new(Model::new("arena"));
/// let b = history.edit("add a box", |m| m.add_mut(&m.worldbody(), element!("body", name = "box")))?;
/// history.edit("move it", |m| m.set_attr_mut(&b, "pos", [0, 0, 1]))?;
/// assert!(history.undo());
/// assert_eq!(history.label(history.position()), Some("add a box"));
/// assert!(history.redo());
/// let lines: Vec<String> = history.diff_lines(0, 2).unwrap();
/// assert_eq!(lines, ["+ body box"]);
/// assert_eq!(history.diff_lines(1, 2).unwrap(), ["~ box pos: (unset) -> 0 0 1"]);
/// # Ok::<(), mjcf::EditError>(())
/// ```
#[derive(Clone, Debug)]
pub struct History {
    entries: VecDeque<(String, Model)>,
    cursor: usize,
    limit: usize,
}

impl History {
    /// A history whose only entry is `model`, labelled `"start"`, with no limit.
    ///
    /// Time: O(1).
    pub fn new(model: Model) -> History {
        History::with_limit(model, usize::MAX)
    }

    /// A history that keeps at most `limit` entries (at least 1: a limit of 0 keeps
    /// 1), forgetting the oldest when a push goes beyond it.
    ///
    /// Time: O(1).
    pub fn with_limit(model: Model, limit: usize) -> History {
        History {
            entries: VecDeque::from([("start".to_string(), model)]),
            cursor: 0,
            limit: limit.max(1),
        }
    }

    /// The version at the cursor: the one the next edit starts from.
    ///
    /// Time: O(1).
    pub fn current(&self) -> &Model {
        &self.entries[self.cursor].1
    }

    /// The index of the current entry.
    ///
    /// Time: O(1).
    pub fn position(&self) -> usize {
        self.cursor
    }

    /// The number of entries kept (redoable ones included).
    ///
    /// Time: O(1).
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Always `false`: a history holds at least its current version.
    ///
    /// Time: O(1).
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// The version at `index`, if there is one.
    ///
    /// Time: O(1).
    pub fn get(&self, index: usize) -> Option<&Model> {
        self.entries.get(index).map(|(_, m)| m)
    }

    /// The label the version at `index` was pushed with.
    ///
    /// Time: O(1).
    pub fn label(&self, index: usize) -> Option<&str> {
        self.entries.get(index).map(|(l, _)| l.as_str())
    }

    /// Makes `model` the current version, labelled `label`: the entries after the
    /// cursor are dropped, and with a limit, the oldest entry if there are too many.
    ///
    /// Time: O(1) amortized, plus O(k) to drop k redoable entries.
    pub fn push(&mut self, label: impl Into<String>, model: Model) {
        self.entries.truncate(self.cursor + 1);
        self.entries.push_back((label.into(), model));
        if self.entries.len() > self.limit {
            self.entries.pop_front();
        }
        self.cursor = self.entries.len() - 1;
    }

    /// Applies `change` to a copy of the current version and, if it succeeds, pushes
    /// the result as [`push`](History::push) does and returns what `change` returned
    /// (the locator `add_mut` gives, say). If it fails, the history is unchanged.
    ///
    /// Time: O(1) plus the cost of `change`.
    ///
    /// # Errors
    /// The error `change` returned.
    pub fn edit<R, E>(
        &mut self,
        label: impl Into<String>,
        change: impl FnOnce(&mut Model) -> Result<R, E>,
    ) -> Result<R, E> {
        let mut model = self.current().clone();
        let out = change(&mut model)?;
        self.push(label, model);
        Ok(out)
    }

    /// Moves the cursor one entry back; `false` (and no change) at the oldest entry.
    ///
    /// Time: O(1).
    pub fn undo(&mut self) -> bool {
        let moved = self.cursor > 0;
        self.cursor -= usize::from(moved);
        moved
    }

    /// Moves the cursor one entry forward; `false` (and no change) at the newest.
    ///
    /// Time: O(1).
    pub fn redo(&mut self) -> bool {
        let moved = self.cursor + 1 < self.entries.len();
        self.cursor += usize::from(moved);
        moved
    }

    /// Moves the cursor to `index` (undo or redo by several steps at once); `false`
    /// (and no change) if there is no such entry.
    ///
    /// Time: O(1).
    pub fn go_to(&mut self, index: usize) -> bool {
        let valid = index < self.entries.len();
        if valid {
            self.cursor = index;
        }
        valid
    }

    /// The changes from entry `from` to entry `to` ([`Model::diff`]), or `None` if
    /// either is not kept.
    ///
    /// Time: that of [`Model::diff`].
    pub fn diff(&self, from: usize, to: usize) -> Option<Vec<Change>> {
        Some(self.get(from)?.diff(self.get(to)?))
    }

    /// The changes from entry `from` to entry `to`, one line each as
    /// [`Change::display`] writes them, or `None` if either entry is not kept.
    ///
    /// Time: that of [`Model::diff`], plus the lines'.
    pub fn diff_lines(&self, from: usize, to: usize) -> Option<Vec<String>> {
        let (old, new) = (self.get(from)?, self.get(to)?);
        Some(old.diff(new).iter().map(|c| c.display(old, new).to_string()).collect())
    }
}
