//! The writer's rules, one function each, in one place for every part of `xml` that
//! asks them: they decide, the writer (`xml::write`) writes, and the reader, the
//! saver, the export and scenes ask the same functions. `xml::write`'s module
//! documentation lists them in a table, each with what it writes, the reader rule that
//! inverts it and the test that round-trips it.
//!
//! The rules the reader inverts by asking the same question of what it reads
//! ([`folds_into_root_class`], [`is_composed_output`], [`is_auto_name`]) are asked
//! by `xml::read` through these very functions, so a rule and its inverse cannot
//! drift apart.

use crate::error::WriteError;
use crate::model::naming::{self, RootClass};
use crate::model::tree::Node;
use crate::model::{Item, Model, settings};
use crate::schema::{AttrType, ElementKind, Multiplicity, Namespace, RefTarget, Role};
use crate::value::FileAsset;

use crate::write_options::WriteOptions;

// ---------------------------------------------------------------------------------
// What is written at all.

/// How an element the composed walk enters appears in the text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Presence {
    /// Not written, nor anything under it.
    Omitted,
    /// Written without tags of its own, its children in its place
    /// ([`root_class_is_wrapper`]).
    Transparent,
    /// A top-level section, written once something in it is ([`section_presence`]).
    OnDemand,
    /// Written.
    Written,
}

/// How the element `item` appears in the text. `section`: it is a top-level section
/// of the composed document ([`is_section`]); `root_class`: how its model's root
/// class is written.
pub(super) fn presence(item: &Item<'_>, section: bool, root_class: RootClass) -> Presence {
    if section {
        return section_presence(item.node, root_class);
    }
    if item.depth > 0 && !item.in_frame && is_silent(item.node) {
        return Presence::Omitted;
    }
    Presence::Written
}

/// Rule *sections on demand*: how a top-level section appears. The settings
/// sections are not written ([`writes_merged_settings`]: the merged ones are); the
/// worldbody is written when it holds anything; the root class as the wrapper
/// ([`root_class_is_wrapper`]) or as a class; every other section once something in
/// it is (a child, or an attribute of its own), so an empty one is left out. The
/// reader makes every section it does not read, empty.
pub(super) fn section_presence(node: &Node, root_class: RootClass) -> Presence {
    let kind = node.kind();
    if writes_merged_settings(kind) {
        return Presence::Omitted;
    }
    match kind.role() {
        Some(Role::Worldbody) if emits(node) => Presence::Written,
        Some(Role::Worldbody) => Presence::Omitted,
        Some(Role::DefaultClass) if root_class_is_wrapper(root_class) => Presence::Transparent,
        Some(Role::DefaultClass) => Presence::Written,
        _ => Presence::OnDemand,
    }
}

/// Whether `item`, entered by the composed walk (`composed`; not the walk of a merged
/// settings section), is a top-level section of the outermost model: the sections
/// the rules about sections ([`writes_merged_settings`], [`merges_keys`],
/// [`section_presence`]) speak of.
pub(super) fn is_section(item: &Item<'_>, composed: bool) -> bool {
    composed && item.depth == 1 && item.inst == 0
}

/// Rule *silent elements*: an element below the sections that writes nothing (no
/// attribute written, no child that writes anything: the empty singletons, such as
/// the 21 of every default class) and is not an attachment frame is left out. The
/// walk does not even give it (`Walk::pruned`). An attachment frame's own children
/// (its joints, its inertial) are written whatever they hold.
pub(super) fn is_silent(node: &Node) -> bool {
    node.attached().is_none() && !emits(node)
}

/// Whether `node` writes anything: a repeated element always does, a singleton when
/// [`singleton_emits`].
pub(super) fn emits(node: &Node) -> bool {
    node.kind().multiplicity() != Multiplicity::Singleton || singleton_emits(node)
}

/// Whether a singleton writes anything: a name or class slot (always written), a
/// written attribute ([`writes_own_attrs`]), or a child that writes anything.
fn singleton_emits(node: &Node) -> bool {
    let kind = node.kind();
    if kind_facts(kind).class.is_some() || kind.identifier().is_some() {
        return true;
    }
    if writes_own_attrs(node) {
        return true;
    }
    // (Most singletons are empty: no iterator for them.)
    let children = node.children();
    !children.is_empty()
        && children
            .iter()
            .any(|c| c.kind().multiplicity() != Multiplicity::Singleton || singleton_emits(c))
}

