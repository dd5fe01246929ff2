//! Model → MJCF text. The only code that produces XML and resolves names.
//!
//! The output has the reference's shape (dm_control_mjcf.md §6): sections and
//! attributes in schema order, empty singletons left out, the root default class
//! wrapped as `<default><default class="/">…</default></default>`, an explicit `class`
//! on every element that can have one and has no `childclass` above it, and
//! `//unnamed_<namespace>_<i>` names for unnamed elements that have an identifier.
//!
// Implementation notes:
// - The walk is iterative (an explicit stack), so a 100,000-deep body chain writes
//   without growing the call stack.
// - Auto names count every element of the namespace before it in document order; the
//   walk visits elements in exactly that order, so a counter per namespace suffices.
//   A resolved reference to an unnamed element needs the target's index, which may
//   lie ahead: those come from a full count made once, only when needed.

use std::collections::HashMap;
use std::fmt::Write as _;

use crate::error::WriteError;
use crate::model::Model;
use crate::schema::{AttrType, ElementKind, Multiplicity, Namespace};
use crate::tree::{ElementId, Node};
use crate::value::{FloatStyle, Reference, Value};

/// Options for [`Model::to_xml_string_with`].
#[derive(Clone, Debug, PartialEq)]
pub struct WriteOptions {
    /// `None` (the default): floats print as the shortest text that reads back exactly
    /// (`0.1`). `Some(p)`: C `%.{p}g`, as the reference prints them (`Some(17)` gives
    /// its exact output, `0.10000000000000001`).
    pub precision: Option<u32>,
    /// Floats whose magnitude is below this print as `0`.
    pub zero_threshold: f64,
    /// Indent with two spaces per level and end with a newline (default `true`);
    /// otherwise one line.
    pub pretty_print: bool,
    /// Name files `stem-<sha1>.ext` (default `true`) or `stem.ext`.
    pub filename_with_hash: bool,
}

impl Default for WriteOptions {
    fn default() -> Self {
        WriteOptions { precision: None, zero_threshold: 0.0, pretty_print: true, filename_with_hash: true }
    }
}

impl Model {
    /// Writes the model as MJCF text with default options.
    ///
    /// # Errors
    /// [`WriteError::MissingRequired`] when a required reference names an element that
    /// was removed.
    ///
    /// # Examples
    /// ```
    /// let m = mjcf::Model::new("empty");
    /// assert_eq!(
    ///     m.to_xml_string().unwrap(),
    ///     "<mujoco model=\"empty\">\n  <default>\n    <default class=\"/\"/>\n  </default>\n</mujoco>\n"
    /// );
    /// ```
    pub fn to_xml_string(&self) -> Result<String, WriteError> {
        self.to_xml_string_with(&WriteOptions::default())
    }

    /// Writes the model as MJCF text.
    pub fn to_xml_string_with(&self, options: &WriteOptions) -> Result<String, WriteError> {
        let mut w = Writer {
            model: self,
            out: String::with_capacity(4096),
            style: FloatStyle { precision: options.precision, zero_threshold: options.zero_threshold },
            options,
            counters: HashMap::new(),
            auto_index: None,
            value: String::new(),
            bad_char: None,
        };
        w.write()?;
        if let Some((tag, attribute, character)) = w.bad_char {
            return Err(WriteError::InvalidCharacter { tag, attribute, character });
        }
        Ok(w.out)
    }
}

struct Writer<'a> {
    model: &'a Model,
    out: String,
    style: FloatStyle,
    options: &'a WriteOptions,
    counters: HashMap<Namespace, usize>,
    auto_index: Option<HashMap<ElementId, usize>>,
    value: String,
    /// The first character XML cannot hold: (tag, attribute, character).
    bad_char: Option<(&'static str, &'static str, char)>,
}

