//! Model-based property test: random action sequences are replayed against the library
//! and against [`Naive`], a deliberately simple test-only model of dm_control's `mjcf`
//! composition, and after every step the two must agree.
//!
//! Properties run `PROPTEST_CASES` cases (default 2000 here) from a fixed seed (set
//! `PROPTEST_RNG_SEED` to explore others). Failures are not persisted to a file: a case
//! worth keeping becomes a named `#[test]` below.
//!
//! # The naive model
//! A plain mutable tree (`Vec` of children, owned `String`s) that composes the way
//! dm_control does it by hand: `attach` **deep-copies** the child and eagerly rewrites
//! every name (`torso` → `robot/torso`) and every reference attribute (a motor's
//! `joint`) with the scope path + `/`, and inserts a frame body named `robot/` under the
//! site's parent, right after the site and after the frames attached there before (or at
//! the end of the worldbody), with the site's `pos`/`quat` copied onto it. The scope is
//! the child's model name, or `name_1`, `name_2`, ... (the smallest free suffix among the
//! scopes of the model that owns the site: reference §2.7, `free_scope` in
//! `src/compose/attach.rs`). Detach deletes the frame subtree and the scope's (and its
//! nested scopes') actuators and sensors; renaming a scope rewrites every stored prefix.
//! Actuators and sensors live in one flat list ordered like dm_control's containers: the
//! top model's own first, then each scope's in depth-first attach order. Identifier
//! uniqueness is checked on the *prefixed* names per namespace across the whole tree;
//! the joints of an attachment frame form a namespace of their own per frame (reference
//! §1.5, §2.5), rendered `robot/j/` (named) or `robot/` (unnamed). Undo keeps a deep
//! clone of the naive model for every version. The library stores none of this: it keeps
//! the child value shared and derives prefixes, order and frame names when writing.
//!
//! # Actions
//! Add a body/geom/site/joint/freejoint (named from a small alphabet, or unnamed) under
//! the worldbody or any body, frames and bodies inside attachments included; add a motor
//! to the top model or inside an attachment; set `name` (or clear it), `pos`, `size`,
//! `rgba`, or a motor's `joint` on an element; remove an element (inside attachments
//! too); attach one of three small robots (one has a site at its worldbody level, one a
//! site in a body, one a dangling joint reference) at any site, nested ones included, or
//! at the world; detach a scope; rename a scope; undo to an earlier version. Elements
//! are picked by an index into the document-order list of their kind, taken from
//! `Model::find_all` on the library side and from a pre-order walk on the naive side (the
//! two lists must have the same length). An invalid action must be refused by both or
//! by neither.
//!
//! # Canonical form
//! The library's `to_xml_string()` is parsed with `quick_xml` and reduced to: the
//! `<worldbody>` tree, the `<actuator>` list and the `<sensor>` list, each element as
//! (tag, name, every other attribute, children in order), plus the scope paths
//! (`Model::scopes` recursively, depth-first in attach order). Left out: the `class`
//! attribute (the `class="/"`, `class="robot/"` the writer adds), the `<default>` section
//! and every other section. Attribute values made only of numbers compare as `f64`
//! vectors (exactly: the writer prints floats that read back exactly), others as text.
//! An auto-name (`//unnamed_geom_3` at the top, `robot//unnamed_geom_1` in scope
//! `robot`) compares as its scope prefix and namespace (``, `geom`; `robot/`, `geom`)
//! without its index, so unnamed elements are compared by position, but still in the
//! right scope and namespace. The first unnamed joint of a frame is written with its
//! frame's name (`robot/`), unless a named frame joint has that name (decision D14); the
//! other unnamed ones with auto-names. The naive model renders to the same form directly; `Display` prints the
//! form one element per line, which is what a failure shows (with the steps replayed
//! and the library's XML).
//!
//! # What it found
//! Two library bugs, both about the names of an attachment frame's joints, kept below as
//! regression `#[test]`s and fixed: a frame accepted two joints of the same name
//! (`a_frame_refuses_two_joints_of_the_same_name`), and a frame joint could not be
//! renamed to a name a joint of its model has
//! (`a_frame_joint_can_be_renamed_like_a_joint_of_its_model`).

use std::collections::BTreeMap;
use std::fmt;
use std::sync::LazyLock;

use mjcf::{EditError, Element, Loc, Model, Namespace};
use proptest::prelude::*;
use proptest::sample::Index;
use proptest::test_runner::{Config, RngSeed};

/// Element names the actions use: `torso`, `hip` and `m` are also names inside the
/// robots, so adding them inside an attachment clashes.
const NAMES: [&str; 5] = ["a", "b", "torso", "hip", "m"];
/// Names for `rename_scope`: two of them are robot names, one a suffixed robot name.
const SCOPE_NAMES: [&str; 4] = ["robot", "arm", "robot_1", "c"];
/// The reference attributes the actions and robots use (prefixed on attach).
const REF_ATTRS: [&str; 1] = ["joint"];

// ---------------------------------------------------------------------------------
// Attribute values and small string helpers.

/// An attribute value: numbers (compared exactly) or text.
#[derive(Clone, Debug, PartialEq)]
enum Val {
    Num(Vec<f64>),
    Str(String),
}

impl Val {
    /// Numbers if every whitespace-separated token is one, text otherwise.
    fn parse(text: &str) -> Val {
        match text.split_whitespace().map(str::parse::<f64>).collect::<Result<Vec<f64>, _>>() {
            Ok(v) if !v.is_empty() => Val::Num(v),
            _ => Val::Str(text.to_string()),
        }
    }

    fn text(s: &str) -> Val {
        Val::Str(s.to_string())
    }

    fn nums(v: &[f64]) -> Val {
        Val::Num(v.to_vec())
    }
}

impl fmt::Display for Val {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Val::Num(v) => {
                let parts: Vec<String> = v.iter().map(|x| x.to_string()).collect();
                write!(f, "{}", parts.join(" "))
            }
            Val::Str(s) => write!(f, "{s}"),
        }
    }
}

/// `name` inside scope path `scope` (`""` for the top model).
fn scoped(scope: &str, name: &str) -> String {
    if scope.is_empty() { name.to_string() } else { format!("{scope}/{name}") }
}

/// The scope path that holds scope `s` (`a/b` → `a`; `a` → `""`, the top model).
fn parent_scope(s: &str) -> &str {
    s.rsplit_once('/').map_or("", |(p, _)| p)
}

/// The last segment of a scope path.
fn last_segment(s: &str) -> &str {
    s.rsplit_once('/').map_or(s, |(_, l)| l)
}

/// Whether scope path `s` is `scope` or lies inside it.
fn within(s: &str, scope: &str) -> bool {
    s == scope || s.strip_prefix(scope).is_some_and(|rest| rest.starts_with('/'))
}

/// Moves a scope path from scope `old` to `new`, if it lies in `old`.
fn move_scope(s: &mut String, old: &str, new: &str) {
    if within(s, old) {
        *s = format!("{new}{}", &s[old.len()..]);
    }
}

/// Moves a prefixed name or reference from scope `old` to `new`, if it has the prefix
/// `old/`.
fn move_name(s: &mut String, old: &str, new: &str) {
    if let Some(rest) = s.strip_prefix(old).filter(|r| r.starts_with('/')) {
        *s = format!("{new}{rest}");
    }
}

/// Moves an element's stored name, scope and references from scope `old` to `new`.
fn move_element(
    name: &mut Option<String>,
    scope: &mut String,
    attrs: &mut BTreeMap<&'static str, Val>,
    old: &str,
    new: &str,
) {
    if let Some(n) = name {
        move_name(n, old, new);
    }
    move_scope(scope, old, new);
    for (k, v) in attrs {
        if let (true, Val::Str(s)) = (REF_ATTRS.contains(k), v) {
            move_name(s, old, new);
        }
    }
}

/// The identifier namespace of a tag.
fn namespace(tag: &str) -> &str {
    match tag {
        "freejoint" => "joint",
        "motor" => "actuator",
        "jointpos" => "sensor",
        t => t,
    }
}

fn is_joint(tag: &str) -> bool {
    tag == "joint" || tag == "freejoint"
}

// ---------------------------------------------------------------------------------
// The naive model.

/// One element of the naive worldbody tree.
#[derive(Clone, Debug, PartialEq)]
struct NNode {
    tag: &'static str,
    /// The full, prefixed identifier (`robot/torso`); a frame's is `robot/`, a named
    /// frame joint's `robot/j/`. `None` for unnamed elements.
    name: Option<String>,
    /// The scope path of the model the element belongs to (`""` for the top model); a
    /// frame belongs to the model that holds the site.
    scope: String,
    /// The scope path of the attachment, for an attachment frame.
    frame: Option<String>,
    attrs: BTreeMap<&'static str, Val>,
    children: Vec<NNode>,
}

impl NNode {
    fn new(tag: &'static str, name: Option<&str>) -> NNode {
        NNode {
            tag,
            name: name.map(str::to_string),
            scope: String::new(),
            frame: None,
            attrs: BTreeMap::new(),
            children: Vec::new(),
        }
    }

    fn attr(mut self, key: &'static str, v: Val) -> NNode {
        self.attrs.insert(key, v);
        self
    }

