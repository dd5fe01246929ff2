//! Element edits: add, insert, set, clear, remove, and their in-place twins.
//!
//! Each edit comes twice: `add(&self, ..) -> Result<(Model, Loc)>` returns a new
//! model for functional code, and `add_mut(&mut self, ..) -> Result<Loc>` replaces
//! `*self` with it. Both are atomic: on error nothing changes, and a clone taken
//! before an in-place edit keeps its content (the new version is a new value; the
//! clone still shares the old one).

use smol_str::SmolStr;

use crate::error::{EditError, ErrorKind};
use crate::schema::{AttrType, Multiplicity};
use crate::value::{AttrInput, Value};

use super::build::{self, Input, ModelFiles, ValueCtx, apply_attrs, check_class_named, empty_node};
use super::follow;
use super::frame::{check_frame_child, frame_settable};
use super::settings::is_settings_section;
use super::tree::{ElementId, Node};
use super::{Attrs, Element, Loc, MergedCache, Model};

impl Model {
    /// Replaces `self` with the model of a successful edit and returns the edit's
    /// result; on error `self` is unchanged.
    pub(crate) fn apply<R>(&mut self, edit: Result<(Model, R), EditError>) -> Result<R, EditError> {
        let (m, r) = edit?;
        *self = m;
        Ok(r)
    }