/// Whether `node` has an attribute that is written ([`writes_attr`]).
pub(super) fn writes_own_attrs(node: &Node) -> bool {
    let kind = node.kind();
    node.attrs().iter().any(|(i, _)| writes_attr(kind.attr(*i as usize).ty))
}

/// Rule *base paths*: attributes of type `ty` are written, but for the base paths
/// (`compiler/@meshdir`, `@texturedir`, `@assetdir`): every file attribute is
/// written as the file's own name ([`file_name`]), relative to the text, so a base
/// path would point elsewhere. The reader uses a base path to find the files, and
/// reads files named so back without one.
pub(super) fn writes_attr(ty: AttrType) -> bool {
    !matches!(ty, AttrType::Basepath { .. })
}

/// Rule *merged settings*: the outermost model's settings sections (`compiler`,
/// `option`, `size`, `visual`, `statistic`) are not written: in their place, the
/// settings merged over the whole composition (`model::settings::merged`). The
/// reader reads them as the model's own (a composed file reads back flat).
pub(super) fn writes_merged_settings(kind: ElementKind) -> bool {
    settings::is_settings_section(kind)
}

/// Rule *merged keys* ([`WriteOptions::merge_keyframes`]): the keyframe section of
/// kind `kind` (a top-level section) is written as one key per key name over the
/// whole composed model (`model::keys::merged_keys`), in place of the model's own
/// keys and the attached models'. The reader reads them as plain keys, which fit
/// the model read back.
pub(super) fn merges_keys(options: &WriteOptions, kind: ElementKind) -> bool {
    options.merge_keyframes && kind.is(Role::Keyframe)
}

// ---------------------------------------------------------------------------------
// The root default classes.

/// Rule *root class wrapper*: at depth 1 of the composed walk, whether an element
/// goes inside the one `<default>` that wraps the root default classes (the
/// outermost model's and every attached model's, siblings in attach order) rather
/// than after it. The wrapper opens at the first and closes before the next
/// section. The reader reads the classes in it as classes of the model, the root
/// class hoisted ([`folds_into_root_class`]).
pub(super) fn in_root_wrapper(kind: ElementKind) -> bool {
    kind.is(Role::DefaultClass)
}

/// Rule *root class as main* (decision D9): the outermost root class written as
/// MuJoCo's main class (naming's [`RootClass::Main`]: it is named `main`, or a class
/// of the model is named `/`, and no attached root class follows) is the wrapper
/// itself: its content is written straight in the wrapper, with no `<default>` of
/// its own. The reader reads the wrapper's content as the root class's.
pub(super) fn root_class_is_wrapper(root_class: RootClass) -> bool {
    root_class == RootClass::Main
}

/// Rule *main wrapper*: whether the wrapper of the root class `root` is written
/// `<default class="main">` rather than `<default>`: when the root class is the
/// wrapper ([`root_class_is_wrapper`]) and is named `main` (so that it reads back
/// named so, and written again gives the same text), or when what it writes in the
/// wrapper is one class named `/`, which the reader would fold into the root class
/// ([`folds_into_root_class`]): the references to `main` would then take `/`'s
/// defaults. A wrapper with an attribute is never folded.
pub(super) fn wrapper_says_main(root_class: RootClass, root: &Node) -> bool {
    if !root_class_is_wrapper(root_class) {
        return false;
    }
    let written = root.children().iter().filter(|c| emits(c)).map(|c| default_child(c));
    root.identifier() == Some("main") || folds_into_root_class(false, written)
}

/// An element inside a `<default>` as the rules about root classes see it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(in crate::xml) enum DefaultChild<'n> {
    /// A class, with its name if it has one.
    Class(Option<&'n str>),
    /// Anything else (a `<geom>` of the class's settings, ...).
    Setting,
}

/// `node`, a child of a `<default>`, as a [`DefaultChild`].
fn default_child(node: &Node) -> DefaultChild<'_> {
    if node.kind().is(Role::DefaultClass) {
        DefaultChild::Class(node.identifier())
    } else {
        DefaultChild::Setting
    }
}

