//! A part of a model: a body's subtree with exactly what it needs, as a model of its
//! own to attach ([`Model::part`]).
//!
//! How it is made, from the source model (a value; the source is not changed):
//! 1. the root body is lifted to the end of the worldbody, with its own pose (now
//!    relative to wherever the part is attached) and, when it has none, the
//!    `childclass` in force at it (its nearest ancestor's), so every element keeps
//!    its default class;
//! 2. every other element of the worldbody goes, with what depends on it
//!    ([`Referrers::Cascade`]: an actuator, sensor, tendon, equality, contact pair or
//!    exclude that refers outside the subtree is left out and reported);
//! 3. the keyframes, and the `<option>`, `<size>`, `<visual>` and `<statistic>`
//!    settings go (they are the scene's, not the part's); `<compiler>` stays, as it
//!    decides how the part's numbers read (angles, Euler sequences, folders);
//! 4. assets nothing refers to any more go (a skybox texture, the floor's material,
//!    a texture only they used), and so do default classes nothing refers to.

use std::collections::HashSet;

use crate::error::{EditError, ErrorKind};
use crate::model::tree::{ElementId, Node};
use crate::model::{Attrs, Loc, Model, Referrers};
use crate::schema::{ElementKind, Namespace, Role};
use crate::value::{Reference, Value};

/// A part of a model ([`Model::part`]): the model to attach, and what of the source
/// it left out because it refers outside the part.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Part {
    /// The part, a model named after its root body.
    pub model: Model,
    /// The actuators, sensors, tendons, equalities, contact pairs and excludes of
    /// the source that refer outside the part (partly, as a weld between a body of
    /// the part and one outside, or wholly), left out (by the names MuJoCo gives
    /// them in the source), and references cleared on elements of the part
    /// (`element: attribute`).
    pub left_out: Vec<String>,
}

/// The settings sections a part leaves behind (the compiler's stay).
fn scene_setting(node: &Node) -> bool {
    node.kind().is(Role::SettingsSection) && node.kind() != ElementKind::COMPILER
}

