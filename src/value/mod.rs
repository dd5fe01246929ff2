//! Typed attribute values: parsed from XML text or from Rust values, formatted back.
//!
//! A [`Value`] is what an element stores for one attribute. Identifiers and references
//! are stored without any scope prefix; the writer adds prefixes while it walks.

mod file;
pub(crate) mod number;
mod scan;

/// A small deterministic generator (xorshift) for the randomised comparisons of the
/// number tests, so that failures repeat.
#[cfg(test)]
mod test_rng {
    pub(crate) struct Rng(pub(crate) u64);

    impl Rng {
        pub(crate) fn next(&mut self) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0
        }

        pub(crate) fn below(&mut self, n: u64) -> u64 {
            self.next() % n
        }
    }
}

use std::fmt;
use std::sync::Arc;

use smol_str::SmolStr;

use crate::error::ValueError;
use crate::id::ElementId;
use crate::schema::{ArrayType, AttrSpec, AttrType, Namespace};

pub use file::FileAsset;
pub(crate) use number::FloatStyle;

/// The value of one attribute.
///
/// Equality and hashing compare floats as the writer writes them: by their bits
/// (`0.0` and `-0.0`, written `0` and `-0`, differ), every NaN being one value (each
/// is written `nan`). So `Value` is [`Eq`] and [`Hash`], a value set twice to NaN is
/// equal to itself, and [`Model`](crate::Model)'s equality, hashing and
/// [`diff`](crate::Model::diff) follow the same rule.
#[derive(Clone, Debug)]
pub enum Value {
    /// A float attribute.
    Float(f64),
    /// An int attribute.
    Int(i64),
    /// A string attribute, verbatim.
    String(SmolStr),
    /// A keyword, in the schema's spelling.
    Keyword(&'static str),
    /// A float array.
    Floats(Arc<[f64]>),
    /// An int array.
    Ints(Arc<[i64]>),
    /// The element's own name (never contains `/`).
    Identifier(SmolStr),
    /// A reference to another element.
    Reference(Reference),
    /// A file, with its contents.
    File(FileAsset),
    /// A folder setting (`meshdir`); never written.
    Basepath(SmolStr),
}

/// A reference attribute's value.
///
/// `Name` is text, interpreted in the scope of the model that holds it, and written
/// with that model's prefix (a dangling name is kept as it is, as MuJoCo reports those
/// when it compiles). `Element` points at an element of the same model by its stable
/// id: renaming the target renames the reference, and removing the target clears it.
/// Reading a model resolves every reference that names an existing element.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Reference {
    /// A name.
    Name(SmolStr),
    /// An element of the same model.
    Element(ElementId),
}

/// A value as given by a caller before it is checked against the schema.
///
/// Anything that converts into it can be passed to [`crate::Element::attr`] and
/// [`crate::Attrs::set`]: text (`"0 0 1"`), numbers, arrays and slices of numbers,
/// `bool` (for `true`/`false` keywords) and [`Value`].
///
/// Equality compares numbers as [`Value`] does: by their bits, every NaN one value.
#[derive(Clone, Debug)]
pub enum AttrInput {
    /// XML text, parsed by the attribute's type.
    Text(SmolStr),
    /// One number.
    Number(f64),
    /// Several numbers.
    Numbers(Vec<f64>),
    /// A boolean keyword.
    Bool(bool),
    /// A typed value, used as is when its type fits.
    Value(Value),
}

/// Whether two floats are the same value as the writer writes them: the same bits,
/// or both NaN.
pub(crate) fn same_float(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

fn same_floats(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| same_float(*x, *y))
}

/// The bits [`same_float`] compares: every NaN gives the bits of one NaN.
fn float_bits(x: f64) -> u64 {
    if x.is_nan() { f64::NAN.to_bits() } else { x.to_bits() }
}

