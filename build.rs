//! Generates the static MJCF schema tables from the schema data in `schema/`.
//!
//! The schema is data, from three files (see `schema/README.md`):
//! - `schema.xml`: dm_control's schema (itself generated from MuJoCo's): every element
//!   and attribute dm_control knows, with types, namespaces and merge rules;
//! - `mujoco-4.0.0-schema.txt`: MuJoCo 4.0's own element tree with every attribute name
//!   (`mj_printSchema`), which has no types;
//! - `mujoco-4.0-types.txt`: the types of what MuJoCo 4.0 has beyond dm_control's
//!   schema (and of `<frame>` and `<replicate>`, which MuJoCo does not print), decided
//!   from MuJoCo's XML reference.
//!
//! dm_control's schema comes first and is kept as it is (its elements, their order and
//! their attributes' order); the types file adds elements and attributes after it; and
//! every element and attribute of MuJoCo's printed schema must then have a type, or
//! the build fails. This script turns the result into `$OUT_DIR/schema_tables.rs`,
//! which `src/schema.rs` includes. No element or attribute list is written by hand
//! anywhere in the crate's code.
//!
//! Output:
//! - `enum Namespace` with one variant per identifier namespace (an element's
//!   `namespace` attribute, or its tag when it has an identifier attribute), plus
//!   `AttachmentFrame`, which the reference also accepts in `find`;
//! - `static ELEMENTS: [ElementSpec; N]`, one entry per `<element>` in `schema.xml`, in
//!   document order (index 0 is `<mujoco>`), then the types file's new elements;
//!   recursive elements list themselves as a child, and an element may be the child
//!   of several (`<frame>` is a child of the worldbody, of bodies, of frames and of
//!   `<replicate>`);
//! - per element, its attributes (schema order) and a perfect hash table of their names
//!   (a seed and a table of attribute indices, see `perfect_table`);
//! - `enum Role` and `static ROLES`, the role of each element, from `schema/roles.txt`
//!   (the behaviour the crate gives element kinds, as data: see `parse_roles`).

use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::path::Path;

use quick_xml::events::{BytesStart, Event};

#[derive(Debug, Default)]
struct Elem {
    name: String,
    repeated: bool,
    on_demand: bool,
    recursive: bool,
    namespace_attr: Option<String>,
    attrs: Vec<Attr>,
    children: Vec<usize>,
    parent: Option<usize>,
    /// The element's path as MuJoCo 4.0's printed schema names it (see `key_of`).
    key: String,
}

#[derive(Debug, Default, Clone)]
struct Attr {
    name: String,
    ty: String,
    required: bool,
    conflict_allowed: bool,
    conflict_behavior: Option<String>,
    valid_values: Option<String>,
    array_type: Option<String>,
    array_size: Option<u32>,
    reference_namespace: Option<String>,
    /// For a reference: the attribute that, when set, makes it a name in another model.
    reference_unless: Option<String>,
    path_namespace: Option<String>,
    default: Option<String>,
}

fn attr_map(e: &BytesStart) -> Vec<(String, String)> {
    e.attributes()
        .map(|a| {
            let a = a.expect("schema.xml: malformed attribute");
            (
                a.key.as_ref().to_string(),
                a.normalized_value(quick_xml::XmlVersion::default())
                    .expect("schema.xml: bad value")
                    .into_owned(),
            )
        })
        .collect()
}

fn get<'a>(m: &'a [(String, String)], k: &str) -> Option<&'a str> {
    m.iter().find(|(n, _)| n == k).map(|(_, v)| v.as_str())
}