    fn child(mut self, c: NNode) -> NNode {
        self.children.push(c);
        self
    }

    fn is_frame(&self) -> bool {
        self.frame.is_some()
    }

    fn holds_frame(&self) -> bool {
        self.is_frame() || self.children.iter().any(NNode::holds_frame)
    }

    /// A deep copy moved into scope `scope`: every name, scope and reference prefixed.
    fn prefixed(&self, scope: &str) -> NNode {
        NNode {
            tag: self.tag,
            name: self.name.as_ref().map(|n| scoped(scope, n)),
            scope: if self.scope.is_empty() {
                scope.to_string()
            } else {
                scoped(scope, &self.scope)
            },
            frame: self.frame.as_ref().map(|f| scoped(scope, f)),
            attrs: self
                .attrs
                .iter()
                .map(|(k, v)| match v {
                    Val::Str(s) if REF_ATTRS.contains(k) => (*k, Val::Str(scoped(scope, s))),
                    v => (*k, v.clone()),
                })
                .collect(),
            children: self.children.iter().map(|c| c.prefixed(scope)).collect(),
        }
    }

    /// Rewrites the stored scope prefix `old` into `new` everywhere in the subtree.
    fn rename_scope(&mut self, old: &str, new: &str) {
        move_element(&mut self.name, &mut self.scope, &mut self.attrs, old, new);
        if let Some(f) = &mut self.frame {
            move_scope(f, old, new);
        }
        for c in &mut self.children {
            c.rename_scope(old, new);
        }
    }
}

/// One actuator or sensor.
#[derive(Clone, Debug, PartialEq)]
struct NItem {
    section: &'static str,
    tag: &'static str,
    name: Option<String>,
    scope: String,
    attrs: BTreeMap<&'static str, Val>,
}

impl NItem {
    fn new(section: &'static str, tag: &'static str, name: Option<&str>) -> NItem {
        NItem {
            section,
            tag,
            name: name.map(str::to_string),
            scope: String::new(),
            attrs: BTreeMap::new(),
        }
    }

    fn attr(mut self, key: &'static str, v: Val) -> NItem {
        self.attrs.insert(key, v);
        self
    }

    fn prefixed(&self, scope: &str) -> NItem {
        let node = NNode {
            tag: self.tag,
            name: self.name.clone(),
            scope: self.scope.clone(),
            frame: None,
            attrs: self.attrs.clone(),
            children: Vec::new(),
        }
        .prefixed(scope);
        NItem {
            section: self.section,
            tag: self.tag,
            name: node.name,
            scope: node.scope,
            attrs: node.attrs,
        }
    }
}

/// The naive model: an owned, mutable tree with eagerly prefixed names.
#[derive(Clone, Debug, PartialEq)]
struct Naive {
    /// The model name (what an attach scopes it by).
    model: String,
    world: Vec<NNode>,
    /// Actuators and sensors, in output order.
    items: Vec<NItem>,
    /// Every scope path, depth first in attach order.
    scopes: Vec<String>,
}

/// Where a picked element lives in the naive model.
#[derive(Clone, Debug)]
enum Target {
    Node(Vec<usize>),
    Item(usize),
}

impl Naive {
    fn new(model: &str) -> Naive {
        Naive { model: model.to_string(), world: Vec::new(), items: Vec::new(), scopes: Vec::new() }
    }

    /// Every element of the worldbody tree in document order: (path, node, whether the
    /// parent is an attachment frame).
    fn walk(&self) -> Vec<(Vec<usize>, &NNode, bool)> {
        fn rec<'a>(
            nodes: &'a [NNode],
            in_frame: bool,
            path: &mut Vec<usize>,
            out: &mut Vec<(Vec<usize>, &'a NNode, bool)>,
        ) {
            for (i, n) in nodes.iter().enumerate() {
                path.push(i);
                out.push((path.clone(), n, in_frame));
                rec(&n.children, n.is_frame(), path, out);
                path.pop();
            }
        }
        let mut out = Vec::new();
        rec(&self.world, false, &mut Vec::new(), &mut out);
        out
    }

    /// The paths of the elements that satisfy `pick`, in document order.
    fn paths(&self, pick: impl Fn(&NNode) -> bool) -> Vec<Vec<usize>> {
        self.walk().into_iter().filter(|(_, n, _)| pick(n)).map(|(p, _, _)| p).collect()
    }

    fn motors(&self) -> Vec<usize> {
        (0..self.items.len()).filter(|&i| self.items[i].section == "actuator").collect()
    }

    fn node(&self, path: &[usize]) -> &NNode {
        let mut n = &self.world[path[0]];
        for &i in &path[1..] {
            n = &n.children[i];
        }
        n
    }

    fn node_mut(&mut self, path: &[usize]) -> &mut NNode {
        let mut n = &mut self.world[path[0]];
        for &i in &path[1..] {
            n = &mut n.children[i];
        }
        n
    }

    /// The child list that holds the element at `path`.
    fn siblings_mut(&mut self, path: &[usize]) -> &mut Vec<NNode> {
        let parent = &path[..path.len() - 1];
        if parent.is_empty() { &mut self.world } else { &mut self.node_mut(parent).children }
    }

    /// Whether the element at `path` is a joint of an attachment frame.
    fn is_frame_joint(&self, path: &[usize]) -> bool {
        let parent = &path[..path.len() - 1];
        is_joint(self.node(path).tag) && !parent.is_empty() && self.node(parent).is_frame()
    }

    /// Whether a (prefixed) identifier is taken in a namespace. Frames and frame joints
    /// are not in the model's namespaces.
    fn taken(&self, ns: &str, name: &str) -> bool {
        let in_tree = self.walk().into_iter().any(|(_, n, in_frame)| {
            !(n.is_frame() || (in_frame && is_joint(n.tag)))
                && namespace(n.tag) == ns
                && n.name.as_deref() == Some(name)
        });
        in_tree
            || self
                .items
                .iter()
                .any(|it| namespace(it.tag) == ns && it.name.as_deref() == Some(name))
    }

    /// The position of a scope in the output order of the sections (0 for the top).
    fn order(&self, scope: &str) -> usize {
        if scope.is_empty() {
            0
        } else {
            1 + self.scopes.iter().position(|s| s == scope).expect("a known scope")
        }
    }

    /// Inserts an (already prefixed) item after every item of its scope and the scopes
    /// before it.
    fn insert_item(&mut self, item: NItem) {
        let k = self.order(&item.scope);
        let at =
            self.items.iter().position(|it| self.order(&it.scope) > k).unwrap_or(self.items.len());
        self.items.insert(at, item);
    }

    /// Adds `node` (unprefixed, without children) under the worldbody (`None`) or the body
    /// or frame at `parent`.
    fn add(&mut self, parent: Option<&[usize]>, mut node: NNode) -> Result<(), String> {
        let tag = node.tag;
        let local = node.name.take();
        let Some(p) = parent else {
            if is_joint(tag) {
                return Err(format!("<worldbody> takes no <{tag}>"));
            }
            node.name = local;
            if let Some(n) = &node.name {
                if self.taken(namespace(tag), n) {
                    return Err(format!("{} {n} exists", namespace(tag)));
                }
            }
            self.world.push(node);
            return Ok(());
        };
        let parent_node = self.node(p);
        node.scope = parent_node.scope.clone();
        if parent_node.is_frame() {
            if !is_joint(tag) {
                return Err(format!("an attachment frame takes no <{tag}>"));
            }
            if tag == "freejoint" {
                // Only on a frame in the worldbody of its model: in the top worldbody, or
                // directly in a frame (the attached model's worldbody content).
                let grand = &p[..p.len() - 1];
                if !(grand.is_empty() || self.node(grand).is_frame()) {
                    return Err("a freejoint needs a frame in a worldbody".into());
                }
                if parent_node.children.iter().any(|c| c.tag == "freejoint") {
                    return Err("the frame has a freejoint".into());
                }
            }
            let frame_name = parent_node.name.clone().expect("frames are named");
            node.name = local.map(|n| format!("{frame_name}{n}/"));
            if let Some(n) = &node.name {
                if parent_node
                    .children
                    .iter()
                    .any(|c| is_joint(c.tag) && c.name.as_ref() == Some(n))
                {
                    return Err(format!("frame joint {n} exists on this frame"));
                }
            }
            // The frame's own joints come before the attached model's content.
            let at = parent_node.children.iter().take_while(|c| is_joint(c.tag)).count();
            self.node_mut(p).children.insert(at, node);
        } else {
            if tag == "freejoint" && parent_node.children.iter().any(|c| c.tag == "freejoint") {
                return Err("the body has a freejoint".into());
            }
            node.name = local.map(|n| scoped(&node.scope, &n));
            if let Some(n) = &node.name {
                if self.taken(namespace(tag), n) {
                    return Err(format!("{} {n} exists", namespace(tag)));
                }
            }
            self.node_mut(p).children.push(node);
        }
        Ok(())
    }

