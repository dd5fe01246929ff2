//! Structural comparison of two MJCF XML documents: a Rust port of
//! `tests/conformance/compare.py`.
//!
//! Equivalent means (as in compare.py):
//!   * the same element tree: same tags, same number of children, children in
//!     the same order;
//!   * on every element the same set of attribute names (order is ignored);
//!   * every attribute value equal either as a string, or, when both values
//!     parse as whitespace-separated lists of Python floats, as number lists of
//!     the same length whose entries agree within a relative tolerance of 1e-9
//!     or an absolute tolerance of 1e-12 (NaN equals NaN, infinities must be
//!     equal);
//!   * the same text content (ElementTree's `.text`, i.e. the character data
//!     before the first child element) after stripping surrounding whitespace.
//!
//! `first_difference` reports the first difference with exactly the wording
//! and element path labels of compare.py, including Python's `repr` quoting
//! of names and values.
//!
//! This file is self-contained (std + `quick-xml` only) because it is shared by
//! integration tests and an example via `#[path = "..."] mod compare;`. Its unit
//! tests run in the `tests` binary (`tests/main.rs`).
//!
//! Known differences from Python's ElementTree / compare.py:
//!   * Parsing and comparing use explicit stacks, so arbitrarily deep documents
//!     work (compare.py dies with `RecursionError` beyond ~1000 levels).
//!   * Only the five predefined entities and character references are
//!     expanded. Expat also expands internal entities declared in an inline
//!     DOCTYPE; here such a reference is an "undefined entity" error.
//!   * The parser (quick-xml plus extra checks: legal XML characters and
//!     names, defined entities, a single root element, no text outside it,
//!     no `]]>` in text, no `<` in attribute values, placement of the XML
//!     declaration and DOCTYPE) may still accept a few documents that expat
//!     rejects; names are checked with XML 1.0 fifth-edition rules, while
//!     expat uses the older, narrower Unicode classes for non-ASCII names.
//!   * Python's `str.isprintable`, used by `repr`, is approximated: all
//!     control, format, private-use and separator characters (categories Cc,
//!     Cf, Co, Zs, Zl, Zp) are escaped exactly as Python does, but code points
//!     unassigned in Python's Unicode database (category Cn) are printed as is
//!     where Python would escape them.
//!   * Python's `float()` accepts every Unicode decimal digit (category Nd);
//!     the digit table below is Python 3.11's (Unicode 14.0).
//!
//! Namespaces are handled as ElementTree does: `p:tag` becomes `{uri}tag`,
//! `xmlns` declarations are dropped from the attributes, an undeclared
//! prefix is a parse error.
//!
//! Attribute values are normalized as expat does (XML 1.0 attribute-value
//! normalization): a literal tab, newline, carriage return or CR LF pair
//! becomes one space, while the same characters written as character
//! references (`&#9;`, `&#10;`, `&#13;`) are kept. Text has its line ends
//! normalized (CR LF and lone CR become LF).

// Shared by several targets that each use only part of the API.
#![allow(dead_code)]

use std::collections::BTreeMap;
use std::fmt::Write as _;

use quick_xml::XmlVersion;
use quick_xml::events::{BytesStart, Event};
use quick_xml::reader::Reader;

/// Relative tolerance for numeric attribute values (compare.py's `REL_TOL`).
pub(crate) const REL_TOL: f64 = 1e-9;
/// Absolute tolerance for numeric attribute values (compare.py's `ABS_TOL`).
pub(crate) const ABS_TOL: f64 = 1e-12;

/// One element of a parsed document, in the shape ElementTree gives it.
///
/// Dropping is iterative, so very deep trees are fine; the derived `Debug`
/// is recursive, so do not print a very deep tree.
#[derive(Debug, Default)]
pub(crate) struct XmlElement {
    /// The tag as written (no namespace processing).
    pub tag: String,
    /// Attributes in document order, values unescaped and normalized.
    pub attrs: Vec<(String, String)>,
    /// ElementTree's `.text`: all character data (text, CDATA, references)
    /// between the start tag and the first child element, unstripped.
    /// Comments and processing instructions in between are skipped.
    pub text: String,
    /// Child elements in document order.
    pub children: Vec<XmlElement>,
}

impl XmlElement {
    /// Creates an element with the given tag and nothing else.
    pub(crate) fn new(tag: impl Into<String>) -> Self {
        XmlElement { tag: tag.into(), attrs: Vec::new(), text: String::new(), children: Vec::new() }
    }

    /// The value of attribute `key` (the last one if it is repeated, like a
    /// Python dict built from the pairs).
    pub(crate) fn get(&self, key: &str) -> Option<&str> {
        self.attrs.iter().rev().find(|(k, _)| k == key).map(|(_, v)| v.as_str())
    }
}

impl Drop for XmlElement {
    fn drop(&mut self) {
        // Avoid recursion: move all descendants into one flat list.
        let mut pending = std::mem::take(&mut self.children);
        while let Some(mut element) = pending.pop() {
            pending.append(&mut element.children);
        }
    }
}

