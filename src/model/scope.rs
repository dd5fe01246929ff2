//! Scopes: attachments named by scope paths (`robot`, `arena/robot_1`) or by the
//! [`Attachment`] handle `attach` returns, and edits that reach into attached models
//! by path copying through their frames.

use std::sync::Arc;

use smol_str::SmolStr;

use crate::error::{EditError, ErrorKind};

use super::tree::{Attached, ElementId, Node};
use super::{Loc, MergedCache, Model};

/// An attachment made by [`Model::attach`]: its frame and its scope path.
///
/// It names the attachment by its frame, so it keeps working after
/// [`Model::rename_scope`]; [`Attachment::scope`] is the path at attach time.
///
/// # Examples
/// ```
/// use mjcf::{Model, Namespace, element};
/// let mut arena = Model::new("arena");
/// let robot = Model::new("robot");
/// let a = arena.attach_mut(&arena.worldbody(), &robot)?;
/// assert_eq!(a.scope(), "robot");
/// arena.detach_mut(&a)?;
/// # Ok::<(), mjcf::EditError>(())
/// ```
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Attachment {
    frame: Loc,
    scope: SmolStr,
}

impl Attachment {
    pub(crate) fn new(frame: Loc, scope: SmolStr) -> Attachment {
        Attachment { frame, scope }
    }

    /// The attachment frame (a body in the written MJCF): add joints, a freejoint or
    /// an inertial to it, or set its pose.
    ///
    /// Time: O(1).
    pub fn frame(&self) -> &Loc {
        &self.frame
    }

    /// The scope path at attach time (`robot_1`, `arena/robot`), the prefix of the
    /// attached model's names.
    ///
    /// Time: O(1).
    pub fn scope(&self) -> &str {
        &self.scope
    }
}

impl From<Attachment> for Loc {
    fn from(a: Attachment) -> Loc {
        a.frame
    }
}

mod sealed {
    pub trait Sealed {}
    impl Sealed for str {}
    impl Sealed for String {}
    impl Sealed for super::Attachment {}
    impl<T: Sealed + ?Sized> Sealed for &T {}
}

/// What names an attachment: a scope path (`"robot"`, `"arena/robot_1"`, a `str` or
/// `String`) or an [`Attachment`].
///
/// A scope path has no leading or trailing `/` and no empty segment; one that does
/// is an [`ErrorKind::InvalidScope`] error everywhere.
pub trait ScopeRef: sealed::Sealed {
    /// The frame ids from `model` down to the attachment, outermost first.
    #[doc(hidden)]
    fn frames_in(&self, model: &Model) -> Result<Vec<ElementId>, EditError>;

    /// The scope path, for messages.
    #[doc(hidden)]
    fn path_text(&self) -> &str;
}

impl ScopeRef for str {
    fn frames_in(&self, model: &Model) -> Result<Vec<ElementId>, EditError> {
        model.scope_frames(self)
    }

    fn path_text(&self) -> &str {
        self
    }
}

impl ScopeRef for String {
    fn frames_in(&self, model: &Model) -> Result<Vec<ElementId>, EditError> {
        model.scope_frames(self)
    }

    fn path_text(&self) -> &str {
        self
    }
}

impl ScopeRef for Attachment {
    fn frames_in(&self, model: &Model) -> Result<Vec<ElementId>, EditError> {
        let mut frames = self.frame.scope().to_vec();
        frames.push(self.frame.id());
        // Each frame must still hold an attachment.
        let mut m = model;
        for f in &frames {
            m = &m
                .node_by_id(*f)
                .and_then(Node::attached)
                .ok_or_else(|| not_attached(m, &self.scope))?
                .model;
        }
        Ok(frames)
    }

    fn path_text(&self) -> &str {
        &self.scope
    }
}

impl<T: ScopeRef + ?Sized> ScopeRef for &T {
    fn frames_in(&self, model: &Model) -> Result<Vec<ElementId>, EditError> {
        (**self).frames_in(model)
    }

    fn path_text(&self) -> &str {
        (**self).path_text()
    }
}

/// Checks the shape of a scope path: non-empty segments separated by single `/`.
pub(crate) fn check_scope_path(path: &str) -> Result<(), EditError> {
    if path.split('/').any(str::is_empty) {
        return Err(EditError::new(ErrorKind::InvalidScope(path.into()), path.to_string()));
    }
    Ok(())
}