fn parse(text: &str) -> Vec<Elem> {
    let mut reader = quick_xml::Reader::from_str(text);
    let mut elems: Vec<Elem> = Vec::new();
    // Stack of open schema tags: ("element", index) / ("attributes"|"children", parent).
    let mut stack: Vec<(String, Option<usize>)> = Vec::new();
    let current_elem = |stack: &[(String, Option<usize>)]| -> Option<usize> {
        stack.iter().rev().find(|(t, _)| t == "element").and_then(|(_, i)| *i)
    };
    loop {
        let ev = reader.read_event().expect("schema.xml: malformed XML");
        let (start, empty) = match &ev {
            Event::Start(s) => (Some(s.clone()), false),
            Event::Empty(s) => (Some(s.clone()), true),
            Event::End(_) => {
                stack.pop();
                (None, false)
            }
            Event::Eof => break,
            _ => (None, false),
        };
        let Some(s) = start else { continue };
        let tag = s.name().as_ref().to_string();
        let m = attr_map(&s);
        match tag.as_str() {
            "element" => {
                let parent = current_elem(&stack);
                let idx = elems.len();
                elems.push(Elem {
                    name: get(&m, "name").expect("element without name").to_string(),
                    repeated: get(&m, "repeated") == Some("true"),
                    on_demand: get(&m, "on_demand") == Some("true"),
                    recursive: get(&m, "recursive") == Some("true"),
                    namespace_attr: get(&m, "namespace").map(str::to_string),
                    parent,
                    ..Elem::default()
                });
                if let Some(p) = parent {
                    elems[p].children.push(idx);
                }
                if !empty {
                    stack.push((tag, Some(idx)));
                }
            }
            "attribute" => {
                let owner = current_elem(&stack).expect("attribute outside element");
                elems[owner].attrs.push(Attr {
                    name: get(&m, "name").expect("attribute without name").to_string(),
                    ty: get(&m, "type").expect("attribute without type").to_string(),
                    required: get(&m, "required") == Some("true"),
                    conflict_allowed: get(&m, "conflict_allowed") == Some("true"),
                    conflict_behavior: get(&m, "conflict_behavior").map(str::to_string),
                    valid_values: get(&m, "valid_values").map(str::to_string),
                    array_type: get(&m, "array_type").map(str::to_string),
                    array_size: get(&m, "array_size").map(|v| v.parse().expect("array_size")),
                    reference_namespace: get(&m, "reference_namespace").map(str::to_string),
                    reference_unless: None,
                    path_namespace: get(&m, "path_namespace").map(str::to_string),
                    default: get(&m, "default").map(str::to_string),
                });
                if !empty {
                    stack.push((tag, None));
                }
            }
            _ => {
                if !empty {
                    stack.push((tag, None));
                }
            }
        }
    }
    for (i, e) in elems.iter_mut().enumerate() {
        if e.recursive {
            e.children.push(i);
        }
    }
    elems
}

fn camel(s: &str) -> String {
    s.split('_')
        .map(|p| {
            let mut c = p.chars();
            match c.next() {
                Some(f) => f.to_ascii_uppercase().to_string() + c.as_str(),
                None => String::new(),
            }
        })
        .collect()
}

fn identifier_attr(e: &Elem) -> Option<usize> {
    e.attrs.iter().position(|a| a.ty == "identifier")
}

fn namespace_of(e: &Elem) -> Option<String> {
    identifier_attr(e)?;
    Some(e.namespace_attr.clone().unwrap_or_else(|| e.name.clone()))
}

