//! `attach`, `detach`, scope renames, and edits that reach into attachments.
//!
//! An attachment is a frame node in the parent's body tree that holds the child
//! `Model` value itself (shared, never copied or rewritten, except a child whose
//! compiler `angle` or `eulerseq` differs from the parent's, which is held converted
//! into the parent's conventions: decision D17) and its scope name. Every
//! position-dependent thing (prefixes, merged settings, default-class names, auto
//! names) is derived by the writer, so detaching is removing that node: the parent
//! comes back exactly as it was before the attach.
//!
//! What composition can make that MuJoCo refuses, and where each shape is decided
//! (an edit's refusal or a [`Model::check`] problem), is stated in
//! [`Model::check`].

use super::angles;
use crate::error::ValueError;
use crate::error::{EditError, ErrorKind};
use crate::model::follow;
use crate::model::frame::placed_frame_attrs;
use crate::model::settings;
use crate::model::tree::{Attached, ElementId, Node};
use crate::model::{Attachment, Loc, MergedCache, Model, ScopeRef};
use crate::schema::Role;
use smol_str::SmolStr;
use std::sync::Arc;

/// Where an attachment frame goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Placement {
    /// [`Model::attach`]: right after a site (placed as the site), or at the end of
    /// the worldbody.
    AtSite,
    /// [`Model::attach_in`]: at the end of a body's or `<frame>`'s children.
    Inside,
}

