//! [`Change`]: one difference between two versions of a model, and how it reads.

use crate::model::{Loc, Model};
use crate::value::Value;

/// One difference between two versions of a model, as found by [`Model::diff`].
///
/// Locators of elements inside attachments are scoped (through the attachment frames,
/// outermost first), like those [`Model::find`] returns for `robot/torso`.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Change {
    /// An element that only the new version has, with its subtree (which is not
    /// reported element by element). `loc` is valid in the new version.
    Added {
        /// The top of the added subtree.
        loc: Loc,
    },
    /// An element that only the old version has, with its subtree. `loc` is valid in
    /// the old version.
    Removed {
        /// The top of the removed subtree.
        loc: Loc,
    },
    /// An attribute set, cleared or changed on an element both versions have.
    AttrChanged {
        /// The element (valid in both versions).
        loc: Loc,
        /// The attribute's XML name.
        attribute: &'static str,
        /// Its value in the old version (`None`: not set).
        old: Option<Value>,
        /// Its value in the new version (`None`: not set).
        new: Option<Value>,
    },
    /// An element both versions have, at another place: under another parent, or
    /// under the same parent in another order relative to its siblings.
    ///
    /// Among the children of one parent that both versions have, the ones that keep
    /// their relative order are a largest such set (counting elements); the others are
    /// reported as moved. So adding or removing siblings moves nothing, and taking one
    /// child from the front to the back reports that one child only.
    ///
    /// No public edit moves an element (`insert` and `add` make new ids, `remove`
    /// drops them), so versions made with this crate's edits differ by `Removed` and
    /// `Added` instead; `Moved` is reported only where an id itself changed place.
    Moved {
        /// The element (valid in both versions).
        loc: Loc,
        /// Its parent in the old version.
        from: Loc,
        /// Its parent in the new version (equal to `from` for a move among siblings).
        to: Loc,
        /// Its position among the old parent's children.
        old_index: usize,
        /// Its position among the new parent's children.
        new_index: usize,
    },
    /// A model attached (see [`Model::attach`]): the frame with its children (such as
    /// a freejoint added to it) and the attached model. Reported instead of `Added`
    /// for the frame, and also for a frame inside an added subtree.
    Attached {
        /// The full scope path in the new version (`robot`, `arena/robot`).
        scope: String,
        /// The attachment frame (valid in the new version).
        frame: Loc,
    },
    /// A model detached (see [`Model::detach`]), or its frame removed with a subtree
    /// ([`Model::remove_with_attachments`]: the subtree's top is `Removed`, each
    /// attachment in it `Detached`).
    Detached {
        /// The full scope path in the old version.
        scope: String,
        /// The attachment frame (valid in the old version).
        frame: Loc,
    },
    /// An attachment renamed (see [`Model::rename_scope`]).
    RenamedScope {
        /// The full scope path in the old version.
        from: String,
        /// The full scope path in the new version.
        to: String,
        /// The attachment frame (valid in both versions).
        frame: Loc,
    },
}

impl Change {
    /// The change as one line for people, with the names MuJoCo will see:
    /// `~ robot/torso rgba: 0.5 0.5 0.5 1 -> 1 0 0 1`, `+ body box_3`,
    /// `- joint dog/hip`, `> body robot/leg moved`, `attached robot`,
    /// `detached robot_1`, `renamed robot_1 -> dog`. `old` and `new` are the two
    /// versions [`Model::diff`] compared.
    ///
    /// Time: O(levels · depth · log n) per line (O(size of the element's model) for
    /// an unnamed element, whose automatic name is its position).
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, element};
    /// let mut m = Model::new("m");
    /// let v0 = m.clone();
    /// m.add_mut(&m.worldbody(), element!("body", name = "box"))?;
    /// let lines: Vec<String> = v0.diff(&m).iter().map(|c| c.display(&v0, &m).to_string()).collect();
    /// assert_eq!(lines, ["+ body box"]);
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn display<'a>(&'a self, old: &'a Model, new: &'a Model) -> impl std::fmt::Display + 'a {
        ChangeDisplay { change: self, old, new }
    }
}

struct ChangeDisplay<'a> {
    change: &'a Change,
    old: &'a Model,
    new: &'a Model,
}

impl std::fmt::Display for ChangeDisplay<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        // `tag name` for an element MuJoCo names; otherwise its path (below).
        let name = |m: &Model, loc: &Loc| match m.element(loc) {
            Some(e) => match e.full_name().filter(|n| !n.is_empty()) {
                Some(n) => format!("{} {n}", e.tag()),
                None => path(e),
            },
            None => format!("{loc:?}"),
        };
        let value = |v: &Option<Value>| {
            v.as_ref().map_or_else(|| "(unset)".to_string(), ToString::to_string)
        };
        match self.change {
            Change::Added { loc } => write!(f, "+ {}", name(self.new, loc)),
            Change::Removed { loc } => write!(f, "- {}", name(self.old, loc)),
            Change::AttrChanged { loc, attribute, old, new } => {
                let n = name(self.new, loc);
                // A named element by its name alone; a path has no space to cut at.
                let n = n.split_once(' ').map_or(n.as_str(), |(_, n)| n);
                write!(f, "~ {n} {attribute}: {} -> {}", value(old), value(new))
            }
            Change::Moved { loc, .. } => write!(f, "> {} moved", name(self.new, loc)),
            Change::Attached { scope, .. } => write!(f, "attached {scope}"),
            Change::Detached { scope, .. } => write!(f, "detached {scope}"),
            Change::RenamedScope { from, to, .. } => write!(f, "renamed {from} -> {to}"),
        }
    }
}

/// The path of an element MuJoCo gives no name (a default class's `<position>`, an
/// `<inertial>`, `<option>`), written as error paths are: from the nearest ancestor
/// that has a name (`tag[name=..]`, the name MuJoCo sees) down through the tags, a
/// tag followed by `[i]` (its rank among its siblings of that tag) where its parent
/// has several: `default[name=large_actuator]/position`,
/// `body[name=robot/torso]/inertial`, `option`. So no two elements read the same.
///
/// Time: O(depth · (width + levels · depth · log n)), plus O(n) per unnamed ancestor
/// that has a namespace (whose automatic name is its position).
fn path(element: crate::model::ElementRef<'_>) -> String {
    let mut steps = Vec::new();
    let mut at = element;
    while let Some(parent) = at.parent() {
        if let Some(n) = at.full_name().filter(|n| !n.is_empty()) {
            steps.push(format!("{}[name={n}]", at.tag()));
            break;
        }
        let same: Vec<_> = parent.children().filter(|c| c.tag() == at.tag()).collect();
        match same.iter().position(|c| c.ptr_eq(&at)) {
            Some(i) if same.len() > 1 => steps.push(format!("{}[{i}]", at.tag())),
            _ => steps.push(at.tag().to_string()),
        }
        at = parent;
    }
    steps.reverse();
    steps.join("/")
}
