//! `attach`, `detach`, scope renames, and edits that reach into attachments.
//!
//! An attachment is a frame node in the parent's body tree that holds the child
//! `Model` value itself (shared, never copied or rewritten) and its scope name. Every
//! position-dependent thing (prefixes, merged settings, default-class names, auto
//! names) is derived by the writer, so detaching is removing that node: the parent
//! comes back exactly as it was before the attach.

use std::sync::Arc;

use smol_str::SmolStr;

use crate::error::ValueError;
use crate::error::{EditError, ErrorKind};
use crate::model::{Loc, MergedCache, Model};
use crate::schema::{ElementKind, Namespace};
use crate::tree::{Attached, Attr, ElementId, Node};

use super::settings;

/// The site attributes an attachment frame copies (reference §3.3).
pub(crate) const FRAME_ATTRS: [&str; 7] = ["pos", "quat", "axisangle", "xyaxes", "zaxis", "euler", "user"];

/// Whether a frame accepts attribute `name` after the attach: the copied ones and
/// `mocap`.
pub(crate) fn frame_settable(name: &str) -> bool {
    name == "mocap" || FRAME_ATTRS.contains(&name)
}

impl Model {
    /// Attaches `child` at `at`, a site (of this model or of a model attached to it) or
    /// a worldbody, and returns the new model and a locator of the attachment frame.
    ///
    /// The frame copies `pos`, `quat`, `axisangle`, `xyaxes`, `zaxis`, `euler` and
    /// `user` from the site, and sits right after it (after frames attached there
    /// before), or at the end of the worldbody. The child's names get the scope prefix
    /// `name/` when written, where `name` is the child's model name, or `name_1`,
    /// `name_2`, ... if the model that receives it already has an attachment of that
    /// name. The child value is shared, not copied: attaching costs O(depth · log
    /// width) whatever its size, and one value can be attached any number of times.
    ///
    /// # Errors
    /// Leaving `self` unchanged: `at` is neither a site nor a worldbody
    /// ([`ErrorKind::InvalidParent`]), it does not exist ([`ErrorKind::NotFound`]), the
    /// child's name holds a `/`, or a global setting conflicts
    /// ([`ErrorKind::AttributeConflict`]).
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Element, Model, Namespace};
    /// let arena = Model::new("arena");
    /// let (arena, _) = arena.add(&arena.worldbody(), Element::new("site").attr("name", "spawn")).unwrap();
    /// let robot = Model::new("robot");
    /// let (robot, _) = robot.add(&robot.worldbody(), Element::new("body").attr("name", "torso")).unwrap();
    /// let spawn = arena.find(Namespace::Site, "spawn").unwrap();
    /// let (scene, _frame) = arena.attach(&spawn, &robot).unwrap();
    /// assert!(scene.find(Namespace::Body, "robot/torso").is_some());
    /// assert_eq!(scene.detach("robot").unwrap(), arena);
    /// ```
    pub fn attach(&self, at: &Loc, child: &Model) -> Result<(Model, Loc), EditError> {
        let (new, frame) =
            self.in_scope(at.scope(), &mut |m: &Model| m.attach_here(at.id(), child).map(|(m, f)| (m, Loc::new(f))))?;
        settings::check(&new).map_err(|k| EditError::new(k, String::new()))?;
        Ok((new, frame.within(at.scope())))
    }

    /// Attaches `child` at the end of the worldbody (see [`Model::attach`]).
    pub fn attach_to_world(&self, child: &Model) -> Result<(Model, Loc), EditError> {
        self.attach(&self.worldbody(), child)
    }

    fn attach_here(&self, at: ElementId, child: &Model) -> Result<(Model, ElementId), EditError> {
        let path = self.path_of(at).ok_or_else(|| EditError::new(ErrorKind::NotFound, format!("{at:?}")))?;
        let err = |k: ErrorKind| EditError::new(k, self.describe(&path));
        let node = self.node_at(&path).ok_or_else(|| err(ErrorKind::NotFound))?;
        let base = child.name();
        if base.contains('/') {
            return Err(err(ErrorKind::InvalidValue {
                tag: "mujoco",
                attribute: "model",
                value: base.to_string(),
                error: ValueError::SlashInIdentifier,
            }));
        }
        let mut index = self.index.clone();
        let scope = index.scopes.free_name(base);
        let tag = node.kind().tag();
        let (parent_path, parent, position, body_kind, attrs) = match tag {
            "worldbody" => {
                let kind = node.kind().child("body").ok_or_else(|| err(ErrorKind::InvalidParent(tag)))?;
                (path.clone(), node, node.children().len(), kind, Vec::new())
            }
            "site" if !path.is_empty() => {
                let (last, parent_path) = path.split_last().map(|(l, p)| (*l, p.to_vec())).unwrap_or_default();
                let parent = self.node_at(&parent_path).ok_or_else(|| err(ErrorKind::NotFound))?;
                let kind = parent.kind().child("body").ok_or_else(|| err(ErrorKind::InvalidParent(tag)))?;
                // Right after the site, after the frames already attached there.
                let mut pos = last + 1;
                while parent.children().get(pos).is_some_and(|c| c.attached().is_some()) {
                    pos += 1;
                }
                let pos = pos.min(parent.children().len());
                (parent_path, parent, pos, kind, frame_attrs(node, kind))
            }
            _ => return Err(err(ErrorKind::InvalidParent(tag))),
        };
        let id = ElementId::fresh();
        let frame = Node::frame(id, body_kind, attrs, Attached { scope: scope.clone(), model: child.clone() });
        // A new frame has no identifier, so indexing it cannot find a duplicate.
        let _ = index.insert_subtree(Some(parent.id()), &frame, position);
        index.scopes.push(scope, id);
        // The merged settings: the child's folded into ours (each cached, so O(1)).
        let mut sections = settings::merged(self).map_err(err)?.to_vec();
        settings::fold_sections(&mut sections, &settings::merged(child).map_err(err)?).map_err(err)?;
        index.merged = MergedCache::known(sections.into());
        let root = self.root.update_path(&parent_path, |p| {
            let mut children = p.children().clone();
            children.insert(position, frame);
            Ok::<_, EditError>(p.with_children(children))
        })?;
        Ok((Model { root, index, files: self.files.clone() }, id))
    }

    /// The model without the attachment at `scope` (`robot`, or `arena/robot` for one
    /// attached inside an attachment). `detach` of a fresh attach gives back exactly
    /// the model it was attached to.
    ///
    /// # Errors
    /// [`ErrorKind::NotAttached`] if no attachment has that scope path.
    pub fn detach(&self, scope: &str) -> Result<Model, EditError> {
        let (outer, last) = split_scope(scope);
        let frames = self.scope_frames(outer)?;
        let (m, ()) = self.in_scope(&frames, &mut |m: &Model| {
            let frame = m.index.frame_of(last).ok_or_else(|| not_attached(scope))?;
            let path = m.path_of(frame).ok_or_else(|| not_attached(scope))?;
            let (pos, parent_path) = path.split_last().ok_or_else(|| not_attached(scope))?;
            let node = m.node_at(&path).ok_or_else(|| not_attached(scope))?;
            let mut index = m.index.clone();
            index.remove_subtree(node);
            index.merged = MergedCache::default();
            let root = m.root.update_path(parent_path, |p| {
                let mut children = p.children().clone();
                children.remove(*pos);
                Ok::<_, EditError>(p.with_children(children))
            })?;
            Ok((Model { root, index, files: m.files.clone() }, ()))
        })?;
        Ok(m)
    }

    /// The model attached at `scope` (`robot`, `arena/robot`), as it is now.
    pub fn attached(&self, scope: &str) -> Option<&Model> {
        self.scoped_model(&self.scope_frames(scope).ok()?)
    }

    /// The scope names of this model's own attachments, in attach order.
    pub fn scopes(&self) -> impl Iterator<Item = &str> {
        self.index.scopes.iter().map(|(s, _)| s.as_str())
    }

    /// The attachment frame of the model attached at `scope`.
    pub fn frame(&self, scope: &str) -> Option<Loc> {
        let frames = self.scope_frames(scope).ok()?;
        let (last, outer) = frames.split_last()?;
        Some(Loc::new(*last).within(outer))
    }

    /// Renames the attachment at `scope` to `to` (the attached value keeps its own
    /// model name).
    ///
    /// # Errors
    /// [`ErrorKind::NotAttached`] for an unknown scope; [`ErrorKind::DuplicateIdentifier`]
    /// if an attachment of the same model already has that name (including this
    /// one, as in the reference); an invalid identifier (`/`, or empty).
    pub fn rename_scope(&self, scope: &str, to: &str) -> Result<Model, EditError> {
        if to.contains('/') || to.is_empty() {
            return Err(EditError::new(
                ErrorKind::InvalidValue {
                    tag: "mujoco",
                    attribute: "model",
                    value: to.to_string(),
                    error: ValueError::SlashInIdentifier,
                },
                scope.to_string(),
            ));
        }
        let (outer, last) = split_scope(scope);
        let frames = self.scope_frames(outer)?;
        let (m, ()) = self.in_scope(&frames, &mut |m: &Model| {
            let frame = m.index.frame_of(last).ok_or_else(|| not_attached(scope))?;
            // As in the reference, the name must be free: renaming to the scope's own
            // name is refused too.
            if m.index.frame_of(to).is_some() {
                return Err(EditError::new(
                    ErrorKind::DuplicateIdentifier { namespace: Namespace::AttachmentFrame, name: to.into() },
                    scope.to_string(),
                ));
            }
            let path = m.path_of(frame).ok_or_else(|| not_attached(scope))?;
            let mut index = m.index.clone();
            index.scopes.rename(frame, to.into());
            let root = m.root.update_path(&path, |n| {
                let a = n.attached().ok_or_else(|| not_attached(scope))?;
                Ok::<_, EditError>(n.with_attached(Attached { scope: to.into(), model: a.model.clone() }))
            })?;
            Ok((Model { root, index, files: m.files.clone() }, ()))
        })?;
        Ok(m)
    }

    /// The scope path (`""`, `robot`, `arena/robot`) of the model that holds the
    /// element at `loc`.
    pub fn scope_path(&self, loc: &Loc) -> Option<String> {
        let mut m = self;
        let mut path: Vec<&str> = Vec::new();
        for f in loc.scope() {
            path.push(m.index.scope_of(*f)?);
            m = &m.node_by_id(*f)?.attached()?.model;
        }
        Some(path.join("/"))
    }

    /// The scope path (`robot`, `arena/robot`) of the attachment whose frame is at
    /// `frame`.
    pub fn scope_of_frame(&self, frame: &Loc) -> Option<String> {
        let outer = self.scope_path(frame)?;
        let scope = self.scoped_model(frame.scope())?.index.scope_of(frame.id())?;
        Some(if outer.is_empty() { scope.to_string() } else { format!("{outer}/{scope}") })
    }

    /// The locator, in this model, of the element `inner` of the model attached at
    /// `scope` (`inner` taken from that model on its own, or from an earlier version).
    pub fn locate_in(&self, scope: &str, inner: &Loc) -> Option<Loc> {
        let frames = self.scope_frames(scope).ok()?;
        Some(inner.clone().within(&frames))
    }

    /// Applies `edit` to the model attached at `scope` and puts the result back in
    /// its place (path copying through the attachments): the way to rename it,
    /// `include_copy` into it, or run any edit written for a standalone model.
    ///
    /// # Errors
    /// [`ErrorKind::NotAttached`] for an unknown scope; whatever `edit` returns; a
    /// conflict of global settings that the edit causes.
    pub fn edit_attached(
        &self,
        scope: &str,
        edit: impl FnOnce(&Model) -> Result<Model, EditError>,
    ) -> Result<Model, EditError> {
        let frames = self.scope_frames(scope)?;
        let mut edit = Some(edit);
        let (m, ()) = self.in_scope(&frames, &mut |m: &Model| match edit.take() {
            Some(f) => f(m).map(|m| (m, ())),
            None => Ok((m.clone(), ())),
        })?;
        settings::check(&m).map_err(|k| EditError::new(k, String::new()))?;
        Ok(m)
    }

    /// The frame ids along a scope path (`a/b` → [frame of a, frame of b in a]).
    pub(crate) fn scope_frames(&self, scope: &str) -> Result<Vec<ElementId>, EditError> {
        let mut frames = Vec::new();
        if scope.is_empty() {
            return Ok(frames);
        }
        let mut m = self;
        for s in scope.split('/') {
            let frame = m.index.frame_of(s).ok_or_else(|| not_attached(scope))?;
            frames.push(frame);
            m = &m.node_by_id(frame).and_then(Node::attached).ok_or_else(|| not_attached(scope))?.model;
        }
        Ok(frames)
    }

    /// Applies `f` to the model attached along `frames` (this model if empty) and puts
    /// the result back by path copying through each frame. Iterative, so attachments
    /// nested any number of levels deep cannot overflow the stack.
    pub(crate) fn in_scope<R>(&self, frames: &[ElementId], f: &mut ScopedEdit<'_, R>) -> Result<(Model, R), EditError> {
        // Down: each model along the way, the path to its frame and the scope name.
        let mut chain: Vec<(&Model, Vec<usize>, SmolStr)> = Vec::with_capacity(frames.len());
        // An error inside names its path with the scopes it is in, outermost first.
        let wrap = |e: EditError, chain: &[(&Model, Vec<usize>, SmolStr)]| {
            let path = chain.iter().rev().fold(e.path().to_string(), |p, (_, _, scope)| scoped_path(scope, &p));
            EditError::new(e.kind().clone(), path)
        };
        let mut m = self;
        for frame in frames {
            let missing = || EditError::new(ErrorKind::NotFound, format!("{frame:?}"));
            let path = m.path_of(*frame).ok_or_else(|| wrap(missing(), &chain))?;
            let Some(attached) = m.node_at(&path).and_then(Node::attached) else {
                return Err(wrap(missing(), &chain));
            };
            chain.push((m, path, attached.scope.clone()));
            m = &attached.model;
        }
        let (mut inner, r) = f(m).map_err(|e| wrap(e, &chain))?;
        // Up: put each new model back into its frame.
        for (outer, path, scope) in chain.into_iter().rev() {
            let mut index = outer.index.clone();
            // The outer fold can only stay if the inner one did.
            let before = outer.node_at(&path).and_then(Node::attached).map(|a| &a.model.index.merged);
            if !before.is_some_and(|b| b.same(&inner.index.merged)) {
                index.merged = MergedCache::default();
            }
            let root = outer
                .root
                .update_path(&path, |n| Ok::<_, EditError>(n.with_attached(Attached { scope, model: inner })))?;
            inner = Model { root, index, files: outer.files.clone() };
        }
        Ok((inner, r))
    }
}