    /// Adds an (unprefixed) item to the model of scope path `scope`.
    fn add_item(&mut self, scope: &str, item: NItem) -> Result<(), String> {
        let item = item.prefixed(scope);
        if let Some(n) = &item.name {
            if self.taken(namespace(item.tag), n) {
                return Err(format!("{} {n} exists", namespace(item.tag)));
            }
        }
        self.insert_item(item);
        Ok(())
    }

    fn set_name(&mut self, t: &Target, local: Option<&str>) -> Result<(), String> {
        match t {
            Target::Node(path) => {
                let node = self.node(path);
                if node.is_frame() {
                    return Err("an attachment frame has no name".into());
                }
                let new = if self.is_frame_joint(path) {
                    let frame = self.node(&path[..path.len() - 1]);
                    let frame_name = frame.name.clone().expect("frames are named");
                    let new = local.map(|n| format!("{frame_name}{n}/"));
                    if new != node.name
                        && new.is_some()
                        && frame.children.iter().any(|c| is_joint(c.tag) && c.name == new)
                    {
                        return Err(format!("frame joint {new:?} exists on this frame"));
                    }
                    new
                } else {
                    let new = local.map(|n| scoped(&node.scope, n));
                    if let (true, Some(n)) = (new != node.name, &new) {
                        if self.taken(namespace(node.tag), n) {
                            return Err(format!("{} {n} exists", namespace(node.tag)));
                        }
                    }
                    new
                };
                self.node_mut(path).name = new;
            }
            Target::Item(i) => {
                let item = &self.items[*i];
                let new = local.map(|n| scoped(&item.scope, n));
                if let (true, Some(n)) = (new != item.name, &new) {
                    if self.taken(namespace(item.tag), n) {
                        return Err(format!("{} {n} exists", namespace(item.tag)));
                    }
                }
                self.items[*i].name = new;
            }
        }
        Ok(())
    }

    /// Sets an attribute (a reference gets the element's scope prefix). Every value the
    /// actions set is valid, so this never refuses.
    fn set_attr(&mut self, t: &Target, key: &'static str, v: Val) -> Result<(), String> {
        let (scope, attrs) = match t {
            Target::Node(path) => {
                let n = self.node_mut(path);
                (n.scope.clone(), &mut n.attrs)
            }
            Target::Item(i) => (self.items[*i].scope.clone(), &mut self.items[*i].attrs),
        };
        let v = match v {
            Val::Str(s) if REF_ATTRS.contains(&key) => Val::Str(scoped(&scope, &s)),
            v => v,
        };
        attrs.insert(key, v);
        Ok(())
    }

    fn remove(&mut self, t: &Target) -> Result<(), String> {
        match t {
            Target::Node(path) => {
                if self.node(path).holds_frame() {
                    return Err("the subtree holds an attachment frame".into());
                }
                let last = path[path.len() - 1];
                self.siblings_mut(path).remove(last);
            }
            Target::Item(i) => {
                self.items.remove(*i);
            }
        }
        Ok(())
    }

    /// Attaches a deep copy of `child` at the site at `site`, or at the world; returns
    /// the new scope path.
    fn attach(&mut self, child: &Naive, site: Option<&[usize]>) -> Result<String, String> {
        let owner = site.map_or(String::new(), |p| self.node(p).scope.clone());
        let taken: Vec<&str> = self
            .scopes
            .iter()
            .filter(|s| parent_scope(s) == owner)
            .map(|s| last_segment(s))
            .collect();
        let base = child.model.as_str();
        let mut name = base.to_string();
        let mut n = 1;
        while taken.contains(&name.as_str()) {
            name = format!("{base}_{n}");
            n += 1;
        }
        let full = scoped(&owner, &name);
        let mut frame = NNode::new("body", Some(&format!("{full}/")));
        frame.scope = owner.clone();
        frame.frame = Some(full.clone());
        frame.children = child.world.iter().map(|c| c.prefixed(&full)).collect();
        match site {
            None => self.world.push(frame),
            Some(p) => {
                for key in ["pos", "quat"] {
                    if let Some(v) = self.node(p).attrs.get(key) {
                        frame.attrs.insert(key, v.clone());
                    }
                }
                let siblings = self.siblings_mut(p);
                let mut at = p[p.len() - 1] + 1;
                while siblings.get(at).is_some_and(NNode::is_frame) {
                    at += 1;
                }
                siblings.insert(at, frame);
            }
        }
        // Depth first in attach order: after the owner and everything inside it.
        let at = if owner.is_empty() {
            self.scopes.len()
        } else {
            1 + self.scopes.iter().rposition(|s| within(s, &owner)).expect("the owner is a scope")
        };
        self.scopes.insert(at, full.clone());
        for (i, s) in child.scopes.iter().enumerate() {
            self.scopes.insert(at + 1 + i, scoped(&full, s));
        }
        for item in &child.items {
            self.insert_item(item.prefixed(&full));
        }
        Ok(full)
    }

    fn detach(&mut self, scope: &str) -> Result<(), String> {
        let path = self
            .walk()
            .into_iter()
            .find(|(_, n, _)| n.frame.as_deref() == Some(scope))
            .map(|(p, _, _)| p)
            .ok_or_else(|| format!("{scope} is not attached"))?;
        let last = path[path.len() - 1];
        self.siblings_mut(&path).remove(last);
        self.scopes.retain(|s| !within(s, scope));
        self.items.retain(|it| !within(&it.scope, scope));
        Ok(())
    }

    fn rename_scope(&mut self, scope: &str, to: &str) -> Result<(), String> {
        let parent = parent_scope(scope);
        if self.scopes.iter().any(|s| parent_scope(s) == parent && last_segment(s) == to) {
            return Err(format!("scope {to} exists"));
        }
        let new = scoped(parent, to);
        for n in &mut self.world {
            n.rename_scope(scope, &new);
        }
        for it in &mut self.items {
            move_element(&mut it.name, &mut it.scope, &mut it.attrs, scope, &new);
        }
        for s in &mut self.scopes {
            move_scope(s, scope, &new);
        }
        Ok(())
    }

    /// The canonical form.
    fn canon(&self) -> Canon {
        // The names of the named frame joints: an unnamed frame joint is written with
        // its frame's name (the first of its frame) unless one of them has that name
        // (a joint `a` of the frame holding a model with an attachment `a`).
        fn named_frame_joints(n: &NNode, out: &mut Vec<String>) {
            for c in &n.children {
                if n.is_frame() && is_joint(c.tag) {
                    out.extend(c.name.clone());
                }
                named_frame_joints(c, out);
            }
        }
        let mut taken = Vec::new();
        self.world.iter().for_each(|n| named_frame_joints(n, &mut taken));
        let node = |n: &NNode, frame_name: Option<&str>| -> CNode {
            fn node(n: &NNode, frame_name: Option<&str>, taken: &[String]) -> CNode {
                let name = match (&n.name, frame_name) {
                    (Some(s), _) => CName::Named(s.clone()),
                    // The first unnamed frame joint (marked by its frame's name).
                    (None, Some(f)) => CName::Named(f.to_string()),
                    (None, None) => auto_name(&n.scope, n.tag),
                };
                let first_unnamed = n
                    .children
                    .iter()
                    .position(|c| is_joint(c.tag) && c.name.is_none())
                    .filter(|_| n.is_frame())
                    .filter(|_| !n.name.as_ref().is_some_and(|f| taken.contains(f)));
                let children = n
                    .children
                    .iter()
                    .enumerate()
                    .map(|(i, c)| {
                        let f = if first_unnamed == Some(i) { n.name.as_deref() } else { None };
                        node(c, f, taken)
                    })
                    .collect();
                CNode {
                    tag: n.tag.to_string(),
                    name,
                    attrs: n.attrs.iter().map(|(k, v)| (k.to_string(), v.clone())).collect(),
                    children,
                }
            }
            node(n, frame_name, &taken)
        };
        let items = |section: &str| -> Vec<CNode> {
            self.items
                .iter()
                .filter(|it| it.section == section)
                .map(|it| CNode {
                    tag: it.tag.to_string(),
                    name: it
                        .name
                        .clone()
                        .map_or_else(|| auto_name(&it.scope, it.tag), CName::Named),
                    attrs: it.attrs.iter().map(|(k, v)| (k.to_string(), v.clone())).collect(),
                    children: Vec::new(),
                })
                .collect()
        };
        Canon {
            worldbody: self.world.iter().map(|n| node(n, None)).collect(),
            actuator: items("actuator"),
            sensor: items("sensor"),
            scopes: self.scopes.clone(),
        }
    }
}

fn auto_name(scope: &str, tag: &str) -> CName {
    let prefix = if scope.is_empty() { String::new() } else { format!("{scope}/") };
    CName::Auto { prefix, ns: namespace(tag).to_string() }
}

// ---------------------------------------------------------------------------------
// The canonical form.

#[derive(Clone, Debug, PartialEq)]
enum CName {
    None,
    Named(String),
    /// An auto-name `P/unnamed_<ns>_<i>`, without its index.
    Auto {
        prefix: String,
        ns: String,
    },
}

#[derive(Clone, Debug, PartialEq)]
struct CNode {
    tag: String,
    name: CName,
    attrs: BTreeMap<String, Val>,
    children: Vec<CNode>,
}