fn main() {
    // tests/support's own tests are left out where the binding crate includes those
    // files (it sets this cfg); declared here for the mjcf crate's targets.
    println!("cargo::rustc-check-cfg=cfg(mjcf_mujoco)");
    // The real models beside the checkout (`../shared/realmodels`, as CI has it): the
    // tests over them are ignored, with a note, where they are not (as this script
    // finds them when it runs).
    println!("cargo::rustc-check-cfg=cfg(mjcf_realmodels)");
    if Path::new("../shared/realmodels/cases").is_dir() {
        println!("cargo::rustc-cfg=mjcf_realmodels");
    }
    let path = Path::new("schema/schema.xml");
    println!("cargo::rerun-if-changed=schema/schema.xml");
    println!("cargo::rerun-if-changed={MUJOCO40_SCHEMA}");
    println!("cargo::rerun-if-changed={MUJOCO40_TYPES}");
    println!("cargo::rerun-if-changed={ROLES}");
    println!("cargo::rerun-if-changed=build.rs");
    let text = std::fs::read_to_string(path).expect("read schema/schema.xml");
    let mut elems = parse(&text);
    assert_eq!(elems[0].name, "mujoco", "schema root must be <mujoco>");
    let printed = std::fs::read_to_string(MUJOCO40_SCHEMA).expect("read MuJoCo 4.0 schema");
    let types = std::fs::read_to_string(MUJOCO40_TYPES).expect("read MuJoCo 4.0 types");
    merge_mujoco40(&mut elems, &parse_printed(&printed), &types);
    let roles_text = std::fs::read_to_string(ROLES).expect("read the element roles");
    let roles = parse_roles(&roles_text, &elems);

    let namespaces: BTreeSet<String> = elems.iter().filter_map(namespace_of).collect();
    let ns_list: Vec<&String> = namespaces.iter().collect();
    let ns_index = |n: &str| -> usize {
        ns_list
            .iter()
            .position(|x| x.as_str() == n)
            .unwrap_or_else(|| panic!("schema: reference to unknown namespace {n}"))
    };

    let mut out = String::new();
    writeln!(out, "// @generated by build.rs from schema/schema.xml. Do not edit.").unwrap();
    writeln!(out).unwrap();

    // Namespace enum.
    writeln!(
        out,
        "/// An identifier namespace of MJCF: identifiers are unique per namespace per model.\n\
         ///\n/// Generated from the schema: one variant per namespace that an element with an\n\
         /// identifier attribute belongs to, plus [`Namespace::AttachmentFrame`].\n\
         #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]\n#[non_exhaustive]\npub enum Namespace {{"
    )
    .unwrap();
    for n in &ns_list {
        writeln!(out, "    /// The `{n}` namespace.").unwrap();
        writeln!(out, "    {},", camel(n)).unwrap();
    }
    writeln!(
        out,
        "    /// Attachment frames, found by the scope name of the model they hold.\n    AttachmentFrame,\n}}\n"
    )
    .unwrap();
    writeln!(out, "impl Namespace {{").unwrap();
    writeln!(out, "    /// Every namespace, in name order.").unwrap();
    write!(out, "    pub const ALL: &'static [Namespace] = &[").unwrap();
    for n in &ns_list {
        write!(out, "Namespace::{}, ", camel(n)).unwrap();
    }
    writeln!(out, "Namespace::AttachmentFrame];").unwrap();
    writeln!(out, "    /// The namespace's MJCF name (`\"body\"`, `\"attachment_frame\"`).")
        .unwrap();
    writeln!(out, "    pub const fn as_str(self) -> &'static str {{\n        match self {{")
        .unwrap();
    for n in &ns_list {
        writeln!(out, "            Namespace::{} => {n:?},", camel(n)).unwrap();
    }
    writeln!(
        out,
        "            Namespace::AttachmentFrame => \"attachment_frame\",\n        }}\n    }}"
    )
    .unwrap();
    writeln!(out, "    /// The namespace with this MJCF name, if any.").unwrap();
    writeln!(
        out,
        "    pub fn from_name(name: &str) -> Option<Namespace> {{\n        Some(match name {{"
    )
    .unwrap();
    for n in &ns_list {
        writeln!(out, "            {n:?} => Namespace::{},", camel(n)).unwrap();
    }
    writeln!(
        out,
        "            \"attachment_frame\" => Namespace::AttachmentFrame,\n            _ => return None,\n        }})\n    }}\n}}\n"
    )
    .unwrap();

    // Per-element attribute tables.
    let mut seeds: Vec<u32> = Vec::with_capacity(elems.len());
    for (i, e) in elems.iter().enumerate() {
        writeln!(out, "static ATTRS_{i}: [AttrSpec; {}] = [", e.attrs.len()).unwrap();
        for a in &e.attrs {
            let ty = match a.ty.as_str() {
                "float" => "AttrType::Float".to_string(),
                "int" => "AttrType::Int".to_string(),
                "string" => "AttrType::String".to_string(),
                "prefix" => "AttrType::NamePrefix".to_string(),
                "identifier" => "AttrType::Identifier".to_string(),
                "keyword" => {
                    let vals = a.valid_values.as_deref().expect("keyword without valid_values");
                    let list: Vec<String> =
                        vals.split_whitespace().map(|v| format!("{v:?}")).collect();
                    format!("AttrType::Keyword(&[{}])", list.join(", "))
                }
                "array" => {
                    let el = match a.array_type.as_deref() {
                        Some("float") => "ArrayType::Float",
                        Some("int") => "ArrayType::Int",
                        other => panic!("schema: array type {other:?}"),
                    };
                    let max = match a.array_size {
                        Some(n) => format!("Some({n})"),
                        None => "None".to_string(),
                    };
                    format!("AttrType::Array {{ elem: {el}, max_len: {max} }}")
                }
                "reference" => {
                    let rn = a.reference_namespace.as_deref().expect("reference without namespace");
                    if let Some(src) = rn.strip_prefix("attrib:") {
                        let pos = e
                            .attrs
                            .iter()
                            .position(|x| x.name == src)
                            .unwrap_or_else(|| panic!("schema: {src} missing on {}", e.name));
                        format!("AttrType::Reference(RefTarget::ByAttribute({pos}))")
                    } else if let Some(u) = &a.reference_unless {
                        ns_index(rn);
                        let pos = e
                            .attrs
                            .iter()
                            .position(|x| x.name == *u)
                            .unwrap_or_else(|| panic!("schema: {u} missing on {}", e.name));
                        format!(
                            "AttrType::Reference(RefTarget::Unless(Namespace::{}, {pos}))",
                            camel(rn)
                        )
                    } else {
                        ns_index(rn);
                        format!("AttrType::Reference(RefTarget::Fixed(Namespace::{}))", camel(rn))
                    }
                }
                "file" => format!(
                    "AttrType::File {{ path_namespace: {} }}",
                    path_ns(a.path_namespace.as_deref())
                ),
                "basepath" => {
                    format!(
                        "AttrType::Basepath {{ path_namespace: {} }}",
                        path_ns(a.path_namespace.as_deref())
                    )
                }
                other => panic!("schema: unknown attribute type {other}"),
            };
            let merge = match (a.conflict_allowed, a.conflict_behavior.as_deref()) {
                (false, _) => "Merge::MustAgree",
                (true, None) | (true, Some("replace")) => "Merge::Replace",
                (true, Some("min")) => "Merge::Min",
                (true, Some("max")) => "Merge::Max",
                (true, Some("max_bytes")) => "Merge::MaxBytes",
                (true, Some(o)) => panic!("schema: conflict behaviour {o}"),
            };
            let default = match &a.default {
                Some(d) => format!("Some({d:?})"),
                None => "None".to_string(),
            };
            writeln!(
                out,
                "    AttrSpec {{ name: {:?}, ty: {ty}, required: {}, merge: {merge}, default: {default} }},",
                a.name, a.required
            )
            .unwrap();
        }
        writeln!(out, "];").unwrap();
        let names: Vec<&str> = e.attrs.iter().map(|a| a.name.as_str()).collect();
        let (seed, table) = perfect_table(&names);
        seeds.push(seed);
        writeln!(out, "static ATTRS_BY_HASH_{i}: [u16; {}] = {:?};", table.len(), table).unwrap();
    }

    writeln!(out, "\npub(crate) static ELEMENTS: [ElementSpec; {}] = [", elems.len()).unwrap();
    for (i, e) in elems.iter().enumerate() {
        let multiplicity = if e.repeated {
            "Multiplicity::Repeated"
        } else if e.on_demand {
            "Multiplicity::OnDemand"
        } else {
            "Multiplicity::Singleton"
        };
        let ns = match namespace_of(e) {
            Some(n) => format!("Some(Namespace::{})", camel(&n)),
            None => "None".to_string(),
        };
        let ident = match identifier_attr(e) {
            Some(p) => format!("Some({p})"),
            None => "None".to_string(),
        };
        let parent = match e.parent {
            Some(p) => format!("Some(ElementKind({p}))"),
            None => "None".to_string(),
        };
        let children: Vec<String> =
            e.children.iter().map(|c| format!("ElementKind({c})")).collect();
        writeln!(
            out,
            "    ElementSpec {{ tag: {:?}, multiplicity: {multiplicity}, namespace: {ns}, identifier: {ident}, parent: {parent}, attrs: &ATTRS_{i}, attr_seed: {}, attrs_by_hash: &ATTRS_BY_HASH_{i}, children: &[{}] }},",
            e.name,
            seeds[i],
            children.join(", ")
        )
        .unwrap();
    }
    writeln!(out, "];").unwrap();
    // The root's sections as constants (`ElementKind::WORLDBODY`): the crate names a
    // section by its constant, never by looking its tag up.
    writeln!(out, "\n#[allow(dead_code)] // Not every section is named by the code.").unwrap();
    writeln!(out, "impl ElementKind {{").unwrap();
    if let Some(root) = elems.iter().position(|e| e.parent.is_none()) {
        for &c in &elems[root].children {
            let name = &elems[c].name;
            writeln!(out, "    /// The root's `<{name}>` section.").unwrap();
            writeln!(
                out,
                "    pub(crate) const {}: ElementKind = ElementKind({c});",
                name.to_uppercase()
            )
            .unwrap();
        }
    }
    writeln!(out, "}}").unwrap();
    write_roles(&mut out, &roles);

    let dest = Path::new(&std::env::var("OUT_DIR").unwrap()).join("schema_tables.rs");
    std::fs::write(dest, out).expect("write schema tables");
}