/// Parses an XML document and returns its root element.
///
/// Comments, processing instructions, the XML declaration and the DOCTYPE
/// are ignored.
pub(crate) fn parse_xml(text: &str) -> Result<XmlElement, String> {
    if let Some((offset, c)) = text.char_indices().find(|&(_, c)| !is_xml_char(c)) {
        return Err(format!(
            "not well-formed (invalid character U+{:04X}) at byte {offset}",
            u32::from(c)
        ));
    }
    let mut reader = Reader::from_str(text);
    reader.config_mut().check_comments = true;
    reader.config_mut().check_end_names = true;

    let mut open: Vec<XmlElement> = Vec::new();
    let mut root: Option<XmlElement> = None;
    // Namespace declarations in scope, and where each open element's start.
    let mut bindings: Vec<(String, String)> = Vec::new();
    let mut binding_marks: Vec<usize> = Vec::new();
    let mut seen_markup = false;
    let mut seen_doctype = false;
    loop {
        let position = reader.buffer_position();
        let event =
            reader.read_event().map_err(|e| format!("{e} at byte {}", reader.error_position()))?;
        let at = |message: &str| format!("{message} at byte {position}");
        let in_document = root.is_some() || !open.is_empty();
        match event {
            Event::Start(start) => {
                if root.is_some() {
                    return Err(at("junk after document element"));
                }
                binding_marks.push(bindings.len());
                open.push(new_element(&start, &mut bindings).map_err(|e| at(&e))?);
            }
            Event::Empty(start) => {
                if root.is_some() {
                    return Err(at("junk after document element"));
                }
                let mark = bindings.len();
                let element = new_element(&start, &mut bindings).map_err(|e| at(&e))?;
                bindings.truncate(mark);
                close_element(element, &mut open, &mut root);
            }
            Event::End(_) => {
                // quick-xml has already checked that the end tag matches.
                let element = open.pop().ok_or_else(|| at("unexpected end tag"))?;
                bindings.truncate(binding_marks.pop().unwrap_or_default());
                close_element(element, &mut open, &mut root);
            }
            Event::Text(content) => {
                if content.contains("]]>") {
                    return Err(at("not well-formed (']]>' in text)"));
                }
                let content = content.xml10_content();
                add_text(&content, &mut open, true).map_err(|e| at(&e))?;
            }
            Event::CData(content) => {
                let content = content.xml10_content();
                add_text(&content, &mut open, false).map_err(|e| at(&e))?;
            }
            Event::GeneralRef(reference) => {
                let resolved = match reference.resolve_char_ref() {
                    Ok(Some(c)) if is_xml_char(c) => c.to_string(),
                    Ok(Some(c)) => {
                        return Err(at(&format!(
                            "reference to invalid character number {}",
                            u32::from(c)
                        )));
                    }
                    Ok(None) => match quick_xml::escape::resolve_xml_entity(&reference) {
                        Some(value) => value.to_owned(),
                        None => {
                            return Err(at(&format!("undefined entity &{};", &*reference)));
                        }
                    },
                    Err(e) => return Err(at(&e.to_string())),
                };
                add_text(&resolved, &mut open, false).map_err(|e| at(&e))?;
            }
            Event::Decl(_) if seen_markup => {
                return Err(at("XML declaration not at start of document"));
            }
            Event::DocType(_) if in_document || seen_doctype => {
                return Err(at("misplaced DOCTYPE"));
            }
            Event::DocType(_) => seen_doctype = true,
            Event::Comment(_) | Event::PI(_) | Event::Decl(_) => {}
            Event::Eof => break,
        }
        seen_markup = true;
    }
    if !open.is_empty() {
        return Err(format!(
            "no element found: {} unclosed element(s) at end of document",
            open.len()
        ));
    }
    root.ok_or_else(|| "no element found".to_owned())
}

/// Compares two XML documents; `Ok(None)` when they are equivalent,
/// `Ok(Some(description))` for the first difference, `Err` when either
/// does not parse.
pub(crate) fn compare_strings(actual: &str, expected: &str) -> Result<Option<String>, String> {
    let actual = parse_xml(actual).map_err(|e| format!("actual XML: {e}"))?;
    let expected = parse_xml(expected).map_err(|e| format!("expected XML: {e}"))?;
    Ok(first_difference(&actual, &expected))
}

/// Returns a description of the first difference, or `None` if the trees are
/// equivalent. Same traversal order and wording as compare.py.
pub(crate) fn first_difference(actual: &XmlElement, expected: &XmlElement) -> Option<String> {
    struct Frame<'a> {
        actual: &'a XmlElement,
        expected: &'a XmlElement,
        path_len: usize,
        next_child: usize,
    }

    // The path of the element on top of the stack; parents are prefixes.
    let mut path = format!("/{}", label(expected, 0));
    if let Some(diff) = node_difference(actual, expected, &path) {
        return Some(diff);
    }
    let mut stack = vec![Frame { actual, expected, path_len: path.len(), next_child: 0 }];
    while let Some(top) = stack.last_mut() {
        path.truncate(top.path_len);
        let (a, e) = (top.actual, top.expected);
        let i = top.next_child;
        if let (Some(a_child), Some(e_child)) = (a.children.get(i), e.children.get(i)) {
            top.next_child += 1;
            path.push('/');
            path.push_str(&label(e_child, i));
            if let Some(diff) = node_difference(a_child, e_child, &path) {
                return Some(diff);
            }
            stack.push(Frame {
                actual: a_child,
                expected: e_child,
                path_len: path.len(),
                next_child: 0,
            });
        } else {
            if let Some(diff) = child_count_difference(a, e, &path) {
                return Some(diff);
            }
            stack.pop();
        }
    }
    None
}

/// True when two attribute values are equivalent (compare.py's
/// `values_equal`).
pub(crate) fn values_equal(actual: &str, expected: &str) -> bool {
    if actual == expected {
        return true;
    }
    match (parse_numbers(actual), parse_numbers(expected)) {
        (Some(a), Some(e)) => numbers_close(&a, &e),
        _ => false,
    }
}

/// Python's `float(text)`, or `None` where Python raises `ValueError`.
/// `text` is expected without surrounding whitespace (as produced by
/// `str.split()`); whitespace makes it invalid here.
pub(crate) fn parse_py_float(text: &str) -> Option<f64> {
    // Python first maps every Unicode decimal digit to its ASCII digit; any
    // other non-ASCII character makes the string invalid.
    let mut ascii = String::with_capacity(text.len());
    for c in text.chars() {
        if c.is_ascii() {
            ascii.push(c);
        } else {
            ascii.push(char::from(b'0' + unicode_decimal(c)?));
        }
    }
    // Underscores are allowed only between two digits (PEP 515).
    let mut cleaned = String::with_capacity(ascii.len());
    let mut prev: Option<char> = None;
    for c in ascii.chars() {
        if c == '_' {
            if !prev.is_some_and(|p| p.is_ascii_digit()) {
                return None;
            }
        } else {
            if prev == Some('_') && !c.is_ascii_digit() {
                return None;
            }
            cleaned.push(c);
        }
        prev = Some(c);
    }
    if prev == Some('_') {
        return None;
    }
    // What remains has Python's grammar, which is also Rust's:
    // [sign] (inf | infinity | nan | digits [. digits] [e [sign] digits]),
    // case-insensitive. Rust's parser also rejects hex, `nan(...)`, spaces.
    if !cleaned.bytes().all(|b| b.is_ascii_alphanumeric() || matches!(b, b'+' | b'-' | b'.')) {
        return None;
    }
    cleaned.parse::<f64>().ok()
}

const XML_NAMESPACE: &str = "http://www.w3.org/XML/1998/namespace";
const XMLNS_NAMESPACE: &str = "http://www.w3.org/2000/xmlns/";