#[derive(Clone, Debug, PartialEq)]
struct Canon {
    worldbody: Vec<CNode>,
    actuator: Vec<CNode>,
    sensor: Vec<CNode>,
    scopes: Vec<String>,
}

impl fmt::Display for Canon {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fn node(f: &mut fmt::Formatter<'_>, n: &CNode, depth: usize) -> fmt::Result {
            write!(f, "{:width$}{}", "", n.tag, width = 2 * depth)?;
            match &n.name {
                CName::None => {}
                CName::Named(s) => write!(f, " name={s}")?,
                CName::Auto { prefix, ns } => write!(f, " auto({prefix},{ns})")?,
            }
            for (k, v) in &n.attrs {
                write!(f, " {k}={v}")?;
            }
            writeln!(f)?;
            n.children.iter().try_for_each(|c| node(f, c, depth + 1))
        }
        for (title, list) in
            [("worldbody", &self.worldbody), ("actuator", &self.actuator), ("sensor", &self.sensor)]
        {
            writeln!(f, "{title}:")?;
            list.iter().try_for_each(|n| node(f, n, 1))?;
        }
        writeln!(f, "scopes: {}", self.scopes.join(" "))
    }
}

/// The name attribute as written: an auto-name `P/unnamed_<ns>_<i>` (the `/` before
/// `unnamed_` cannot come from a user identifier) loses its index.
fn classify(name: &str) -> CName {
    if let Some(i) = name.find("/unnamed_") {
        let rest = &name[i + "/unnamed_".len()..];
        if let Some((ns, index)) = rest.rsplit_once('_') {
            if name[..i].ends_with('/') && index.parse::<usize>().is_ok() {
                let prefix = if &name[..i] == "/" { "" } else { &name[..i] };
                return CName::Auto { prefix: prefix.to_string(), ns: ns.to_string() };
            }
        }
    }
    CName::Named(name.to_string())
}

/// A parsed XML element.
#[derive(Debug, Default)]
struct XNode {
    tag: String,
    attrs: Vec<(String, String)>,
    children: Vec<XNode>,
}

fn parse_xml(xml: &str) -> Result<XNode, String> {
    use quick_xml::events::{BytesStart, Event};
    fn open(t: &BytesStart<'_>) -> Result<XNode, String> {
        let mut attrs = Vec::new();
        for a in t.attributes() {
            let a = a.map_err(|e| e.to_string())?;
            let v =
                a.normalized_value(quick_xml::XmlVersion::default()).map_err(|e| e.to_string())?;
            attrs.push((a.key.as_ref().to_string(), v.to_string()));
        }
        // An attachment frame written as MuJoCo's `<frame>` (decision D10: its model's
        // top-level bodies carry freejoints) is the same attachment frame as a `<body>`
        // here: the naive model knows no D10, and these models hold no other frames.
        let tag = match t.name().as_ref() {
            "frame" => "body".to_string(),
            other => other.to_string(),
        };
        Ok(XNode { tag, attrs, children: Vec::new() })
    }
    let mut reader = quick_xml::Reader::from_str(xml);
    let mut stack = vec![XNode::default()];
    loop {
        match reader.read_event().map_err(|e| e.to_string())? {
            Event::Start(t) => stack.push(open(&t)?),
            Event::Empty(t) => {
                let n = open(&t)?;
                stack.last_mut().ok_or("unbalanced")?.children.push(n);
            }
            Event::End(_) => {
                let n = stack.pop().ok_or("unbalanced")?;
                stack.last_mut().ok_or("unbalanced")?.children.push(n);
            }
            Event::Eof => break,
            _ => {}
        }
    }
    let mut doc = stack.pop().ok_or("unbalanced")?;
    if !stack.is_empty() || doc.children.len() != 1 {
        return Err("not one root element".into());
    }
    Ok(doc.children.remove(0))
}

/// Every scope path of the composition, depth first in attach order.
fn lib_scopes(m: &Model) -> Vec<String> {
    fn rec(m: &Model, prefix: &str, out: &mut Vec<String>) {
        for s in m.scopes() {
            let path = format!("{prefix}{s}");
            out.push(path.clone());
            if let Ok(inner) = m.attached(s) {
                rec(inner, &format!("{path}/"), out);
            }
        }
    }
    let mut out = Vec::new();
    rec(m, "", &mut out);
    out
}

/// The canonical form of the library's output `xml` of `m`.
fn lib_canon(m: &Model, xml: &str) -> Result<Canon, String> {
    fn node(x: &XNode) -> CNode {
        let mut name = CName::None;
        let mut attrs = BTreeMap::new();
        for (k, v) in &x.attrs {
            match k.as_str() {
                "name" => name = classify(v),
                "class" => {}
                _ => {
                    attrs.insert(k.clone(), Val::parse(v));
                }
            }
        }
        CNode { tag: x.tag.clone(), name, attrs, children: x.children.iter().map(node).collect() }
    }
    let root = parse_xml(xml)?;
    if root.tag != "mujoco" {
        return Err(format!("root element <{}>", root.tag));
    }
    let section = |tag: &str| -> Vec<CNode> {
        root.children
            .iter()
            .filter(|c| c.tag == tag)
            .flat_map(|c| c.children.iter().map(node))
            .collect()
    };
    Ok(Canon {
        worldbody: section("worldbody"),
        actuator: section("actuator"),
        sensor: section("sensor"),
        scopes: lib_scopes(m),
    })
}

// ---------------------------------------------------------------------------------
// Building the same things on both sides.

/// The library element for a naive node (unprefixed).
fn element_of(n: &NNode) -> Element {
    let mut e = Element::new(n.tag);
    if let Some(name) = &n.name {
        e = e.attr("name", name.as_str());
    }
    for (k, v) in &n.attrs {
        e = match v {
            Val::Num(x) => e.attr(k, x.clone()),
            Val::Str(s) => e.attr(k, s.as_str()),
        };
    }
    n.children.iter().fold(e, |e, c| e.child(element_of(c)))
}

fn element_of_item(it: &NItem) -> Element {
    element_of(&NNode {
        tag: it.tag,
        name: it.name.clone(),
        scope: String::new(),
        frame: None,
        attrs: it.attrs.clone(),
        children: Vec::new(),
    })
}

/// The library model for a naive model without attachments.
fn lib_of(n: &Naive) -> Model {
    assert!(n.scopes.is_empty(), "only plain models are built on both sides");
    let mut m = Model::new(&n.model);
    for node in &n.world {
        m = m.add(&m.worldbody(), element_of(node)).expect("a valid robot").0;
    }
    for it in &n.items {
        let section = m.section(it.section).expect("a section");
        m = m.add(&section, element_of_item(it)).expect("a valid robot").0;
    }
    m
}

fn some(s: &str) -> Option<&str> {
    Some(s)
}

/// `robot`: a body with a slide joint, two geoms (one unnamed) and a site in the body;
/// a motor on the joint.
fn naive_robot() -> Naive {
    let mut r = Naive::new("robot");
    r.world.push(
        NNode::new("body", some("torso"))
            .attr("pos", Val::nums(&[0.0, 0.0, 0.1]))
            .child(
                NNode::new("joint", some("slide"))
                    .attr("type", Val::text("slide"))
                    .attr("axis", Val::nums(&[1.0, 0.0, 0.0])),
            )
            .child(
                NNode::new("geom", some("torso"))
                    .attr("type", Val::text("box"))
                    .attr("size", Val::nums(&[0.1, 0.1, 0.1])),
            )
            .child(
                NNode::new("geom", None)
                    .attr("type", Val::text("sphere"))
                    .attr("size", Val::nums(&[0.05]))
                    .attr("rgba", Val::nums(&[1.0, 0.0, 0.0, 1.0])),
            )
            .child(NNode::new("site", some("mount")).attr("pos", Val::nums(&[0.0, 0.0, 0.2]))),
    );
    r.items.push(NItem::new("actuator", "motor", some("m")).attr("joint", Val::text("slide")));
    r
}

/// `arm`: a site with a pose at the worldbody level, two nested bodies with joints, an
/// unnamed motor, and a sensor.
fn naive_arm() -> Naive {
    let mut r = Naive::new("arm");
    r.world.push(
        NNode::new("site", some("base"))
            .attr("pos", Val::nums(&[0.0, 0.0, 0.05]))
            .attr("quat", Val::nums(&[0.0, 1.0, 0.0, 0.0])),
    );
    r.world.push(
        NNode::new("body", some("upper"))
            .child(NNode::new("joint", some("hip")).attr("type", Val::text("hinge")))
            .child(NNode::new("geom", None).attr("size", Val::nums(&[0.05])))
            .child(
                NNode::new("body", some("lower"))
                    .attr("pos", Val::nums(&[0.0, 0.0, 0.3]))
                    .child(NNode::new("joint", some("knee")))
                    .child(NNode::new("geom", some("tip")).attr("size", Val::nums(&[0.02])))
                    .child(NNode::new("site", some("hand"))),
            ),
    );
    r.items.push(NItem::new("actuator", "motor", some("hip")).attr("joint", Val::text("hip")));
    r.items.push(NItem::new("actuator", "motor", None).attr("joint", Val::text("knee")));
    r.items.push(NItem::new("sensor", "jointpos", some("hip_pos")).attr("joint", Val::text("hip")));
    r
}