/// The error for a scope path that names no attachment; `m` is the model where the
/// search stopped, whose attachments are listed.
pub(crate) fn not_attached(m: &Model, scope: &str) -> EditError {
    let missing = scope.rsplit('/').next().unwrap_or(scope);
    let names: Vec<&str> = m.index.attachments().map(|(s, _)| s.as_str()).collect();
    let mut attached: Vec<SmolStr> = crate::suggest::nearest(missing, names.iter().copied(), 3)
        .into_iter()
        .map(SmolStr::from)
        .collect();
    for n in names.iter().take(20) {
        if !attached.iter().any(|a| a == n) {
            attached.push((*n).into());
        }
    }
    EditError::new(ErrorKind::NotAttached { scope: scope.into(), attached }, scope.to_string())
}

impl Model {
    /// The frame ids along a scope path (`a/b` → [frame of a, frame of b in a]).
    ///
    /// # Errors
    /// [`ErrorKind::InvalidScope`] for a malformed path, [`ErrorKind::NotAttached`]
    /// (listing what is attached there) when a segment names no attachment.
    pub(crate) fn scope_frames(&self, scope: &str) -> Result<Vec<ElementId>, EditError> {
        check_scope_path(scope)?;
        let mut frames = Vec::new();
        let mut m = self;
        for s in scope.split('/') {
            let frame = m.index.frame_of(s).ok_or_else(|| not_attached(m, scope))?;
            frames.push(frame);
            m = &m
                .node_by_id(frame)
                .and_then(Node::attached)
                .ok_or_else(|| not_attached(m, scope))?
                .model;
        }
        Ok(frames)
    }

    /// The model attached along `frames` (this model if empty).
    pub(crate) fn scoped_model(&self, frames: &[ElementId]) -> Option<&Model> {
        let mut m = self;
        for f in frames {
            m = &m.node_by_id(*f)?.attached()?.model;
        }
        Some(m)
    }

    /// Applies `f` to the model attached along `frames` (this model if empty) and puts
    /// the result back by path copying through each frame. Iterative, so attachments
    /// nested any number of levels deep cannot overflow the stack.
    ///
    /// Time: O(levels · depth · (log n + √width)) plus what `f` costs.
    pub(crate) fn in_scope<R>(
        &self,
        frames: &[ElementId],
        f: impl FnOnce(&Model) -> Result<(Model, R), EditError>,
    ) -> Result<(Model, R), EditError> {
        // Down: each model along the way, the path to its frame and the scope name.
        let mut chain: Vec<(&Model, Vec<usize>, SmolStr)> = Vec::with_capacity(frames.len());
        // An error inside names its path with the scopes it is in, outermost first.
        let wrap = |e: EditError, chain: &[(&Model, Vec<usize>, SmolStr)]| {
            let path = chain
                .iter()
                .rev()
                .fold(e.path().to_string(), |p, (_, _, scope)| scoped_path(scope, &p));
            EditError::new(e.kind().clone(), path)
        };
        let mut m = self;
        for frame in frames {
            let missing = || {
                EditError::new(
                    ErrorKind::StaleLocator { id: *frame, origin: m.name().into() },
                    String::new(),
                )
            };
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
            // Our merged settings fold the attached model's: if its memo is another
            // (the edit may have changed them), ours starts afresh.
            let memo_kept = outer
                .node_at(&path)
                .and_then(Node::attached)
                .is_some_and(|a| a.model.index.merged.same(&inner.index.merged));
            if !memo_kept {
                index.merged = MergedCache::default();
            }
            let root = outer.root.update_path(&path, |n| {
                Ok::<_, EditError>(n.with_attached(Attached { scope, model: inner }))
            })?;
            inner = outer.next(root, index);
        }
        Ok((inner, r))
    }

    /// The model attached at `scope` (a scope path or an [`Attachment`]), as it is
    /// now.
    ///
    /// Time: O(levels · depth · log n).
    ///
    /// # Errors
    /// [`ErrorKind::InvalidScope`] for a malformed scope path;
    /// [`ErrorKind::NotAttached`] (listing what is attached there) when nothing is
    /// attached at `scope`, or an [`Attachment`] was detached.
    pub fn attached(&self, scope: impl ScopeRef) -> Result<&Model, EditError> {
        let frames = scope.frames_in(self)?;
        self.scoped_model(&frames).ok_or_else(|| not_attached(self, scope.path_text()))
    }

    /// The scope names of this model's own attachments, in attach order.
    ///
    /// Time: O(a log a) for all `a` attachments of this model, to start (they are
    /// listed in attach order, their frames' order); O(1) per scope name after that.
    pub fn scopes(&self) -> impl Iterator<Item = &str> {
        self.index.attachments().map(|(s, _)| s.as_str())
    }