/// Rule *root class hoisting*, the reader's side: a root `<default>` without
/// attributes (`wrapper_attrs`) whose whole content (`children`, in order) is one
/// class named `/` is read as the root class with that class's content
/// (`xml::read`'s `hoist_root_class`): the shape `<default><default class="/">…`
/// this crate and dm_control write a root class in. The writer asks the same of
/// what it is about to write ([`wrapper_says_main`]).
pub(in crate::xml) fn folds_into_root_class<'n>(
    wrapper_attrs: bool,
    children: impl IntoIterator<Item = DefaultChild<'n>>,
) -> bool {
    let mut children = children.into_iter();
    !wrapper_attrs
        && children.next() == Some(DefaultChild::Class(Some("/")))
        && children.next().is_none()
}

/// Rule *composed output*, the reader's side: a `<default>` whose classes
/// (`children`) are the outermost root class and others beside it is how a composed
/// model is written (the root class `/`, or `/1` where a class holds `/`
/// (naming's `RootClass::Numbered`), beside the attached models' root classes
/// `robot/`, which must not inherit from it). A file holding one is read with its
/// automatic names kept (see [`is_auto_name`]).
pub(in crate::xml) fn is_composed_output<'n>(
    children: impl IntoIterator<Item = DefaultChild<'n>>,
) -> bool {
    let (mut classes, mut root) = (0usize, false);
    for c in children {
        if let DefaultChild::Class(name) = c {
            classes += 1;
            root |= name.is_some_and(is_outermost_root_class_name);
        }
    }
    root && classes > 1
}

/// Whether `name` is one the outermost root class is written with beside attached
/// root classes: `/`, or `/k` for a number `k` (naming's `RootClass::Numbered`).
fn is_outermost_root_class_name(name: &str) -> bool {
    name.strip_prefix('/').is_some_and(|k| k.is_empty() || k.parse::<u32>().is_ok_and(|k| k > 0))
}

// ---------------------------------------------------------------------------------
// Names.

/// The start of the automatic names of the outermost model (`model::naming`:
/// `//unnamed_<namespace>_<i>`, then `~k` where a literal name holds it, then `_`
/// inside a `<replicate>`).
const AUTO_NAME_START: &str = "//unnamed_";

/// Rule *automatic names*, the reader's side: the writer writes every unnamed
/// element that has a name slot with its automatic name (`model::naming`), so that
/// MuJoCo and a reader of the text can name it; the reader reads a name of the
/// outermost model's automatic form back as no name at all (`xml::read`'s
/// `forget_auto_name`), so that it is derived again, from the element's place, when
/// the model is written. In a composed output ([`is_composed_output`]) the names are
/// kept: they were counted over each attached model's own elements, which the flat
/// model read back no longer tells apart.
pub(in crate::xml) fn is_auto_name(name: &str) -> bool {
    name.starts_with(AUTO_NAME_START)
}

/// Rule *unnamed model*: the `model` attribute written for `node` when it is the
/// root of a model without a name (`None` for any other element, and for a root
/// with a name, written as any attribute): the name the reader gives a model read
/// without one (`model::UNNAMED`).
pub(super) fn implicit_model_name(node: &Node) -> Option<&'static str> {
    if node.kind() != ElementKind::ROOT {
        return None;
    }
    let i = ElementKind::ROOT.attr_index("model")?;
    node.attr(i).is_none().then_some(crate::model::UNNAMED)
}

/// How a reference by name (not resolved to an element) is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum NamedReference {
    /// As the model's root class is named (`main` and `/` where no class has that
    /// name).
    RootClass,
    /// As it is, without the instance's prefix.
    Bare,
    /// With the instance's prefix, as every name of the instance.
    Prefixed,
}