/// The hash of an attribute name that `src/schema.rs` (`attr_hash`) computes: both
/// must stay the same function.
fn attr_hash(name: &[u8], seed: u32) -> u32 {
    let mut h = seed ^ (name.len() as u32).wrapping_mul(0x9E37_79B9);
    for &b in name {
        h = (h ^ u32::from(b)).wrapping_mul(0x0100_0193);
    }
    h ^ (h >> 15)
}

/// A collision-free table of attribute names (a perfect hash): the seed and the table,
/// whose slot `attr_hash(name, seed) & (len - 1)` holds the attribute's index (the
/// first attribute of that name) or `u16::MAX`. The smallest power-of-two size for
/// which some seed below 4,000 works.
fn perfect_table(names: &[&str]) -> (u32, Vec<u16>) {
    let mut unique: Vec<(usize, &str)> = Vec::new();
    for (i, n) in names.iter().enumerate() {
        if !unique.iter().any(|(_, u)| u == n) {
            unique.push((i, n));
        }
    }
    let mut size = unique.len().max(1).next_power_of_two();
    loop {
        for seed in 0..4000u32 {
            let mut table = vec![u16::MAX; size];
            let fits = unique.iter().all(|&(i, n)| {
                let slot = attr_hash(n.as_bytes(), seed) as usize & (size - 1);
                let free = table[slot] == u16::MAX;
                table[slot] = i as u16;
                free
            });
            if fits {
                return (seed, table);
            }
        }
        size *= 2;
    }
}