/// `robot_1` (the name an attach gives the second `robot`): a ball and a site at the
/// worldbody level, and a motor whose joint does not exist.
fn naive_ball() -> Naive {
    let mut r = Naive::new("robot_1");
    r.world.push(
        NNode::new("body", some("ball"))
            .child(NNode::new("joint", some("roll")).attr("type", Val::text("ball")))
            .child(
                NNode::new("geom", some("ball"))
                    .attr("type", Val::text("sphere"))
                    .attr("size", Val::nums(&[0.1])),
            ),
    );
    r.world.push(NNode::new("site", some("tip")).attr("pos", Val::nums(&[0.0, 0.0, 0.1])));
    r.items.push(NItem::new("actuator", "motor", some("m")).attr("joint", Val::text("ghost")));
    r
}

/// The robots, as naive models and as library values.
struct Robots {
    naive: Vec<Naive>,
    lib: Vec<Model>,
}

impl Robots {
    fn new() -> Robots {
        let naive = vec![naive_robot(), naive_arm(), naive_ball()];
        let lib = naive.iter().map(lib_of).collect();
        Robots { naive, lib }
    }
}

/// The starting scene: a site to attach at.
fn start() -> Naive {
    let mut n = Naive::new("scene");
    n.world.push(NNode::new("site", some("spawn")).attr("pos", Val::nums(&[0.0, 0.0, 0.5])));
    n.world.push(
        NNode::new("body", some("base"))
            .attr("pos", Val::nums(&[1.0, 0.0, 0.0]))
            .child(NNode::new("geom", None).attr("size", Val::nums(&[0.2])))
            .child(NNode::new("site", some("s")).attr("pos", Val::nums(&[0.0, 0.0, 0.3]))),
    );
    n
}

// ---------------------------------------------------------------------------------
// Actions.

#[derive(Clone, Copy, Debug)]
enum Kind {
    Body,
    Geom,
    Site,
    Joint,
    Freejoint,
}

impl Kind {
    /// A new element of this kind, as the actions add it (unprefixed).
    fn fresh(self, name: Option<usize>) -> NNode {
        let name = name.map(|i| NAMES[i]);
        match self {
            Kind::Body => NNode::new("body", name),
            Kind::Geom => NNode::new("geom", name).attr("size", Val::nums(&[0.05])),
            Kind::Site => NNode::new("site", name),
            Kind::Joint => NNode::new("joint", name),
            Kind::Freejoint => NNode::new("freejoint", name),
        }
    }
}

/// Which list an element is picked from (every element of that kind, in document order,
/// inside attachments too; bodies include frames, joints include frame joints).
#[derive(Clone, Copy, Debug, PartialEq)]
enum PickKind {
    Body,
    /// Attachment frames only.
    Frame,
    Geom,
    Site,
    Joint,
    Motor,
}

#[derive(Clone, Debug)]
enum Change {
    /// Set the name (`None`: clear it).
    Name(Option<usize>),
    Pos([f64; 3]),
    Size(Vec<f64>),
    Rgba([f64; 4]),
    /// A motor's `joint` reference (a plain name, prefixed by the motor's scope).
    MotorJoint(usize),
}

impl fmt::Display for Change {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Change::Name(Some(i)) => write!(f, "name={}", NAMES[*i]),
            Change::Name(None) => write!(f, "name=(cleared)"),
            Change::Pos(p) => write!(f, "pos={}", Val::nums(p)),
            Change::Size(v) => write!(f, "size={}", Val::nums(v)),
            Change::Rgba(c) => write!(f, "rgba={}", Val::nums(c)),
            Change::MotorJoint(j) => write!(f, "joint={}", NAMES[*j]),
        }
    }
}

#[derive(Clone, Debug)]
enum Action {
    /// Add an element under the worldbody (`None`) or a picked body or frame.
    Add {
        kind: Kind,
        parent: Option<(PickKind, Index)>,
        name: Option<usize>,
    },
    /// Add a motor to the top model (`None`) or to a picked scope.
    AddMotor {
        scope: Option<Index>,
        name: Option<usize>,
        joint: usize,
    },
    Set {
        pick: PickKind,
        at: Index,
        change: Change,
    },
    Remove {
        pick: PickKind,
        at: Index,
    },
    /// Attach robot `robot` at a picked site, or at the world (`None`).
    Attach {
        robot: usize,
        at: Option<Index>,
    },
    Detach {
        scope: Index,
    },
    RenameScope {
        scope: Index,
        to: usize,
    },
    /// Go back to a picked earlier version.
    Undo {
        to: Index,
    },
}

fn name() -> impl Strategy<Value = Option<usize>> {
    prop::option::weighted(0.75, 0..NAMES.len())
}

fn coord() -> impl Strategy<Value = f64> {
    prop_oneof![3 => -2.0..2.0f64, 1 => Just(0.0), 1 => Just(0.1)]
}

fn kind() -> impl Strategy<Value = Kind> {
    prop_oneof![3 => Just(Kind::Body), 3 => Just(Kind::Geom), 2 => Just(Kind::Site), 2 => Just(Kind::Joint), 1 => Just(Kind::Freejoint)]
}

/// What is added to a frame: mostly joints, sometimes something a frame refuses.
fn frame_kind() -> impl Strategy<Value = Kind> {
    prop_oneof![3 => Just(Kind::Joint), 2 => Just(Kind::Freejoint), 1 => Just(Kind::Geom)]
}

fn change_for(pick: PickKind) -> BoxedStrategy<Change> {
    let name = name().prop_map(Change::Name);
    let pos = prop::array::uniform3(coord()).prop_map(Change::Pos);
    let size = prop::collection::vec(0.01..1.0f64, 1..=3).prop_map(Change::Size);
    let rgba = prop::array::uniform4(0.0..=1.0f64).prop_map(Change::Rgba);
    match pick {
        PickKind::Body | PickKind::Frame => prop_oneof![name, pos].boxed(),
        PickKind::Geom => prop_oneof![name, pos, size, rgba].boxed(),
        PickKind::Site => prop_oneof![name, pos, rgba].boxed(),
        PickKind::Joint => name.boxed(),
        PickKind::Motor => prop_oneof![name, (0..NAMES.len()).prop_map(Change::MotorJoint)].boxed(),
    }
}

fn pick_kind() -> impl Strategy<Value = PickKind> {
    prop_oneof![
        Just(PickKind::Body),
        Just(PickKind::Geom),
        Just(PickKind::Site),
        Just(PickKind::Joint),
        Just(PickKind::Motor)
    ]
}

fn action() -> impl Strategy<Value = Action> {
    prop_oneof![
        5 => (kind(), prop::option::weighted(0.8, any::<Index>()), name())
            .prop_map(|(kind, parent, name)| Action::Add { kind, parent: parent.map(|i| (PickKind::Body, i)), name }),
        2 => (frame_kind(), any::<Index>(), name())
            .prop_map(|(kind, at, name)| Action::Add { kind, parent: Some((PickKind::Frame, at)), name }),
        1 => (prop::option::of(any::<Index>()), name(), 0..NAMES.len())
            .prop_map(|(scope, name, joint)| Action::AddMotor { scope, name, joint }),
        4 => (pick_kind(), any::<Index>())
            .prop_flat_map(|(pick, at)| change_for(pick).prop_map(move |change| Action::Set { pick, at, change })),
        2 => (pick_kind(), any::<Index>()).prop_map(|(pick, at)| Action::Remove { pick, at }),
        4 => (0..3usize, prop::option::weighted(0.7, any::<Index>())).prop_map(|(robot, at)| Action::Attach { robot, at }),
        1 => any::<Index>().prop_map(|scope| Action::Detach { scope }),
        1 => (any::<Index>(), 0..SCOPE_NAMES.len()).prop_map(|(scope, to)| Action::RenameScope { scope, to }),
        1 => any::<Index>().prop_map(|to| Action::Undo { to }),
    ]
}

// ---------------------------------------------------------------------------------
// Replaying an action on both sides.

/// Picks elements by index on both sides, from the document-order list of one kind.
struct Picker<'a> {
    lib: &'a Model,
    naive: &'a Naive,
}

impl Picker<'_> {
    /// The picked element on both sides, or `None` if there is none of that kind. The
    /// two lists must have the same length.
    fn pick(&self, kind: PickKind, at: &Index) -> Result<Option<(Target, Loc)>, String> {
        let nodes = |pick: fn(&NNode) -> bool| {
            self.naive.paths(pick).into_iter().map(Target::Node).collect()
        };
        let (n, l): (Vec<Target>, Vec<Loc>) = match kind {
            PickKind::Body => (nodes(|n| n.tag == "body"), self.lib.find_all(Namespace::Body)),
            PickKind::Frame => {
                let frames = self.lib.find_all(Namespace::Body).into_iter();
                (
                    nodes(NNode::is_frame),
                    frames.filter(|l| self.lib.scope_of_frame(l).is_some()).collect(),
                )
            }
            PickKind::Geom => (nodes(|n| n.tag == "geom"), self.lib.find_all(Namespace::Geom)),
            PickKind::Site => (nodes(|n| n.tag == "site"), self.lib.find_all(Namespace::Site)),
            PickKind::Joint => (nodes(|n| is_joint(n.tag)), self.lib.find_all(Namespace::Joint)),
            PickKind::Motor => (
                self.naive.motors().into_iter().map(Target::Item).collect(),
                self.lib.find_all(Namespace::Actuator),
            ),
        };
        if n.len() != l.len() {
            return Err(format!(
                "{kind:?} list: the naive model has {}, find_all gives {}",
                n.len(),
                l.len()
            ));
        }
        if n.is_empty() {
            return Ok(None);
        }
        let i = at.index(n.len());
        Ok(Some((n[i].clone(), l[i].clone())))
    }

    /// A picked scope path (the scope lists are compared after every step).
    fn scope(&self, at: &Index) -> Option<&str> {
        let scopes = &self.naive.scopes;
        if scopes.is_empty() { None } else { Some(&scopes[at.index(scopes.len())]) }
    }
}