/// One step of the walk.
enum Step<'a> {
    /// Write this element; `childclass` tells whether an ancestor sets `childclass`.
    Enter { node: &'a Node, depth: usize, childclass: bool },
    /// Close an element.
    Exit { tag: &'static str, depth: usize },
}

/// Whether a singleton writes anything: a written attribute, or a child that does.
fn singleton_emits(node: &Node) -> bool {
    let kind = node.kind();
    if node.attrs().iter().any(|(i, _)| !matches!(kind.attr(*i as usize).ty, AttrType::Basepath { .. })) {
        return true;
    }
    if kind.class_attr().is_some() || kind.identifier().is_some() {
        return true;
    }
    node.children().iter().any(|c| c.kind().multiplicity() != Multiplicity::Singleton || singleton_emits(c))
}

fn emits(node: &Node) -> bool {
    node.kind().multiplicity() != Multiplicity::Singleton || singleton_emits(node)
}

impl<'a> Writer<'a> {
    fn write(&mut self) -> Result<(), WriteError> {
        let root = &self.model.root;
        let mut stack: Vec<Step<'a>> = vec![Step::Enter { node: root, depth: 0, childclass: false }];
        while let Some(step) = stack.pop() {
            match step {
                Step::Exit { tag, depth } => {
                    self.indent(depth);
                    self.out.push_str("</");
                    self.out.push_str(tag);
                    self.out.push('>');
                    self.newline();
                }
                Step::Enter { node, depth, childclass } => {
                    let kind = node.kind();
                    let is_root_default = kind.tag() == "default" && kind.spec().parent == Some(ElementKind::ROOT);
                    let depth = if is_root_default {
                        self.indent(depth);
                        self.out.push_str("<default>");
                        self.newline();
                        stack.push(Step::Exit { tag: "default", depth });
                        depth + 1
                    } else {
                        depth
                    };
                    self.indent(depth);
                    self.out.push('<');
                    self.out.push_str(kind.tag());
                    self.write_attrs(node, childclass)?;
                    let children: Vec<&'a Node> = node.children().iter().filter(|c| emits(c)).collect();
                    if children.is_empty() {
                        self.out.push_str("/>");
                        self.newline();
                        continue;
                    }
                    self.out.push('>');
                    self.newline();
                    stack.push(Step::Exit { tag: kind.tag(), depth });
                    let child_cc = childclass || sets_childclass(node);
                    for c in children.into_iter().rev() {
                        stack.push(Step::Enter { node: c, depth: depth + 1, childclass: child_cc });
                    }
                }
            }
        }
        Ok(())
    }

    fn indent(&mut self, depth: usize) {
        if self.options.pretty_print {
            for _ in 0..depth {
                self.out.push_str("  ");
            }
        }
    }

    fn newline(&mut self) {
        if self.options.pretty_print {
            self.out.push('\n');
        }
    }

    /// Writes ` name="value"` for every attribute, in schema order, including the
    /// auto name and the implicit default class.
    fn write_attrs(&mut self, node: &Node, childclass: bool) -> Result<(), WriteError> {
        let kind = node.kind();
        let is_default = kind.tag() == "default";
        // Identifier slot: an auto name when unset (default classes render their own).
        let auto_name = match (kind.identifier(), kind.namespace()) {
            (Some(i), Some(ns)) => {
                let n = self.counters.entry(ns).or_insert(0);
                let index = *n;
                *n += 1;
                (node.attr(i).is_none() || is_default).then_some((i, ns, index))
            }
            _ => None,
        };
        let implicit_class = match kind.class_attr() {
            Some(c) if node.attr(c).is_none() && !childclass => Some(c),
            _ => None,
        };
        let mut set = node.attrs().iter().peekable();
        let mut virtuals: [Option<usize>; 2] = [auto_name.map(|a| a.0), implicit_class];
        virtuals.sort_by_key(|v| v.unwrap_or(usize::MAX));
        let mut virt = virtuals.iter().flatten().copied().peekable();
        loop {
            let next_set = set.peek().map(|(i, _)| *i as usize);
            let next_virt = virt.peek().copied();
            let take_virtual = match (next_set, next_virt) {
                (None, None) => break,
                (Some(_), None) => false,
                (None, Some(_)) => true,
                (Some(s), Some(v)) => v <= s,
            };
            self.value.clear();
            if take_virtual {
                let i = virt.next().unwrap_or_default();
                if Some(i) == auto_name.map(|a| a.0) {
                    // Skip the stored value at the same slot, if any (default classes).
                    if next_set == Some(i) {
                        set.next();
                    }
                    if is_default {
                        self.default_class_name(node.identifier());
                    } else if let Some((_, ns, index)) = auto_name {
                        self.auto_name(ns, index);
                    }
                } else {
                    // Implicit class: the model's root class.
                    self.default_class_name(self.root_class_name());
                }
                self.emit_attr(kind.tag(), kind.attr(i).name);
            } else if let Some((i, v)) = set.next() {
                let i = *i as usize;
                let spec = kind.attr(i);
                if self.value_text(node, i, v)? {
                    self.emit_attr(kind.tag(), spec.name);
                }
            }
        }
        Ok(())
    }

    fn root_class_name(&self) -> Option<&'a str> {
        let kind = ElementKind::ROOT.child("default")?;
        self.model.root.child_of_kind(kind)?.identifier()
    }

    /// Writes `P + name`, or `/` when both are empty, into `self.value`.
    fn default_class_name(&mut self, name: Option<&str>) {
        let name = name.unwrap_or("");
        if name.is_empty() {
            self.value.push('/');
        } else {
            self.value.push_str(name);
        }
    }

    /// Writes `//unnamed_<ns>_<index>` into `self.value`.
    fn auto_name(&mut self, ns: Namespace, index: usize) {
        let _ = write!(self.value, "//unnamed_{}_{}", ns.as_str(), index);
    }

    /// Writes the text of attribute `i` into `self.value`; `false` if it is not written.
    fn value_text(&mut self, node: &Node, i: usize, v: &Value) -> Result<bool, WriteError> {
        match v {
            Value::Basepath(_) => Ok(false),
            Value::File(f) => {
                self.value.push_str(&f.vfs_name(self.options.filename_with_hash));
                Ok(true)
            }
            Value::Reference(Reference::Element(target)) => self.reference_text(node, i, *target),
            _ => {
                v.write_plain(&mut self.value, self.style);
                Ok(true)
            }
        }
    }

    fn reference_text(&mut self, node: &Node, i: usize, target: ElementId) -> Result<bool, WriteError> {
        let kind = node.kind();
        let Some(entry) = self.model.index.elems.get(&target) else {
            let spec = kind.attr(i);
            if spec.required {
                return Err(WriteError::MissingRequired {
                    tag: kind.tag(),
                    attribute: spec.name,
                    path: self.model.path_of(node.id()).map(|p| self.model.describe(&p)).unwrap_or_default(),
                });
            }
            return Ok(false);
        };
        if entry.kind.tag() == "default" {
            let name = entry.name.clone();
            self.default_class_name(name.as_deref());
            return Ok(true);
        }
        match (&entry.name, entry.kind.namespace()) {
            (Some(n), _) => self.value.push_str(n),
            (None, Some(ns)) => {
                let index = self.auto_index_of(target);
                self.auto_name(ns, index);
            }
            (None, None) => return Ok(false),
        }
        Ok(true)
    }

    fn auto_index_of(&mut self, id: ElementId) -> usize {
        if self.auto_index.is_none() {
            let mut counts: HashMap<Namespace, usize> = HashMap::new();
            let mut map = HashMap::new();
            for n in self.model.root.descendants() {
                if let Some(ns) = n.kind().namespace() {
                    let c = counts.entry(ns).or_insert(0);
                    map.insert(n.id(), *c);
                    *c += 1;
                }
            }
            self.auto_index = Some(map);
        }
        self.auto_index.as_ref().and_then(|m| m.get(&id).copied()).unwrap_or(0)
    }

    /// Appends ` name="<escaped self.value>"`.
    fn emit_attr(&mut self, tag: &'static str, name: &'static str) {
        self.out.push(' ');
        self.out.push_str(name);
        self.out.push_str("=\"");
        if let Some(c) = escape_into(&mut self.out, &self.value) {
            self.bad_char.get_or_insert((tag, name, c));
        }
        self.out.push('"');
    }
}

fn sets_childclass(node: &Node) -> bool {
    node.kind().attr_index("childclass").and_then(|i| node.attr(i)).is_some()
}

/// Escapes an attribute value as lxml does: `& < > "` as entities, tab, newline and
/// carriage return as character references, and every non-ASCII character as a
/// numeric character reference.
///
/// Returns the first character that XML 1.0 cannot hold at all (most control
/// characters, U+FFFE, U+FFFF), if any; it is written as a reference all the same.
pub(crate) fn escape_into(out: &mut String, s: &str) -> Option<char> {
    let clean = s.bytes().all(|b| (0x20..0x7f).contains(&b) && !matches!(b, b'&' | b'<' | b'>' | b'"'));
    if clean {
        out.push_str(s);
        return None;
    }
    let bad = s.chars().find(|c| !crate::value::is_xml_char(*c));
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            ' '..='~' => out.push(c),
            _ => {
                let _ = write!(out, "&#{};", c as u32);
            }
        }
    }
    bad
}