impl PartialEq for Value {
    /// Equality with floats compared by their bits, every NaN one value (see
    /// [`Value`]).
    fn eq(&self, other: &Value) -> bool {
        match (self, other) {
            (Value::Float(a), Value::Float(b)) => same_float(*a, *b),
            (Value::Floats(a), Value::Floats(b)) => Arc::ptr_eq(a, b) || same_floats(a, b),
            (Value::Int(a), Value::Int(b)) => a == b,
            (Value::Ints(a), Value::Ints(b)) => a == b,
            (Value::String(a), Value::String(b)) => a == b,
            (Value::Keyword(a), Value::Keyword(b)) => a == b,
            (Value::Identifier(a), Value::Identifier(b)) => a == b,
            (Value::Reference(a), Value::Reference(b)) => a == b,
            (Value::File(a), Value::File(b)) => a == b,
            (Value::Basepath(a), Value::Basepath(b)) => a == b,
            _ => false,
        }
    }
}

impl Eq for Value {}

impl std::hash::Hash for Value {
    /// Consistent with equality: floats by their bits, every NaN hashed as one.
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        std::mem::discriminant(self).hash(state);
        match self {
            Value::Float(x) => state.write_u64(float_bits(*x)),
            Value::Floats(xs) => {
                state.write_usize(xs.len());
                xs.iter().for_each(|x| state.write_u64(float_bits(*x)));
            }
            Value::Int(x) => x.hash(state),
            Value::Ints(xs) => xs.hash(state),
            Value::String(t) | Value::Identifier(t) | Value::Basepath(t) => t.hash(state),
            Value::Keyword(k) => k.hash(state),
            Value::Reference(r) => r.hash(state),
            Value::File(f) => f.hash(state),
        }
    }
}

impl PartialEq for AttrInput {
    /// Equality with numbers compared by their bits, every NaN one value (see
    /// [`Value`]).
    fn eq(&self, other: &AttrInput) -> bool {
        match (self, other) {
            (AttrInput::Text(a), AttrInput::Text(b)) => a == b,
            (AttrInput::Number(a), AttrInput::Number(b)) => same_float(*a, *b),
            (AttrInput::Numbers(a), AttrInput::Numbers(b)) => same_floats(a, b),
            (AttrInput::Bool(a), AttrInput::Bool(b)) => a == b,
            (AttrInput::Value(a), AttrInput::Value(b)) => a == b,
            _ => false,
        }
    }
}

impl From<&str> for AttrInput {
    fn from(v: &str) -> Self {
        AttrInput::Text(v.into())
    }
}
impl From<String> for AttrInput {
    fn from(v: String) -> Self {
        AttrInput::Text(v.into())
    }
}
impl From<&String> for AttrInput {
    fn from(v: &String) -> Self {
        AttrInput::Text(v.into())
    }
}
impl From<SmolStr> for AttrInput {
    fn from(v: SmolStr) -> Self {
        AttrInput::Text(v)
    }
}
impl From<f64> for AttrInput {
    fn from(v: f64) -> Self {
        AttrInput::Number(v)
    }
}
impl From<f32> for AttrInput {
    fn from(v: f32) -> Self {
        AttrInput::Number(v.into())
    }
}
impl From<i32> for AttrInput {
    fn from(v: i32) -> Self {
        AttrInput::Number(v.into())
    }
}
impl From<u32> for AttrInput {
    fn from(v: u32) -> Self {
        AttrInput::Number(v.into())
    }
}
impl From<bool> for AttrInput {
    fn from(v: bool) -> Self {
        AttrInput::Bool(v)
    }
}
impl<const N: usize> From<[f64; N]> for AttrInput {
    fn from(v: [f64; N]) -> Self {
        AttrInput::Numbers(v.to_vec())
    }
}
impl<const N: usize> From<[i32; N]> for AttrInput {
    fn from(v: [i32; N]) -> Self {
        AttrInput::Numbers(v.iter().map(|x| f64::from(*x)).collect())
    }
}

