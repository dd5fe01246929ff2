//! Number text: parsing with the reference's rules and formatting in two styles.
//!
//! - Parsing follows Python as dm_control uses it: floats as `float()` (`nan`, `inf`,
//!   `1e-3`), integers as `int(float(s))` with a check that the value is integral.
//! - Formatting prints the shortest text that reads back to the same double by
//!   default (`0.1`), laid out like C's `%g` with 17 digits of room (`1e-05`,
//!   `10000000000000000`, `1e+17`); with a precision it prints C's `%.{p}g` exactly.

use std::fmt;
use std::fmt::Write as _;

mod shortest;
mod tables;

/// How floats are written.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FloatStyle {
    /// `None`: shortest round-trip. `Some(p)`: C `%.{p}g`.
    pub precision: Option<u32>,
    /// Values with a magnitude below this are written as `0`.
    pub zero_threshold: f64,
}

impl Default for FloatStyle {
    fn default() -> Self {
        FloatStyle { precision: None, zero_threshold: 0.0 }
    }
}

/// Parses a float the way Python's `float()` does for the inputs MJCF uses.
pub(crate) fn parse_float(text: &str) -> Option<f64> {
    if let Some(x) = super::scan::plain_float(text.as_bytes()) {
        return Some(x);
    }
    let t = text.trim();
    if t.is_empty() {
        return None;
    }
    // Rust accepts what Python accepts here (`inf`, `-Infinity`, `nan`, `1e5`, `.5`,
    // `5.`), except that Python also allows `_` between digits; MJCF files never use it.
    t.parse::<f64>().ok()
}

/// Parses an integer as `int(float(text))`, rejecting non-integral values.
pub(crate) fn parse_int(text: &str) -> Option<i64> {
    if let Some(v) = super::scan::plain_int(text.as_bytes()) {
        return Some(v);
    }
    let t = text.trim();
    if let Ok(v) = t.parse::<i64>() {
        return Some(v);
    }
    float_to_int(parse_float(t)?)
}

/// The fast path of `scan`, then the general parser: how arrays read their numbers.
impl super::scan::Number for f64 {
    fn lead(bytes: &[u8], i: &mut usize) -> Option<f64> {
        super::scan::lead_float(bytes, i)
    }
    fn parse(text: &str) -> Option<f64> {
        parse_float(text)
    }
}

impl super::scan::Number for i64 {
    fn lead(bytes: &[u8], i: &mut usize) -> Option<i64> {
        super::scan::lead_int(bytes, i)
    }
    fn parse(text: &str) -> Option<i64> {
        parse_int(text)
    }
}

/// Converts an integral, in-range float to an integer.
pub(crate) fn float_to_int(v: f64) -> Option<i64> {
    // 2^63 is exactly representable; every double below it in magnitude fits.
    const LIMIT: f64 = 9_223_372_036_854_775_808.0; // 2^63
    if v.is_finite() && v.fract() == 0.0 && (-LIMIT..LIMIT).contains(&v) {
        Some(v as i64)
    } else {
        None
    }
}

/// Appends the text of `x` in the given style.
pub(crate) fn write_float(out: &mut String, x: f64, style: FloatStyle) {
    write_floats(out, std::slice::from_ref(&x), style);
}

/// Appends the texts of `xs` in the given style, separated by single spaces.
pub(crate) fn write_floats(out: &mut String, xs: &[f64], style: FloatStyle) {
    if let Some(p) = style.precision {
        for (i, &x) in xs.iter().enumerate() {
            if i > 0 {
                out.push(' ');
            }
            match special(x, style.zero_threshold) {
                Ok(x) => write_g(out, x, p.max(1)),
                Err(text) => out.push_str(text),
            }
        }
        return;
    }
    // The shortest texts are gathered on the stack and appended a few hundred bytes at
    // a time: one UTF-8 check and one copy per batch instead of per number.
    let mut buf = [0u8; 256];
    let mut n = 0;
    for (i, &x) in xs.iter().enumerate() {
        if n > buf.len() - 2 * MAX_SHORTEST {
            out.push_str(std::str::from_utf8(&buf[..n]).unwrap_or_default());
            n = 0;
        }
        if i > 0 {
            buf[n] = b' ';
            n += 1;
        }
        n = match special(x, style.zero_threshold) {
            Ok(x) => shortest_into(&mut buf, n, x),
            Err(text) => put(&mut buf, n, text.as_bytes()),
        };
    }
    out.push_str(std::str::from_utf8(&buf[..n]).unwrap_or_default());
}