/// Builds an element from a start tag with ElementTree's namespace
/// handling: `p:tag` and `p:attr` become `{uri}tag` / `{uri}attr` (an
/// unprefixed tag takes the default namespace, an unprefixed attribute
/// none), `xmlns` / `xmlns:p` declarations are not attributes, and an
/// undeclared prefix is an error. The tag's declarations are pushed onto
/// `bindings` (prefix, uri; `""` is the default namespace); the caller pops
/// them when the element ends.
fn new_element(
    start: &BytesStart<'_>,
    bindings: &mut Vec<(String, String)>,
) -> Result<XmlElement, String> {
    let mut attributes = Vec::new();
    for attr in start.attributes() {
        let attr = attr.map_err(|e| e.to_string())?;
        let key = attr.key.as_ref();
        check_name(key)?;
        if attr.value.contains('<') {
            return Err("not well-formed ('<' in an attribute value)".to_owned());
        }
        let value = attr.normalized_value(XmlVersion::default()).map_err(|e| e.to_string())?;
        if let Some(c) = value.chars().find(|&c| !is_xml_char(c)) {
            return Err(format!("reference to invalid character number {}", u32::from(c)));
        }
        let (prefix, local) = split_qname(key)?;
        match (prefix, local) {
            (None, "xmlns") => {
                if value == XML_NAMESPACE || value == XMLNS_NAMESPACE {
                    return Err("reserved namespace name bound".to_owned());
                }
                bindings.push((String::new(), value.into_owned()));
            }
            (Some("xmlns"), declared) => {
                let reserved = match declared {
                    "xmlns" => true,
                    "xml" => value != XML_NAMESPACE,
                    _ => value == XML_NAMESPACE || value == XMLNS_NAMESPACE,
                };
                if reserved {
                    return Err(format!("reserved prefix or namespace in {key}"));
                }
                if value.is_empty() {
                    return Err(format!("must not undeclare prefix {declared}"));
                }
                bindings.push((declared.to_owned(), value.into_owned()));
            }
            _ => attributes.push((key.to_owned(), value.into_owned())),
        }
    }
    let tag = start.name();
    let tag = tag.as_ref();
    check_name(tag)?;
    let mut element = XmlElement::new(expanded_name(tag, bindings, true)?);
    for (key, value) in attributes {
        let key = expanded_name(&key, bindings, false)?;
        if element.attrs.iter().any(|(k, _)| *k == key) {
            return Err(format!("duplicate attribute {key}"));
        }
        element.attrs.push((key, value));
    }
    Ok(element)
}

/// Splits `prefix:local`; more than one colon or an empty part is an error
/// (as in expat's namespace mode).
fn split_qname(name: &str) -> Result<(Option<&str>, &str), String> {
    match name.split_once(':') {
        None => Ok((None, name)),
        Some((prefix, local))
            if !prefix.is_empty() && !local.is_empty() && !local.contains(':') =>
        {
            Ok((Some(prefix), local))
        }
        Some(_) => Err(format!("not well-formed (invalid qualified name {name:?})")),
    }
}

/// ElementTree's `{uri}local` form of a tag (`is_element`) or attribute name.
fn expanded_name(
    name: &str,
    bindings: &[(String, String)],
    is_element: bool,
) -> Result<String, String> {
    let (prefix, local) = split_qname(name)?;
    let lookup = |prefix: &str| {
        bindings.iter().rev().find(|(p, _)| p == prefix).map(|(_, uri)| uri.as_str())
    };
    let uri = match prefix {
        None if is_element => lookup("").unwrap_or_default(),
        None => "",
        Some("xml") => XML_NAMESPACE,
        Some(prefix) => match lookup(prefix) {
            Some(uri) if prefix != "xmlns" => uri,
            _ => return Err(format!("unbound prefix in {name}")),
        },
    };
    Ok(if uri.is_empty() { local.to_owned() } else { format!("{{{uri}}}{local}") })
}

/// Checks the `Name` production of XML 1.0 (fifth edition).
fn check_name(name: &str) -> Result<(), String> {
    let is_start = |c: char| {
        matches!(u32::from(c),
            0x3A | 0x41..=0x5A | 0x5F | 0x61..=0x7A | 0xC0..=0xD6 | 0xD8..=0xF6
            | 0xF8..=0x2FF | 0x370..=0x37D | 0x37F..=0x1FFF | 0x200C..=0x200D
            | 0x2070..=0x218F | 0x2C00..=0x2FEF | 0x3001..=0xD7FF | 0xF900..=0xFDCF
            | 0xFDF0..=0xFFFD | 0x1_0000..=0xE_FFFF)
    };
    let is_char = |c: char| {
        is_start(c)
            || matches!(u32::from(c),
                0x2D | 0x2E | 0x30..=0x39 | 0xB7 | 0x300..=0x36F | 0x203F..=0x2040)
    };
    let mut chars = name.chars();
    match chars.next() {
        Some(first) if is_start(first) && chars.all(is_char) => Ok(()),
        _ => Err(format!("not well-formed (invalid name {name:?})")),
    }
}

fn close_element(element: XmlElement, open: &mut [XmlElement], root: &mut Option<XmlElement>) {
    match open.last_mut() {
        Some(parent) => parent.children.push(element),
        None => *root = Some(element),
    }
}

/// Adds character data to the open element, ElementTree style: it belongs
/// to `.text` only before the first child (afterwards it is a child's
/// `.tail`, which compare.py ignores). Outside the root element only
/// whitespace (and only as plain text) is allowed.
fn add_text(content: &str, open: &mut [XmlElement], plain: bool) -> Result<(), String> {
    match open.last_mut() {
        Some(element) => {
            if element.children.is_empty() {
                element.text.push_str(content);
            }
            Ok(())
        }
        None if plain && content.chars().all(|c| matches!(c, ' ' | '\t' | '\n' | '\r')) => Ok(()),
        None => Err("not well-formed (character data outside the root element)".to_owned()),
    }
}

/// The `Char` production of XML 1.0.
fn is_xml_char(c: char) -> bool {
    matches!(u32::from(c),
        0x9 | 0xA | 0xD | 0x20..=0xD7FF | 0xE000..=0xFFFD | 0x1_0000..=0x10_FFFF)
}

fn label(element: &XmlElement, index: usize) -> String {
    let is_default = element.tag == "default";
    let mut name = element.get("name");
    if name.is_none() && is_default {
        name = element.get("class");
    }
    let mut label = format!("{}[{}]", element.tag, index);
    if let Some(name) = name {
        let key = if is_default { "class" } else { "name" };
        let _ = write!(label, "({key}={})", py_repr(name));
    }
    label
}

fn attr_map(element: &XmlElement) -> BTreeMap<&str, &str> {
    element.attrs.iter().map(|(k, v)| (k.as_str(), v.as_str())).collect()
}

