//! Generates the static MJCF schema tables from `schema/schema.xml`.
//!
//! The schema is data (dm_control's `schema.xml`, itself generated from MuJoCo's schema).
//! This script turns it into `$OUT_DIR/schema_tables.rs`, which `src/schema/mod.rs`
//! includes. No element or attribute list is written by hand anywhere in the crate.
//!
//! Output:
//! - `enum Namespace` with one variant per identifier namespace (an element's
//!   `namespace` attribute, or its tag when it has an identifier attribute), plus
//!   `AttachmentFrame`, which the reference also accepts in `find`;
//! - `static ELEMENTS: [ElementSpec; N]`, one entry per `<element>` in the schema, in
//!   document order (index 0 is `<mujoco>`); recursive elements list themselves as a
//!   child;
//! - per element, its attributes (schema order) and a name-sorted index into them.

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
    let path = Path::new("schema/schema.xml");
    println!("cargo::rerun-if-changed=schema/schema.xml");
    println!("cargo::rerun-if-changed=build.rs");
    let text = std::fs::read_to_string(path).expect("read schema/schema.xml");
    let elems = parse(&text);
    assert_eq!(elems[0].name, "mujoco", "schema root must be <mujoco>");

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
    for (i, e) in elems.iter().enumerate() {
        writeln!(out, "static ATTRS_{i}: [AttrSpec; {}] = [", e.attrs.len()).unwrap();
        for a in &e.attrs {
            let ty = match a.ty.as_str() {
                "float" => "AttrType::Float".to_string(),
                "int" => "AttrType::Int".to_string(),
                "string" => "AttrType::String".to_string(),
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
        let mut by_name: Vec<usize> = (0..e.attrs.len()).collect();
        by_name.sort_by(|x, y| e.attrs[*x].name.cmp(&e.attrs[*y].name));
        by_name.dedup_by(|x, y| e.attrs[*x].name == e.attrs[*y].name);
        writeln!(out, "static ATTRS_BY_NAME_{i}: [u16; {}] = {:?};", by_name.len(), by_name)
            .unwrap();
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
            "    ElementSpec {{ tag: {:?}, multiplicity: {multiplicity}, namespace: {ns}, identifier: {ident}, parent: {parent}, attrs: &ATTRS_{i}, attrs_by_name: &ATTRS_BY_NAME_{i}, children: &[{}] }},",
            e.name,
            children.join(", ")
        )
        .unwrap();
    }
    writeln!(out, "];").unwrap();

    let dest = Path::new(&std::env::var("OUT_DIR").unwrap()).join("schema_tables.rs");
    std::fs::write(dest, out).expect("write schema tables");
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
