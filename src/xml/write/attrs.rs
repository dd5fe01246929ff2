//! An element's attributes as written: in schema order, the name slot from the
//! naming rules (`model::naming`), the implicit class ([`rules::implicit_class`]),
//! names and references with their instance's prefix
//! ([`rules::named_reference`]), references to removed elements
//! ([`rules::removed_reference`]), files by their written names
//! ([`rules::file_name`]), and no base path ([`rules::writes_attr`]).

use crate::error::WriteError;
use crate::model::naming::Written as WrittenName;
use crate::model::tree::{ElementId, Node};
use crate::model::{Entry, Insts, Item};
use crate::schema::AttrType;
use crate::value::{Reference, Value};

use super::Writer;
use crate::xml::rules::{self, NamedReference};

impl<'a> Writer<'a> {
    /// Writes ` name="value"` for every attribute, in schema order, including the
    /// element's name (its own with its prefix, an attachment frame's, a frame
    /// joint's, an automatic one: `model::naming`) and the implicit class.
    /// `childclass_above`: a `childclass` of the same model is above
    /// ([`rules::childclass_above`]).
    pub(super) fn write_attrs(
        &mut self,
        insts: &Insts<'a>,
        item: &Item<'a>,
        childclass_above: bool,
    ) -> Result<(), WriteError> {
        let (inst, node) = (item.inst, item.node);
        let kind = node.kind();
        // The name slot is always written from the naming rules.
        // (Kept apart from its slot: a name repacked with it is copied through memory.)
        let name = kind.identifier().and_then(|_| insts.name_of_item(item));
        let name_slot = kind.identifier().filter(|_| name.is_some());
        let implicit_class =
            rules::implicit_class(kind, childclass_above, |c| self.has_live(insts, inst, node, c));
        // The stored attributes, merged in schema order with the two slots written
        // from the rules (each replacing a stored value at its slot).
        let mut set = node.attrs().iter().peekable();
        let mut virtuals: [Option<usize>; 2] = [name_slot, implicit_class];
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
            self.text.value.clear();
            if take_virtual {
                let i = virt.next().unwrap_or_default();
                if next_set == Some(i) {
                    set.next();
                }
                let attr = kind.attr(i).name;
                let written = match name {
                    Some(written) if name_slot == Some(i) => written,
                    // The implicit class: the model's root class.
                    _ => insts.root_class_name(inst),
                };
                self.emit_written(insts, inst, kind.tag(), attr, written);
            } else if let Some((i, v)) = set.next() {
                self.emit_value(insts, inst, node, *i as usize, v)?;
            }
        }
        Ok(())
    }

    /// Appends ` attr="…"` for a name in instance `inst`: an element's own name as
    /// prefix and name, each escaped with no copy between; any other spelt first.
    #[inline(always)]
    pub(super) fn emit_written(
        &mut self,
        insts: &Insts<'a>,
        inst: usize,
        tag: &'static str,
        attr: &'static str,
        written: WrittenName<'_>,
    ) {
        let names = &insts.list[inst].names;
        if let WrittenName::Own(n) = written {
            let parts = [names.prefix.as_str(), n];
            self.text.parts_attr(tag, attr, parts, names.prefix_clean);
            return;
        }
        self.text.value.clear();
        written.write(&names.prefix, &mut self.text.value);
        self.text.value_attr(tag, attr);
    }

    /// Appends ` name="value"` for attribute `i` (holding `v`), if it is written.
    fn emit_value(
        &mut self,
        insts: &Insts<'a>,
        inst: usize,
        node: &Node,
        i: usize,
        v: &Value,
    ) -> Result<(), WriteError> {
        let kind = node.kind();
        let (tag, attr) = (kind.tag(), kind.attr(i).name);
        // Names are written as prefix and name, each escaped, with no copy between.
        let names = &insts.list[inst].names;
        let prefix = names.prefix.as_str();
        let parts = match v {
            // Numbers and schema keywords are plain ASCII with nothing to escape.
            Value::Float(_)
            | Value::Floats(_)
            | Value::Int(_)
            | Value::Ints(_)
            | Value::Keyword(_) => {
                self.text.plain_attr(attr, v);
                return Ok(());
            }
            Value::Basepath(_) => return Ok(()),
            Value::Reference(Reference::Element(target)) => {
                return self.emit_reference(insts, inst, node, i, *target);
            }
            // (The name slot is written by `write_attrs`.)
            Value::Identifier(n) => [prefix, n.as_str()],
            Value::String(n) if kind.attr(i).ty == AttrType::NamePrefix => [prefix, n.as_str()],
            Value::Reference(Reference::Name(n)) => {
                let model = insts.list[inst].model;
                match rules::named_reference(model, node, i, n) {
                    NamedReference::RootClass => {
                        let root = insts.root_class_name(inst);
                        self.emit_written(insts, inst, tag, attr, root);
                        return Ok(());
                    }
                    NamedReference::Bare => ["", n.as_str()],
                    NamedReference::Prefixed => [prefix, n.as_str()],
                }
            }
            Value::File(f) => {
                self.text.value.push_str(&rules::file_name(f, self.options));
                self.text.value_attr(tag, attr);
                return Ok(());
            }
            _ => {
                v.write_plain(&mut self.text.value, self.text.style);
                self.text.value_attr(tag, attr);
                return Ok(());
            }
        };
        self.text.parts_attr(tag, attr, parts, names.prefix_clean);
        Ok(())
    }

    /// Appends ` name="…"` for attribute `i`, a reference to element `target`, if it
    /// is written ([`rules::removed_reference`]).
    fn emit_reference(
        &mut self,
        insts: &Insts<'a>,
        inst: usize,
        node: &Node,
        i: usize,
        target: ElementId,
    ) -> Result<(), WriteError> {
        let Some(entry) = self.entry(insts, inst, target) else {
            return rules::removed_reference(insts.list[inst].model, node, i);
        };
        if let Some(written) = insts.name_of_entry(inst, target, entry) {
            let kind = node.kind();
            self.emit_written(insts, inst, kind.tag(), kind.attr(i).name, written);
        }
        Ok(())
    }

    /// The index entry of `id` in the model of instance `inst`.
    fn entry(&mut self, insts: &Insts<'a>, inst: usize, id: ElementId) -> Option<&'a Entry> {
        let elems = &insts.list[inst].model.index.elems;
        if let Some((m, e)) = self.entries.get(&id) {
            if m.ptr_eq(elems) {
                return *e;
            }
        }
        let e = elems.get(&id);
        self.entries.insert(id, (elems, e));
        e
    }

    /// Whether `node` (of instance `inst`) sets a `childclass` that is written
    /// ([`rules::childclass_below`]).
    pub(super) fn sets_childclass(&mut self, insts: &Insts<'a>, inst: usize, node: &Node) -> bool {
        let childclass = rules::kind_facts(node.kind()).childclass;
        childclass.is_some_and(|i| self.has_live(insts, inst, node, i))
    }

    /// Whether attribute `i` of `node` is set and will be written: a reference to an
    /// element that was removed is not (an optional reference; a required one fails).
    fn has_live(&mut self, insts: &Insts<'a>, inst: usize, node: &Node, i: usize) -> bool {
        match node.attr(i) {
            None => false,
            Some(Value::Reference(Reference::Element(id))) => {
                self.entry(insts, inst, *id).is_some()
            }
            Some(_) => true,
        }
    }
}