    /// The scope path of every attachment in the composition, those inside attached
    /// models included (`robot`, `robot/hand`, `robot_1`, ...), each after the path of
    /// the attachment it is in; this model's own come first, in attach order.
    ///
    /// Time: O(A · (levels · log n + log A)) for the `A` attachments at all levels
    /// (each model's own are listed in attach order, as [`Model::scopes`] does).
    ///
    /// # Examples
    /// ```
    /// use mjcf::Model;
    /// let hand = Model::new("hand");
    /// let (arm, _) = Model::new("arm").attach_to_world(&hand)?;
    /// let (scene, _) = Model::new("scene").attach_to_world(&arm)?;
    /// let (scene, _) = scene.attach_to_world(&arm)?;
    /// assert_eq!(scene.scope_paths(), ["arm", "arm_1", "arm_1/hand", "arm/hand"]);
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn scope_paths(&self) -> Vec<String> {
        let mut out = Vec::new();
        let mut stack: Vec<(String, &Model)> = vec![(String::new(), self)];
        while let Some((prefix, model)) = stack.pop() {
            for s in model.scopes() {
                let path = format!("{prefix}{s}");
                if let Ok(inner) = model.attached(s) {
                    stack.push((format!("{path}/"), inner));
                }
                out.push(path);
            }
        }
        out
    }

    /// The attachment at `scope`, as a handle: its frame and its scope path now.
    ///
    /// Time: O(levels · depth · log n).
    ///
    /// # Errors
    /// [`ErrorKind::InvalidScope`] or [`ErrorKind::NotAttached`], as for
    /// [`Model::attached`].
    pub fn attachment(&self, scope: impl ScopeRef) -> Result<Attachment, EditError> {
        let frames = scope.frames_in(self)?;
        let (last, outer) =
            frames.split_last().ok_or_else(|| not_attached(self, scope.path_text()))?;
        let frame = self.scoped_loc(outer, *last);
        let path = self.scope_of_frame(&frame).unwrap_or_else(|| scope.path_text().to_string());
        Ok(Attachment::new(frame, path.into()))
    }

    /// The attachment frame of the model attached at `scope`.
    ///
    /// Time: O(levels · depth · log n).
    ///
    /// # Errors
    /// [`ErrorKind::InvalidScope`] or [`ErrorKind::NotAttached`], as for
    /// [`Model::attached`].
    pub fn frame(&self, scope: impl ScopeRef) -> Result<Loc, EditError> {
        Ok(self.attachment(scope)?.frame)
    }

    /// The scope path (`""`, `robot`, `arena/robot`) of the model that holds the
    /// element at `loc`, or `None` if `loc` is not in this model.
    ///
    /// Time: O(levels · depth · log n).
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
    /// `frame`, or `None` if `frame` is not an attachment frame of this model.
    ///
    /// Time: O(levels · depth · log n).
    pub fn scope_of_frame(&self, frame: &Loc) -> Option<String> {
        let outer = self.scope_path(frame)?;
        let scope = self.scoped_model(frame.scope())?.index.scope_of(frame.id())?;
        Some(if outer.is_empty() { scope.to_string() } else { format!("{outer}/{scope}") })
    }

    /// The locator, in this model, of the element `inner` of the model attached at
    /// `scope` (`inner` taken from that model on its own, or from an earlier version).
    ///
    /// Time: O(levels · depth · log n).
    ///
    /// # Errors
    /// [`ErrorKind::InvalidScope`] or [`ErrorKind::NotAttached`], as for
    /// [`Model::attached`].
    pub fn locate_in(&self, scope: impl ScopeRef, inner: &Loc) -> Result<Loc, EditError> {
        let frames = scope.frames_in(self)?;
        let mut loc = inner.clone().within(&frames);
        loc.origin = self.name().into();
        Ok(loc)
    }

    /// A locator of the element `id` of the model attached along `frames`.
    pub(crate) fn scoped_loc(&self, frames: &[ElementId], id: ElementId) -> Loc {
        if frames.is_empty() {
            // A locator of this model's own element holds no frame list (and making
            // an empty `Arc` would allocate).
            return Loc { scope: None, id, origin: self.name().into() };
        }
        Loc::scoped(Arc::from(frames), id, self.name())
    }
}

fn scoped_path(scope: &str, path: &str) -> String {
    if path.is_empty() { format!("<{scope}>") } else { format!("<{scope}>/{path}") }
}

impl Loc {
    /// The same element, seen from a model `outer` levels of attachment further out.
    pub(crate) fn within(self, outer: &[ElementId]) -> Loc {
        if outer.is_empty() {
            return self;
        }
        let mut scope: Vec<ElementId> = outer.to_vec();
        scope.extend_from_slice(self.scope());
        Loc { scope: Some(Arc::from(scope)), ..self }
    }
}
