//! Fast paths for reading numbers: the plain decimals that MJCF files are made of
//! (`0.35`, `-1`, `0.0012`), read without the general parser. Each fast path accepts
//! only text whose value it gets exactly right and returns `None` for anything else,
//! which the general parser (`number::parse_float`, `number::parse_int`) then reads:
//! what is accepted, and the value read, are the same as with the general parser alone.
//! A leaf module: the general parser comes in through [`Number`], which `number`
//! implements for `f64` and `i64`.

use std::sync::Arc;

/// Exact powers of ten as doubles (10^22 is the largest one a double holds exactly).
const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// `text` as a double if it is a plain decimal: an optional `-`, digits with at most
/// one `.` among or around them (at least one digit), no exponent, at most 19 digits
/// and a value whose digits form an integer up to 2^53 with at most 22 after the
/// point. Then the integer and the power of ten are both exact doubles, and one IEEE
/// division rounds their quotient correctly, as `f64::from_str` rounds (Clinger's
/// fast path). Anything else is `None`.
pub(crate) fn plain_float(text: &[u8]) -> Option<f64> {
    let mut i = 0;
    let x = lead_float(text, &mut i)?;
    (i == text.len()).then_some(x)
}

/// The plain decimal (as [`plain_float`] reads it) that starts at `bytes[*i]` and
/// ends at the end or at ASCII whitespace; `*i` is moved to where the digits and
/// point stop (also when the text there is not a plain decimal: `None`).
pub(super) fn lead_float(bytes: &[u8], i: &mut usize) -> Option<f64> {
    let neg = bytes.get(*i) == Some(&b'-');
    if neg {
        *i += 1;
    }
    let mut mantissa: u64 = 0;
    let mut count: usize = 0;
    let mut point: Option<usize> = None;
    while let Some(&b) = bytes.get(*i) {
        let d = b.wrapping_sub(b'0');
        if d < 10 {
            // Wraps only past 19 digits, which are refused below.
            mantissa = mantissa.wrapping_mul(10).wrapping_add(u64::from(d));
            count += 1;
        } else if b == b'.' && point.is_none() {
            point = Some(count);
        } else {
            break;
        }
        *i += 1;
    }
    let ends = bytes.get(*i).is_none_or(u8::is_ascii_whitespace);
    let after = count - point.unwrap_or(count);
    if !ends || count == 0 || count > 19 || mantissa > 1 << 53 || after >= POW10.len() {
        return None;
    }
    let x = mantissa as f64 / POW10[after];
    Some(if neg { -x } else { x })
}

/// `text` as an integer if it is plain: an optional `-` and 1 to 18 digits (which
/// cannot overflow). Anything else is `None`.
pub(crate) fn plain_int(text: &[u8]) -> Option<i64> {
    let mut i = 0;
    let v = lead_int(text, &mut i)?;
    (i == text.len()).then_some(v)
}

/// The plain integer (as [`plain_int`] reads it) that starts at `bytes[*i]` and ends
/// at the end or at ASCII whitespace; `*i` is moved to where the digits stop.
pub(super) fn lead_int(bytes: &[u8], i: &mut usize) -> Option<i64> {
    let neg = bytes.get(*i) == Some(&b'-');
    if neg {
        *i += 1;
    }
    let start = *i;
    let mut v: i64 = 0;
    while let Some(&b) = bytes.get(*i) {
        let d = b.wrapping_sub(b'0');
        if d >= 10 {
            break;
        }
        // Wraps only past 18 digits, which are refused below.
        v = v.wrapping_mul(10).wrapping_add(i64::from(d));
        *i += 1;
    }
    let count = *i - start;
    let ends = bytes.get(*i).is_none_or(u8::is_ascii_whitespace);
    if !ends || count == 0 || count > 18 {
        return None;
    }
    Some(if neg { -v } else { v })
}