/// `x`, or `0` below the zero threshold, or the text of a NaN or an infinity.
fn special(x: f64, zero_threshold: f64) -> Result<f64, &'static str> {
    let x = if x.abs() < zero_threshold { 0.0 } else { x };
    if x.is_nan() {
        Err("nan")
    } else if x.is_infinite() {
        Err(if x > 0.0 { "inf" } else { "-inf" })
    } else {
        Ok(x)
    }
}

/// The longest shortest text: a sign, 17 digits, a point and `e-308`, or a sign,
/// `0.000` and 17 digits.
const MAX_SHORTEST: usize = 25;

/// Copies `bytes` into `buf` at `at`; returns the end.
fn put(buf: &mut [u8], at: usize, bytes: &[u8]) -> usize {
    buf[at..at + bytes.len()].copy_from_slice(bytes);
    at + bytes.len()
}

const PAIRS: &[u8; 200] = b"0001020304050607080910111213141516171819\
2021222324252627282930313233343536373839\
4041424344454647484950515253545556575859\
6061626364656667686970717273747576777879\
8081828384858687888990919293949596979899";

/// Writes the `len` decimal digits of `v` into `buf[at..at + len]`.
fn digits_into(buf: &mut [u8], at: usize, len: usize, mut v: u64) {
    let mut end = at + len;
    while v >= 100 {
        let r = (v % 100) as usize * 2;
        v /= 100;
        buf[end - 2..end].copy_from_slice(&PAIRS[r..r + 2]);
        end -= 2;
    }
    if v >= 10 {
        let r = v as usize * 2;
        buf[end - 2..end].copy_from_slice(&PAIRS[r..r + 2]);
    } else {
        buf[end - 1] = b'0' + v as u8;
    }
}

fn digit_count(v: u64) -> usize {
    v.checked_ilog10().map_or(1, |l| l as usize + 1)
}

/// Writes the shortest text of a finite `x` into `buf` at `at`; returns the end.
fn shortest_into(buf: &mut [u8], mut at: usize, x: f64) -> usize {
    if x.is_sign_negative() {
        buf[at] = b'-';
        at += 1;
    }
    let a = x.abs();
    // Integers below 2^53 are exact, and their shortest digits are their own (with
    // trailing zeros, which the layout puts back): the same text, without the float
    // digit search. (`as` truncates; `-0` keeps its sign above.)
    const EXACT: f64 = 9_007_199_254_740_992.0; // 2^53
    if a < EXACT {
        // (Through i64: one instruction each way, where u64 takes several.)
        let i = a as i64;
        if i as f64 == a {
            let i = i as u64;
            let len = digit_count(i);
            digits_into(buf, at, len, i);
            return at + len;
        }
    }
    // Short decimals (`0.05`, `1.57`, `-0.3`: most of MJCF's non-integers), found
    // directly: the shortest text has k decimals when some integer r makes r / 10^k
    // this double. r and 10^k are exact doubles and the division is correctly
    // rounded (to even, as the rounding interval takes its bounds: when the mantissa
    // is even), so the test is exact; the first k that passes gives the shortest
    // length, and in this range an interval holds at most one multiple of 10^-6 (its
    // width is below 2.4e-7), so that r is Rust's candidate too.
    if (1e-3..1e9).contains(&a) {
        const POW10: [f64; 7] = [1.0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6];
        for (k, p) in POW10.iter().enumerate().skip(1) {
            let r = (a * p + 0.5) as i64;
            if r as f64 / p == a {
                return layout_into(buf, at, r as u64, -(k as i32), 17);
            }
        }
    }
    let (mut digits, mut e10) = shortest::digits(a);
    while digits % 10 == 0 {
        digits /= 10;
        e10 += 1;
    }
    layout_into(buf, at, digits, e10, 17)
}