/// A readable name for a picked naive element.
fn describe(naive: &Naive, t: &Target) -> String {
    let (tag, name) = match t {
        Target::Node(p) => (naive.node(p).tag, naive.node(p).name.clone()),
        Target::Item(i) => (naive.items[*i].tag, naive.items[*i].name.clone()),
    };
    format!("<{tag} {}>", name.unwrap_or_else(|| format!("unnamed {t:?}")))
}

/// One replayed action: what it was, and each side's result.
struct Outcome {
    what: String,
    lib: Result<Model, EditError>,
    naive: Result<Naive, String>,
}

/// Applies `a` (not `Undo`) to both sides; `Ok(None)` if there was nothing to pick.
fn apply(
    a: &Action,
    lib: &Model,
    naive: &Naive,
    robots: &Robots,
) -> Result<Option<Outcome>, String> {
    let picker = Picker { lib, naive };
    let mut n = naive.clone();
    let out = match a {
        Action::Add { kind, parent, name } => {
            let node = kind.fresh(*name);
            let (np, lp, where_) = match parent {
                None => (None, lib.worldbody(), "worldbody".to_string()),
                Some((pick, i)) => match picker.pick(*pick, i)? {
                    Some((Target::Node(p), loc)) => {
                        let where_ = describe(naive, &Target::Node(p.clone()));
                        (Some(p), loc, where_)
                    }
                    _ => return Ok(None),
                },
            };
            let element = element_of(&node);
            Outcome {
                what: format!(
                    "add <{} {}> to {where_}",
                    node.tag,
                    node.name.as_deref().unwrap_or("(unnamed)")
                ),
                lib: lib.add(&lp, element).map(|(m, _)| m),
                naive: n.add(np.as_deref(), node).map(|()| n),
            }
        }
        Action::AddMotor { scope, name, joint } => {
            let item = NItem::new("actuator", "motor", name.map(|i| NAMES[i]))
                .attr("joint", Val::text(NAMES[*joint]));
            let (s, loc) = match scope {
                None => (String::new(), lib.actuator()),
                Some(i) => {
                    let Some(s) = picker.scope(i) else { return Ok(None) };
                    let inner =
                        lib.attached(s).ok().ok_or_else(|| format!("library lost scope {s}"))?;
                    let loc = lib
                        .locate_in(s, &inner.actuator())
                        .ok()
                        .ok_or_else(|| format!("no locator in {s}"))?;
                    (s.to_string(), loc)
                }
            };
            let element = element_of_item(&item);
            Outcome {
                what: format!(
                    "add <motor {}> on {} in scope {s:?}",
                    item.name.as_deref().unwrap_or("(unnamed)"),
                    NAMES[*joint]
                ),
                lib: lib.add(&loc, element).map(|(m, _)| m),
                naive: n.add_item(&s, item).map(|()| n),
            }
        }
        Action::Set { pick, at, change } => {
            let Some((t, loc)) = picker.pick(*pick, at)? else { return Ok(None) };
            let what = format!("set {change} on {}", describe(naive, &t));
            let (lib, naive) = match change {
                Change::Name(Some(i)) => {
                    (lib.set_attr(&loc, "name", NAMES[*i]), n.set_name(&t, Some(NAMES[*i])))
                }
                Change::Name(None) => (lib.clear_attr(&loc, "name"), n.set_name(&t, None)),
                Change::Pos(p) => {
                    (lib.set_attr(&loc, "pos", *p), n.set_attr(&t, "pos", Val::nums(p)))
                }
                Change::Size(s) => {
                    (lib.set_attr(&loc, "size", s.clone()), n.set_attr(&t, "size", Val::nums(s)))
                }
                Change::Rgba(c) => {
                    (lib.set_attr(&loc, "rgba", *c), n.set_attr(&t, "rgba", Val::nums(c)))
                }
                Change::MotorJoint(j) => (
                    lib.set_attr(&loc, "joint", NAMES[*j]),
                    n.set_attr(&t, "joint", Val::text(NAMES[*j])),
                ),
            };
            Outcome { what, lib, naive: naive.map(|()| n) }
        }
        Action::Remove { pick, at } => {
            let Some((t, loc)) = picker.pick(*pick, at)? else { return Ok(None) };
            Outcome {
                what: format!("remove {}", describe(naive, &t)),
                lib: lib.remove(&loc),
                naive: n.remove(&t).map(|()| n),
            }
        }
        Action::Attach { robot, at } => {
            let child = &robots.lib[*robot];
            let (lib, naive, where_) = match at {
                None => (
                    lib.attach_to_world(child),
                    n.attach(&robots.naive[*robot], None),
                    "world".to_string(),
                ),
                Some(i) => {
                    let Some((t, loc)) = picker.pick(PickKind::Site, i)? else { return Ok(None) };
                    let Target::Node(p) = &t else { unreachable!("sites are nodes") };
                    (
                        lib.attach(&loc, child),
                        n.attach(&robots.naive[*robot], Some(p)),
                        describe(naive, &t),
                    )
                }
            };
            Outcome {
                what: format!("attach {} at {where_}", child.name()),
                lib: lib.map(|(m, _)| m),
                naive: naive.map(|_| n),
            }
        }
        Action::Detach { scope } => {
            let Some(s) = picker.scope(scope) else { return Ok(None) };
            Outcome {
                what: format!("detach {s}"),
                lib: lib.detach(s),
                naive: n.detach(s).map(|()| n),
            }
        }
        Action::RenameScope { scope, to } => {
            let Some(s) = picker.scope(scope) else { return Ok(None) };
            let to = SCOPE_NAMES[*to];
            Outcome {
                what: format!("rename scope {s} to {to}"),
                lib: lib.rename_scope(s, to),
                naive: n.rename_scope(s, to).map(|()| n),
            }
        }
        Action::Undo { .. } => unreachable!("undo is handled by the replay loop"),
    };
    Ok(Some(out))
}