/// Which numbers an array holds: how its parts are read fast, and by the general
/// parser.
pub(crate) trait Number: Copy + Default {
    /// As [`lead_float`]: the plain number at `bytes[*i]`, or `None`.
    fn lead(bytes: &[u8], i: &mut usize) -> Option<Self>;
    /// The general parser, for parts that are not plain.
    fn parse(text: &str) -> Option<Self>;
}

/// The whitespace-separated parts of `text` (as `str::split_ascii_whitespace` splits),
/// each read in one pass when it is plain, else by the general parser; `None` if one
/// cannot be read. The numbers go straight into their one shared allocation (the
/// first 16 through a buffer on the stack, as arrays are short).
pub(crate) fn parse_array<T: Number>(text: &str) -> Option<Arc<[T]>> {
    let bytes = text.as_bytes();
    let mut buf = [T::default(); 16];
    let mut n = 0;
    let mut more: Vec<T> = Vec::new();
    let mut i = 0;
    loop {
        while i < bytes.len() && bytes[i].is_ascii_whitespace() {
            i += 1;
        }
        if i == bytes.len() {
            break;
        }
        let start = i;
        let x = match T::lead(bytes, &mut i) {
            Some(x) => x,
            None => {
                while i < bytes.len() && !bytes[i].is_ascii_whitespace() {
                    i += 1;
                }
                // Both ends are at ASCII bytes or the text's ends: character
                // boundaries.
                T::parse(text.get(start..i)?)?
            }
        };
        if n < buf.len() {
            buf[n] = x;
            n += 1;
        } else {
            if more.is_empty() {
                more.extend_from_slice(&buf);
            }
            more.push(x);
        }
    }
    Some(if more.is_empty() { Arc::from(&buf[..n]) } else { more.into() })
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::value::test_rng::Rng;

    fn check_float(s: &str) {
        let want = s.parse::<f64>().ok();
        if let Some(got) = plain_float(s.as_bytes()) {
            let want = want.unwrap_or_else(|| panic!("{s:?}: fast path read what Rust does not"));
            assert_eq!(got.to_bits(), want.to_bits(), "{s:?}");
        }
    }

    #[test]
    fn plain_floats_read_as_rust_reads_them() {
        for s in [
            "0",
            "-0",
            "0.0",
            "-0.0",
            ".5",
            "5.",
            "-.5",
            "-5.",
            ".",
            "-",
            "",
            "-.",
            "1.2.3",
            "1e5",
            "+1",
            " 1",
            "1 ",
            "0.1",
            "0.2",
            "0.3",
            "1.7976931348623157",
            "9007199254740993",
            "9007199254740992",
            "900719925474099.3",
            "0.0000000000000000000001",
            "0.00000000000000000000001",
            "12345678901234567890",
            "1234567890123456789",
            "99999999999999999999",
            "-999999999999999999.9",
            "inf",
            "nan",
            "0x10",
            "1_0",
            "١",
            "0.35",
            "0.0012",
            "30.0",
            "-30.0",
        ] {
            check_float(s);
        }
        let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
        let alphabet = b"0123456789.-e+ ";
        for _ in 0..200_000 {
            let len = 1 + rng.below(24) as usize;
            let s: String = (0..len)
                .map(|_| {
                    // Mostly digits, some of the rest.
                    let k = rng.below(30) as usize;
                    char::from(if k < 20 {
                        b'0' + (k % 10) as u8
                    } else {
                        alphabet[10 + (k - 20) % 5]
                    })
                })
                .collect();
            check_float(&s);
        }
        // Random decimals of every length and scale the fast path takes.
        for _ in 0..200_000 {
            let digits = 1 + rng.below(19) as usize;
            let mut s: String =
                (0..digits).map(|_| char::from(b'0' + rng.below(10) as u8)).collect();
            let point = rng.below(digits as u64 + 1) as usize;
            s.insert(point, '.');
            if rng.below(2) == 0 {
                s.insert(0, '-');
            }
            check_float(&s);
            assert!(
                plain_float(s.as_bytes()).is_some()
                    || s.trim_start_matches(['-', '.', '0']).len() > 15
                    || s == "."
                    || s == "-.",
                "{s:?} should take the fast path"
            );
        }
    }

    #[test]
    fn plain_ints_read_as_rust_reads_them() {
        let mut rng = Rng(12345);
        for s in
            ["0", "-0", "-", "", "+1", "1.0", "999999999999999999", "9999999999999999999", " 1"]
        {
            if let Some(v) = plain_int(s.as_bytes()) {
                assert_eq!(Some(v), s.parse::<i64>().ok(), "{s:?}");
            }
        }
        for _ in 0..100_000 {
            let len = 1 + rng.below(20) as usize;
            let mut s: String = (0..len).map(|_| char::from(b'0' + rng.below(10) as u8)).collect();
            if rng.below(2) == 0 {
                s.insert(0, '-');
            }
            match plain_int(s.as_bytes()) {
                Some(v) => assert_eq!(Some(v), s.parse::<i64>().ok(), "{s:?}"),
                None => assert!(len > 18, "{s:?}"),
            }
        }
    }

    #[test]
    fn arrays_split_as_split_ascii_whitespace_does() {
        // The reader's rules before the fast paths.
        let slow = |s: &str| {
            let t = s.trim();
            if t.is_empty() { None } else { t.parse::<f64>().ok() }
        };
        for s in [
            "",
            " ",
            "1",
            " 1 ",
            "1 2 3",
            "1\t2\n3\r4\x0C5",
            "1\u{A0}",
            "1\u{A0}2",
            "\u{2003}1 2",
            "1e3 -inf nan",
            "1  x",
            "0 0 0.1",
        ] {
            let want: Option<Vec<f64>> = s.split_ascii_whitespace().map(slow).collect();
            let got = parse_array::<f64>(s).map(|a| a.to_vec());
            assert_eq!(
                got.map(|v| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>()),
                want.map(|v| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>()),
                "{s:?}"
            );
        }
        let slow_int = |s: &str| {
            let t = s.trim();
            t.parse::<i64>().ok().or_else(|| crate::value::number::float_to_int(slow(t)?))
        };
        // Random arrays of plain and other parts, with every kind of separator.
        let mut rng = Rng(777);
        let parts = [
            "0",
            "-0",
            "1",
            "-1.5",
            ".5",
            "5.",
            "1e2",
            "+3",
            "x",
            "1.2.3",
            "-",
            "007",
            "12345678901234567890",
            "0.1234567890123456789",
            "2.0",
            "nan",
            "\u{A0}1",
        ];
        let seps = [" ", "  ", "\t", "\n", "\r\n", "\x0C", "\u{A0}"];
        for _ in 0..20_000 {
            let mut s = String::new();
            for _ in 0..rng.below(6) {
                s.push_str(seps[rng.below(seps.len() as u64) as usize]);
                s.push_str(parts[rng.below(parts.len() as u64) as usize]);
            }
            if rng.below(2) == 0 {
                s.push(' ');
            }
            let want: Option<Vec<u64>> =
                s.split_ascii_whitespace().map(|p| slow(p).map(f64::to_bits)).collect();
            let got = parse_array::<f64>(&s).map(|a| a.iter().map(|x| x.to_bits()).collect());
            assert_eq!(got, want, "{s:?}");
            let want: Option<Vec<i64>> = s.split_ascii_whitespace().map(slow_int).collect();
            let got = parse_array::<i64>(&s).map(|a| a.to_vec());
            assert_eq!(got, want, "{s:?}");
        }
        let long: String = (0..40).map(|i| format!("{i}.5 ")).collect();
        let got = parse_array::<f64>(&long).expect("reads");
        assert_eq!(got.len(), 40);
        assert_eq!(got[39], 39.5);
    }
}