impl<const N: usize> From<[f32; N]> for AttrInput {
    fn from(v: [f32; N]) -> Self {
        AttrInput::Numbers(v.iter().map(|x| f64::from(*x)).collect())
    }
}

impl From<Vec<i32>> for AttrInput {
    fn from(v: Vec<i32>) -> Self {
        AttrInput::Numbers(v.into_iter().map(f64::from).collect())
    }
}

impl From<&[f64]> for AttrInput {
    fn from(v: &[f64]) -> Self {
        AttrInput::Numbers(v.to_vec())
    }
}
impl From<Vec<f64>> for AttrInput {
    fn from(v: Vec<f64>) -> Self {
        AttrInput::Numbers(v)
    }
}
impl From<Value> for AttrInput {
    fn from(v: Value) -> Self {
        AttrInput::Value(v)
    }
}

/// What the reader needs beyond the text to build a value: the element's namespace (a
/// body may not be named `world`).
pub(crate) fn parse_text(
    spec: &AttrSpec,
    namespace: Option<Namespace>,
    text: &str,
) -> Result<Value, ValueError> {
    let mut value = Value::Int(0);
    parse_text_into(spec, namespace, text, &mut value)?;
    Ok(value)
}

/// [`parse_text`] into `dst`, where the value is to stay (the reader's list of an
/// element's attributes): a value returned is written in parts and copied whole,
/// which stalls the copy, once per attribute read. `dst` is unspecified on an error.
pub(crate) fn parse_text_into(
    spec: &AttrSpec,
    namespace: Option<Namespace>,
    text: &str,
    dst: &mut Value,
) -> Result<(), ValueError> {
    if matches!(
        spec.ty,
        AttrType::String
            | AttrType::NamePrefix
            | AttrType::Identifier
            | AttrType::Reference(_)
            | AttrType::Basepath { .. }
    ) {
        check_xml_text(text)?;
    }
    match spec.ty {
        AttrType::Float => {
            *dst = Value::Float(number::parse_float(text).ok_or(ValueError::NotFloat)?)
        }
        AttrType::Int => *dst = Value::Int(number::parse_int(text).ok_or(ValueError::NotInt)?),
        AttrType::String | AttrType::NamePrefix => *dst = Value::String(text.into()),
        AttrType::Keyword(valid) => {
            let found = valid.iter().find(|v| v.eq_ignore_ascii_case(text.trim()));
            *dst = Value::Keyword(found.ok_or(ValueError::NotKeyword { valid })?);
        }
        AttrType::Array { elem, max_len } => {
            *dst = match elem {
                ArrayType::Float => {
                    Value::Floats(scan::parse_array(text).ok_or(ValueError::NotFloatArray)?)
                }
                ArrayType::Int => {
                    Value::Ints(scan::parse_array(text).ok_or(ValueError::NotIntArray)?)
                }
            };
            check_len(dst, max_len)?;
        }
        AttrType::Identifier => *dst = identifier(text, namespace)?,
        AttrType::Reference(_) => *dst = Value::Reference(Reference::Name(text.into())),
        AttrType::Basepath { .. } => *dst = Value::Basepath(text.into()),
        AttrType::File { .. } => return Err(ValueError::FileNeedsLoading),
    }
    Ok(())
}

fn check_len(value: &Value, max_len: Option<u32>) -> Result<(), ValueError> {
    let len = match value {
        Value::Floats(v) => v.len(),
        Value::Ints(v) => v.len(),
        _ => return Ok(()),
    };
    match max_len {
        Some(max) if len > max as usize => Err(ValueError::TooLong { max, len }),
        _ => Ok(()),
    }
}

/// Whether XML 1.0 can hold `c` (its `Char` production).
pub(crate) fn is_xml_char(c: char) -> bool {
    matches!(c, '\t' | '\n' | '\r' | '\u{20}'..='\u{D7FF}' | '\u{E000}'..='\u{FFFD}' | '\u{10000}'..)
}

