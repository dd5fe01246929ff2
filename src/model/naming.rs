//! The names MuJoCo sees: the one place that decides what name every element of a
//! composed model is written with.
//!
//! The composed walk (`super::cursor`) keeps, per model instance, its [`InstNames`]
//! (the scope prefix, accumulated once as the walk descends, and how its root default
//! class is written) and counts automatic names as it enters elements. This module
//! turns what the walk knows of an element into a [`Written`] name, and
//! [`Written::write`] spells it. The writer,
//! [`ElementRef::full_name`](crate::ElementRef::full_name),
//! [`Model::from_full_name`], [`Model::check`] and the diff all read names through
//! here, so they cannot disagree.
//!
//! The rules are the manual's ([Names](crate::guide#names)), `P` there being the
//! instance's prefix ([`InstNames::prefix`]); the outermost root class's cases are
//! [`RootClass`]'s. What the manual calls giving way is decided here, always in
//! favour of the name that is not generated: an automatic name's `~k` is the first
//! free one, and [`Written::write`] places it before the replicate `_`.

use std::fmt::Write as _;

use smol_str::SmolStr;

use super::tree::Node;
use super::{Entry, Model};
use crate::schema::{ElementKind, Namespace};

/// How the outermost model's root default class is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum RootClass {
    /// As a class named `/` in the `<default>` wrapper (dm_control's shape); an
    /// attached model's is named by its prefix (`robot/`).
    Slash,
    /// As MuJoCo's main class, the `<default>` wrapper itself, referred to as `main`:
    /// when it is named `main` (`<default class="main">` inside the wrapper is a
    /// repeated name for MuJoCo; decision D9), or a class of the model is named `/`
    /// (read from MJCF), and no attached model's root class follows (which would
    /// inherit from it).
    Main,
    /// As a class named `/k` (the first `k` from 1 that no class of the model holds):
    /// when `/` is taken by a class of the model and attached models' root classes
    /// follow it in the wrapper.
    Numbered(u32),
    /// By its own name (`P` + name): a root class with a name other than `main`.
    Own,
}

/// What an instance of the composition needs for naming (kept by the walk).
#[derive(Clone, Debug)]
pub(crate) struct InstNames {
    /// `""` for the outermost model, `robot/`, `arena/robot/` for attachments.
    pub(crate) prefix: String,
    /// Whether `prefix` is written as it is (no character to escape).
    pub(crate) prefix_clean: bool,
    /// Whether the instance's attachment frame lies inside a `<replicate>` (of any
    /// model above): then all of its elements are replicated by MuJoCo.
    pub(crate) in_replicate: bool,
    /// How its root default class is written.
    pub(crate) root_class: RootClass,
    /// Whether a literal name of the model starts with `/`, so that automatic names
    /// must be checked against the model's names.
    literal_auto_clash: bool,
}

impl InstNames {
    /// The naming state of the outermost model.
    pub(crate) fn top(model: &Model) -> InstNames {
        InstNames {
            prefix: String::new(),
            prefix_clean: true,
            in_replicate: false,
            root_class: top_root_class(model),
            literal_auto_clash: model.index.has_slashed_segment(""),
        }
    }

    /// The naming state of `model`, attached as `scope` under this instance, at a
    /// frame that lies inside a `<replicate>` (`in_replicate`) or not.
    pub(crate) fn attached(&self, scope: &str, model: &Model, in_replicate: bool) -> InstNames {
        let mut names = self.clone();
        names.descend(scope, model, in_replicate);
        names
    }

    /// [`InstNames::attached`] in place: this naming state becomes that of `model`,
    /// attached as `scope` under it. The prefix grows by the scope only, so following
    /// a chain of attachments this way is linear in the prefix's final length.
    pub(crate) fn descend(&mut self, scope: &str, model: &Model, in_replicate: bool) {
        self.prefix.push_str(scope);
        self.prefix.push('/');
        // Cleanness is byte by byte: the parent's, then the new scope's (`/` is
        // clean), without scanning the whole prefix again at every level.
        self.prefix_clean = self.prefix_clean && crate::value::is_clean(scope.as_bytes());
        self.in_replicate = self.in_replicate || in_replicate;
        self.root_class = match root_default(model).and_then(Node::identifier) {
            Some(n) if !n.is_empty() => RootClass::Own,
            _ => RootClass::Slash,
        };
        self.literal_auto_clash = model.index.has_slashed_segment("");
    }

    /// Whether this instance is the outermost model.
    fn is_top(&self) -> bool {
        self.prefix.is_empty()
    }