/// Rule *references by name*: how the reference `name` in attribute `i` of `node`
/// (an element of `model`) is written. `main` and `/` naming a class name the root
/// class unless a class has that name (as the reader resolves them), and are written
/// as the root class is ([`NamedReference::RootClass`]), so that the text reads back
/// to the same class in any scope; the one world body is `world` in every scope
/// (decision D5); a name in another model (`RefTarget::Unless`, such as `<attach
/// body>` of an asset model) is not this model's. Every other name takes the
/// instance's prefix.
pub(super) fn named_reference(model: &Model, node: &Node, i: usize, name: &str) -> NamedReference {
    let ty = node.kind().attr(i).ty;
    let builtin =
        |ns| ty == AttrType::Reference(RefTarget::Fixed(ns)) && naming::is_builtin_name(ns, name);
    if builtin(Namespace::Default)
        && !model.index.names.contains_key(&(Namespace::Default, name.into()))
    {
        return NamedReference::RootClass;
    }
    let elsewhere =
        matches!(ty, AttrType::Reference(RefTarget::Unless(_, k)) if node.attr(k).is_some());
    if elsewhere || builtin(Namespace::Body) {
        NamedReference::Bare
    } else {
        NamedReference::Prefixed
    }
}

/// Rule *removed references*: attribute `i` of `node` (an element of `model`) refers
/// to an element that was removed. An optional reference is left out (`Ok`); a
/// required one cannot be, and fails with [`WriteError::MissingRequired`]. The reader
/// reads the element without the attribute.
pub(super) fn removed_reference(model: &Model, node: &Node, i: usize) -> Result<(), WriteError> {
    let kind = node.kind();
    let spec = kind.attr(i);
    if !spec.required {
        return Ok(());
    }
    Err(WriteError::MissingRequired {
        tag: kind.tag(),
        attribute: spec.name,
        path: model.path_of(node.id()).map(|p| model.describe(&p)).unwrap_or_default(),
    })
}

// ---------------------------------------------------------------------------------
// Classes.

/// Rule *childclass scope*: whether the children of an element are under a
/// `childclass` of its model: it is under one itself (`above`), or it sets one that
/// is written (`sets`, asked only then: a reference to a class that was not removed). An attached model starts
/// outside any (`childclass_above`): the childclass of its frame's model is not its.
pub(super) fn childclass_below(above: bool, sets: impl FnOnce() -> bool) -> bool {
    above || sets()
}

/// Rule *childclass scope*: whether an element of instance `inst` is under a
/// `childclass` of its own model, its parent being of instance `parent_inst` with
/// its children under one (`parent_below`) or not.
pub(super) fn childclass_above(parent: Option<(usize, bool)>, inst: usize) -> bool {
    parent.is_some_and(|(parent_inst, parent_below)| parent_below && parent_inst == inst)
}

/// Rule *implicit class*: the attribute slot of `kind` that takes the model's root
/// class name (`class="/"`, `class="robot/"`) when nothing else gives the element a
/// class: it can have one, no `childclass` of its model is above it
/// (`childclass_above`), and it has no class of its own that is written (`own`,
/// asked of the slot only then). Written out, the root class an element falls back
/// on is said, as the reference writes it: an attached model's elements must not
/// fall back on the outermost model's root class. The reader reads it as a
/// reference to the root class.
pub(super) fn implicit_class(
    kind: ElementKind,
    childclass_above: bool,
    own: impl FnOnce(usize) -> bool,
) -> Option<usize> {
    match kind_facts(kind).class {
        Some(c) if !childclass_above && !own(c) => Some(c),
        _ => None,
    }
}

/// What the writer asks of every element's kind, looked up by name once per kind.
pub(super) struct KindFacts {
    /// `kind.class_attr()`.
    pub(super) class: Option<usize>,
    /// The index of `childclass`.
    pub(super) childclass: Option<usize>,
}

/// The [`KindFacts`] of `kind`.
pub(super) fn kind_facts(kind: ElementKind) -> &'static KindFacts {
    static FACTS: std::sync::OnceLock<Vec<KindFacts>> = std::sync::OnceLock::new();
    const NONE: KindFacts = KindFacts { class: None, childclass: None };
    let table = FACTS.get_or_init(|| {
        ElementKind::all()
            .map(|k| KindFacts { class: k.class_attr(), childclass: k.attr_index("childclass") })
            .collect()
    });
    table.get(kind.0 as usize).unwrap_or(&NONE)
}

// ---------------------------------------------------------------------------------
// Attachment frames.