/// Whether a byte is written as it is: printable ASCII other than `& < > "`.
#[cfg(test)]
fn clean_byte(b: u8) -> bool {
    (0x20..0x7f).contains(&b) && !matches!(b, b'&' | b'<' | b'>' | b'"')
}

/// Whether every byte of `s` is written in XML as it is (`clean_byte` in the tests):
/// eight bytes at a time (names are scanned once per attribute written, and most are
/// a few dozen bytes).
pub(crate) fn is_clean(s: &[u8]) -> bool {
    const ONES: u64 = 0x0101_0101_0101_0101;
    const HIGH: u64 = 0x8080_8080_8080_8080;
    // Nonzero iff some byte of `x` is zero (exact as to whether one is).
    fn zero_byte(x: u64) -> u64 {
        x.wrapping_sub(ONES) & !x & HIGH
    }
    fn clean8(x: u64) -> bool {
        // A byte below 0x20; a byte of 0x7f or more (the +1 carries out of a byte
        // only from 0xff, itself caught by `x & HIGH`); one of the four to escape.
        let special = (x.wrapping_sub(ONES * 0x20) & !x & HIGH)
            | ((x | x.wrapping_add(ONES)) & HIGH)
            | zero_byte(x ^ (ONES * u64::from(b'&')))
            | zero_byte(x ^ (ONES * u64::from(b'<')))
            | zero_byte(x ^ (ONES * u64::from(b'>')))
            | zero_byte(x ^ (ONES * u64::from(b'"')));
        special == 0
    }
    let word = |c: &[u8]| c.try_into().map(u64::from_le_bytes);
    let mut chunks = s.chunks_exact(8);
    for c in &mut chunks {
        if !word(c).is_ok_and(clean8) {
            return false;
        }
    }
    // The last 1 to 7 bytes: the last eight bytes again where there are eight (read
    // at once: a tail copied to a padded buffer byte by byte and read back as a word
    // stalls the read), else the bytes shifted into a word of clean ones.
    let rest = chunks.remainder();
    if rest.is_empty() {
        return true;
    }
    if let Some(tail) = s.len().checked_sub(8) {
        return word(&s[tail..]).is_ok_and(clean8);
    }
    let mut x = ONES * u64::from(b'a');
    for (k, &b) in rest.iter().enumerate() {
        let shift = 8 * k;
        x = (x & !(0xff << shift)) | (u64::from(b) << shift);
    }
    clean8(x)
}

/// Refuses text that XML cannot hold, so that every value can be written and read back.
fn check_xml_text(text: &str) -> Result<(), ValueError> {
    // ASCII text (names, mostly) is checked by byte: only control characters other
    // than tab, newline and carriage return are refused.
    if text.bytes().all(|b| (0x20..0x80).contains(&b) || matches!(b, b'\t' | b'\n' | b'\r')) {
        return Ok(());
    }
    match text.chars().find(|c| !is_xml_char(*c)) {
        Some(c) => Err(ValueError::InvalidCharacter(c)),
        None => Ok(()),
    }
}

/// Checks an identifier: no `/`, and a body is not named `world`.
/// Names read from MJCF may hold `/` (MuJoCo accepts it; a file this crate wrote holds
/// `robot/torso`): such a name is one literal name. Names given through the API may
/// not ([`from_input`] refuses them), as `/` separates scopes in lookups there.
pub(crate) fn identifier(text: &str, namespace: Option<Namespace>) -> Result<Value, ValueError> {
    if namespace == Some(Namespace::Body) && text == "world" {
        return Err(ValueError::WorldBody);
    }
    Ok(Value::Identifier(text.into()))
}