impl Model {
    /// Attaches `child` at `at`, a site (of this model or of a model attached to it) or
    /// a worldbody, and returns the new model and a locator of the attachment frame.
    /// ([`Model::attach_in`] attaches at a body or a MuJoCo `<frame>`.)
    ///
    /// The frame sits right after the site (after frames attached there before), or
    /// at the end of the worldbody, and takes the site's pose as MuJoCo reads it: its
    /// `pos`, `quat`, `axisangle`, `xyaxes`, `zaxis` and `euler`, its classes' where it
    /// sets none, and for `fromto` its middle and direction
    /// ([D15](crate::decisions#d15-an-attachment-frame-sits-where-mujoco-places-its-site));
    /// it copies the site's `user` too. It is written as a `<body>` named with the
    /// scope (`robot/`), or as MuJoCo's `<frame>` when it lies in the world, the child
    /// has a free body at its top level, and the frame has no joints, no inertial, no
    /// `user` and no `mocap`, so that those bodies stay at the top level
    /// ([D10](crate::decisions#d10-free-bodies-attached-in-the-world-stay-at-the-top-level)).
    ///
    /// The child's names get the scope prefix `name/` when written (all the names:
    /// [Names](crate::guide#names)), where `name` is the child's model name, or
    /// `name_1`, `name_2`, ... if the model that receives it already has an
    /// attachment of that name, or a literal name read from MJCF that starts with
    /// `name/` (a composed model read back holds `robot/torso`). The scope lives in
    /// the attachment: the child value is never renamed
    /// ([D2](crate::decisions#d2-the-scope-name-lives-in-the-attachment)). The child
    /// value is shared, not copied, whatever its size, and one value can be attached
    /// any number of times
    /// ([D1](crate::decisions#d1-a-model-value-can-be-attached-any-number-of-times)).
    /// Global settings (`<compiler>`, `<option>`, `<size>`, `<visual>`,
    /// `<statistic>`) are merged when the model is written, never stored, so
    /// [`Model::detach`] gives back exactly the model before the attach
    /// ([D3](crate::decisions#d3-detach-gives-back-exactly-the-parent-it-was-attached-to)).
    ///
    /// A child whose compiler `angle` or `eulerseq` is set and differs from this
    /// model's (merged, over everything attached) is not refused: the model held by
    /// the attachment is the child converted into this model's conventions (its
    /// `euler`s and `axisangle`s, a `<replicate>`'s `euler`, a limited hinge's or
    /// ball's `range` and a hinge's `ref` and `springref`, set on each joint; MuJoCo
    /// reads no other number by these settings: a key's `qpos`, a tendon's range, an
    /// actuator's `ctrlrange` and a camera's `fovy` are in fixed units), so
    /// MuJoCo compiles every element as in the child's own file
    /// ([decision D17](crate::decisions#d17-models-in-other-angle-conventions-are-converted-not-refused)).
    /// Where one side leaves the attribute unset, the merged settings take the other
    /// side's value and nothing is converted; the merged settings keep this model's
    /// values. Each such attach converts anew
    /// (O(size of the child)) and holds its own copy: for a fleet, attach the copy
    /// the first attach holds ([`Model::attached`]), which is then shared.
    ///
    /// Time: O(levels · depth · (log n + √width)), independent of the size of `child`
    /// (plus one step per frame already attached at the same site). Two parts can
    /// cost more: the merged global settings are folded anew, O(a · depth · log n),
    /// when an edit since the last attach changed settings or attachments (a set
    /// `option`, a detach); and after a detach or a scope rename, choosing the `k`-th
    /// free name `name_k` tries the names before it, O(k · log n).
    ///
    /// # Errors
    /// Leaving `self` unchanged:
    /// - [`ErrorKind::InvalidParent`]: `at` is neither a site nor a worldbody (as
    ///   dm_control refuses; [`Model::attach_in`] takes a body or `<frame>`);
    /// - [`ErrorKind::StaleLocator`]: `at` is not in this model;
    /// - [`ErrorKind::InvalidValue`] (with [`ValueError::SlashInIdentifier`]): the
    ///   child's model name holds a `/`;
    /// - [`ErrorKind::AttributeConflict`]: a global setting of the child (or of what
    ///   is attached to it) disagrees with this model's merged settings; or the
    ///   child's `eulerseq` cannot be converted (a `<replicate>` turning about several
    ///   axes, a sequence that is not three of `xyzXYZ`).
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, Namespace, element};
    /// let mut arena = Model::new("arena");
    /// let spawn = arena.add_mut(&arena.worldbody(), element!("site", name = "spawn", pos = [1.0, 0.0, 0.0]))?;
    /// let mut robot = Model::new("robot");
    /// robot.add_mut(&robot.worldbody(), element!("body", name = "torso"))?;
    /// let (scene, a) = arena.attach(&spawn, &robot)?;
    /// assert_eq!(a.scope(), "robot");
    /// assert!(scene.find(Namespace::Body, "robot/torso").is_some());
    /// assert_eq!(scene.floats(a.frame(), "pos")?, [1.0, 0.0, 0.0]); // copied from the site
    /// assert_eq!(scene.detach(&a)?, arena); // exactly the model before the attach
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn attach(&self, at: &Loc, child: &Model) -> Result<(Model, Attachment), EditError> {
        let mut new = self.clone();
        let a = new.attach_mut(at, child)?;
        Ok((new, a))
    }

    /// [`Model::attach`] in place: returns the attachment (its frame and scope).
    /// As [`Model::add_mut`], it copies only the nodes (and index nodes) that `self`
    /// shares with other values: the way to build a fleet.
    ///
    /// Time: as [`Model::attach`].
    ///
    /// # Errors
    /// As [`Model::attach`]; `self` is unchanged on error.
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, Namespace, element};
    /// let mut arena = Model::new("arena");
    /// let spawn = arena.add_mut(&arena.worldbody(), element!("site", name = "spawn"))?;
    /// let robot = Model::new("robot");
    /// let a = arena.attach_mut(&spawn, &robot)?;
    /// let b = arena.attach_mut(&spawn, &robot)?;
    /// assert_eq!((a.scope(), b.scope()), ("robot", "robot_1"));
    /// arena.add_mut(a.frame(), element!("freejoint"))?;
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn attach_mut(&mut self, at: &Loc, child: &Model) -> Result<Attachment, EditError> {
        self.attach_named_mut(at, child, child.name(), Placement::AtSite)
    }

    /// Attaches `child` inside `at`, a body (the worldbody too) or a MuJoCo `<frame>`
    /// of this model or of a model attached to it, as MjSpec attaches at a body or
    /// frame: the attachment frame is `at`'s last child, with no pose of its own, so
    /// the child's top level is placed in `at`'s coordinates. Scopes, merging,
    /// detach and `==` are [`Model::attach`]'s; the frame is written as
    /// [`Model::attach`]'s are (a body named with the scope, or a MuJoCo `<frame>`).
    /// A child whose top-level bodies are free, attached inside a body other than the
    /// worldbody, is what MuJoCo refuses ("free joint can only be used on top
    /// level"): [`Model::check`] reports it.
    ///
    /// Time: as [`Model::attach`].
    ///
    /// # Errors
    /// As [`Model::attach`]; [`ErrorKind::InvalidParent`] when `at` is neither a body
    /// nor a `<frame>`, or is an attachment frame (attach inside its parent, or at a
    /// body of its model).
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, Namespace, element};
    /// let mut table = Model::new("table");
    /// let top = table.add_mut(&table.worldbody(), element!("body", name = "top", pos = [0.0, 0.0, 0.8]))?;
    /// let mut arm = Model::new("arm");
    /// arm.add_mut(&arm.worldbody(), element!("body", name = "base"))?;
    /// let (scene, a) = table.attach_in(&top, &arm)?; // no site needed
    /// assert!(scene.find(Namespace::Body, "arm/base").is_some());
    /// assert_eq!(scene.element(a.frame()).and_then(|f| f.parent()).map(|p| p.loc()), Some(top));
    /// assert_eq!(scene.detach(&a)?, table);
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn attach_in(&self, at: &Loc, child: &Model) -> Result<(Model, Attachment), EditError> {
        let mut new = self.clone();
        let a = new.attach_in_mut(at, child)?;
        Ok((new, a))
    }

    /// [`Model::attach_in`] in place: returns the attachment (its frame and scope).
    ///
    /// Time: as [`Model::attach`].
    ///
    /// # Errors
    /// As [`Model::attach_in`]; `self` is unchanged on error.
    pub fn attach_in_mut(&mut self, at: &Loc, child: &Model) -> Result<Attachment, EditError> {
        self.attach_named_mut(at, child, child.name(), Placement::Inside)
    }

    /// [`Model::attach_in`] under a scope name of the caller's choice, as
    /// [`Model::attach_as`] (MjSpec's `body.attach_frame(..., prefix="gripper/")`).
    ///
    /// Time: as [`Model::attach`].
    ///
    /// # Errors
    /// As [`Model::attach_in`] and [`Model::attach_as`].
    pub fn attach_in_as(
        &self,
        at: &Loc,
        child: &Model,
        scope: &str,
    ) -> Result<(Model, Attachment), EditError> {
        let mut new = self.clone();
        new.check_scope_name(scope)?;
        let a = new.attach_named_mut(at, child, scope, Placement::Inside)?;
        Ok((new, a))
    }

    /// [`Model::attach`] under a scope name of the caller's choice instead of the
    /// child's model name (MjSpec's `attach(child, prefix="gripper/")`): the child's
    /// names are written `gripper/...`, the scope made unique as [`Model::attach`]
    /// makes a model name unique (`gripper_1`, ...; [`Attachment::scope`] tells which).
    ///
    /// Time: as [`Model::attach`].
    ///
    /// # Errors
    /// As [`Model::attach`], and [`ErrorKind::InvalidValue`] if `scope` is empty,
    /// holds a `/` ([`ValueError::SlashInIdentifier`]) or a character XML cannot
    /// hold ([`ValueError::InvalidCharacter`]), as [`Model::rename_scope`] refuses.
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, Namespace, element};
    /// let mut hand = Model::new("jaco_hand");
    /// hand.add_mut(&hand.worldbody(), element!("body", name = "palm"))?;
    /// let arm = Model::new("arm");
    /// let (arm, a) = arm.attach_as(&arm.worldbody(), &hand, "gripper")?;
    /// let (arm, b) = arm.attach_as(&arm.worldbody(), &hand, "gripper")?;
    /// assert_eq!((a.scope(), b.scope()), ("gripper", "gripper_1"));
    /// assert!(arm.find(Namespace::Body, "gripper_1/palm").is_some());
    /// assert!(arm.attach_as(&arm.worldbody(), &hand, "a/b").is_err());
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn attach_as(
        &self,
        at: &Loc,
        child: &Model,
        scope: &str,
    ) -> Result<(Model, Attachment), EditError> {
        let mut new = self.clone();
        let a = new.attach_as_mut(at, child, scope)?;
        Ok((new, a))
    }

    /// [`Model::attach_as`] in place: returns the attachment (its frame and scope).
    ///
    /// Time: as [`Model::attach`].
    ///
    /// # Errors
    /// As [`Model::attach_as`]; `self` is unchanged on error.
    pub fn attach_as_mut(
        &mut self,
        at: &Loc,
        child: &Model,
        scope: &str,
    ) -> Result<Attachment, EditError> {
        self.check_scope_name(scope)?;
        self.attach_named_mut(at, child, scope, Placement::AtSite)
    }

    /// Refuses a scope name given by the caller that is empty, holds a `/` or a
    /// character XML cannot hold.
    fn check_scope_name(&self, scope: &str) -> Result<(), EditError> {
        if scope.is_empty() {
            return Err(EditError::new(
                ErrorKind::InvalidValue {
                    tag: "mujoco",
                    attribute: "model",
                    value: String::new(),
                    error: ValueError::SlashInIdentifier,
                },
                String::new(),
            ));
        }
        crate::model::check_model_name(scope).map_err(|k| EditError::new(k, String::new()))
    }

    /// [`Model::attach_mut`] with the scope's base name given (`base`, `base_1`, ...),
    /// placed as `placement` says.
    fn attach_named_mut(
        &mut self,
        at: &Loc,
        child: &Model,
        base: &str,
        placement: Placement,
    ) -> Result<Attachment, EditError> {
        // The child in the conventions (angle unit, euler sequence) in force for the
        // whole composition, which every model in it shares (`compose::angles`).
        let err = |k: ErrorKind| EditError::new(k, String::new());
        // Settings whose fold into ours changed nothing (the last attach of the same
        // model did so) hold no convention other than ours: nothing to convert. (Asked
        // of the caches as they are, without taking a share of either: a child whose
        // settings are not counted yet was not absorbed.)
        let absorbed = child.index.merged.get().is_some_and(|t| self.index.merged.absorbs(t));
        let converted = if absorbed {
            None
        } else {
            angles::into_conventions(&settings::merged(self).map_err(err)?, child).map_err(err)?
        };
        let child = converted.as_ref().unwrap_or(child);
        if at.scope().is_empty() {
            // In place: every check comes first, then the edit copies only what other
            // versions share (nothing, when `self` owns the path alone).
            let (frame, scope) = self.attach_here(at, child, base, placement)?;
            return Ok(Attachment::new(self.scoped_loc(&[], frame), scope));
        }
        let (new, frame) = self.in_scope(at.scope(), |m: &Model| {
            let mut m = m.clone();
            let (frame, _) = m.attach_here(at, child, base, placement)?;
            Ok((m, frame))
        })?;
        settings::check(&new).map_err(|k| EditError::new(k, String::new()))?;
        let frame = self.scoped_loc(at.scope(), frame);
        let scope = new.scope_of_frame(&frame).unwrap_or_default();
        *self = new;
        Ok(Attachment::new(frame, scope.into()))
    }

    /// Attaches `child` at the end of the worldbody (see [`Model::attach`]).
    ///
    /// Time: as [`Model::attach`].
    ///
    /// # Errors
    /// As [`Model::attach`].
    pub fn attach_to_world(&self, child: &Model) -> Result<(Model, Attachment), EditError> {
        self.attach(&self.worldbody(), child)
    }

    /// [`Model::attach`] of `child` [`welded`](Model::welded): its top-level bodies
    /// lose their free joints and their `mocap` flag, so they are fixed to the body
    /// that holds the site instead of floating. MuJoCo accepts a free joint only on
    /// a body whose parent is the world ("free joint can only be used on top level")
    /// and a mocap body only as a fixed child of the world, so attaching a model with
    /// free bodies at a site inside a body, or a model with mocap bodies anywhere
    /// (the attachment frame is written as a body), is refused by MuJoCo and
    /// reported by [`Model::check`]
    /// ([`ProblemKind::FreeJointNotTopLevel`](crate::ProblemKind::FreeJointNotTopLevel),
    /// [`ProblemKind::MocapNotFixedChildOfWorld`](crate::ProblemKind::MocapNotFixedChildOfWorld));
    /// this is the remedy (a gripper on an arm, say).
    ///
    /// Time: as [`Model::attach`], plus [`Model::welded`].
    ///
    /// # Errors
    /// As [`Model::attach`].
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, element};
    /// let mut arm = Model::new("arm");
    /// let link = arm.add_mut(&arm.worldbody(), element!("body", name = "link"))?;
    /// arm.add_mut(&link, element!("joint", name = "shoulder"))?;
    /// arm.add_mut(&link, element!("geom", size = [0.1]))?;
    /// let tip = arm.add_mut(&link, element!("site", name = "tip"))?;
    /// let mut ball = Model::new("ball");
    /// let b = ball.add_mut(&ball.worldbody(), element!("body", name = "b"))?;
    /// ball.add_mut(&b, element!("freejoint"))?;
    /// ball.add_mut(&b, element!("geom", size = [0.1]))?;
    /// assert!(!arm.attach(&tip, &ball)?.0.check().is_empty()); // MuJoCo refuses it
    /// let (held, _) = arm.attach_welded(&tip, &ball)?;
    /// assert!(held.check().is_empty());
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn attach_welded(&self, at: &Loc, child: &Model) -> Result<(Model, Attachment), EditError> {
        self.attach(at, &child.welded()?)
    }

    /// The model with its top-level bodies fixed (through `<frame>`s, `<replicate>`s
    /// and attachments that keep them top level): their free joints removed and
    /// their `mocap` flag cleared; what [`Model::attach_welded`] attaches. Every
    /// other element stays, and references to a removed joint are cleared as
    /// [`Model::remove`] clears them; a key keeps its values (the joint's 7 positions
    /// included), which [`Model::check`] then reports as longer than the model.
    ///
    /// Time: O(N) for a composed model of N elements, plus one edit per joint or
    /// mocap body.
    ///
    /// # Errors
    /// As [`Model::remove`] and [`Model::clear_attr`] (not expected: every element
    /// edited was just found).
    pub fn welded(&self) -> Result<Model, EditError> {
        let mut out = self.clone();
        for (loc, mocap) in crate::model::check::top_level_floating(self) {
            if mocap {
                out.clear_attr_mut(&loc, "mocap")?;
            } else {
                out.remove_mut(&loc)?;
            }
        }
        Ok(out)
    }

    /// Attaches `child` at `at`, an element of this model's own tree, in place;
    /// returns the frame's id and the scope name. Every check (and the settings fold,
    /// which can fail) comes before the first change, so on error `self` is unchanged.
    fn attach_here(
        &mut self,
        at: &Loc,
        child: &Model,
        base: &str,
        placement: Placement,
    ) -> Result<(ElementId, SmolStr), EditError> {
        let path = self.path_of(at.id()).ok_or_else(|| self.stale(at))?;
        let err = |k: ErrorKind| EditError::new(k, self.describe(&path));
        let node = self.node_at(&path).ok_or_else(|| err(ErrorKind::NotFound))?;
        if base.contains('/') {
            return Err(err(ErrorKind::InvalidValue {
                tag: "mujoco",
                attribute: "model",
                value: base.to_string(),
                error: ValueError::SlashInIdentifier,
            }));
        }
        let tag = node.kind().tag();
        let (parent_path, parent, position, body_kind, attrs) = match node.kind().role() {
            // At the end of the worldbody's (or body's, or frame's) children, in its
            // coordinates.
            Some(Role::Body | Role::Frame)
                if placement == Placement::Inside && node.attached().is_none() =>
            {
                let kind = node
                    .kind()
                    .child_of_role(Role::Body)
                    .ok_or_else(|| err(ErrorKind::InvalidParent(tag)))?;
                (path.clone(), node, node.children().len(), kind, Vec::new())
            }
            Some(Role::Worldbody) => {
                let kind = node
                    .kind()
                    .child_of_role(Role::Body)
                    .ok_or_else(|| err(ErrorKind::InvalidParent(tag)))?;
                (path.clone(), node, node.children().len(), kind, Vec::new())
            }
            Some(Role::Site) if placement == Placement::AtSite && !path.is_empty() => {
                let (last, parent_path) =
                    path.split_last().map(|(l, p)| (*l, p.to_vec())).unwrap_or_default();
                let parent = self.node_at(&parent_path).ok_or_else(|| err(ErrorKind::NotFound))?;
                let kind = parent
                    .kind()
                    .child_of_role(Role::Body)
                    .ok_or_else(|| err(ErrorKind::InvalidParent(tag)))?;
                // Right after the site, after the frames already attached there.
                let mut pos = last + 1;
                while parent.children().get(pos).is_some_and(|c| c.attached().is_some()) {
                    pos += 1;
                }
                let pos = pos.min(parent.children().len());
                (parent_path, parent, pos, kind, placed_frame_attrs(self, &path, node, kind))
            }
            _ => return Err(err(ErrorKind::InvalidParent(tag))),
        };
        let parent_id = parent.id();
        // The merged settings: the child's folded into ours (each cached, so O(1)).
        let ours = settings::merged(self).map_err(err)?;
        let theirs = settings::merged(child).map_err(err)?;
        let sections = if self.index.merged.absorbs(&theirs) {
            ours.clone()
        } else {
            settings::folded(&ours, &theirs).map_err(err)?
        };
        // Folding `theirs` changed nothing: the next attach of the same model (its
        // merged sections the same `Arc`) skips the fold.
        let absorbed = Arc::ptr_eq(&sections, &ours).then_some(theirs);
        let scope = self.index.free_scope_name(base);
        let id = ElementId::fresh();
        let frame = Node::frame(
            id,
            body_kind,
            attrs,
            Attached { scope: scope.name.clone(), model: child.clone() },
        );
        // No check is left: from here on `self` changes.
        let Some(parent) = self.node_at_mut(&parent_path) else {
            // Found above, so this cannot happen; no content changed if it did.
            return Err(EditError::new(ErrorKind::NotFound, String::new()));
        };
        let ord = parent.children.insert(position, frame.clone());
        let index = &mut self.index;
        // A new frame has no identifier, so indexing it cannot find a duplicate.
        let _ = index.insert_subtree_at(Some(parent_id), &frame, position, ord);
        let name = scope.name.clone();
        index.scopes.push(base, scope, id);
        // The fold just made is the new version's.
        index.merged = MergedCache::filled(sections, absorbed);
        Ok((id, name))
    }

    /// The model without the attachment at `scope` (an [`Attachment`], or a scope
    /// path: `robot`, or `arena/robot` for one attached inside an attachment).
    /// `detach` of a fresh attach gives back exactly the model it was attached to.
    ///
    /// Time: O(levels · depth · (log n + √width)) (the attached model is not walked).
    ///
    /// # Errors
    /// [`ErrorKind::NotAttached`] (listing the scopes attached there) if nothing is
    /// attached at `scope` (or the [`Attachment`] was detached already);
    /// [`ErrorKind::InvalidScope`] for a malformed path.
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, Namespace, element};
    /// let mut robot = Model::new("robot");
    /// robot.add_mut(&robot.worldbody(), element!("body", name = "torso"))?;
    /// let arena = Model::new("arena");
    /// let (scene, _) = arena.attach(&arena.worldbody(), &robot)?;
    /// let (scene, b) = scene.attach(&scene.worldbody(), &robot)?;
    /// let one = scene.detach(&b)?; // by the handle
    /// assert_eq!(one.scopes().collect::<Vec<_>>(), ["robot"]);
    /// assert_eq!(one.detach("robot")?, arena); // by the scope path
    /// assert!(one.find(Namespace::Body, "robot/torso").is_some());
    /// assert!(one.detach(&b).is_err()); // already detached
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn detach(&self, scope: impl ScopeRef) -> Result<Model, EditError> {
        let frames = scope.frames_in(self)?;
        let (last, outer) =
            frames.split_last().ok_or_else(|| not_attached(self, scope.path_text()))?;
        let (m, ()) = self.in_scope(outer, |m: &Model| {
            let missing = || not_attached(m, scope.path_text());
            let path = m.path_of(*last).ok_or_else(missing)?;
            let (pos, parent_path) = path.split_last().ok_or_else(missing)?;
            let node = m.node_at(&path).ok_or_else(missing)?;
            let mut index = m.index.clone();
            index.remove_subtree(node);
            // The frame's own joints leave the model's keys (`model::follow`).
            let follow = follow::has_keys(m) && follow::moves_layout(node);
            let root = m.root.update_path(parent_path, |p| {
                let mut children = p.children().clone();
                children.remove(*pos);
                Ok::<_, EditError>(p.with_children(children))
            })?;
            let out = m.next(root, index);
            Ok((if follow { m.keys_followed(out) } else { out }, ()))
        })?;
        Ok(m)
    }

    /// [`Model::detach`] in place.
    ///
    /// Time: as [`Model::detach`].
    ///
    /// # Errors
    /// As [`Model::detach`]; `self` is unchanged on error.
    pub fn detach_mut(&mut self, scope: impl ScopeRef) -> Result<(), EditError> {
        let r = self.detach(scope).map(|m| (m, ()));
        self.apply(r)
    }

    /// Renames the attachment at `scope` to `to` (the attached value keeps its own
    /// model name). Its names are written with the new prefix; locators and
    /// [`Attachment`] handles keep working.
    ///
    /// Time: O(levels · depth · (log n + √width)).
    ///
    /// # Errors
    /// [`ErrorKind::NotAttached`] for an unknown scope; [`ErrorKind::InvalidScope`]
    /// for a malformed path; [`ErrorKind::DuplicateIdentifier`] (in
    /// [`Namespace::AttachmentFrame`](crate::Namespace::AttachmentFrame)) if an
    /// attachment of the same model already has that name (including this one, as in
    /// the reference), or a literal name of the model read from MJCF starts with it
    /// and a `/` (`robot/torso`: the attachment's names would be written the same); [`ErrorKind::InvalidValue`] if `to` is empty, holds a `/`
    /// ([`ValueError::SlashInIdentifier`]) or a character XML cannot hold, such as NUL
    /// ([`ValueError::InvalidCharacter`]).
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, Namespace, element};
    /// let mut robot = Model::new("robot");
    /// robot.add_mut(&robot.worldbody(), element!("body", name = "torso"))?;
    /// let mut arena = Model::new("arena");
    /// let a = arena.attach_mut(&arena.worldbody(), &robot)?;
    /// let renamed = arena.rename_scope(&a, "left")?;
    /// assert!(renamed.find(Namespace::Body, "left/torso").is_some());
    /// assert!(renamed.find(Namespace::Body, "robot/torso").is_none());
    /// assert_eq!(renamed.attached(&a)?.name(), "robot"); // the model keeps its name
    /// assert!(arena.rename_scope("robot", "a/b").is_err());
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn rename_scope(&self, scope: impl ScopeRef, to: &str) -> Result<Model, EditError> {
        let text = scope.path_text().to_string();
        if to.contains('/') || to.is_empty() {
            return Err(EditError::new(
                ErrorKind::InvalidValue {
                    tag: "mujoco",
                    attribute: "model",
                    value: to.to_string(),
                    error: ValueError::SlashInIdentifier,
                },
                text,
            ));
        }
        // A scope name becomes the attached model's name prefix in every written name.
        crate::model::check_model_name(to).map_err(|k| EditError::new(k, text.clone()))?;
        let frames = scope.frames_in(self)?;
        let (frame, outer) = frames.split_last().ok_or_else(|| not_attached(self, &text))?;
        let (m, ()) = self.in_scope(outer, |m: &Model| {
            // As in the reference, the name must be free: renaming to the scope's own
            // name is refused too; so is the part before the `/` of a literal name
            // (`robot` beside `robot/torso` read from MJCF), which the attachment's
            // names would meet.
            if m.index.frame_of(to).is_some() || m.index.has_slashed_segment(to) {
                return Err(EditError::new(
                    ErrorKind::DuplicateIdentifier {
                        namespace: crate::Namespace::AttachmentFrame,
                        name: to.into(),
                    },
                    text.clone(),
                ));
            }
            let path = m.path_of(*frame).ok_or_else(|| not_attached(m, &text))?;
            let mut index = m.index.clone();
            index.rename_scope(*frame, to.into());
            let root = m.root.update_path(&path, |n| {
                let a = n.attached().ok_or_else(|| not_attached(m, &text))?;
                Ok::<_, EditError>(
                    n.with_attached(Attached { scope: to.into(), model: a.model.clone() }),
                )
            })?;
            Ok((m.next(root, index), ()))
        })?;
        Ok(m)
    }

    /// [`Model::rename_scope`] in place.
    ///
    /// Time: as [`Model::rename_scope`].
    ///
    /// # Errors
    /// As [`Model::rename_scope`]; `self` is unchanged on error.
    pub fn rename_scope_mut(&mut self, scope: impl ScopeRef, to: &str) -> Result<(), EditError> {
        let r = self.rename_scope(scope, to).map(|m| (m, ()));
        self.apply(r)
    }

    /// Applies `edit` to the model attached at `scope` and puts the result back in
    /// its place (path copying through the attachments): the way to rename it,
    /// `include_copy` into it, or run any edit written for a standalone model.
    ///
    /// Time: O(levels · depth · (log n + √width)) plus what `edit` costs, plus
    /// O(a · depth · log n) to refold the merged settings if the edit changed them.
    ///
    /// # Errors
    /// [`ErrorKind::NotAttached`] for an unknown scope, [`ErrorKind::InvalidScope`]
    /// for a malformed path; whatever `edit` returns; [`ErrorKind::AttributeConflict`]
    /// for a conflict of global settings that the edit causes.
    pub fn edit_attached(
        &self,
        scope: impl ScopeRef,
        edit: impl FnOnce(&Model) -> Result<Model, EditError>,
    ) -> Result<Model, EditError> {
        let frames = scope.frames_in(self)?;
        let (m, ()) = self.in_scope(&frames, |m: &Model| edit(m).map(|m| (m, ())))?;
        settings::check(&m).map_err(|k| EditError::new(k, String::new()))?;
        Ok(m)
    }

    /// [`Model::edit_attached`] in place, with an in-place edit of the attached
    /// model.
    ///
    /// Time: as [`Model::edit_attached`].
    ///
    /// # Errors
    /// As [`Model::edit_attached`]; `self` is unchanged on error.
    pub fn edit_attached_mut<R>(
        &mut self,
        scope: impl ScopeRef,
        edit: impl FnOnce(&mut Model) -> Result<R, EditError>,
    ) -> Result<R, EditError> {
        let frames = scope.frames_in(self)?;
        let r = self.in_scope(&frames, |m: &Model| {
            let mut m = m.clone();
            let r = edit(&mut m)?;
            Ok((m, r))
        });
        let (m, r) = r?;
        settings::check(&m).map_err(|k| EditError::new(k, String::new()))?;
        *self = m;
        Ok(r)
    }
}

fn not_attached(m: &Model, scope: &str) -> EditError {
    crate::model::scope_not_attached(m, scope)
}