    /// The name `elem`, an element of this instance's `model`, is written with
    /// (`None` for elements without a namespace). `ctx` says where it is; `auto`
    /// gives its automatic-name position and whether a `<replicate>` of the model is
    /// above it (asked only for an element written with its automatic name).
    #[inline]
    pub(crate) fn name_of<'n>(
        &self,
        model: &Model,
        elem: Named<'n>,
        ctx: &ElemCtx<'n>,
        auto: impl FnOnce() -> (u32, bool),
    ) -> Option<Written<'n>> {
        if let Some(scope) = elem.scope {
            return Some(Written::Frame(scope));
        }
        let ns = elem.kind.namespace()?;
        let ident = elem.ident.filter(|n| !n.is_empty());
        // (The root default class is the one element with a namespace directly in
        // the root.)
        let root_class = elem.kind.spec().parent == Some(ElementKind::ROOT);
        // Most elements: their own name.
        if let (Some(n), None, false) = (ident, ctx.frame, root_class) {
            return Some(Written::Own(n));
        }
        if root_class {
            return Some(match (self.root_class, ident) {
                (RootClass::Own, Some(n)) => Written::Own(n),
                (RootClass::Main, _) => Written::Main,
                (RootClass::Numbered(k), _) => Written::RootNumbered(k),
                _ => Written::RootClass,
            });
        }
        if let Some(frame) = ctx.frame {
            let scope = frame.attached().map_or("", |a| a.scope.as_str());
            match ident {
                Some(n) => {
                    // The attached model's literal joint `n/` is written the same.
                    let taken = frame.attached().is_some_and(|a| {
                        a.model.index.names.contains_key(&(ns, SmolStr::from(format!("{n}/"))))
                    });
                    if !taken {
                        return Some(Written::FrameJoint(scope, n));
                    }
                }
                None if ctx.first_unnamed && !ctx.enclosing_joint_named(scope) => {
                    return Some(Written::Frame(scope));
                }
                None => {}
            }
        }
        let (index, replicated) = auto();
        let replicated = replicated || self.in_replicate;
        let clash = self.auto_clash(model, ns, index, replicated);
        Some(Written::Auto { ns, index, clash, replicated })
    }

    /// The first `k` (0 for none) such that the automatic name with `~k` is no literal
    /// name of the model.
    fn auto_clash(&self, model: &Model, ns: Namespace, index: u32, replicated: bool) -> u32 {
        if !self.literal_auto_clash {
            return 0;
        }
        let mut text = String::new();
        for k in 0.. {
            text.clear();
            // Spelt in the outermost model (`//unnamed_...`); an attached model's own
            // name for it lacks the first `/` (its prefix `P` takes that place).
            Written::Auto { ns, index, clash: k, replicated }.write("", &mut text);
            let own = if self.is_top() { &text[..] } else { &text[1..] };
            if !model.index.names.contains_key(&(ns, SmolStr::from(own))) {
                return k;
            }
        }
        0
    }
}

/// What an element's name is made from: its kind, its own name, and for an
/// attachment frame its scope.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Named<'n> {
    kind: ElementKind,
    ident: Option<&'n str>,
    scope: Option<&'n str>,
}

impl<'n> Named<'n> {
    /// From the element's node.
    pub(crate) fn of_node(node: &'n Node) -> Named<'n> {
        Named {
            kind: node.kind(),
            ident: node.identifier(),
            scope: node.attached().map(|a| a.scope.as_str()),
        }
    }

    /// From the element's index entry.
    pub(crate) fn of_entry(entry: &'n Entry) -> Named<'n> {
        Named {
            kind: entry.kind,
            ident: entry.name().map(SmolStr::as_str),
            scope: entry.scope().map(SmolStr::as_str),
        }
    }
}

/// Where an element is, as far as its name depends on it.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct ElemCtx<'n> {
    /// For an own child of an attachment frame (a frame joint): the frame.
    pub(crate) frame: Option<&'n Node>,
    /// For a frame joint: whether it is the first unnamed joint of its frame.
    pub(crate) first_unnamed: bool,
    /// The attachment frame that holds the element's model (its instance's frame, a
    /// node of the instance above), if any.
    pub(crate) enclosing: Option<&'n Node>,
}

impl ElemCtx<'_> {
    /// Whether the frame that holds this instance has a joint named `scope` (written
    /// `P/scope/`, as this instance's unnamed frame joint of scope `scope` would be).
    fn enclosing_joint_named(&self, scope: &str) -> bool {
        self.enclosing.is_some_and(|f| {
            f.children()
                .iter()
                .any(|c| c.kind().namespace().is_some() && c.identifier() == Some(scope))
        })
    }
}

/// The first unnamed joint (element with a namespace and no name) of an attachment
/// frame, if any.
pub(crate) fn first_unnamed_joint(frame: &Node) -> Option<super::tree::ElementId> {
    frame
        .children()
        .iter()
        .find(|c| c.kind().namespace().is_some() && c.identifier().is_none_or(str::is_empty))
        .map(Node::id)
}