/// Converts a caller's input to a value of the attribute's type. `Ok(None)` means the
/// input clears the attribute (an empty identifier, reference or string, as in the
/// reference implementation).
pub(crate) fn from_input(
    spec: &AttrSpec,
    namespace: Option<Namespace>,
    input: &AttrInput,
) -> Result<Option<Value>, ValueError> {
    // Text that clears (empty names, references, strings) is handled by the caller,
    // `ValueCtx::assign`, the one place that decides what clears.
    // A name given through the API cannot hold `/`, which separates scopes there.
    let slash = match input {
        AttrInput::Text(t) | AttrInput::Value(Value::Identifier(t)) => t.contains('/'),
        _ => false,
    };
    if slash && spec.ty == AttrType::Identifier {
        return Err(ValueError::SlashInIdentifier);
    }
    match input {
        AttrInput::Text(t) => parse_text(spec, namespace, t).map(Some),
        AttrInput::Bool(b) => match spec.ty {
            AttrType::Keyword(_) => {
                parse_text(spec, namespace, if *b { "true" } else { "false" }).map(Some)
            }
            _ => Err(ValueError::WrongType),
        },
        AttrInput::Number(x) => match spec.ty {
            AttrType::Float => Ok(Some(Value::Float(*x))),
            AttrType::Int => {
                number::float_to_int(*x).map(|v| Some(Value::Int(v))).ok_or(ValueError::NotInt)
            }
            AttrType::Array { .. } => from_input(spec, namespace, &AttrInput::Numbers(vec![*x])),
            _ => Err(ValueError::WrongType),
        },
        AttrInput::Numbers(xs) => match spec.ty {
            AttrType::Array { elem, max_len } => {
                let value = match elem {
                    ArrayType::Float => Value::Floats(xs.as_slice().into()),
                    ArrayType::Int => {
                        let v: Option<Vec<i64>> =
                            xs.iter().map(|x| number::float_to_int(*x)).collect();
                        Value::Ints(v.ok_or(ValueError::NotIntArray)?.into())
                    }
                };
                check_len(&value, max_len)?;
                Ok(Some(value))
            }
            AttrType::Float | AttrType::Int if xs.len() == 1 => {
                from_input(spec, namespace, &AttrInput::Number(xs[0]))
            }
            _ => Err(ValueError::WrongType),
        },
        AttrInput::Value(v) => check_value(spec, namespace, v).map(Some),
    }
}

/// Checks that a typed value fits the attribute.
fn check_value(
    spec: &AttrSpec,
    namespace: Option<Namespace>,
    v: &Value,
) -> Result<Value, ValueError> {
    if let Value::String(t)
    | Value::Identifier(t)
    | Value::Basepath(t)
    | Value::Reference(Reference::Name(t)) = v
    {
        check_xml_text(t)?;
    }
    let fits = match (spec.ty, v) {
        (AttrType::Float, Value::Float(_)) | (AttrType::Int, Value::Int(_)) => true,
        (AttrType::String | AttrType::NamePrefix, Value::String(_))
        | (AttrType::Basepath { .. }, Value::Basepath(_)) => true,
        (AttrType::Keyword(valid), Value::Keyword(k)) => {
            return valid
                .iter()
                .find(|x| x.eq_ignore_ascii_case(k))
                .map(|x| Value::Keyword(x))
                .ok_or(ValueError::NotKeyword { valid });
        }
        (AttrType::Array { elem: ArrayType::Float, max_len }, Value::Floats(_))
        | (AttrType::Array { elem: ArrayType::Int, max_len }, Value::Ints(_)) => {
            check_len(v, max_len)?;
            true
        }
        (AttrType::Identifier, Value::Identifier(t)) => return identifier(t, namespace),
        (AttrType::Reference(_), Value::Reference(_)) => true,
        (AttrType::File { .. }, Value::File(_)) => true,
        _ => false,
    };
    if fits { Ok(v.clone()) } else { Err(ValueError::WrongType) }
}