/// Rule *attachment frame tag*: the tag an element is written with. An attachment
/// frame is written as a `<body>` (named by its scope, with the pose copied from
/// its site: `model::naming`), or as MuJoCo's `<frame>` where its parent is in the
/// world (`parent_in_world`) and [`frame_keeps_bodies_top_level`] (decision D10); any
/// other element with its own tag. The reader reads either as an element of that
/// tag (a body with a literal name, decision D13; a `<frame>`, decision D12).
pub(super) fn written_tag(
    node: &Node,
    parent_in_world: bool,
    frames: &mut FrameTags,
) -> &'static str {
    match node.attached() {
        Some(_) if parent_in_world && frames.keeps_bodies_top_level(node) => "frame",
        Some(_) => "body",
        None => node.kind().tag(),
    }
}

/// Rule *world level*: whether the children of an element written as `tag` are in
/// MuJoCo's world (its top-level bodies, where a freejoint may be): the outermost
/// worldbody's (`worldbody`), and a `<frame>`'s in the world (an attachment frame
/// written so, or MuJoCo's own).
pub(super) fn passes_world_on(worldbody: bool, parent_in_world: bool, tag: &str) -> bool {
    worldbody || parent_in_world && tag == "frame"
}

/// Whether an attachment frame in the world is written as MuJoCo's `<frame>` (and the
/// answers a writer keeps): decided in the model, where `Model::check` reads it too.
pub(crate) use crate::model::frame::{FrameTags, frame_keeps_bodies_top_level};

// ---------------------------------------------------------------------------------
// Files.

/// Rule *file names*: a file attribute is written as the file's name in the text's
/// folder, where `Model::export` and `Model::assets` put it (they ask this too): `stem-<sha1>.ext` with
/// [`WriteOptions::filename_with_hash`] (the reference's), `stem.ext` without. The
/// reader reads `stem-<sha1 of the contents>` back as `stem`
/// (`FileAsset::named_as`), so writing it again gives the same name.
pub(in crate::xml) fn file_name(file: &FileAsset, options: &WriteOptions) -> String {
    file.vfs_name(options.filename_with_hash)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::naming::Written;

    /// Every automatic name of the outermost model, replicated and told apart from a
    /// literal name too, is one the reader forgets; an attached model's, an own name
    /// and a root class name are not.
    #[test]
    fn the_reader_forgets_exactly_the_outermost_automatic_names() {
        let mut forgotten = Vec::new();
        for (clash, replicated) in [(0, false), (0, true), (2, false), (1, true)] {
            let auto = Written::Auto { ns: Namespace::Geom, index: 12, clash, replicated };
            forgotten.push(auto.to_string_in(""));
            assert!(!is_auto_name(&auto.to_string_in("robot/")), "{auto:?} in robot/");
        }
        assert!(forgotten.iter().all(|n| is_auto_name(n)), "{forgotten:?}");
        for kept in [Written::Own("unnamed_geom_0"), Written::RootClass, Written::Frame("r")] {
            assert!(!is_auto_name(&kept.to_string_in("")), "{kept:?}");
        }
    }

    /// The wrapper is folded exactly when it holds one class `/` and nothing else
    /// (no attribute either); a composed output is a class `/` beside another class.
    #[test]
    fn the_root_class_rules_tell_the_shapes_apart() {
        use DefaultChild::{Class, Setting};
        let slash = Class(Some("/"));
        assert!(folds_into_root_class(false, [slash]));
        assert!(!folds_into_root_class(true, [slash]));
        assert!(!folds_into_root_class(false, [slash, Setting]));
        assert!(!folds_into_root_class(false, [Setting, slash]));
        assert!(!folds_into_root_class(false, [Class(Some("a"))]));
        assert!(!folds_into_root_class(false, []));
        assert!(is_composed_output([slash, Class(Some("robot/"))]));
        assert!(is_composed_output([Setting, Class(None), slash]));
        assert!(!is_composed_output([slash, Setting]));
        assert!(!is_composed_output([Class(Some("a")), Class(Some("b"))]));
        assert!(is_composed_output([Class(Some("/1")), Class(Some("robot/"))]));
        assert!(!is_composed_output([Class(Some("/x")), Class(Some("robot/"))]));
        assert!(!is_composed_output([Class(Some("/0")), Class(Some("robot/"))]));
    }
}