impl Model {
    /// The part of this model rooted at the body named `body`: its subtree with
    /// exactly what it needs (the default classes it uses, its assets, the
    /// actuators, sensors, tendons, equalities, contact pairs and excludes that refer
    /// only into it, the compiler settings), as a model of its own to attach
    /// ([`Model::attach_as`], [`Model::attach_in`]): MjSpec's `attach` of another
    /// model's body. What refers outside the part is left out and reported; the source's `<option>`, `<size>`, `<visual>`, `<statistic>`,
    /// keyframes, lights, cameras and other bodies, and the assets and classes only
    /// they used, do not come. The root keeps its own position and orientation, now
    /// relative to where the part is attached. See the module documentation of
    /// `compose::part` for the steps.
    ///
    /// A part whose root has a free joint, attached below a body, is what MuJoCo
    /// refuses ("free joint can only be used on top level"): [`Model::check`] of the
    /// result reports it.
    ///
    /// Time: O(r · n) for a source of `n` elements, where `r` is the number of
    /// elements removed (each removal checks what refers to it).
    ///
    /// # Errors
    /// [`ErrorKind::NotFound`] (with the nearest names) when no body is named
    /// `body`; [`ErrorKind::InvalidParent`] for the world body.
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, Namespace};
    /// let scene = Model::from_xml_str(r#"<mujoco model="scene">
    ///   <asset><texture name="sky" type="skybox" builtin="gradient" width="8" height="8"/></asset>
    ///   <worldbody>
    ///     <light pos="0 0 3"/><geom name="floor" type="plane" size="1 1 .1"/>
    ///     <body name="arm"><joint name="j"/><geom size=".1"/>
    ///       <body name="hand" pos="0 0 .5"><joint name="finger"/><geom size=".05"/></body>
    ///     </body>
    ///   </worldbody>
    ///   <actuator><motor name="m_j" joint="j"/><motor name="m_finger" joint="finger"/></actuator>
    /// </mujoco>"#)?;
    /// let hand = scene.part("hand")?;
    /// assert!(hand.model.find(Namespace::Actuator, "m_finger").is_some());
    /// assert!(hand.model.find(Namespace::Actuator, "m_j").is_none());
    /// assert!(hand.model.find(Namespace::Geom, "floor").is_none());
    /// assert!(hand.model.find(Namespace::Texture, "sky").is_none());
    /// let table = Model::new("table");
    /// let (scene, a) = table.attach_as(&table.worldbody(), &hand.model, "gripper")?;
    /// assert!(scene.find(Namespace::Joint, "gripper/finger").is_some());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn part(&self, body: &str) -> Result<Part, EditError> {
        let root = self.lookup(Namespace::Body, body)?;
        self.part_at(&root)
    }

    /// [`Model::part`] of the body at `root` (of this model's own tree).
    ///
    /// Time: as [`Model::part`].
    ///
    /// # Errors
    /// [`ErrorKind::StaleLocator`] when `root` is not in this model (or lies in an
    /// attached model: take the part of that model); [`ErrorKind::InvalidParent`]
    /// when it is not a body (the world body included) or is an attachment frame.
    pub fn part_at(&self, root: &Loc) -> Result<Part, EditError> {
        if !root.scope().is_empty() {
            return Err(self.stale(root));
        }
        let path = self.path_of(root.id()).ok_or_else(|| self.stale(root))?;
        let node = self.node_at(&path).cloned().ok_or_else(|| self.stale(root))?;
        if !node.kind().is(Role::Body) || node.attached().is_some() {
            let tag = node.kind().tag();
            return Err(EditError::new(ErrorKind::InvalidParent(tag), self.describe(&path)));
        }
        let childclass = self.class_in_force(&path, &node);
        let mut m = self.lifted(root, node)?;
        if let Some(class) = childclass {
            m = m.set(root, Attrs::new().set("childclass", class.as_str()))?;
        }
        let mut left_out = Vec::new();
        let wb = m.worldbody();
        let others: Vec<Loc> = m
            .element(&wb)
            .map(|w| w.children().map(|c| c.loc()).filter(|c| c != root).collect())
            .unwrap_or_default();
        for other in others {
            let r = m.remove_with_attachments_cascading(&other)?;
            left_out.extend(r.removed);
            left_out.extend(r.cleared.into_iter().map(|(e, a)| format!("{e}: {a}")));
            m = r.model;
        }
        m = m.without_scene_settings()?;
        m = m.without_unused(|n| n.kind().spec().parent == Some(ElementKind::ASSET))?;
        m = m.without_unused(|n| n.kind().is(Role::DefaultClass))?;
        if let Some(name) = node_name(&m, root) {
            m.set_name(&name);
        }
        Ok(Part { model: m, left_out })
    }

    /// The `childclass` in force at the body at `path` from its ancestors (bodies
    /// and frames), when the body has none of its own.
    fn class_in_force(&self, path: &[usize], node: &Node) -> Option<String> {
        fn childclass(n: &Node) -> Option<&Value> {
            n.kind().attr_index("childclass").and_then(|i| n.attr(i))
        }
        if childclass(node).is_some() {
            return None;
        }
        // One walk down the path (looking each ancestor up from the root was
        // O(depth²)), the nearest ancestor's winning.
        let mut nearest = None;
        let mut at = &self.root;
        for &i in path {
            nearest = childclass(at).or(nearest);
            at = at.children().get(i)?;
        }
        self.class_name(nearest?)
    }

    /// The name of the default class a reference names.
    fn class_name(&self, v: &Value) -> Option<String> {
        match v {
            Value::Reference(Reference::Name(n)) => Some(n.to_string()),
            Value::Reference(Reference::Element(id)) => {
                self.node_by_id(*id)?.identifier().map(str::to_string)
            }
            other => other.as_str().map(str::to_string),
        }
    }

    /// The model with the body `node` (at `root`) moved to the end of the worldbody,
    /// same element ids (so references to it still resolve).
    fn lifted(&self, root: &Loc, node: Node) -> Result<Model, EditError> {
        let mut m = self.remove_with_attachments(root)?;
        let wb = m.worldbody();
        let wb_path = m.path_of(wb.id()).ok_or_else(|| m.stale(&wb))?;
        let parent = m.node_at(&wb_path).ok_or_else(|| m.stale(&wb))?;
        let position = parent.children().len();
        let (ord, _) = parent.children().slot_at_insert(position);
        let parent_id = parent.id();
        // Its names were taken out with it: inserting them again finds no duplicate.
        if let Err(d) = m.index.insert_subtree_at(Some(parent_id), &node, position, ord) {
            let kind = ErrorKind::DuplicateIdentifier { namespace: d.namespace, name: d.name };
            return Err(EditError::new(kind, String::new()));
        }
        let parent = m.node_at_mut(&wb_path).ok_or_else(|| self.stale(&wb))?;
        parent.children.insert(position, node);
        Ok(m)
    }

    /// Removes `loc` and its attachments, cascading to what depends on it.
    fn remove_with_attachments_cascading(&self, loc: &Loc) -> Result<crate::Removal, EditError> {
        // Attachments in it go first (a cascade removes through `remove`, which
        // refuses to take attachments along).
        let mut m = self.clone();
        let inside: Vec<ElementId> = m.node_by_id(loc.id()).map_or_else(Vec::new, |n| {
            n.descendants().filter(|d| d.attached().is_some()).map(Node::id).collect()
        });
        for frame in inside {
            let frame = m.scoped_loc(&[], frame);
            if m.element(&frame).is_some() {
                m = m.remove_with_attachments(&frame)?;
            }
        }
        m.remove_with(loc, Referrers::Cascade)
    }

    /// The model without keyframes and the scene's settings sections (all but the
    /// compiler's).
    fn without_scene_settings(&self) -> Result<Model, EditError> {
        let mut m = self.clone();
        let sections: Vec<(ElementId, bool)> = m
            .root
            .children()
            .iter()
            .map(|c| (c.id(), scene_setting(c) || c.kind().is(Role::Keyframe)))
            .collect();
        for (id, drop) in sections {
            if drop {
                let loc = m.scoped_loc(&[], id);
                m = m.remove(&loc)?;
            }
        }
        Ok(m)
    }

    /// The model without the elements `which` picks that nothing refers to, until
    /// none is left (a texture only a removed material used goes in the next round).
    fn without_unused(&self, which: impl Fn(&Node) -> bool) -> Result<Model, EditError> {
        let mut m = self.clone();
        let mut kept: HashSet<ElementId> = HashSet::new();
        loop {
            let candidates: Vec<ElementId> = m
                .root
                .descendants()
                .filter(|n| which(n) && !kept.contains(&n.id()) && n.identifier().is_some())
                .map(Node::id)
                .collect();
            let mut changed = false;
            // Deepest first (nested classes before the class holding them).
            for id in candidates.into_iter().rev() {
                let loc = m.scoped_loc(&[], id);
                if m.element(&loc).is_none() {
                    continue;
                }
                match m.remove_with(&loc, Referrers::Refuse) {
                    Ok(r) => {
                        m = r.model;
                        changed = true;
                    }
                    Err(_) => {
                        kept.insert(id);
                    }
                }
            }
            if !changed {
                return Ok(m);
            }
        }
    }
}

/// The root body's name, as the part's model name (a name with `/` is not one).
fn node_name(m: &Model, root: &Loc) -> Option<String> {
    let name = m.element(root)?.identifier()?.to_string();
    crate::model::check_model_name(&name).ok().map(|()| name)
}