/// Replays `actions` on both sides from the starting scene; after every step the two
/// must agree on acceptance and on the canonical form.
fn replay(actions: &[Action], robots: &Robots) -> Result<(), String> {
    let naive = start();
    let lib = lib_of(&naive);
    let xml = lib.to_xml_string().map_err(|e| e.to_string())?;
    // Every version: the library value, the naive model, and the library's output then.
    let mut history: Vec<(Model, Naive, String)> = vec![(lib, naive, xml)];
    let mut log: Vec<String> = Vec::new();
    let fail = |log: &[String], msg: String| -> String {
        format!("{msg}\nsteps:\n  {}", log.join("\n  "))
    };
    for (step, a) in actions.iter().enumerate() {
        if let Action::Undo { to } = a {
            let i = to.index(history.len());
            history.truncate(i + 1);
            log.push(format!("{step}: undo to version {i}"));
            // The old value is as it was, whatever was done since.
            let (lib, _, xml) = &history[i];
            let now = lib.to_xml_string().map_err(|e| fail(&log, e.to_string()))?;
            if &now != xml {
                return Err(fail(
                    &log,
                    format!("version {i} changed after the fact:\nwas:\n{xml}\nnow:\n{now}"),
                ));
            }
            continue;
        }
        let (lib, naive, _) = history.last().expect("the start is never dropped");
        let Some(out) = apply(a, lib, naive, robots).map_err(|e| fail(&log, e))? else {
            log.push(format!("{step}: {a:?}: nothing to pick"));
            continue;
        };
        match (out.lib, out.naive) {
            (Ok(l), Ok(n)) => {
                log.push(format!("{step}: {} -> ok", out.what));
                let xml =
                    l.to_xml_string().map_err(|e| fail(&log, format!("writing failed: {e}")))?;
                let got = lib_canon(&l, &xml).map_err(|e| fail(&log, format!("{e} in\n{xml}")))?;
                let want = n.canon();
                if got != want {
                    return Err(fail(
                        &log,
                        format!(
                            "library and naive model differ\nlibrary:\n{got}naive:\n{want}library XML:\n{xml}"
                        ),
                    ));
                }
                history.push((l, n, xml));
            }
            (Err(e), Err(why)) => {
                log.push(format!("{step}: {} -> refused by both ({e}; naive: {why})", out.what));
                // A refused edit leaves the value as it was (and, values being
                // persistent, so does every later edit).
                let (lib, _, xml) = history.last().expect("the start is never dropped");
                let now = lib.to_xml_string().map_err(|e| fail(&log, e.to_string()))?;
                if &now != xml {
                    return Err(fail(
                        &log,
                        format!("the refused edit changed the value:\nwas:\n{xml}\nnow:\n{now}"),
                    ));
                }
            }
            (Ok(_), Err(why)) => {
                return Err(fail(
                    &log,
                    format!(
                        "{step}: {}: the library accepts what the naive model refuses ({why})",
                        out.what
                    ),
                ));
            }
            (Err(e), Ok(_)) => {
                return Err(fail(
                    &log,
                    format!(
                        "{step}: {}: the library refuses ({e}), the naive model accepts",
                        out.what
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// Built once: every case attaches the same values.
static ROBOTS: LazyLock<Robots> = LazyLock::new(Robots::new);

fn config() -> Config {
    let cases = std::env::var("PROPTEST_CASES").ok().and_then(|c| c.parse().ok()).unwrap_or(2000);
    let mut c = Config { cases, failure_persistence: None, ..Config::default() };
    if std::env::var_os("PROPTEST_RNG_SEED").is_none() {
        c.rng_seed = RngSeed::Fixed(0x006d_6f64_656c);
    }
    c
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn library_agrees_with_the_naive_model(actions in prop::collection::vec(action(), 1..24)) {
        if let Err(msg) = replay(&actions, &ROBOTS) {
            prop_assert!(false, "{}", msg);
        }
    }
}

// ---------------------------------------------------------------------------------
// The oracle itself, against hand-written expectations (and the library with it).

/// The path of the element named `name` (prefixed) in the naive tree.
fn path_of(n: &Naive, name: &str) -> Vec<usize> {
    n.paths(|x| x.name.as_deref() == Some(name))
        .into_iter()
        .next()
        .unwrap_or_else(|| panic!("no {name}"))
}

fn canon_of(m: &Model) -> String {
    lib_canon(m, &m.to_xml_string().unwrap()).unwrap().to_string()
}

/// Each robot on its own: the naive rendering (auto-names in the top scope, attribute
/// values) is what the library writes, and the arm's is as written out here.
#[test]
fn robots_are_the_same_on_both_sides() {
    for (n, m) in ROBOTS.naive.iter().zip(&ROBOTS.lib) {
        assert_eq!(canon_of(m), n.canon().to_string(), "robot {}", n.model);
    }
    assert_eq!(
        naive_arm().canon().to_string(),
        "worldbody:
  site name=base pos=0 0 0.05 quat=0 1 0 0
  body name=upper
    joint name=hip type=hinge
    geom auto(,geom) size=0.05
    body name=lower pos=0 0 0.3
      joint name=knee
      geom name=tip size=0.02
      site name=hand
actuator:
  motor name=hip joint=hip
  motor auto(,actuator) joint=knee
sensor:
  jointpos name=hip_pos joint=hip
scopes: \n"
    );
}

/// The same robot attached at a site and then at the world: scopes `robot` and
/// `robot_1`; the first frame right after the site with the site's position, the second
/// at the end of the worldbody; every name and the motors' joints prefixed.
#[test]
fn attach_twice_gives_scopes_robot_and_robot_1() {
    const EXPECTED: &str = "worldbody:
  site name=spawn pos=0 0 0.5
  body name=robot/ pos=0 0 0.5
    body name=robot/torso pos=0 0 0.1
      joint name=robot/slide axis=1 0 0 type=slide
      geom name=robot/torso size=0.1 0.1 0.1 type=box
      geom auto(robot/,geom) rgba=1 0 0 1 size=0.05 type=sphere
      site name=robot/mount pos=0 0 0.2
  body name=b
  body name=robot_1/
    body name=robot_1/torso pos=0 0 0.1
      joint name=robot_1/slide axis=1 0 0 type=slide
      geom name=robot_1/torso size=0.1 0.1 0.1 type=box
      geom auto(robot_1/,geom) rgba=1 0 0 1 size=0.05 type=sphere
      site name=robot_1/mount pos=0 0 0.2
actuator:
  motor name=robot/m joint=robot/slide
  motor name=robot_1/m joint=robot_1/slide
sensor:
scopes: robot robot_1
";
    let mut n = Naive::new("scene");
    n.world.push(NNode::new("site", some("spawn")).attr("pos", Val::nums(&[0.0, 0.0, 0.5])));
    n.world.push(NNode::new("body", some("b")));
    assert_eq!(n.attach(&ROBOTS.naive[0], Some(&[0])), Ok("robot".to_string()));
    assert_eq!(n.attach(&ROBOTS.naive[0], None), Ok("robot_1".to_string()));
    assert_eq!(n.canon().to_string(), EXPECTED);

    let m = Model::new("scene");
    let (m, spawn) = m
        .add(
            &m.worldbody(),
            Element::new("site").attr("name", "spawn").attr("pos", [0.0, 0.0, 0.5]),
        )
        .unwrap();
    let (m, _) = m.add(&m.worldbody(), Element::new("body").attr("name", "b")).unwrap();
    let (m, _) = m.attach(&spawn, &ROBOTS.lib[0]).unwrap();
    let (m, _) = m.attach_to_world(&ROBOTS.lib[0]).unwrap();
    assert_eq!(canon_of(&m), EXPECTED);
}

/// A robot attached at the worldbody-level site of an attached arm, a ball at that
/// robot's site, joints on the arm's frame and a top-level motor (which comes first in
/// the actuators although added last); then the arm's scope renamed, and the middle scope
/// detached with the ball inside it.
#[test]
fn nested_attach_rename_and_detach() {
    const NESTED: &str = "worldbody:
  body name=c/
    freejoint name=c/
    joint name=c/j/
    site name=c/base pos=0 0 0.05 quat=0 1 0 0
    body name=c/robot/ pos=0 0 0.05 quat=0 1 0 0
      body name=c/robot/torso pos=0 0 0.1
        joint name=c/robot/slide axis=1 0 0 type=slide
        geom name=c/robot/torso size=0.1 0.1 0.1 type=box
        geom auto(c/robot/,geom) rgba=1 0 0 1 size=0.05 type=sphere
        site name=c/robot/mount pos=0 0 0.2
        body name=c/robot/robot_1/ pos=0 0 0.2
          body name=c/robot/robot_1/ball
            joint name=c/robot/robot_1/roll type=ball
            geom name=c/robot/robot_1/ball size=0.1 type=sphere
          site name=c/robot/robot_1/tip pos=0 0 0.1
    body name=c/upper
      joint name=c/hip type=hinge
      geom auto(c/,geom) size=0.05
      body name=c/lower pos=0 0 0.3
        joint name=c/knee
        geom name=c/tip size=0.02
        site name=c/hand
actuator:
  motor name=m joint=j
  motor name=c/hip joint=c/hip
  motor auto(c/,actuator) joint=c/knee
  motor name=c/robot/m joint=c/robot/slide
  motor name=c/robot/robot_1/m joint=c/robot/robot_1/ghost
sensor:
  jointpos name=c/hip_pos joint=c/hip
scopes: c c/robot c/robot/robot_1
";
    const DETACHED: &str = "worldbody:
  body name=c/
    freejoint name=c/
    joint name=c/j/
    site name=c/base pos=0 0 0.05 quat=0 1 0 0
    body name=c/upper
      joint name=c/hip type=hinge
      geom auto(c/,geom) size=0.05
      body name=c/lower pos=0 0 0.3
        joint name=c/knee
        geom name=c/tip size=0.02
        site name=c/hand
actuator:
  motor name=m joint=j
  motor name=c/hip joint=c/hip
  motor auto(c/,actuator) joint=c/knee
sensor:
  jointpos name=c/hip_pos joint=c/hip
scopes: c
";
    let mut n = Naive::new("scene");
    n.attach(&ROBOTS.naive[1], None).unwrap();
    let base = path_of(&n, "arm/base");
    assert_eq!(n.attach(&ROBOTS.naive[0], Some(&base)), Ok("arm/robot".to_string()));
    let mount = path_of(&n, "arm/robot/mount");
    assert_eq!(n.attach(&ROBOTS.naive[2], Some(&mount)), Ok("arm/robot/robot_1".to_string()));
    n.add(Some(&[0]), NNode::new("freejoint", None)).unwrap();
    n.add(Some(&[0]), NNode::new("joint", some("j"))).unwrap();
    n.add_item("", NItem::new("actuator", "motor", some("m")).attr("joint", Val::text("j")))
        .unwrap();
    n.rename_scope("arm", "c").unwrap();
    assert_eq!(n.canon().to_string(), NESTED);
    n.detach("c/robot").unwrap();
    assert_eq!(n.canon().to_string(), DETACHED);

    let (m, arm) = Model::new("scene").attach_to_world(&ROBOTS.lib[1]).unwrap();
    let (m, _) = m.attach(&m.find(Namespace::Site, "arm/base").unwrap(), &ROBOTS.lib[0]).unwrap();
    let (m, _) =
        m.attach(&m.find(Namespace::Site, "arm/robot/mount").unwrap(), &ROBOTS.lib[2]).unwrap();
    let (m, _) = m.add(arm.frame(), Element::new("freejoint")).unwrap();
    let (m, _) = m.add(arm.frame(), Element::new("joint").attr("name", "j")).unwrap();
    let (m, _) =
        m.add(&m.actuator(), Element::new("motor").attr("name", "m").attr("joint", "j")).unwrap();
    let m = m.rename_scope("arm", "c").unwrap();
    assert_eq!(canon_of(&m), NESTED);
    assert_eq!(canon_of(&m.detach("c/robot").unwrap()), DETACHED);
}

/// What the reference refuses, the naive model refuses (and the library too); the
/// accepted counterparts are accepted by both.
#[test]
fn refusals_follow_the_reference() {
    // A body `b` with a site `s` holding `robot`, and `robot_1` attached at the world.
    let mut n = Naive::new("scene");
    n.world.push(NNode::new("body", some("b")).child(NNode::new("site", some("s"))));
    n.attach(&ROBOTS.naive[0], Some(&[0, 0])).unwrap();
    n.attach(&ROBOTS.naive[0], None).unwrap();
    let m = Model::new("scene");
    let (m, b) = m
        .add(
            &m.worldbody(),
            Element::new("body").attr("name", "b").child(Element::new("site").attr("name", "s")),
        )
        .unwrap();
    let (m, robot) = m.attach(&m.find(Namespace::Site, "s").unwrap(), &ROBOTS.lib[0]).unwrap();
    let (m, robot_1) = m.attach_to_world(&ROBOTS.lib[0]).unwrap();
    assert_eq!(canon_of(&m), n.canon().to_string());

    fn check<T>(what: &str, ok: bool, lib: Result<T, EditError>, naive: Result<(), String>) {
        assert_eq!(naive.is_ok(), ok, "naive model, {what}: {naive:?}");
        assert_eq!(lib.is_ok(), ok, "library, {what}: {:?}", lib.err());
    }
    let torso = m.find(Namespace::Body, "robot/torso").unwrap();
    let geom = |name: &str| Element::new("geom").attr("name", name);
    let frame_b = path_of(&n, "robot/");
    let frame_w = path_of(&n, "robot_1/");
    let joint = |name: Option<&str>| NNode::new("joint", name);

    check(
        "a joint in the worldbody",
        false,
        m.add(&m.worldbody(), Element::new("joint")),
        n.clone().add(None, joint(None)),
    );
    check(
        "geom torso in robot/torso, where robot/torso is a geom",
        false,
        m.add(&torso, geom("torso")),
        n.clone().add(Some(&path_of(&n, "robot/torso")), NNode::new("geom", some("torso"))),
    );
    check(
        "geom torso in b",
        true,
        m.add(&b, geom("torso")),
        n.clone().add(Some(&[0]), NNode::new("geom", some("torso"))),
    );
    check(
        "a geom on a frame",
        false,
        m.add(robot.frame(), geom("g")),
        n.clone().add(Some(&frame_b), NNode::new("geom", some("g"))),
    );
    check(
        "a freejoint on a frame inside a body",
        false,
        m.add(robot.frame(), Element::new("freejoint")),
        n.clone().add(Some(&frame_b), NNode::new("freejoint", None)),
    );
    let mut n2 = n.clone();
    n2.add(Some(&frame_w), NNode::new("freejoint", None)).unwrap();
    let (m2, _) = m.add(robot_1.frame(), Element::new("freejoint")).unwrap();
    assert_eq!(canon_of(&m2), n2.canon().to_string());
    check(
        "a second freejoint on a world frame",
        false,
        m2.add(robot_1.frame(), Element::new("freejoint")),
        n2.clone().add(Some(&frame_w), NNode::new("freejoint", None)),
    );
    check(
        "a frame joint named like a joint of the model",
        true,
        m.add(robot_1.frame(), Element::new("joint").attr("name", "slide")),
        n.clone().add(Some(&frame_w), joint(some("slide"))),
    );
    check(
        "a name on a frame",
        false,
        m.set_attr(robot.frame(), "name", "x"),
        n.clone().set_name(&Target::Node(frame_b.clone()), Some("x")),
    );
    check(
        "b renamed b",
        true,
        m.set_attr(&b, "name", "b"),
        n.clone().set_name(&Target::Node(vec![0]), Some("b")),
    );
    check(
        "removing b, which holds a frame",
        false,
        m.remove(&b),
        n.clone().remove(&Target::Node(vec![0])),
    );
    let s = m.find(Namespace::Site, "s").unwrap();
    let mut n3 = n.clone();
    check(
        "removing the site robot is attached at",
        true,
        m.remove(&s),
        n3.remove(&Target::Node(vec![0, 0])),
    );
    assert_eq!(canon_of(&m.remove(&s).unwrap()), n3.canon().to_string());
    assert!(n3.canon().to_string().contains("body name=robot/\n"), "the frame stays");
    check(
        "robot renamed robot",
        false,
        m.rename_scope("robot", "robot"),
        n.clone().rename_scope("robot", "robot"),
    );
    check(
        "robot renamed robot_1",
        false,
        m.rename_scope("robot", "robot_1"),
        n.clone().rename_scope("robot", "robot_1"),
    );
    check(
        "robot_1 renamed c",
        true,
        m.rename_scope("robot_1", "c"),
        n.clone().rename_scope("robot_1", "c"),
    );
}

// ---------------------------------------------------------------------------------
// Library bugs the property test found, kept as regression tests: each asserts the
// reference's behaviour, which the library has followed since the fix.

/// Reference §1.5 and §8 ("duplicate frame-joint name on one frame: ValueError
/// `Duplicated identifier 'jx' in namespace <joint@attachment_frame_NNN>`",
/// `testDuplicateAttachmentFrameJointIdentifiers`): the joints of one attachment frame
/// have a namespace of their own. The library accepted a second joint `j` on a frame
/// (and renaming `k` to `j` there), and wrote two joints named `robot/j/`.
/// Minimal case found: attach, then add a joint `torso` to the frame twice.
/// The cause was that no check compared a frame joint's name with its siblings' (the
/// index keeps frame joints out of the model's joint namespace); now an add and a
/// rename compare it with the frame's other joints.
#[test]
fn a_frame_refuses_two_joints_of_the_same_name() {
    let (m, frame) = Model::new("scene").attach_to_world(&ROBOTS.lib[0]).unwrap();
    let (m, _) = m.add(frame.frame(), Element::new("joint").attr("name", "j")).unwrap();
    let (m, k) = m.add(frame.frame(), Element::new("joint").attr("name", "k")).unwrap();
    // The oracle refuses both.
    let mut n = Naive::new("scene");
    n.attach(&ROBOTS.naive[0], None).unwrap();
    n.add(Some(&[0]), NNode::new("joint", some("j"))).unwrap();
    n.add(Some(&[0]), NNode::new("joint", some("k"))).unwrap();
    assert!(n.clone().add(Some(&[0]), NNode::new("joint", some("j"))).is_err());
    assert!(n.clone().set_name(&Target::Node(vec![0, 1]), Some("j")).is_err());
    assert!(
        m.add(frame.frame(), Element::new("joint").attr("name", "j")).is_err(),
        "a second joint j on the frame is accepted:\n{}",
        m.add(frame.frame(), Element::new("joint").attr("name", "j"))
            .unwrap()
            .0
            .to_xml_string()
            .unwrap()
    );
    assert!(m.set_attr(&k, "name", "j").is_err(), "the frame joint k can be renamed j, next to j");
}

/// Reference §1.5, §2.2 and dm_control's `Identifier._assign`, which checks a rename in
/// the element's own namespace (per frame, for a frame joint): a frame joint may take
/// the name of a joint of the model that holds the frame (adding one with that name is
/// accepted even then). The library refused the rename with
/// `DuplicateIdentifier`: a rename was checked against the model's joint namespace,
/// which holds no frame joints, instead of the frame's own.
#[test]
fn a_frame_joint_can_be_renamed_like_a_joint_of_its_model() {
    let m = Model::new("scene");
    let (m, _) = m
        .add(
            &m.worldbody(),
            Element::new("body").attr("name", "b").child(Element::new("joint").attr("name", "k")),
        )
        .unwrap();
    let (m, frame) = m.attach_to_world(&ROBOTS.lib[0]).unwrap();
    let (m, j) = m.add(frame.frame(), Element::new("joint").attr("name", "j")).unwrap();
    // The oracle accepts it, and the library accepts adding a frame joint named k.
    let mut n = Naive::new("scene");
    n.world.push(NNode::new("body", some("b")).child(NNode::new("joint", some("k"))));
    n.attach(&ROBOTS.naive[0], None).unwrap();
    n.add(Some(&[1]), NNode::new("joint", some("j"))).unwrap();
    n.set_name(&Target::Node(vec![1, 0]), Some("k")).unwrap();
    assert!(m.add(frame.frame(), Element::new("joint").attr("name", "k")).is_ok());
    match m.set_attr(&j, "name", "k") {
        Ok(renamed) => assert_eq!(canon_of(&renamed), n.canon().to_string()),
        Err(e) => panic!("renaming the frame joint j to k is refused: {e}"),
    }
}