impl Value {
    /// Appends the value's XML text for the simple types (everything but identifiers,
    /// references and files, whose text depends on where the element sits).
    pub(crate) fn write_plain(&self, out: &mut String, style: FloatStyle) {
        use fmt::Write as _;
        match self {
            Value::Float(x) => number::write_float(out, *x, style),
            Value::Int(i) => {
                let _ = write!(out, "{i}");
            }
            Value::String(s) | Value::Identifier(s) | Value::Basepath(s) => out.push_str(s),
            Value::Keyword(k) => out.push_str(k),
            Value::Floats(v) => number::write_floats(out, v, style),
            Value::Ints(v) => {
                for (i, x) in v.iter().enumerate() {
                    if i > 0 {
                        out.push(' ');
                    }
                    let _ = write!(out, "{x}");
                }
            }
            Value::Reference(Reference::Name(s)) => out.push_str(s),
            Value::Reference(Reference::Element(id)) => {
                let _ = write!(out, "{id:?}");
            }
            Value::File(f) => out.push_str(&f.vfs_name(true)),
        }
    }

    /// The value as a float, for float attributes.
    ///
    /// Time: O(1).
    pub fn as_float(&self) -> Option<f64> {
        match self {
            Value::Float(x) => Some(*x),
            _ => None,
        }
    }

    /// The value as an integer, for int attributes.
    ///
    /// Time: O(1).
    pub fn as_int(&self) -> Option<i64> {
        match self {
            Value::Int(x) => Some(*x),
            _ => None,
        }
    }

    /// The value as text for string-like attributes (strings, keywords, identifiers,
    /// named references, folder settings).
    ///
    /// Time: O(1).
    pub fn as_str(&self) -> Option<&str> {
        match self {
            Value::String(s) | Value::Identifier(s) | Value::Basepath(s) => Some(s),
            Value::Reference(Reference::Name(s)) => Some(s),
            Value::Keyword(k) => Some(k),
            _ => None,
        }
    }

    /// The value as floats, for float arrays.
    ///
    /// Time: O(1).
    pub fn as_floats(&self) -> Option<&[f64]> {
        match self {
            Value::Floats(v) => Some(v),
            _ => None,
        }
    }

    /// The value as integers, for int arrays.
    ///
    /// Time: O(1).
    pub fn as_ints(&self) -> Option<&[i64]> {
        match self {
            Value::Ints(v) => Some(v),
            _ => None,
        }
    }
}