/// An edit of the model inside an attachment, returning the new model and a result.
pub(crate) type ScopedEdit<'f, R> = dyn FnMut(&Model) -> Result<(Model, R), EditError> + 'f;

fn scoped_path(scope: &str, path: &str) -> String {
    if path.is_empty() { format!("<{scope}>") } else { format!("<{scope}>/{path}") }
}

fn split_scope(scope: &str) -> (&str, &str) {
    scope.rsplit_once('/').unwrap_or(("", scope))
}

fn not_attached(scope: &str) -> EditError {
    EditError::new(ErrorKind::NotAttached(scope.into()), scope.to_string())
}

/// The frame attributes copied from a site, as attributes of `body_kind`.
fn frame_attrs(site: &Node, body_kind: ElementKind) -> Vec<Attr> {
    let site_kind = site.kind();
    FRAME_ATTRS
        .iter()
        .filter_map(|name| {
            let v = site.attr(site_kind.attr_index(name)?)?;
            Some((u16::try_from(body_kind.attr_index(name)?).ok()?, v.clone()))
        })
        .collect()
}

impl Loc {
    /// The same element, seen from a model `outer` levels of attachment further out.
    pub(crate) fn within(self, outer: &[ElementId]) -> Loc {
        if outer.is_empty() {
            return self;
        }
        let mut scope: Vec<ElementId> = outer.to_vec();
        scope.extend_from_slice(self.scope());
        Loc::scoped(Arc::from(scope), self.id())
    }
}