/// A name as the writer writes it, relative to the instance's prefix `P`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Written<'n> {
    /// `P` + the element's own name.
    Own(&'n str),
    /// `P` + scope + `/`: an attachment frame, or the first unnamed joint of one.
    Frame(&'n str),
    /// `P` + scope + `/` + name + `/`: a named joint of an attachment frame.
    FrameJoint(&'n str, &'n str),
    /// `P/unnamed_<ns>_<index>` (`//...` in the outermost model), then `~<clash>`
    /// when `clash > 0`, then `_` inside a `<replicate>`.
    Auto {
        /// The namespace.
        ns: Namespace,
        /// The position among the model's elements of the namespace.
        index: u32,
        /// The `~k` that tells it apart from a literal name (0: none).
        clash: u32,
        /// Inside a `<replicate>`.
        replicated: bool,
    },
    /// An unnamed root default class: `P` (`/` in the outermost model).
    RootClass,
    /// The outermost model's root class written as MuJoCo's main class: `main`.
    Main,
    /// The outermost model's root class as `/k` ([`RootClass::Numbered`]).
    RootNumbered(u32),
}

impl Written<'_> {
    /// Appends the name, in the instance whose prefix is `prefix`, to `out`: the one
    /// spelling of every written name.
    pub(crate) fn write(&self, prefix: &str, out: &mut String) {
        match *self {
            Written::Own(n) => {
                out.push_str(prefix);
                out.push_str(n);
            }
            Written::Frame(scope) => {
                out.push_str(prefix);
                out.push_str(scope);
                out.push('/');
            }
            Written::FrameJoint(scope, n) => {
                out.push_str(prefix);
                out.push_str(scope);
                out.push('/');
                out.push_str(n);
                out.push('/');
            }
            Written::Auto { ns, index, clash, replicated } => {
                out.push_str(if prefix.is_empty() { "/" } else { prefix });
                let _ = write!(out, "/unnamed_{}_{index}", ns.as_str());
                if clash > 0 {
                    let _ = write!(out, "~{clash}");
                }
                if replicated {
                    out.push('_');
                }
            }
            Written::RootClass => out.push_str(if prefix.is_empty() { "/" } else { prefix }),
            Written::Main => out.push_str("main"),
            Written::RootNumbered(k) => {
                let _ = write!(out, "/{k}");
            }
        }
    }

    /// The name as a string (see [`Written::write`]).
    pub(crate) fn to_string_in(self, prefix: &str) -> String {
        let mut s = String::new();
        self.write(prefix, &mut s);
        s
    }
}

/// Whether `name` in namespace `ns` names what MuJoCo resolves without an element
/// of that name: the world body `world`, and the root default class as `main`
/// (MuJoCo's name) or `/` (dm_control's). The reader resolves the class names to the
/// root class unless a class holds the name, `check` accepts them, and the writer
/// writes them as the root class is named (`world` as it is, in every scope).
pub(crate) fn is_builtin_name(ns: Namespace, name: &str) -> bool {
    matches!((ns, name), (Namespace::Body, "world") | (Namespace::Default, "/" | "main"))
}

fn root_default(model: &Model) -> Option<&Node> {
    model.root.child_of_kind(ElementKind::DEFAULT)
}

/// How the outermost `model`'s root default class is written ([`RootClass`]).
fn top_root_class(model: &Model) -> RootClass {
    let name = root_default(model).and_then(Node::identifier).filter(|n| !n.is_empty());
    if name.is_some_and(|n| n != "main") {
        return RootClass::Own;
    }
    let taken = |n: &str| model.index.names.contains_key(&(Namespace::Default, SmolStr::from(n)));
    let slash_taken = taken("/");
    if model.index.scopes.is_empty() {
        if name.is_some() || slash_taken {
            return RootClass::Main;
        }
        return RootClass::Slash;
    }
    if !slash_taken {
        return RootClass::Slash;
    }
    let k = (1u32..).find(|k| !taken(&format!("/{k}"))).unwrap_or(1);
    RootClass::Numbered(k)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `Walk::own` counts a model's automatic names as the composed walk does, which
    /// enters the outermost model's settings sections and no attached model's: so no
    /// element with a namespace may sit in a settings section.
    #[test]
    fn settings_sections_hold_no_element_with_a_namespace() {
        for section in ElementKind::ROOT.spec().children {
            if !super::super::settings::is_settings_section(*section) {
                continue;
            }
            let mut stack = vec![*section];
            while let Some(k) = stack.pop() {
                assert!(k.namespace().is_none(), "{} in {}", k.tag(), section.tag());
                stack.extend(k.spec().children.iter().copied().filter(|c| *c != k));
            }
        }
    }

    /// Every name is spelt by `Written::write`, in the outermost model and in an
    /// attached one.
    #[test]
    fn written_names_are_spelt_once() {
        let auto =
            |clash, replicated| Written::Auto { ns: Namespace::Geom, index: 3, clash, replicated };
        let cases: [(Written<'_>, &str, &str); 10] = [
            (Written::Own("torso"), "", "torso"),
            (Written::Own("torso"), "robot/", "robot/torso"),
            (Written::Frame("hand"), "robot/", "robot/hand/"),
            (Written::FrameJoint("hand", "root"), "", "hand/root/"),
            (auto(0, false), "", "//unnamed_geom_3"),
            (auto(2, true), "robot/", "robot//unnamed_geom_3~2_"),
            (Written::RootClass, "", "/"),
            (Written::RootClass, "robot/", "robot/"),
            (Written::Main, "robot/", "main"),
            (Written::RootNumbered(1), "", "/1"),
        ];
        for (w, prefix, want) in cases {
            assert_eq!(w.to_string_in(prefix), want);
        }
    }
}