/// Lays out the decimal `digits` × 10^`e10` (`digits` > 0, without trailing zeros) in
/// `%g` form with room for `room` digits (as [`layout`]) into `buf` at `at`; returns
/// the end.
fn layout_into(buf: &mut [u8], at: usize, digits: u64, e10: i32, room: i32) -> usize {
    let len = digit_count(digits);
    // The exponent of the first digit, as `{:e}` gives it.
    let exp = e10 + len as i32 - 1;
    if exp < -4 || exp >= room {
        // d.ddde±XX: the digits one place right, the first moved back before the point.
        digits_into(buf, at + 1, len, digits);
        buf[at] = buf[at + 1];
        let mut n = at + 1;
        if len > 1 {
            buf[at + 1] = b'.';
            n = at + 1 + len;
        }
        n = put(buf, n, if exp < 0 { b"e-" } else { b"e+" });
        // At least two digits, as C's `%g`.
        let a = exp.unsigned_abs() as usize;
        if a >= 100 {
            buf[n] = b'0' + (a / 100) as u8;
            n += 1;
        }
        put(buf, n, &PAIRS[a % 100 * 2..a % 100 * 2 + 2])
    } else if exp < 0 {
        let zeros = (-exp - 1) as usize;
        let n = put(buf, at, b"0.0000");
        let n = n - 4 + zeros;
        digits_into(buf, n, len, digits);
        n + len
    } else {
        let int_len = exp as usize + 1;
        if len <= int_len {
            digits_into(buf, at, len, digits);
            buf[at + len..at + int_len].fill(b'0');
            at + int_len
        } else {
            digits_into(buf, at + 1, len, digits);
            buf.copy_within(at + 1..at + 1 + int_len, at);
            buf[at + int_len] = b'.';
            at + 1 + len
        }
    }
}