/// The checks compare.py does on one element before visiting its children.
fn node_difference(actual: &XmlElement, expected: &XmlElement, path: &str) -> Option<String> {
    if actual.tag != expected.tag {
        return Some(format!(
            "{path}: tag differs: actual <{}> vs expected <{}>",
            actual.tag, expected.tag
        ));
    }
    let a_attrs = attr_map(actual);
    let e_attrs = attr_map(expected);
    let missing: Vec<(&str, &str)> =
        e_attrs.iter().filter(|(k, _)| !a_attrs.contains_key(*k)).map(|(k, v)| (*k, *v)).collect();
    let extra: Vec<(&str, &str)> =
        a_attrs.iter().filter(|(k, _)| !e_attrs.contains_key(*k)).map(|(k, v)| (*k, *v)).collect();
    if !missing.is_empty() || !extra.is_empty() {
        let list = |pairs: &[(&str, &str)]| {
            pairs.iter().map(|(k, v)| format!("{k}={}", py_repr(v))).collect::<Vec<_>>().join(", ")
        };
        let mut parts = Vec::new();
        if !missing.is_empty() {
            parts.push(format!("missing attributes {}", list(&missing)));
        }
        if !extra.is_empty() {
            parts.push(format!("unexpected attributes {}", list(&extra)));
        }
        return Some(format!("{path}: {}", parts.join("; ")));
    }
    for (key, e_value) in &e_attrs {
        let a_value = a_attrs.get(key).copied().unwrap_or_default();
        if !values_equal(a_value, e_value) {
            return Some(format!(
                "{path}: attribute {} differs: actual {} vs expected {}",
                py_repr(key),
                py_repr(a_value),
                py_repr(e_value)
            ));
        }
    }
    let a_text = py_strip(&actual.text);
    let e_text = py_strip(&expected.text);
    if a_text != e_text {
        return Some(format!(
            "{path}: text differs: actual {} vs expected {}",
            py_repr(a_text),
            py_repr(e_text)
        ));
    }
    None
}

/// The check compare.py does on one element after visiting its children.
fn child_count_difference(
    actual: &XmlElement,
    expected: &XmlElement,
    path: &str,
) -> Option<String> {
    let (a_len, e_len) = (actual.children.len(), expected.children.len());
    if a_len > e_len {
        let extra = &actual.children[e_len];
        return Some(format!(
            "{path}: {a_len} children in actual vs {e_len} expected; first extra: {}",
            label(extra, e_len)
        ));
    }
    if a_len < e_len {
        let missing = &expected.children[a_len];
        return Some(format!(
            "{path}: {a_len} children in actual vs {e_len} expected; first missing: {}",
            label(missing, a_len)
        ));
    }
    None
}

fn parse_numbers(text: &str) -> Option<Vec<f64>> {
    let values: Option<Vec<f64>> = py_split(text).map(parse_py_float).collect();
    values.filter(|v| !v.is_empty())
}

fn numbers_close(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len()
        && a.iter().zip(b).all(|(&x, &y)| {
            if x.is_nan() || y.is_nan() {
                x.is_nan() && y.is_nan()
            } else if x.is_infinite() || y.is_infinite() {
                x == y
            } else {
                (x - y).abs() <= ABS_TOL.max(REL_TOL * x.abs().max(y.abs()))
            }
        })
}

/// Python's `str.isspace` for one character.
fn py_isspace(c: char) -> bool {
    c.is_whitespace() || ('\u{1c}'..='\u{1f}').contains(&c)
}

/// Python's `str.split()` without arguments.
fn py_split(text: &str) -> impl Iterator<Item = &str> {
    text.split(py_isspace).filter(|part| !part.is_empty())
}

/// Python's `str.strip()` without arguments.
fn py_strip(text: &str) -> &str {
    text.trim_matches(py_isspace)
}

/// The first code point of every run of ten Unicode decimal digits (category
/// Nd) in Python 3.11's Unicode database (14.0).
const DECIMAL_ZEROS: [u32; 66] = [
    0x30, 0x660, 0x6f0, 0x7c0, 0x966, 0x9e6, 0xa66, 0xae6, 0xb66, 0xbe6, 0xc66, 0xce6, 0xd66,
    0xde6, 0xe50, 0xed0, 0xf20, 0x1040, 0x1090, 0x17e0, 0x1810, 0x1946, 0x19d0, 0x1a80, 0x1a90,
    0x1b50, 0x1bb0, 0x1c40, 0x1c50, 0xa620, 0xa8d0, 0xa900, 0xa9d0, 0xa9f0, 0xaa50, 0xabf0, 0xff10,
    0x104a0, 0x10d30, 0x11066, 0x110f0, 0x11136, 0x111d0, 0x112f0, 0x11450, 0x114d0, 0x11650,
    0x116c0, 0x11730, 0x118e0, 0x11950, 0x11c50, 0x11d50, 0x11da0, 0x16a60, 0x16ac0, 0x16b50,
    0x1d7ce, 0x1d7d8, 0x1d7e2, 0x1d7ec, 0x1d7f6, 0x1e140, 0x1e2f0, 0x1e950, 0x1fbf0,
];

/// Python's `unicodedata.decimal(c)`.
fn unicode_decimal(c: char) -> Option<u8> {
    let code = u32::from(c);
    DECIMAL_ZEROS
        .iter()
        .find(|&&zero| (zero..zero + 10).contains(&code))
        .and_then(|&zero| u8::try_from(code - zero).ok())
}

/// Code point ranges of categories Cc, Cf, Co, Zs (except the space), Zl, Zp
/// and Cs in Python 3.11's Unicode database: the characters that
/// `str.isprintable` rejects, except unassigned ones (Cn).
const NON_PRINTABLE: [(u32, u32); 28] = [
    (0x0, 0x1f),
    (0x7f, 0xa0),
    (0xad, 0xad),
    (0x600, 0x605),
    (0x61c, 0x61c),
    (0x6dd, 0x6dd),
    (0x70f, 0x70f),
    (0x890, 0x891),
    (0x8e2, 0x8e2),
    (0x1680, 0x1680),
    (0x180e, 0x180e),
    (0x2000, 0x200f),
    (0x2028, 0x202f),
    (0x205f, 0x2064),
    (0x2066, 0x206f),
    (0x3000, 0x3000),
    (0xd800, 0xf8ff),
    (0xfeff, 0xfeff),
    (0xfff9, 0xfffb),
    (0x110bd, 0x110bd),
    (0x110cd, 0x110cd),
    (0x13430, 0x13438),
    (0x1bca0, 0x1bca3),
    (0x1d173, 0x1d17a),
    (0xe0001, 0xe0001),
    (0xe0020, 0xe007f),
    (0xf0000, 0xffffd),
    (0x100000, 0x10fffd),
];