    /// Adds `element` as the last child of `parent`; returns the new model and the new
    /// element's locator.
    ///
    /// `parent` may lie inside an attachment (a `Loc` found as `robot/torso`): the
    /// attached model is edited and put back in its place. On an attachment frame
    /// only joints, one `inertial` and (for a frame directly in the worldbody) one
    /// `freejoint` can be added.
    ///
    /// Time: O(levels · depth · (log n + √width) + s · log n) for an element of `s`
    /// elements (each is checked and indexed), plus reading the files it names; an
    /// on-demand child (`inertial`, `freejoint`) also scans the parent's children,
    /// O(width).
    ///
    /// # Errors
    /// Leaving `self` unchanged:
    /// - [`ErrorKind::StaleLocator`]: `parent` is not in this model;
    /// - [`ErrorKind::InvalidChild`]: a tag is not a valid child of its parent (with
    ///   the nearest valid tag), or not a joint, inertial or freejoint on a frame;
    /// - [`ErrorKind::DuplicateChild`]: a second `inertial`, `freejoint` or other
    ///   on-demand child, or a singleton (`option`, `compiler`) added as a child;
    /// - [`ErrorKind::UnknownAttribute`], [`ErrorKind::InvalidValue`]: an attribute
    ///   that the element does not have, or a value that does not fit it;
    /// - [`ErrorKind::MissingRequired`]: a required attribute is not set (a nested
    ///   default class without `class`, an `inertial` without `mass`, ...);
    /// - [`ErrorKind::FileNotFound`], [`ErrorKind::FileOutsideRoot`]: a file
    ///   attribute names a file that cannot be read, or (confined) lies outside the
    ///   model's folder;
    /// - [`ErrorKind::DuplicateIdentifier`]: a name is taken in its namespace (on a
    ///   frame: by another joint of that frame);
    /// - [`ErrorKind::FreejointNotTopLevel`]: a freejoint on a frame that is not
    ///   directly in the worldbody.
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, element};
    /// let m = Model::new("m");
    /// let (m2, geom) = m.add(&m.worldbody(), element!("geom", name = "floor", size = [1.0, 1.0, 0.1]))?;
    /// assert_eq!(m2.get(&geom)?.identifier(), Some("floor"));
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn add(&self, parent: &Loc, element: Element) -> Result<(Model, Loc), EditError> {
        self.insert_at(parent, None, element)
    }

    /// [`Model::add`] in place: adds `element` to `self` and returns its locator.
    ///
    /// The nodes on the edited path that `self` shares with no other value (a clone,
    /// an earlier version) are edited where they are, the others are copied, so a
    /// model built by a loop of in-place edits copies almost nothing; a clone taken
    /// before keeps its content either way.
    ///
    /// Time: as [`Model::add`].
    ///
    /// # Errors
    /// As [`Model::add`]; `self` is unchanged on error.
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, element};
    /// let mut m = Model::new("m");
    /// let before = m.clone();
    /// let body = m.add_mut(&m.worldbody(), element!("body", name = "torso"))?;
    /// m.add_mut(&body, element!("geom", size = [0.1]))?;
    /// assert_ne!(m, before); // the clone kept its content
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn add_mut(&mut self, parent: &Loc, element: Element) -> Result<Loc, EditError> {
        self.insert_at_mut(parent, None, element)
    }

    /// Inserts `element` at `index` among the parent's repeated and on-demand children
    /// (singletons always come first and are not counted); an index past the end
    /// appends.
    ///
    /// Time: as [`Model::add`].
    ///
    /// # Errors
    /// As [`Model::add`].
    pub fn insert(
        &self,
        parent: &Loc,
        index: usize,
        element: Element,
    ) -> Result<(Model, Loc), EditError> {
        self.insert_at(parent, Some(index), element)
    }

    /// [`Model::insert`] in place; returns the new element's locator.
    ///
    /// Time: as [`Model::add`].
    ///
    /// # Errors
    /// As [`Model::add`]; `self` is unchanged on error.
    pub fn insert_mut(
        &mut self,
        parent: &Loc,
        index: usize,
        element: Element,
    ) -> Result<Loc, EditError> {
        self.insert_at_mut(parent, Some(index), element)
    }

    fn insert_at(
        &self,
        parent: &Loc,
        index: Option<usize>,
        element: Element,
    ) -> Result<(Model, Loc), EditError> {
        let mut new = self.clone();
        let loc = new.insert_at_mut(parent, index, element)?;
        Ok((new, loc))
    }

    fn insert_at_mut(
        &mut self,
        parent: &Loc,
        index: Option<usize>,
        element: Element,
    ) -> Result<Loc, EditError> {
        if parent.scope().is_empty() {
            // In place: on error nothing changed (see `insert_here`).
            let id = self.insert_here(parent, index, &element)?;
            return Ok(self.scoped_loc(&[], id));
        }
        let (m, loc) = self.in_scope(parent.scope(), |m: &Model| {
            let mut m = m.clone();
            let id = m.insert_here(parent, index, &element)?;
            // Named after the model it is in, as before the in-place edits.
            let loc = m.scoped_loc(&[], id);
            Ok((m, loc))
        })?;
        *self = m;
        Ok(loc.within(parent.scope()))
    }

    /// Inserts `element` under `loc`, an element of this model's own tree, in place;
    /// returns the new element's id. The element is built and checked, then indexed
    /// (a duplicate name found there is taken out again), and only then does the tree
    /// change, so on error `self` holds what it held. Nodes (and index nodes) that
    /// other versions share are copied; those `self` owns alone are edited in place.
    fn insert_here(
        &mut self,
        loc: &Loc,
        index: Option<usize>,
        element: &Element,
    ) -> Result<ElementId, EditError> {
        let path = self.locate(loc)?;
        // The element path for errors, made only when there is one: the parent's path
        // (O(width) to describe) and the new element's own part.
        let mut sub = String::new();
        let at = |m: &Model, sub: &str| -> String {
            let outer = m.describe(&path);
            match (outer.is_empty(), sub.is_empty()) {
                (true, _) => sub.to_string(),
                (false, true) => outer,
                (false, false) => format!("{outer}/{sub}"),
            }
        };
        let parent_node = self.node_at(&path).ok_or_else(|| self.stale(loc))?;
        let basepaths = self.basepaths();
        let model_files = ModelFiles::default();
        let ctx = ValueCtx { files: &self.files, basepaths: &basepaths, model_files: &model_files };
        let node = build::build(&ctx, parent_node.kind(), element, &mut sub)
            .map_err(|k| EditError::new(k, at(self, &sub)))?;
        if let Some(a) = parent_node.attached() {
            let grand = path.split_last().and_then(|(_, p)| self.node_at(p));
            check_frame_child(grand, parent_node, &node, &a.scope)
                .map_err(|k| EditError::new(k, at(self, &sub)))?;
        }
        if node.kind().multiplicity() == Multiplicity::OnDemand
            && parent_node.children().iter().any(|c| c.kind() == node.kind())
        {
            return Err(EditError::new(
                ErrorKind::DuplicateChild(node.kind().tag()),
                at(self, &sub),
            ));
        }
        let children = parent_node.children();
        let singletons = children
            .iter()
            .take_while(|c| c.kind().multiplicity() == Multiplicity::Singleton)
            .count();
        let position = match index {
            Some(i) => (singletons + i).min(children.len()),
            None => children.len(),
        };
        let parent_id = parent_node.id();
        let id = node.id();
        // Keys follow a new joint, actuator or mocap body (`follow`): the model before
        // the edit (an O(1) clone) for the layout to follow from.
        let before = (follow::has_keys(self) && follow::moves_layout(&node)).then(|| self.clone());
        // The index is filled first (with the slot the insert will give), so that a
        // duplicate name leaves the tree untouched.
        let (ord, _) = children.slot_at_insert(position);
        if let Err(d) = self.index.insert_subtree_at(Some(parent_id), &node, position, ord) {
            // Back to the index as it was: what was inserted is taken out (the
            // duplicate's own name stays with the element that has it).
            self.index.remove_subtree(&node);
            return Err(EditError::new(
                ErrorKind::DuplicateIdentifier { namespace: d.namespace, name: d.name },
                at(self, &sub),
            ));
        }
        // An edit inside a global settings section (or of the root's own children)
        // may change the merged settings: their memo starts afresh, as `Model::next`
        // decides for the other edits.
        let in_settings = path.first().is_none_or(|&s| {
            self.root.children().get(s).is_none_or(|n| is_settings_section(n.kind()))
        });
        if in_settings {
            self.index.merged = MergedCache::default();
        }
        let Some(parent) = self.node_at_mut(&path) else {
            // Found above, so this cannot happen.
            return Err(self.stale(loc));
        };
        parent.children.insert(position, node);
        if let Some(before) = before {
            *self = before.keys_followed(self.clone());
        }
        Ok(id)
    }

    /// Sets and clears attributes of the element at `loc`, all or nothing. The
    /// assignments apply in order (a later one for the same attribute wins), and a
    /// folder setting (`meshdir`) applies to the file attributes after it.
    ///
    /// On an attachment frame only `pos`, `quat`, `axisangle`, `xyaxes`, `zaxis`,
    /// `euler`, `user` and `mocap` can be set.
    ///
    /// Time: O(levels · depth · (log n + √width) + k) for `k` assignments, plus
    /// reading the files they name; an edit of a global setting (`option`,
    /// `compiler`, ...) in a composed model also refolds the merged settings:
    /// O(a · depth · log n).
    ///
    /// # Errors
    /// Leaving `self` unchanged:
    /// - [`ErrorKind::StaleLocator`]: `loc` is not in this model;
    /// - [`ErrorKind::UnknownAttribute`], [`ErrorKind::InvalidValue`]: an attribute
    ///   the element does not have (or a frame does not take), or a value that does
    ///   not fit it;
    /// - [`ErrorKind::MissingRequired`]: clearing a required attribute (or the
    ///   `class` of a nested default class);
    /// - [`ErrorKind::FileNotFound`], [`ErrorKind::FileOutsideRoot`]: a file that
    ///   cannot be read, or (confined) lies outside the model's folder;
    /// - [`ErrorKind::DuplicateIdentifier`]: a new name that is already taken;
    /// - [`ErrorKind::AttributeConflict`]: a global setting that no longer agrees
    ///   with an attached model's (or, set inside an attachment, with the rest).
    pub fn set(&self, loc: &Loc, attrs: Attrs) -> Result<Model, EditError> {
        let (m, ()) =
            self.in_scope(loc.scope(), |m: &Model| m.set_here(loc, &attrs).map(|m| (m, ())))?;
        // An edit of a global setting, on either side of an attachment, may conflict;
        // no other edit takes part in the merge.
        if self.in_settings_section(loc) {
            super::settings::check(&m).map_err(|k| EditError::new(k, String::new()))?;
        }
        Ok(m)
    }

    /// [`Model::set`] in place.
    ///
    /// Time: as [`Model::set`].
    ///
    /// # Errors
    /// As [`Model::set`]; `self` is unchanged on error.
    pub fn set_mut(&mut self, loc: &Loc, attrs: Attrs) -> Result<(), EditError> {
        let r = self.set(loc, attrs).map(|m| (m, ()));
        self.apply(r)
    }

    /// Sets one attribute.
    ///
    /// Time: as [`Model::set`].
    ///
    /// # Errors
    /// As [`Model::set`].
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, element};
    /// let m0 = Model::new("m");
    /// let (m1, g) = m0.add(&m0.worldbody(), element!("geom", name = "g", size = [0.1]))?;
    /// let m2 = m1.set_attr(&g, "pos", [0.0, 0.0, 1.0])?;
    /// assert_eq!(m2.floats(&g, "pos")?, [0.0, 0.0, 1.0]);
    /// assert!(m1.floats(&g, "pos").is_err()); // not set in the older version
    /// // Values are checked against the schema.
    /// assert!(m2.set_attr(&g, "type", "cube").is_err());
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn set_attr(
        &self,
        loc: &Loc,
        name: &str,
        value: impl Into<AttrInput>,
    ) -> Result<Model, EditError> {
        self.set(loc, Attrs::new().set(name, value))
    }

    /// [`Model::set_attr`] in place.
    ///
    /// Time: as [`Model::set`].
    ///
    /// # Errors
    /// As [`Model::set`]; `self` is unchanged on error.
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, element};
    /// let mut m = Model::new("m");
    /// let g = m.add_mut(&m.worldbody(), element!("geom", size = [0.1]))?;
    /// m.set_attr_mut(&g, "rgba", [1, 0, 0, 1])?;
    /// assert_eq!(m.floats(&g, "rgba")?, [1.0, 0.0, 0.0, 1.0]);
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn set_attr_mut(
        &mut self,
        loc: &Loc,
        name: &str,
        value: impl Into<AttrInput>,
    ) -> Result<(), EditError> {
        self.set_mut(loc, Attrs::new().set(name, value))
    }

    /// Clears one attribute.
    ///
    /// Time: as [`Model::set`].
    ///
    /// # Errors
    /// As [`Model::set`] (a required attribute cannot be cleared).
    pub fn clear_attr(&self, loc: &Loc, name: &str) -> Result<Model, EditError> {
        self.set(loc, Attrs::new().clear(name))
    }

    /// [`Model::clear_attr`] in place.
    ///
    /// Time: as [`Model::set`].
    ///
    /// # Errors
    /// As [`Model::set`]; `self` is unchanged on error.
    pub fn clear_attr_mut(&mut self, loc: &Loc, name: &str) -> Result<(), EditError> {
        self.set_mut(loc, Attrs::new().clear(name))
    }

    /// Whether the element lies in a global settings section (`option`, ...).
    fn in_settings_section(&self, loc: &Loc) -> bool {
        let Some(m) = self.scoped_model(loc.scope()) else { return false };
        let Some(section) = m.path_of(loc.id()).and_then(|p| p.first().copied()) else {
            return false;
        };
        m.root
            .children()
            .get(section)
            .is_some_and(|n| super::settings::is_settings_section(n.kind()))
    }

    fn set_here(&self, loc: &Loc, attrs: &Attrs) -> Result<Model, EditError> {
        let path = self.locate(loc)?;
        let err = |k: ErrorKind| EditError::new(k, self.describe(&path));
        let node = self.node_at(&path).ok_or_else(|| self.stale(loc))?;
        let kind = node.kind();
        let mut basepaths = self.basepaths();
        let mut changes = Vec::with_capacity(attrs.len());
        let model_files = ModelFiles::default();
        for (name, input) in attrs.items() {
            if node.attached().is_some() && !frame_settable(name) {
                let valid = super::frame::FRAME_ATTRS.iter().copied().chain(["mocap"]);
                return Err(err(ErrorKind::UnknownAttribute {
                    tag: "body",
                    attribute: name.clone(),
                    suggestion: crate::suggest::closest(name, valid),
                }));
            }
            let ctx =
                ValueCtx { files: &self.files, basepaths: &basepaths, model_files: &model_files };
            let change = ctx.assign(kind, name, input.as_ref().map(Input::Given)).map_err(err)?;
            // A folder setting applies to file attributes set after it in the same call.
            if let AttrType::Basepath { path_namespace } = kind.attr(change.0).ty {
                basepaths.set(
                    path_namespace,
                    change.1.as_ref().and_then(Value::as_str).map(SmolStr::from),
                );
            }
            changes.push(change);
        }
        let mut new_attrs = node.attrs().to_vec();
        apply_attrs(kind, &mut new_attrs, changes).map_err(err)?;
        if let Some(parent) = path.split_last().and_then(|(_, p)| self.node_at(p)) {
            check_class_named(parent.kind(), kind, &new_attrs).map_err(err)?;
        }
        let new_node = node.with_attrs(new_attrs);
        let mut index = self.index.clone();
        let old_name = node.identifier();
        let new_name = new_node.identifier();
        if old_name != new_name {
            if let (Some(ns), Some(name)) = (kind.namespace(), new_name) {
                // A frame's joints have a namespace of their own: that frame's joints.
                let frame = path
                    .split_last()
                    .and_then(|(_, p)| self.node_at(p))
                    .filter(|p| p.attached().is_some());
                let taken = match frame {
                    Some(f) => f
                        .children()
                        .iter()
                        .any(|c| c.id() != node.id() && c.identifier() == Some(name)),
                    None => index.names.contains_key(&(ns, SmolStr::from(name))),
                };
                if taken {
                    return Err(err(ErrorKind::DuplicateIdentifier {
                        namespace: ns,
                        name: name.into(),
                    }));
                }
            }
            index.rename(node.id(), new_name.map(SmolStr::from));
        }
        // Keys follow a joint's or actuator's edit, and a body's new `mocap` (a body's
        // other attributes move no joint, actuator or mocap body).
        let relayout = if kind.is(crate::schema::Role::Body) {
            attrs.items().iter().any(|(name, _)| name == "mocap")
        } else {
            follow::moves_layout(node)
        };
        let follow = relayout && follow::has_keys(self);
        let root = self.root.update_path(&path, |_| Ok::<_, EditError>(new_node))?;
        let out = self.next(root, index);
        Ok(if follow { self.keys_followed(out) } else { out })
    }

    /// Removes the element at `loc` with its subtree. A singleton (such as `option`)
    /// stays but loses its attributes and children.
    ///
    /// References to removed elements that were resolved (read from XML) become dead:
    /// an optional one is no longer written, a required one makes writing fail. A
    /// reference held as a plain name is written as it is.
    ///
    /// Time: O(levels · depth · (log n + √width) + s · log n) for a subtree of `s`
    /// elements.
    ///
    /// # Errors
    /// [`ErrorKind::AffectsAttachments`] if the subtree holds an attachment frame, or
    /// the element is a global section (or part of one) while models are attached: use
    /// [`Model::detach`] or [`Model::remove_with_attachments`];
    /// [`ErrorKind::StaleLocator`] if `loc` is not in this model.
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, Namespace, element};
    /// let mut m = Model::new("m");
    /// let body = m.add_mut(&m.worldbody(), element!("body", name = "torso"))?;
    /// m.add_mut(&body, element!("geom", name = "chest", size = [0.1]))?;
    /// let without = m.remove(&body)?; // the body and its geom
    /// assert!(without.find(Namespace::Geom, "chest").is_none());
    /// assert!(m.find(Namespace::Geom, "chest").is_some()); // `m` is unchanged
    /// assert!(without.get(&body).is_err()); // the locator names nothing there
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn remove(&self, loc: &Loc) -> Result<Model, EditError> {
        let (m, ()) =
            self.in_scope(loc.scope(), |m: &Model| m.remove_here(loc, false).map(|m| (m, ())))?;
        Ok(m)
    }

    /// [`Model::remove`] in place.
    ///
    /// Time: as [`Model::remove`].
    ///
    /// # Errors
    /// As [`Model::remove`]; `self` is unchanged on error.
    pub fn remove_mut(&mut self, loc: &Loc) -> Result<(), EditError> {
        let r = self.remove(loc).map(|m| (m, ()));
        self.apply(r)
    }

    /// Removes the element at `loc` like [`Model::remove`], together with the
    /// attachments in its subtree (their frames go with it). A global section keeps
    /// merging the attachments' settings: only this model's own are cleared.
    ///
    /// Time: O(levels · depth · (log n + √width) + s · log n) for a subtree of `s`
    /// elements of this model (the models attached in it are not walked).
    ///
    /// # Errors
    /// [`ErrorKind::StaleLocator`] if `loc` is not in this model.
    pub fn remove_with_attachments(&self, loc: &Loc) -> Result<Model, EditError> {
        let (m, ()) =
            self.in_scope(loc.scope(), |m: &Model| m.remove_here(loc, true).map(|m| (m, ())))?;
        Ok(m)
    }

    /// [`Model::remove_with_attachments`] in place.
    ///
    /// Time: as [`Model::remove_with_attachments`].
    ///
    /// # Errors
    /// As [`Model::remove_with_attachments`]; `self` is unchanged on error.
    pub fn remove_with_attachments_mut(&mut self, loc: &Loc) -> Result<(), EditError> {
        let r = self.remove_with_attachments(loc).map(|m| (m, ()));
        self.apply(r)
    }

    fn remove_here(&self, loc: &Loc, affect_attachments: bool) -> Result<Model, EditError> {
        let path = self.locate(loc)?;
        let node = self.node_at(&path).cloned().ok_or_else(|| self.stale(loc))?;
        let in_section_chain = {
            let mut n = &self.root;
            path.iter().all(|&i| match n.children().get(i) {
                Some(c) => {
                    n = c;
                    c.kind().multiplicity() == Multiplicity::Singleton
                }
                None => false,
            })
        };
        let holds_frame =
            !self.index.scopes.is_empty() && node.descendants().any(|n| n.attached().is_some());
        if !affect_attachments
            && (holds_frame
                || (!self.index.scopes.is_empty() && in_section_chain && node.attached().is_none()))
        {
            return Err(EditError::new(ErrorKind::AffectsAttachments, self.describe(&path)));
        }
        let mut index = self.index.clone();
        index.remove_subtree(&node);
        let root = if path.is_empty() || node.kind().multiplicity() == Multiplicity::Singleton {
            let parent_id = self.index.parent(node.id());
            let fresh = Node::new(
                node.id(),
                node.kind(),
                Vec::new(),
                empty_node(node.kind()).children().clone(),
            );
            // The emptied element holds no identifiers, so this finds no duplicate.
            let _ = index.insert_subtree(parent_id, &fresh, path.last().copied().unwrap_or(0));
            self.root.update_path(&path, |_| Ok::<_, EditError>(fresh))?
        } else {
            let (last, parent_path) = path.split_last().ok_or_else(|| self.stale(loc))?;
            self.root.update_path(parent_path, |p| {
                let mut children = p.children().clone();
                children.remove(*last);
                Ok::<_, EditError>(p.with_children(children))
            })?
        };
        let out = self.next(root, index);
        let follow = follow::has_keys(self) && follow::moves_layout(&node);
        Ok(if follow { self.keys_followed(out) } else { out })
    }

    /// [`Model::with_name`] in place.
    ///
    /// Time: O(1).
    pub fn set_name(&mut self, name: &str) {
        *self = self.with_name(name);
    }
}