#[cfg(test)]
/// Splits Rust's `{:e}` text (`-1.2345e-5`) into sign, digits and decimal exponent.
fn split_sci(s: &str) -> (bool, &str, &str, i32) {
    let (neg, s) = match s.strip_prefix('-') {
        Some(r) => (true, r),
        None => (false, s),
    };
    let (mant, exp) = s.split_once('e').unwrap_or((s, "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    let (int, frac) = mant.split_once('.').unwrap_or((mant, ""));
    (neg, int, frac, exp)
}

fn push_exponent(out: &mut String, exp: i32) {
    out.push('e');
    out.push(if exp < 0 { '-' } else { '+' });
    let a = exp.unsigned_abs();
    if a < 10 {
        out.push('0');
    }
    let _ = write!(out, "{a}");
}

/// Lays out significant digits `d0.d1d2...` × 10^exp in `%g` form with room for
/// `room` digits before switching to exponent notation.
fn layout(out: &mut String, neg: bool, digits: &str, exp: i32, room: i32) {
    if neg {
        out.push('-');
    }
    let digits = digits.trim_end_matches('0');
    let digits = if digits.is_empty() { "0" } else { digits };
    if exp < -4 || exp >= room {
        out.push_str(&digits[..1]);
        if digits.len() > 1 {
            out.push('.');
            out.push_str(&digits[1..]);
        }
        push_exponent(out, exp);
    } else if exp < 0 {
        out.push_str("0.");
        for _ in 0..(-exp - 1) {
            out.push('0');
        }
        out.push_str(digits);
    } else {
        let int_len = exp as usize + 1;
        if digits.len() <= int_len {
            out.push_str(digits);
            for _ in digits.len()..int_len {
                out.push('0');
            }
        } else {
            out.push_str(&digits[..int_len]);
            out.push('.');
            out.push_str(&digits[int_len..]);
        }
    }
}

/// `{:e}` text formatted on the stack (a float's is at most a few dozen bytes; a
/// longer one, as `%g` with hundreds of digits gives, goes to the heap).
struct Buf {
    bytes: [u8; 64],
    len: usize,
    heap: Vec<u8>,
}

impl Buf {
    fn new() -> Buf {
        Buf { bytes: [0; 64], len: 0, heap: Vec::new() }
    }

    fn as_bytes(&self) -> &[u8] {
        if self.heap.is_empty() { &self.bytes[..self.len] } else { &self.heap }
    }
}

impl fmt::Write for Buf {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        let end = self.len + s.len();
        if self.heap.is_empty() && end <= self.bytes.len() {
            self.bytes[self.len..end].copy_from_slice(s.as_bytes());
            self.len = end;
        } else {
            if self.heap.is_empty() {
                self.heap.extend_from_slice(&self.bytes[..self.len]);
            }
            self.heap.extend_from_slice(s.as_bytes());
        }
        Ok(())
    }
}

/// Lays out `{:e}` text (`-1.2345e-5`, ASCII) with room for `room` digits: the
/// digits (`12345`) are gathered on the stack, without the text's `.`.
fn layout_sci(out: &mut String, sci: &[u8], room: i32) {
    let (neg, s) = match sci.split_first() {
        Some((b'-', rest)) => (true, rest),
        _ => (false, sci),
    };
    let e = s.iter().position(|&b| b == b'e').unwrap_or(s.len());
    let (mant, exp_text) = (&s[..e], s.get(e + 1..).unwrap_or(&[]));
    let exp = std::str::from_utf8(exp_text).ok().and_then(|t| t.parse().ok()).unwrap_or(0);
    let mut digits = [0u8; 64];
    let mut n = 0;
    let mut long = Vec::new();
    for &b in mant.iter().filter(|&&b| b != b'.') {
        if n < digits.len() {
            digits[n] = b;
            n += 1;
        } else {
            if long.is_empty() {
                long.extend_from_slice(&digits);
            }
            long.push(b);
        }
    }
    let digits = if long.is_empty() { &digits[..n] } else { &long[..] };
    layout(out, neg, std::str::from_utf8(digits).unwrap_or("0"), exp, room);
}

fn write_g(out: &mut String, x: f64, p: u32) {
    let p = p.min(400);
    let mut s = Buf::new();
    let _ = write!(s, "{:.*e}", (p - 1) as usize, x);
    layout_sci(out, s.as_bytes(), p as i32);
}

/// The text of `x` in the given style.
#[cfg(test)]
pub(crate) fn float_text(x: f64, style: FloatStyle) -> String {
    let mut s = String::new();
    write_float(&mut s, x, style);
    s
}

/// Parses a `size/@memory` value into bytes: a decimal integer with an optional
/// case-insensitive suffix K, M, G, T, P or E (powers of 1024).
pub(crate) fn parse_bytes(text: &str) -> Option<u128> {
    let t = text.trim();
    let (num, shift) = match t.chars().last()?.to_ascii_uppercase() {
        'K' => (&t[..t.len() - 1], 10),
        'M' => (&t[..t.len() - 1], 20),
        'G' => (&t[..t.len() - 1], 30),
        'T' => (&t[..t.len() - 1], 40),
        'P' => (&t[..t.len() - 1], 50),
        'E' => (&t[..t.len() - 1], 60),
        _ => (t, 0),
    };
    let n: u128 = num.trim().parse().ok()?;
    n.checked_mul(1u128 << shift)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn g(x: f64, p: u32) -> String {
        float_text(x, FloatStyle { precision: Some(p), zero_threshold: 0.0 })
    }
    fn short(x: f64) -> String {
        float_text(x, FloatStyle::default())
    }

    /// The text as formatted before the stack buffer and the integer shortcut.
    fn old_shortest(x: f64) -> String {
        let s = format!("{x:e}");
        let (neg, int, frac, exp) = split_sci(&s);
        let digits = format!("{int}{frac}");
        let mut out = String::new();
        layout(&mut out, neg, &digits, exp, 17);
        out
    }

    fn old_g(x: f64, p: u32) -> String {
        let s = format!("{:.*e}", (p - 1) as usize, x);
        let (neg, int, frac, exp) = split_sci(&s);
        let digits = format!("{int}{frac}");
        let mut out = String::new();
        layout(&mut out, neg, &digits, exp, p as i32);
        out
    }

    #[test]
    fn same_text_as_formatting_through_strings() {
        let mut xs: Vec<f64> = vec![0.0, -0.0, 1.0, -1.0, 0.5, 1e16, 1e17, 1e-5, 123.456];
        xs.extend((-2000..2000).map(f64::from));
        xs.extend((0..64).map(|k| 2f64.powi(k)));
        xs.extend((0..64).flat_map(|k| [2f64.powi(k) - 1.0, 2f64.powi(k) + 1.0, -(2f64.powi(k))]));
        xs.extend((-30..30).map(|k| 10f64.powi(k)));
        // Pseudo-random bit patterns (every exponent), finite ones only.
        let mut r: u64 = 0x2545_f491_4f6c_dd1d;
        for _ in 0..20_000 {
            r ^= r << 13;
            r ^= r >> 7;
            r ^= r << 17;
            let x = f64::from_bits(r);
            if x.is_finite() {
                xs.push(x);
                xs.push(x.trunc());
            }
        }
        for x in xs {
            assert_eq!(short(x), old_shortest(x), "{x:e}");
            for p in [1, 5, 17] {
                assert_eq!(g(x, p), old_g(x, p), "{x:e} at {p}");
            }
        }
    }

    use crate::value::test_rng::Rng;

    fn same_as_rust(x: f64) {
        assert_eq!(short(x), old_shortest(x), "{:#x}", x.to_bits());
    }

    /// The shortest digits are Rust's own (`{:e}`), on random bit patterns of every
    /// exponent.
    #[test]
    fn shortest_is_rusts_on_random_bits() {
        let mut r = Rng(0x9e37_79b9_7f4a_7c15);
        for _ in 0..2_000_000 {
            let x = f64::from_bits(r.next());
            if x.is_finite() {
                same_as_rust(x);
            }
        }
    }

    /// The short-decimal shortcut's range, densely: random bit patterns there, and
    /// decimals of 1 to 7 places with their neighbouring doubles.
    #[test]
    fn shortest_is_rusts_on_short_decimals_range() {
        let mut r = Rng(0x5851_f42d_4c95_7f2d);
        let (lo, hi) = (1e-3f64.to_bits() - 2, 1e9f64.to_bits() + 2);
        for _ in 0..1_000_000 {
            same_as_rust(f64::from_bits(lo + r.next() % (hi - lo)));
        }
        for _ in 0..300_000 {
            let places = (r.next() % 7 + 1) as i32;
            let digits = r.next() % 10u64.pow(places as u32 + (r.next() % 9) as u32);
            let x = digits as f64 / 10f64.powi(places);
            for y in
                [x, f64::from_bits(x.to_bits() + 1), f64::from_bits(x.to_bits().saturating_sub(1))]
            {
                same_as_rust(y);
            }
        }
    }

    /// Exact ties (the value halfway between the two shortest candidates), where Ryu
    /// would round to even and Rust rounds up; exact values and exact bounds (Ryu's
    /// general case) at every small binary exponent.
    #[test]
    fn shortest_is_rusts_on_ties_and_exact_values() {
        // (Exact: the step between doubles there is 0.25.)
        assert_eq!(short(-(1_149_636_667_324_797.0 + 0.25)), "-1149636667324797.3");
        assert_eq!(short(1_149_636_667_324_796.0 + 0.25), "1149636667324796.3");
        let mut r = Rng(0x2545_f491_4f6c_dd1d);
        // In [2^50, 2^51) the step is 0.25: N + 0.25 and N + 0.75 are all ties.
        for _ in 0..100_000 {
            let n = (1u64 << 50) + (r.next() >> 14);
            for f in [0.25, 0.5, 0.75] {
                same_as_rust(n as f64 + f);
                same_as_rust(-(n as f64 + f));
            }
        }
        // m × 2^e for every exponent near 0, with short and full mantissas.
        for e in -80..=80 {
            for _ in 0..2_000 {
                let bits = r.next();
                for m in
                    [bits >> 11, bits >> 40, bits >> 50, (bits >> 11) | 1, (bits >> 11) & !0xff]
                {
                    same_as_rust(m as f64 * 2f64.powi(e));
                }
            }
        }
    }

    #[test]
    fn shortest_is_rusts_on_subnormals_powers_and_short_decimals() {
        let mut xs: Vec<f64> = Vec::new();
        // Subnormals, the smallest normal and their neighbours.
        let mut r = Rng(0x1234_5678_9abc_def1);
        for k in 1..2_000u64 {
            xs.push(f64::from_bits(k));
            xs.push(f64::from_bits((1 << 52) - k));
            xs.push(f64::from_bits(r.next() & ((1 << 52) - 1)));
            xs.push(f64::from_bits((1 << 52) - 1 + k));
        }
        // Powers of two and ten, and the doubles either side of them.
        for e in -1074i64..=1023 {
            let p = if e >= -1022 {
                f64::from_bits(((e + 1023) as u64) << 52)
            } else {
                f64::from_bits(1 << (e + 1074))
            };
            xs.extend([p, f64::from_bits(p.to_bits() + 1), f64::from_bits(p.to_bits() - 1)]);
        }
        for e in -330..=308 {
            let p: f64 = format!("1e{e}").parse().unwrap();
            if p > 0.0 && p.is_finite() {
                xs.extend([p, f64::from_bits(p.to_bits() + 1), f64::from_bits(p.to_bits() - 1)]);
            }
        }
        xs.retain(|x| x.is_finite());
        xs.extend([f64::MAX, f64::MIN_POSITIVE, 5e-324, f64::EPSILON]);
        // Short decimals as MJCF files hold them (`0.05`, `-1.57`, `2.5e-3`).
        for k in 1..20_000u32 {
            for text in [
                format!("0.{k}"),
                format!("{}.{}", k / 100, k % 100),
                format!("{k}e-3"),
                format!("{k}e-7"),
                format!("{k}.{k}"),
                format!("{k}e20"),
            ] {
                xs.push(text.parse().unwrap());
            }
        }
        // Integers beyond 2^53, where the integer shortcut does not apply.
        for _ in 0..100_000 {
            xs.push((r.next() >> (r.next() % 11)) as f64);
        }
        for x in xs {
            same_as_rust(x);
            same_as_rust(-x);
        }
    }

    /// Arrays are the texts of their numbers joined by spaces, however long.
    #[test]
    fn arrays_join_the_texts_of_their_numbers() {
        let mut r = Rng(0x0123_4567_89ab_cdef);
        let xs: Vec<f64> = (0..1_000)
            .map(|i| match i % 5 {
                0 => f64::from_bits(r.next()),
                1 => (r.next() % 2000) as f64 / 100.0 - 10.0,
                2 => f64::NAN,
                3 => -1e-300,
                _ => (r.next() >> 20) as f64,
            })
            .collect();
        for style in [
            FloatStyle::default(),
            FloatStyle { precision: Some(17), zero_threshold: 0.0 },
            FloatStyle { precision: None, zero_threshold: 1e-3 },
        ] {
            for len in [0, 1, 2, 7, 10, 11, 100, 1_000] {
                let mut joined = String::new();
                write_floats(&mut joined, &xs[..len], style);
                let each: Vec<String> = xs[..len].iter().map(|x| float_text(*x, style)).collect();
                assert_eq!(joined, each.join(" "));
            }
        }
    }

    /// dm_control's own output for these numbers (observed by running it), precision
    /// 17 and 5.
    #[test]
    fn percent_g_matches_the_reference_table() {
        let table: &[(f64, &str)] = &[
            (0.1, "0.10000000000000001"),
            (1e-20, "9.9999999999999995e-21"),
            (1.0, "1"),
            (-0.0, "-0"),
            (3.0, "3"),
            (1e16, "10000000000000000"),
            (1e17, "1e+17"),
            (1e-5, "1.0000000000000001e-05"),
            (1e-4, "0.0001"),
            (f64::NAN, "nan"),
            (f64::INFINITY, "inf"),
            (f64::NEG_INFINITY, "-inf"),
        ];
        for (x, want) in table {
            assert_eq!(g(*x, 17), *want, "{x}");
        }
        assert_eq!(g(0.1, 5), "0.1");
        assert_eq!(g(1e-20, 5), "1e-20");
        assert_eq!(g(1.2345678e16, 5), "1.2346e+16");
        assert_eq!(g(123456.0, 3), "1.23e+05");
        assert_eq!(g(0.5, 1), "0.5");
        assert_eq!(g(2.5, 1), "2");
        assert_eq!(g(100.0, 3), "100");
        assert_eq!(g(1000.0, 3), "1e+03");
    }

    /// Outputs of C's printf("%.{p}g") (via Python's `%` operator) for a spread of
    /// values and precisions, including halfway cases.
    #[test]
    fn percent_g_matches_c_printf() {
        let cases: &[(f64, u32, &str)] = &[
            (0.25, 1, "0.2"),
            (0.35, 1, "0.3"),
            (0.125, 2, "0.12"),
            (2.675, 3, "2.67"),
            (-1.5e-7, 3, "-1.5e-07"),
            (123.456, 2, "1.2e+02"),
            (99999.5, 5, "1e+05"),
            (0.00012345, 3, "0.000123"),
            (1e100, 17, "1e+100"),
            (6.02214076e23, 6, "6.02214e+23"),
            (5e-324, 17, "4.9406564584124654e-324"),
        ];
        for (x, p, want) in cases {
            assert_eq!(g(*x, *p), *want, "{x} at {p}");
        }
    }

    #[test]
    fn shortest_round_trip_is_the_default() {
        let table: &[(f64, &str)] = &[
            (0.1, "0.1"),
            (1e-20, "1e-20"),
            (1.0, "1"),
            (-0.0, "-0"),
            (1e16, "10000000000000000"),
            (1e17, "1e+17"),
            (1e-5, "1e-05"),
            (1e-4, "0.0001"),
            (3e20, "3e+20"),
            (1e-16, "1e-16"),
            (100.0, "100"),
            (-2.5, "-2.5"),
            (0.30000000000000004, "0.30000000000000004"),
            (123456789.125, "123456789.125"),
        ];
        for (x, want) in table {
            assert_eq!(short(*x), *want, "{x}");
        }
    }

    #[test]
    fn zero_threshold_writes_zero() {
        let style = FloatStyle { precision: None, zero_threshold: 1e-3 };
        assert_eq!(float_text(1e-4, style), "0");
        assert_eq!(float_text(-1e-4, style), "0");
        assert_eq!(float_text(2e-3, style), "0.002");
    }

    #[test]
    fn parsing_follows_python() {
        assert_eq!(parse_float("1e-3"), Some(1e-3));
        assert!(parse_float("nan").unwrap().is_nan());
        assert_eq!(parse_float("-inf"), Some(f64::NEG_INFINITY));
        assert_eq!(parse_float(" 2 "), Some(2.0));
        assert_eq!(parse_float("abc"), None);
        assert_eq!(parse_float(""), None);
        assert_eq!(parse_int("3"), Some(3));
        assert_eq!(parse_int("3.0"), Some(3));
        assert_eq!(parse_int("1e3"), Some(1000));
        assert_eq!(parse_int("1.5"), None);
        assert_eq!(parse_int("1e400"), None);
        assert_eq!(parse_int("-9223372036854775808"), Some(i64::MIN));
    }

    #[test]
    fn bytes_with_suffixes() {
        assert_eq!(parse_bytes("10000"), Some(10000));
        assert_eq!(parse_bytes("1M"), Some(1 << 20));
        assert_eq!(parse_bytes("2k"), Some(2048));
        assert_eq!(parse_bytes("1X"), None);
        assert_eq!(parse_bytes(""), None);
    }

    proptest::proptest! {
        #[test]
        fn shortest_reads_back_exactly(x in proptest::num::f64::ANY) {
            let t = short(x);
            let back = parse_float(&t).unwrap();
            proptest::prop_assert!(back == x || (back.is_nan() && x.is_nan()), "{} -> {}", x, t);
            if !x.is_nan() {
                proptest::prop_assert_eq!(back.is_sign_negative(), x.is_sign_negative());
            }
        }

        #[test]
        fn precision_17_reads_back_exactly(x in proptest::num::f64::NORMAL) {
            proptest::prop_assert_eq!(parse_float(&g(x, 17)).unwrap(), x);
        }
    }
}