fn py_isprintable(c: char) -> bool {
    let code = u32::from(c);
    !NON_PRINTABLE.iter().any(|&(first, last)| (first..=last).contains(&code))
}

/// Python's `repr` of a `str`.
fn py_repr(text: &str) -> String {
    let quote = if text.contains('\'') && !text.contains('"') { '"' } else { '\'' };
    let mut out = String::with_capacity(text.len() + 2);
    out.push(quote);
    for c in text.chars() {
        let code = u32::from(c);
        match c {
            _ if c == quote || c == '\\' => {
                out.push('\\');
                out.push(c);
            }
            '\t' => out.push_str("\\t"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            _ if code < 0x20 || code == 0x7f => {
                let _ = write!(out, "\\x{code:02x}");
            }
            _ if code < 0x7f || py_isprintable(c) => out.push(c),
            _ if code <= 0xff => {
                let _ = write!(out, "\\x{code:02x}");
            }
            _ if code <= 0xffff => {
                let _ = write!(out, "\\u{code:04x}");
            }
            _ => {
                let _ = write!(out, "\\U{code:08x}");
            }
        }
    }
    out.push(quote);
    out
}

// These modules' own tests run in the mjcf crate's test targets, not in the binding
// crate's, which include them too (its build script sets `mjcf_mujoco`).
#[cfg(all(test, not(mjcf_mujoco)))]
mod tests {
    use super::*;

    fn diff(actual: &str, expected: &str) -> Option<String> {
        match compare_strings(actual, expected) {
            Ok(result) => result,
            Err(e) => panic!("parse error: {e}"),
        }
    }

    #[test]
    fn equal_documents() {
        let xml = r#"<?xml version="1.0"?>
<!-- leading comment -->
<mujoco model="m">
  <worldbody>
    <body name="a" pos="0 0 1"><geom size="1"/></body>
  </worldbody>
</mujoco>"#;
        assert_eq!(diff(xml, xml), None);
    }

    #[test]
    fn attribute_order_is_ignored() {
        assert_eq!(diff(r#"<a x="1" y="b" z="c"/>"#, r#"<a z="c" y="b" x="1"/>"#), None);
    }

    #[test]
    fn whitespace_and_comments_are_ignored() {
        assert_eq!(
            diff("<a>\n  <b/>\n  <!-- c -->\n  <c>t</c>\n</a>", "<a><b/><c>  t\n</c></a>"),
            None
        );
    }

    #[test]
    fn numeric_tolerance() {
        assert_eq!(diff(r#"<a v="1 2"/>"#, r#"<a v="1.0000000001 2"/>"#), None);
        assert_eq!(
            diff(r#"<a v="1 2"/>"#, r#"<a v="1.00000001 2"/>"#).as_deref(),
            Some("/a[0]: attribute 'v' differs: actual '1 2' vs expected '1.00000001 2'")
        );
        assert_eq!(diff(r#"<a v="0.10000000000000001"/>"#, r#"<a v="0.1"/>"#), None);
        // Absolute tolerance near zero.
        assert_eq!(diff(r#"<a v="0"/>"#, r#"<a v="1e-13"/>"#), None);
        assert_eq!(
            diff(r#"<a v="0"/>"#, r#"<a v="1e-11"/>"#).as_deref(),
            Some("/a[0]: attribute 'v' differs: actual '0' vs expected '1e-11'")
        );
        // Different lengths, whitespace layout, non-numbers.
        assert_eq!(
            diff(r#"<a v="1 2"/>"#, r#"<a v="1 2 3"/>"#).as_deref(),
            Some("/a[0]: attribute 'v' differs: actual '1 2' vs expected '1 2 3'")
        );
        assert_eq!(diff("<a v=\" 1   2 \"/>", r#"<a v="1 2"/>"#), None);
        assert_eq!(
            diff(r#"<a v="x"/>"#, r#"<a v="y"/>"#).as_deref(),
            Some("/a[0]: attribute 'v' differs: actual 'x' vs expected 'y'")
        );
        assert_eq!(
            diff(r#"<a v=""/>"#, r#"<a v=" "/>"#).as_deref(),
            Some("/a[0]: attribute 'v' differs: actual '' vs expected ' '")
        );
    }

    #[test]
    fn nan_and_inf() {
        assert_eq!(diff(r#"<a v="nan 1"/>"#, r#"<a v="NaN 1"/>"#), None);
        assert_eq!(diff(r#"<a v="inf"/>"#, r#"<a v="Infinity"/>"#), None);
        assert_eq!(diff(r#"<a v="-inf"/>"#, r#"<a v="-INF"/>"#), None);
        assert_eq!(
            diff(r#"<a v="nan"/>"#, r#"<a v="0"/>"#).as_deref(),
            Some("/a[0]: attribute 'v' differs: actual 'nan' vs expected '0'")
        );
        assert_eq!(
            diff(r#"<a v="inf"/>"#, r#"<a v="-inf"/>"#).as_deref(),
            Some("/a[0]: attribute 'v' differs: actual 'inf' vs expected '-inf'")
        );
        assert_eq!(
            diff(r#"<a v="inf"/>"#, r#"<a v="1e308"/>"#).as_deref(),
            Some("/a[0]: attribute 'v' differs: actual 'inf' vs expected '1e308'")
        );
        // Overflow to infinity, as in Python.
        assert_eq!(diff(r#"<a v="1e400"/>"#, r#"<a v="inf"/>"#), None);
    }

    #[test]
    fn python_float_syntax() {
        // Expected values from Python 3.11's float().
        let valid: &[(&str, f64)] = &[
            ("1", 1.0),
            ("+1.5", 1.5),
            ("-1.5", -1.5),
            ("1e-3", 0.001),
            ("1E3", 1000.0),
            (".5", 0.5),
            ("5.", 5.0),
            ("1.e5", 100000.0),
            ("inf", f64::INFINITY),
            ("-inf", f64::NEG_INFINITY),
            ("+inf", f64::INFINITY),
            ("Infinity", f64::INFINITY),
            ("-infinity", f64::NEG_INFINITY),
            ("INF", f64::INFINITY),
            ("1_000", 1000.0),
            ("1e1_0", 1e10),
            ("\u{661}\u{662}", 12.0),
            ("\u{ff11}\u{ff12}", 12.0),
            ("00012", 12.0),
            ("1e400", f64::INFINITY),
            ("1e-400", 0.0),
        ];
        for &(text, value) in valid {
            assert_eq!(parse_py_float(text), Some(value), "{text:?}");
        }
        for text in ["nan", "NaN", "-nan", "+nan"] {
            assert!(parse_py_float(text).is_some_and(f64::is_nan), "{text:?}");
        }
        assert!(parse_py_float("-0").is_some_and(|v| v == 0.0 && v.is_sign_negative()));
        let invalid = [
            "",
            ".",
            "e5",
            "1e",
            "1e+",
            ".e5",
            "infinit",
            "infinityy",
            "nan(1)",
            "0x1",
            "1__0",
            "_1",
            "1_",
            "1_.5",
            "1._5",
            "1e_1",
            "1_e1",
            "1.5f",
            "1d",
            "0b1",
            "+-1",
            "--1",
            "\u{b2}",
            "\u{bd}",
            "\u{66b}",
            "1\u{66b}5",
            "in_f",
            " 1",
            "1 ",
        ];
        for text in invalid {
            assert_eq!(parse_py_float(text), None, "{text:?}");
        }
    }

    #[test]
    fn differing_tag() {
        assert_eq!(
            diff(
                r#"<mujoco><worldbody><body name="b"><site/></body></worldbody></mujoco>"#,
                r#"<mujoco><worldbody><body name="b"><geom/></body></worldbody></mujoco>"#
            )
            .as_deref(),
            Some(
                "/mujoco[0]/worldbody[0]/body[0](name='b')/geom[0]: tag differs: \
                 actual <site> vs expected <geom>"
            )
        );
    }

    #[test]
    fn missing_and_extra_attributes() {
        assert_eq!(
            diff(r#"<a x="1"/>"#, r#"<a x="1" z="3" y="2"/>"#).as_deref(),
            Some("/a[0]: missing attributes y='2', z='3'")
        );
        assert_eq!(
            diff(r#"<a x="1" q="it's"/>"#, r#"<a x="1"/>"#).as_deref(),
            Some(r#"/a[0]: unexpected attributes q="it's""#)
        );
        assert_eq!(
            diff(r#"<a b="1" c="2"/>"#, r#"<a c="2" d="3"/>"#).as_deref(),
            Some("/a[0]: missing attributes d='3'; unexpected attributes b='1'")
        );
    }

    #[test]
    fn child_counts() {
        assert_eq!(
            diff(
                r#"<mujoco><worldbody><body name="a"/><geom name="g"/></worldbody></mujoco>"#,
                r#"<mujoco><worldbody><body name="a"/></worldbody></mujoco>"#
            )
            .as_deref(),
            Some(
                "/mujoco[0]/worldbody[0]: 2 children in actual vs 1 expected; \
                 first extra: geom[1](name='g')"
            )
        );
        assert_eq!(
            diff(
                r#"<mujoco><default/></mujoco>"#,
                r#"<mujoco><default><default class="main"/><default class="x"/></default></mujoco>"#
            )
            .as_deref(),
            Some(
                "/mujoco[0]/default[0]: 0 children in actual vs 2 expected; \
                 first missing: default[0](class='main')"
            )
        );
    }

    #[test]
    fn children_are_compared_before_counts() {
        // The first difference inside a common child wins over the count.
        assert_eq!(
            diff(r#"<a><b x="1"/><c/><d/></a>"#, r#"<a><b x="2"/></a>"#).as_deref(),
            Some("/a[0]/b[0]: attribute 'x' differs: actual '1' vs expected '2'")
        );
    }

    #[test]
    fn labels() {
        // A default with a name shows it as the class; the label comes from
        // the expected element.
        assert_eq!(
            diff(
                r#"<mujoco><default name="n"><x/></default></mujoco>"#,
                r#"<mujoco><default name="n"><y/></default></mujoco>"#
            )
            .as_deref(),
            Some("/mujoco[0]/default[0](class='n')/y[0]: tag differs: actual <x> vs expected <y>")
        );
        assert_eq!(
            diff(
                r#"<m><w/><w/><w/><b name="x"/></m>"#,
                r#"<m><w/><w/><w/><b name="robot/"><g/></b></m>"#
            )
            .as_deref(),
            Some(
                "/m[0]/b[3](name='robot/'): attribute 'name' differs: actual 'x' vs expected 'robot/'"
            )
        );
    }

    #[test]
    fn text_difference() {
        assert_eq!(
            diff("<a><b> one\n</b></a>", "<a><b>two</b></a>").as_deref(),
            Some("/a[0]/b[0]: text differs: actual 'one' vs expected 'two'")
        );
        // Only the text before the first child counts (ElementTree's .text).
        assert_eq!(diff("<a>x<b/>y</a>", "<a>x<b/>z</a>"), None);
        assert_eq!(
            diff("<a>x<!--c-->y<b/></a>", "<a>xy<b/></a>"),
            None,
            "comments are transparent"
        );
        assert_eq!(diff("<a>x<![CDATA[<y>]]></a>", "<a>x&lt;y&gt;</a>"), None);
        assert_eq!(
            diff("<a>\u{e9}\ttab</a>", "<a>&#233;</a>").as_deref(),
            Some("/a[0]: text differs: actual '\u{e9}\\ttab' vs expected '\u{e9}'")
        );
    }

    #[test]
    fn attribute_value_unescaping() {
        let root = parse_xml("<a b=\"1\n2\t3\r\n4&#10;5&#9;&#13;&lt;&amp;&#x41;&#232;\"/>")
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(root.get("b"), Some("1 2 3 4\n5\t\r<&A\u{e8}"));
        assert_eq!(
            diff(r#"<a b="x&#10;y"/>"#, r#"<a b="x y"/>"#).as_deref(),
            Some(r"/a[0]: attribute 'b' differs: actual 'x\ny' vs expected 'x y'")
        );
    }

    #[test]
    fn text_line_ends_are_normalized() {
        let root = parse_xml("<a>1\r\n2\r3</a>").unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(root.text, "1\n2\n3");
    }

    #[test]
    fn repr_matches_python() {
        // Expected strings from Python 3.11's repr().
        assert_eq!(py_repr("abc"), "'abc'");
        assert_eq!(py_repr("it's"), "\"it's\"");
        assert_eq!(py_repr("it's \"q\""), "'it\\'s \"q\"'");
        assert_eq!(py_repr("a\\b"), "'a\\\\b'");
        assert_eq!(py_repr("\t\n\r\u{1}\u{7f}"), "'\\t\\n\\r\\x01\\x7f'");
        assert_eq!(py_repr("\u{a0}\u{ad}\u{e9}"), "'\\xa0\\xad\u{e9}'");
        assert_eq!(py_repr("\u{2028}\u{feff}\u{4e2d}"), "'\\u2028\\ufeff\u{4e2d}'");
        assert_eq!(py_repr("\u{e0001}\u{1f600}"), "'\\U000e0001\u{1f600}'");
    }

    #[test]
    fn parse_errors() {
        let bad = [
            "",
            "   ",
            "<a>",
            "<a></b>",
            "<a/><b/>",
            "<a/>junk",
            "x<a/>",
            r#"<a b="1" b="2"/>"#,
            r#"<a b="&foo;"/>"#,
            "<a>&foo;</a>",
            "<a>&#0;</a>",
            "<a>&#1;</a>",
            r#"<a b="&#1;"/>"#,
            "<a>\u{1}</a>",
            "<a><!-- a -- b --></a>",
            "</a>",
        ];
        for text in bad {
            assert!(parse_xml(text).is_err(), "{text:?} should not parse");
        }
        assert!(compare_strings("<a/>", "<a>").is_err());
        assert!(compare_strings("<a", "<a/>").is_err());
    }

    #[test]
    fn accepted_prologs() {
        for text in [
            "\u{feff}<a/>",
            "  <a/>  ",
            "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<!DOCTYPE a>\n<?pi x?><a/><!-- c -->\n",
        ] {
            match parse_xml(text) {
                Ok(root) => assert_eq!(root.tag, "a"),
                Err(e) => panic!("{text:?}: {e}"),
            }
        }
    }

    #[test]
    fn deep_nesting_does_not_overflow() {
        const DEPTH: usize = 100_000;
        let mut xml = String::with_capacity(DEPTH * 10);
        for _ in 0..DEPTH {
            xml.push_str("<a>");
        }
        xml.push_str("<b x=\"1\"/>");
        for _ in 0..DEPTH {
            xml.push_str("</a>");
        }
        assert_eq!(diff(&xml, &xml), None);
        let changed = xml.replace("x=\"1\"", "x=\"2\"");
        let result = diff(&xml, &changed).unwrap_or_default();
        assert!(result.starts_with("/a[0]/a[0]/a[0]/"), "{}", &result[..40]);
        assert!(
            result.ends_with("/a[0]/b[0]: attribute 'x' differs: actual '1' vs expected '2'"),
            "{}",
            &result[result.len().saturating_sub(80)..]
        );
        assert_eq!(result.matches("/a[0]").count(), DEPTH);
    }

    /// Runs the real compare.py (`compare_strings`) on each pair and checks
    /// that this port gives the same answer: the same message, or an error
    /// for the same inputs. Returns false (skip) when python3 is missing.
    fn agrees_with_python(pairs: &[(String, String)]) -> bool {
        use std::io::Write as _;
        use std::process::{Command, Stdio};

        let script = r#"
import json, sys
sys.path.insert(0, sys.argv[1])
import compare
def run(a, e):
    try:
        return {"ok": compare.compare_strings(a, e)}
    except Exception as ex:
        return {"error": str(ex)}
pairs = json.load(sys.stdin)
print(json.dumps([run(a, e) for a, e in pairs]))
"#;
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/conformance");
        let child = Command::new("python3")
            .arg("-c")
            .arg(script)
            .arg(dir)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn();
        let Ok(mut child) = child else {
            eprintln!("python3 not available; skipping the comparison with compare.py");
            return false;
        };
        let input = serde_json::to_string(pairs).unwrap_or_else(|e| panic!("{e}"));
        if let Some(mut stdin) = child.stdin.take() {
            stdin.write_all(input.as_bytes()).unwrap_or_else(|e| panic!("{e}"));
        }
        let output = child.wait_with_output().unwrap_or_else(|e| panic!("{e}"));
        assert!(output.status.success(), "compare.py failed: {output:?}");
        let results: Vec<serde_json::Value> =
            serde_json::from_slice(&output.stdout).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(results.len(), pairs.len());
        for ((actual_xml, expected_xml), python) in pairs.iter().zip(results) {
            let ours = compare_strings(actual_xml, expected_xml);
            let context = format!("{actual_xml:?} vs {expected_xml:?}: {ours:?} / {python}");
            match python.get("ok") {
                Some(value) => {
                    let ours = ours.unwrap_or_else(|e| panic!("{context}: {e}"));
                    assert_eq!(ours.as_deref(), value.as_str(), "{context}");
                }
                None => assert!(ours.is_err(), "{context}"),
            }
        }
        true
    }

    #[test]
    fn agrees_with_compare_py_on_tricky_inputs() {
        let pairs: &[(&str, &str)] = &[
            (r#"<a v="1 2"/>"#, r#"<a v="1.0000000001 2"/>"#),
            (r#"<a v="1 2"/>"#, r#"<a v="1.00000001 2"/>"#),
            (r#"<a v="0.10000000000000001"/>"#, r#"<a v="0.1"/>"#),
            (r#"<a v="1_000"/>"#, r#"<a v="1000"/>"#),
            ("<a v=\"\u{661}\u{662}\"/>", r#"<a v="12"/>"#),
            (r#"<a v="nan"/>"#, r#"<a v="-NaN"/>"#),
            (r#"<a v="0x1"/>"#, r#"<a v="1"/>"#),
            (r#"<a v="inf"/>"#, r#"<a v="1e400"/>"#),
            ("<a v=\"1\n2\"/>", r#"<a v="1&#10;2"/>"#),
            ("<a v=\"a\nb\"/>", r#"<a v="a&#10;b"/>"#),
            (r#"<a v="&#233;&#10;&#9;"/>"#, r#"<a v="x"/>"#),
            (r#"<a v="&#1;"/>"#, r#"<a v="x"/>"#),
            ("<a>&#1;</a>", "<a/>"),
            ("<a>&#0;</a>", "<a/>"),
            ("<a>\u{1}</a>", "<a/>"),
            (r#"<a v="&foo;"/>"#, "<a/>"),
            ("<a>&foo;</a>", "<a/>"),
            ("<a/><b/>", "<a/>"),
            ("<a/>x", "<a/>"),
            ("<a/>", "<a>"),
            ("<a/>", ""),
            ("<a/>", "<a></b>"),
            ("<a/>", "<a><!-- x -- y --></a>"),
            (r#"<a b="1" b="2"/>"#, "<a/>"),
            ("\u{feff}<a/>", "<?xml version='1.0'?><!DOCTYPE a><a/>"),
            ("<a b=c/>", "<a/>"),
            ("<a b/>", "<a/>"),
            ("<a>x</a >", "<a\n/>"),
            (r#"<a b = "1"/>"#, r#"<a b='1"'/>"#),
            ("<a>]]></a>", "<a/>"),
            (r#"<a b="x<y"/>"#, "<a/>"),
            (r#"<a b="&#x110000;"/>"#, "<a/>"),
            ("<a>&#xD800;</a>", "<a/>"),
            ("<a>&#xFFFE;</a>", "<a/>"),
            ("<![CDATA[x]]><a/>", "<a/>"),
            ("<a/><!--c--><?p?>", "<a><![CDATA[x]]></a>"),
            ("<a:b/>", "<a/>"),
            ("<a><b></a></b>", "<a/>"),
            ("<a>&lt</a>", "<a/>"),
            ("<a>& b</a>", "<a/>"),
            (r#"<a b="&"/>"#, "<a/>"),
            ("<1a/>", "<a/>"),
            (r#"<a 1b="x"/>"#, "<a/>"),
            (r#"<a -b="x"/>"#, "<a/>"),
            (r#"<a.b b.c-d="x"/>"#, r#"<a.b b.c-d="y"/>"#),
            ("<!DOCTYPE a [<!ENTITY x \"y\">]><a/>", "<a/>"),
            ("<a>x</a><!DOCTYPE a>", "<a/>"),
            ("<!DOCTYPE a><!DOCTYPE a><a/>", "<a/>"),
            (" <?xml version='1.0'?><a/>", "<a/>"),
            ("<a></A>", "<a/>"),
            (
                r#"<a xmlns="u" xmlns:p="v" p:x="1" y="2"><p:b/><c xmlns=""/></a>"#,
                r#"<a xmlns="u"><b/></a>"#,
            ),
            (r#"<p:a xmlns:p="v"/>"#, r#"<q:a xmlns:q="v"/>"#),
            (r#"<a xml:lang="en"/>"#, r#"<a lang="en"/>"#),
            (r#"<a xmlns:p="v" xmlns:q="v" p:x="1" q:x="2"/>"#, "<a/>"),
            (r#"<a p:x="1"/>"#, "<a/>"),
            (r#"<a xmlns:p=""/>"#, "<a/>"),
            (r#"<a:b:c xmlns:a="u"/>"#, "<a/>"),
            (r#"<a xmlns:a="u" a:b:c="1"/>"#, "<a/>"),
            ("<xmlns:a/>", "<a/>"),
            (r#"<a xmlns:xml="x"/>"#, "<a/>"),
            (r#"<a xmlns:xml="http://www.w3.org/XML/1998/namespace"/>"#, "<a/>"),
            (r#"<a xmlns:xmlns="x"/>"#, "<a/>"),
            ("<:a/>", "<a/>"),
            (r#"<a: xmlns:a="u"/>"#, "<a/>"),
            (r#"<a xmlns="u" xmlns="v"/>"#, "<a/>"),
            (
                r#"<p:a xmlns:p="u"><p:b xmlns:p="w" p:c="1"/><p:d/></p:a>"#,
                r#"<x:a xmlns:x="u"><y:b xmlns:y="w" y:c="2"/></x:a>"#,
            ),
            (r#"<a xmlns="">t</a>"#, "<a>u</a>"),
            (
                r#"<a xmlns:p="&amp;&#10;x
y"><p:b/></a>"#,
                "<a><b/></a>",
            ),
            (r#"<a b="1" xmlns:p="u" p:b="2"/>"#, r#"<a b="1"/>"#),
            ("<xml:a/>", "<a/>"),
            (r#"<a xmlns="http://www.w3.org/XML/1998/namespace"/>"#, "<a/>"),
            (r#"<a xmlns:p="http://www.w3.org/2000/xmlns/"/>"#, "<a/>"),
            (r#"<a v="it's &quot;"/>"#, r#"<a v="\"/>"#),
            (r#"<a v="&#xa0;&#xad;&#x2028;"/>"#, r#"<a v="&#x4e2d;"/>"#),
            ("<a>x<b/>y</a>", "<a>x<b/>z</a>"),
            ("<a>x<!--c-->y<?p q?>z</a>", "<a>xyzz</a>"),
            ("<a> \u{85}t\u{a0}</a>", "<a>t</a>"),
            ("<a>\r\nx\ry</a>", "<a>x\ny</a>"),
            (r#"<a><b/><c/></a>"#, r#"<a><b/></a>"#),
            (r#"<a><default/></a>"#, r#"<a><default><default class="c"/></default></a>"#),
            (
                r#"<a><default name="n"/></a>"#,
                r#"<a><default name="n" class="c"><x/></default></a>"#,
            ),
            (r#"<a p="1"/>"#, r#"<a q="2" r="it's"/>"#),
            (r#"<a><b name="x"/></a>"#, r#"<b/>"#),
        ];
        let pairs: Vec<(String, String)> =
            pairs.iter().map(|(a, e)| (a.to_string(), e.to_string())).collect();
        agrees_with_python(&pairs);
    }

    /// Every expected file of the corpus parses and equals itself; and
    /// compare.py and this port agree on pairs of different expected files
    /// (consecutive files of each case, and each case's first file against
    /// the next case's first file).
    #[test]
    fn corpus_files() {
        let root = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/conformance/cases");
        let mut dirs: Vec<_> = std::fs::read_dir(root)
            .unwrap_or_else(|e| panic!("{e}"))
            .map(|entry| entry.unwrap_or_else(|e| panic!("{e}")).path())
            .collect();
        dirs.sort();
        let mut firsts = Vec::new();
        let mut pairs = Vec::new();
        for dir in dirs {
            let mut files: Vec<_> = std::fs::read_dir(&dir)
                .unwrap_or_else(|e| panic!("{e}"))
                .map(|entry| entry.unwrap_or_else(|e| panic!("{e}")).path())
                .filter(|path| {
                    path.file_name()
                        .and_then(|name| name.to_str())
                        .is_some_and(|name| name.starts_with("expected_") && name.ends_with(".xml"))
                })
                .collect();
            files.sort();
            let texts: Vec<String> = files
                .iter()
                .map(|path| std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{e}")))
                .collect();
            for (path, text) in files.iter().zip(&texts) {
                match compare_strings(text, text) {
                    Ok(None) => {}
                    other => panic!("{}: {other:?}", path.display()),
                }
            }
            for window in texts.windows(2) {
                pairs.push((window[0].clone(), window[1].clone()));
            }
            if let Some(first) = texts.first() {
                firsts.push(first.clone());
            }
        }
        assert!(firsts.len() > 100, "corpus not found under {root}");
        for window in firsts.windows(2) {
            pairs.push((window[0].clone(), window[1].clone()));
        }
        agrees_with_python(&pairs);
    }
}