fn path_ns(p: Option<&str>) -> &'static str {
    match p {
        None => "None",
        Some("mesh") => "Some(PathNamespace::Mesh)",
        Some("texture") => "Some(PathNamespace::Texture)",
        Some("asset") => "Some(PathNamespace::Asset)",
        Some(o) => panic!("schema: path namespace {o}"),
    }
}

/// The element roles: the behaviour the crate gives element kinds (the file says how to
/// read it).
const ROLES: &str = "schema/roles.txt";

/// The roles of `roles.txt`, in its order, and the role of each element.
struct Roles {
    /// Per role: its name, its group, its doc.
    decls: Vec<(String, Option<String>, String)>,
    /// Per element: the index of its role.
    of: Vec<Option<usize>>,
}

/// Reads `roles.txt` (`role` and `element` lines) against the element tree: every
/// path names an element, an element gets one role, every role has an element.
fn parse_roles(text: &str, elems: &[Elem]) -> Roles {
    let mut roles = Roles { decls: Vec::new(), of: vec![None; elems.len()] };
    for (n, line) in text.lines().enumerate() {
        let at = format!("{ROLES}:{}", n + 1);
        if line.trim_start().starts_with('#') || line.trim().is_empty() {
            continue;
        }
        let (spec, doc) = line.split_once('|').unwrap_or((line, ""));
        let w: Vec<&str> = spec.split_whitespace().collect();
        match w.as_slice() {
            ["role", name, opts @ ..] => {
                assert!(!doc.trim().is_empty(), "{at}: role {name} without a doc");
                assert!(roles.decls.iter().all(|(r, _, _)| r != name), "{at}: {name} twice");
                let group = match opts {
                    [] => None,
                    [g] => Some(g.strip_prefix("group=").unwrap_or_else(|| panic!("{at}: {g}"))),
                    _ => panic!("{at}: cannot read: {line}"),
                };
                roles.decls.push((name.to_string(), group.map(str::to_string), doc.trim().into()));
            }
            ["element", key, role] => {
                let r = roles.decls.iter().position(|(n, _, _)| n == role);
                let r = r.unwrap_or_else(|| panic!("{at}: role {role} is not declared above"));
                let mut found = false;
                for (i, e) in elems.iter().enumerate() {
                    if e.key == *key {
                        assert!(roles.of[i].is_none(), "{at}: {key} has a role already");
                        roles.of[i] = Some(r);
                        found = true;
                    }
                }
                assert!(found, "{at}: no element at {key}");
            }
            _ => panic!("{at}: cannot read: {line}"),
        }
    }
    for (r, (name, _, _)) in roles.decls.iter().enumerate() {
        assert!(roles.of.contains(&Some(r)), "{ROLES}: no element has role {name}");
    }
    roles
}