impl fmt::Display for Value {
    /// Formats the value as XML text with shortest round-trip floats; references to
    /// elements show their id, as the name depends on the model.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut s = String::new();
        self.write_plain(&mut s, FloatStyle::default());
        f.write_str(&s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The eight-bytes-at-a-time scan says what the byte-by-byte one says: every byte
    /// value at every position of strings of every length up to 24, and random ones.
    #[test]
    fn is_clean_is_every_byte_clean() {
        for len in 1..=24 {
            for at in 0..len {
                for b in 0..=255u8 {
                    let mut s = vec![b'a'; len];
                    s[at] = b;
                    assert_eq!(is_clean(&s), clean_byte(b), "{b:#x} at {at} of {len}");
                }
            }
        }
        let mut r: u64 = 0x2545_f491_4f6c_dd1d;
        for _ in 0..100_000 {
            r ^= r << 13;
            r ^= r >> 7;
            r ^= r << 17;
            let len = (r % 40) as usize;
            // Mostly clean bytes, with a few of anything.
            let s: Vec<u8> = (0..len)
                .map(|k| {
                    let x = r.rotate_left(k as u32 * 7);
                    if x % 16 == 0 { (x >> 8) as u8 } else { 0x20 + ((x >> 8) % 95) as u8 }
                })
                .collect();
            assert_eq!(is_clean(&s), s.iter().all(|&b| clean_byte(b)), "{s:?}");
        }
        assert!(is_clean(b""));
    }
    use crate::schema::ElementKind;

    fn spec(path: &[&str], attr: &str) -> (&'static AttrSpec, Option<Namespace>) {
        let mut k = ElementKind::ROOT;
        for p in path {
            k = k.child(p).unwrap();
        }
        (k.attr(k.attr_index(attr).unwrap()), k.namespace())
    }

    fn parse(path: &[&str], attr: &str, text: &str) -> Result<Value, ValueError> {
        let (s, ns) = spec(path, attr);
        parse_text(s, ns, text)
    }

    fn text(v: &Value) -> String {
        let mut s = String::new();
        v.write_plain(&mut s, FloatStyle::default());
        s
    }

    const GEOM: &[&str] = &["worldbody", "geom"];
    const BODY: &[&str] = &["worldbody", "body"];

    #[test]
    fn floats_ints_and_arrays() {
        assert_eq!(parse(GEOM, "mass", "1e-3"), Ok(Value::Float(1e-3)));
        assert_eq!(parse(GEOM, "mass", "heavy"), Err(ValueError::NotFloat));
        assert_eq!(parse(GEOM, "condim", "3.0"), Ok(Value::Int(3)));
        assert_eq!(parse(GEOM, "condim", "1.5"), Err(ValueError::NotInt));
        assert_eq!(text(&parse(GEOM, "size", "0.1  0.2\n0.3").unwrap()), "0.1 0.2 0.3");
        assert_eq!(text(&parse(GEOM, "size", "0.1").unwrap()), "0.1");
        assert_eq!(parse(GEOM, "size", "1 2 3 4"), Err(ValueError::TooLong { max: 3, len: 4 }));
        assert_eq!(parse(GEOM, "size", "1,2"), Err(ValueError::NotFloatArray));
        assert_eq!(text(&parse(GEOM, "size", "").unwrap()), "");
        assert_eq!(text(&parse(GEOM, "user", "1 2 3 4 5 6 7").unwrap()), "1 2 3 4 5 6 7");
    }

    #[test]
    fn keywords_match_case_insensitively_and_print_canonically() {
        assert_eq!(parse(GEOM, "type", "BOX"), Ok(Value::Keyword("box")));
        assert_eq!(parse(&["option"], "integrator", "rk4"), Ok(Value::Keyword("RK4")));
        assert!(matches!(parse(GEOM, "type", "cube"), Err(ValueError::NotKeyword { .. })));
        let (s, ns) = spec(&["compiler"], "autolimits");
        assert_eq!(from_input(s, ns, &AttrInput::Bool(true)), Ok(Some(Value::Keyword("true"))));
    }

    #[test]
    fn identifiers_reject_slash_and_world_bodies() {
        assert_eq!(
            parse(BODY, "name", "a/b"),
            Ok(Value::Identifier("a/b".into())),
            "read: one literal name"
        );
        let (s, ns) = spec(BODY, "name");
        assert_eq!(
            from_input(s, ns, &"a/b".into()),
            Err(ValueError::SlashInIdentifier),
            "given: refused"
        );
        assert_eq!(parse(BODY, "name", "world"), Err(ValueError::WorldBody));
        assert_eq!(parse(GEOM, "name", "world"), Ok(Value::Identifier("world".into())));
    }

    #[test]
    fn numbers_convert_to_the_attribute_type() {
        let (s, ns) = spec(GEOM, "condim");
        assert_eq!(from_input(s, ns, &4.into()), Ok(Some(Value::Int(4))));
        assert_eq!(from_input(s, ns, &4.5.into()), Err(ValueError::NotInt));
        let (s, ns) = spec(GEOM, "size");
        assert_eq!(text(&from_input(s, ns, &0.1.into()).unwrap().unwrap()), "0.1");
        assert_eq!(
            from_input(s, ns, &[1.0, 2.0, 3.0, 4.0].into()),
            Err(ValueError::TooLong { max: 3, len: 4 })
        );
        let (s, ns) = spec(GEOM, "name");
        assert_eq!(from_input(s, ns, &1.0.into()), Err(ValueError::WrongType));
        let (s, ns) = spec(&["compiler"], "inertiagrouprange");
        assert_eq!(from_input(s, ns, &[0.0, 3.0].into()), Ok(Some(Value::Ints([0, 3].into()))));
    }
}