/// Writes `enum Role`, its group predicates and `static ROLES` (one per element).
fn write_roles(out: &mut String, roles: &Roles) {
    writeln!(
        out,
        "\n/// What the crate does with an element kind: its role, from `schema/roles.txt`.\n\
         #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]\npub(crate) enum Role {{"
    )
    .unwrap();
    for (name, _, doc) in &roles.decls {
        writeln!(out, "    /// {doc}\n    {},", camel(name)).unwrap();
    }
    writeln!(out, "}}\n\nimpl Role {{").unwrap();
    writeln!(out, "    /// Every role, in the file's order.\n    #[cfg(test)]").unwrap();
    let all: Vec<String> =
        roles.decls.iter().map(|(n, _, _)| format!("Role::{}", camel(n))).collect();
    writeln!(out, "    pub(crate) const ALL: &'static [Role] = &[{}];", all.join(", ")).unwrap();
    writeln!(out, "    /// The role's name in `schema/roles.txt`.\n    #[cfg(test)]").unwrap();
    writeln!(out, "    pub(crate) const fn name(self) -> &'static str {{\n        match self {{")
        .unwrap();
    for (name, _, _) in &roles.decls {
        writeln!(out, "            Role::{} => {name:?},", camel(name)).unwrap();
    }
    writeln!(out, "        }}\n    }}").unwrap();
    let mut groups: Vec<&str> = Vec::new();
    for g in roles.decls.iter().filter_map(|(_, g, _)| g.as_deref()) {
        if !groups.contains(&g) {
            groups.push(g);
        }
    }
    for g in groups {
        let members: Vec<String> = roles
            .decls
            .iter()
            .filter(|(_, gr, _)| gr.as_deref() == Some(g))
            .map(|(n, _, _)| format!("Role::{}", camel(n)))
            .collect();
        writeln!(
            out,
            "    /// Whether the role is in group `{g}` of `schema/roles.txt`.\n    \
             pub(crate) const fn is_{g}(self) -> bool {{\n        matches!(self, {})\n    }}",
            members.join(" | ")
        )
        .unwrap();
    }
    writeln!(out, "}}\n\nstatic ROLES: [Option<Role>; {}] = [", roles.of.len()).unwrap();
    for r in &roles.of {
        match r {
            Some(r) => writeln!(out, "    Some(Role::{}),", camel(&roles.decls[*r].0)).unwrap(),
            None => writeln!(out, "    None,").unwrap(),
        }
    }
    writeln!(out, "];").unwrap();
}

/// MuJoCo 4.0's own element tree (`mujoco.mj_printSchema`): every element and the
/// names of its attributes, no types.
const MUJOCO40_SCHEMA: &str = "schema/mujoco-4.0.0-schema.txt";
/// The types of what MuJoCo 4.0 has beyond dm_control's schema, decided from MuJoCo's
/// XML reference (the file says how to read it).
const MUJOCO40_TYPES: &str = "schema/mujoco-4.0-types.txt";

/// One element of MuJoCo's printed schema.
struct Printed {
    /// Its path (see `key_of`).
    key: String,
    /// `!`, `?`, `*` or `R`.
    marker: char,
    attrs: Vec<String>,
}

/// Reads MuJoCo's printed schema: an element per line (three spaces of indent per
/// level, its name, its marker in parentheses, the first of its attribute names);
/// lines indented further continue the attribute names.
fn parse_printed(text: &str) -> Vec<Printed> {
    let mut out: Vec<Printed> = Vec::new();
    let mut stack: Vec<String> = Vec::new();
    for line in text.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        if words.is_empty() {
            continue;
        }
        let indent = line.len() - line.trim_start().len();
        let marker = words
            .get(1)
            .and_then(|m| m.strip_prefix('('))
            .and_then(|m| m.strip_suffix(')'))
            .filter(|m| m.len() == 1)
            .and_then(|m| m.chars().next());
        match marker {
            Some(marker) if indent < 30 => {
                let depth = indent / 3;
                assert!(depth <= stack.len(), "{MUJOCO40_SCHEMA}: bad indent: {line}");
                stack.truncate(depth);
                stack.push(words[0].to_string());
                let key = if depth == 0 { "mujoco".to_string() } else { stack[1..].join("/") };
                let attrs = words[2..].iter().map(|w| w.to_string()).collect();
                out.push(Printed { key, marker, attrs });
            }
            _ => {
                let last = out.last_mut().unwrap_or_else(|| panic!("{MUJOCO40_SCHEMA}: {line}"));
                last.attrs.extend(words.iter().map(|w| w.to_string()));
            }
        }
    }
    out
}

/// The path of an element as MuJoCo's printed schema names it, from its tags below
/// `<mujoco>`: `mujoco` for the root; a recursive element nested in itself is the
/// element (`default/default/joint` is `default/joint`); `(world)body` is the body
/// (`worldbody/body`), and `worldbody/X` is `(world)body/X` (the worldbody is the
/// top-level body), except the worldbody itself, which MuJoCo's printed schema merges
/// with the body although it takes no attributes.
fn key_of(tags: &[&str]) -> String {
    let mut rest: Vec<&str> = Vec::new();
    for t in tags {
        if rest.last() != Some(t) {
            rest.push(t);
        }
    }
    match rest.as_slice() {
        [] => "mujoco".to_string(),
        ["worldbody"] => "worldbody".to_string(),
        ["worldbody", "body", tail @ ..] | ["worldbody", tail @ ..] => {
            std::iter::once("(world)body").chain(tail.iter().copied()).collect::<Vec<_>>().join("/")
        }
        _ => rest.join("/"),
    }
}

fn dm_key(elems: &[Elem], i: usize) -> String {
    let mut tags = Vec::new();
    let mut cur = Some(i);
    while let Some(c) = cur {
        tags.push(elems[c].name.as_str());
        cur = elems[c].parent;
    }
    tags.pop(); // <mujoco>
    tags.reverse();
    key_of(&tags)
}

/// An attribute from a type in the types file.
fn typed_attr(name: &str, ty: &str, flags: &[&str], at: &str) -> Attr {
    let mut a = Attr { name: name.to_string(), ..Attr::default() };
    for f in flags {
        match *f {
            "required" => a.required = true,
            other => match other.strip_prefix("unless=") {
                Some(u) if ty.starts_with("ref:") => a.reference_unless = Some(u.to_string()),
                _ => panic!("{at}: unknown flag {other}"),
            },
        }
    }
    if let Some(values) = ty.strip_prefix("keyword:") {
        a.ty = "keyword".into();
        a.valid_values = Some(values.replace(',', " "));
    } else if let Some(ns) = ty.strip_prefix("ref:") {
        a.ty = "reference".into();
        a.reference_namespace = Some(ns.to_string());
    } else if ty == "file" || ty.starts_with("file:") {
        a.ty = "file".into();
        a.path_namespace = ty.strip_prefix("file:").map(str::to_string);
    } else if let Some((elem, size)) = ty.split_once('[') {
        let size = size.strip_suffix(']').unwrap_or_else(|| panic!("{at}: bad array type {ty}"));
        assert!(elem == "float" || elem == "int", "{at}: bad array type {ty}");
        a.ty = "array".into();
        a.array_type = Some(elem.to_string());
        a.array_size = (!size.is_empty())
            .then(|| size.parse().unwrap_or_else(|_| panic!("{at}: bad array size {ty}")));
    } else {
        assert!(
            matches!(ty, "float" | "int" | "string" | "prefix" | "identifier"),
            "{at}: unknown type {ty}"
        );
        a.ty = ty.to_string();
    }
    a
}

/// Adds what MuJoCo 4.0 has beyond dm_control's schema: the elements and attributes of
/// the types file, each under every element at its path; then checks that every
/// element and attribute of MuJoCo's printed schema is there. dm_control's elements
/// keep their indices and their attributes' order; new ones come after.
fn merge_mujoco40(elems: &mut Vec<Elem>, printed: &[Printed], types: &str) {
    for i in 0..elems.len() {
        elems[i].key = dm_key(elems, i);
    }
    let with_key = |elems: &[Elem], key: &str| -> Vec<usize> {
        (0..elems.len()).filter(|&i| elems[i].key == key).collect()
    };
    let printed_of = |key: &str| printed.iter().find(|p| p.key == key);
    // (new kinds, the path whose children they take, tags left out)
    let mut take_children: Vec<(Vec<usize>, String, Vec<String>)> = Vec::new();
    for (n, line) in types.lines().enumerate() {
        let at = format!("{MUJOCO40_TYPES}:{}", n + 1);
        if line.trim_start().starts_with('#') || line.trim().is_empty() {
            continue;
        }
        let (spec, source) = line.split_once('|').unwrap_or_else(|| panic!("{at}: no source"));
        assert!(!source.trim().is_empty(), "{at}: no source");
        let w: Vec<&str> = spec.split_whitespace().collect();
        match w.as_slice() {
            ["element", key, multiplicity, opts @ ..] => {
                let (parent_key, tag) = key.rsplit_once('/').unwrap_or(("mujoco", key));
                let parents = with_key(elems, parent_key);
                assert!(!parents.is_empty(), "{at}: no element at {parent_key}");
                let (repeated, on_demand) = match *multiplicity {
                    "repeated" => (true, false),
                    "on_demand" => (false, true),
                    "singleton" => (false, false),
                    other => panic!("{at}: multiplicity {other}"),
                };
                if let Some(p) = printed_of(key) {
                    let fits = match p.marker {
                        '*' | 'R' => repeated,
                        '?' | '!' => !repeated,
                        _ => false,
                    };
                    assert!(fits, "{at}: {multiplicity} but MuJoCo marks it ({})", p.marker);
                }
                let mut namespace_attr = None;
                let mut children_of = None;
                let mut without = Vec::new();
                for o in opts {
                    if let Some(ns) = o.strip_prefix("ns=") {
                        namespace_attr = Some(ns.to_string());
                    } else if let Some(c) = o.strip_prefix("children=") {
                        children_of = Some(c.to_string());
                    } else if let Some(t) = o.strip_prefix('-') {
                        without.push(t.to_string());
                    } else {
                        panic!("{at}: unknown option {o}");
                    }
                }
                let mut new = Vec::new();
                for p in parents {
                    assert!(
                        elems[p].children.iter().all(|&c| elems[c].name != *tag),
                        "{at}: {key} is in dm_control's schema already"
                    );
                    let i = elems.len();
                    elems.push(Elem {
                        name: tag.to_string(),
                        repeated,
                        on_demand,
                        namespace_attr: namespace_attr.clone(),
                        parent: Some(p),
                        key: key.to_string(),
                        ..Elem::default()
                    });
                    elems[p].children.push(i);
                    new.push(i);
                }
                if let Some(c) = children_of {
                    take_children.push((new, c, without));
                }
            }
            ["attr", key, name, ty, flags @ ..] => {
                let targets = with_key(elems, key);
                assert!(!targets.is_empty(), "{at}: no element at {key}");
                if let Some(p) = printed_of(key) {
                    assert!(
                        p.attrs.iter().any(|a| a == name),
                        "{at}: MuJoCo 4.0 lists no {name} on {key}"
                    );
                }
                let attr = typed_attr(name, ty, flags, &at);
                for t in targets {
                    assert!(
                        elems[t].attrs.iter().all(|a| a.name != *name),
                        "{at}: {key} has {name} in dm_control's schema already"
                    );
                    elems[t].attrs.push(attr.clone());
                }
            }
            ["folder", key, name, folder] => {
                let targets = with_key(elems, key);
                assert!(!targets.is_empty(), "{at}: no element at {key}");
                for t in targets {
                    let a = elems[t].attrs.iter_mut().find(|a| a.name == *name);
                    let a = a.unwrap_or_else(|| panic!("{at}: {key} has no {name}"));
                    assert!(a.ty == "file" && a.path_namespace.is_none(), "{at}: {key}@{name}");
                    a.path_namespace = Some(folder.to_string());
                }
            }
            ["retype", key, name, ty] => {
                let targets = with_key(elems, key);
                assert!(!targets.is_empty(), "{at}: no element at {key}");
                let attr = typed_attr(name, ty, &[], &at);
                for t in targets {
                    let a = elems[t].attrs.iter_mut().find(|a| a.name == *name);
                    let a = a.unwrap_or_else(|| panic!("{at}: {key} has no {name}"));
                    assert!(a.ty != attr.ty, "{at}: {key}@{name} has that type already");
                    let (required, conflict_allowed) = (a.required, a.conflict_allowed);
                    let conflict_behavior = a.conflict_behavior.take();
                    *a = Attr { required, conflict_allowed, conflict_behavior, ..attr.clone() };
                }
            }
            ["required", key, name] => {
                let targets = with_key(elems, key);
                assert!(!targets.is_empty(), "{at}: no element at {key}");
                for t in targets {
                    let a = elems[t].attrs.iter_mut().find(|a| a.name == *name);
                    let a = a.unwrap_or_else(|| panic!("{at}: {key} has no {name}"));
                    assert!(!a.required, "{at}: {key}@{name} is required already");
                    a.required = true;
                }
            }
            ["child", parent_key, key] => {
                let kinds = with_key(elems, key);
                let [kind] = kinds[..] else { panic!("{at}: {key} is not one element") };
                let parents = with_key(elems, parent_key);
                assert!(!parents.is_empty(), "{at}: no element at {parent_key}");
                for p in parents {
                    let tag = &elems[kind].name;
                    assert!(
                        elems[p].children.iter().all(|&c| elems[c].name != *tag),
                        "{at}: {parent_key} has a {tag} already"
                    );
                    elems[p].children.push(kind);
                }
            }
            _ => panic!("{at}: cannot read: {line}"),
        }
    }
    for (new, from, without) in take_children {
        let kinds = with_key(elems, &from);
        let [src] = kinds[..] else { panic!("{MUJOCO40_TYPES}: {from} is not one element") };
        let children: Vec<usize> = elems[src]
            .children
            .iter()
            .copied()
            .filter(|&c| !without.contains(&elems[c].name))
            .collect();
        for i in new {
            elems[i].children = children.clone();
        }
    }
    for p in printed {
        let kinds = with_key(elems, &p.key);
        assert!(
            !kinds.is_empty(),
            "{MUJOCO40_SCHEMA}: {} is in neither schema.xml nor {MUJOCO40_TYPES}",
            p.key
        );
        for k in kinds {
            for a in &p.attrs {
                assert!(
                    elems[k].attrs.iter().any(|x| x.name == *a),
                    "{MUJOCO40_SCHEMA}: {}@{a} has no type: add it to {MUJOCO40_TYPES}",
                    p.key
                );
            }
        }
    }
}
