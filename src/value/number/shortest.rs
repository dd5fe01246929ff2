//! The shortest decimal digits of a double that read back to it, chosen exactly as
//! Rust's `{}` / `{:e}` choose them (`core::num::flt2dec`'s Grisu with its Dragon
//! fallback), without going through `core::fmt`.
//!
//! The algorithm is Ryu (Ulf Adams, "Ryū: fast float-to-string conversion", PLDI 2018;
//! the reference implementation is Apache-2.0 / Boost), with two changes that make its
//! choice Rust's:
//! - a tie (the value exactly halfway between the two shortest candidates) rounds up,
//!   as Rust's Dragon does (`2 * mant >= scale`), where Ryu rounds to even: e.g.
//!   1149636667324797.25 is `1149636667324797.3` in Rust, `…797.2` in Ryu;
//! - the interval of the smallest normal (2^-1022) is asymmetric, as for every other
//!   power of two (Rust's `decode` treats it so; Ryu treats it as symmetric, since the
//!   subnormal below it is one full step away).
//!
//! Both algorithms otherwise pick the same digits: the shortest in the rounding
//! interval (its bounds included when the mantissa is even), and of the two
//! candidates of that length around the value, the closer. The unit tests compare
//! with `format!` on millions of values.

use super::tables::{POW5, POW5_INV};

const MANTISSA_BITS: u32 = 52;
const EXPONENT_BIAS: i32 = 1023;
const POW5_INV_BITCOUNT: i32 = 125;
const POW5_BITCOUNT: i32 = 125;

/// floor(log2(5^e)) + 1 for 0 <= e <= 3528.
fn pow5bits(e: i32) -> i32 {
    (((e as u32) * 1_217_359) >> 19) as i32 + 1
}

/// floor(log10(2^e)) for 0 <= e <= 1650.
fn log10_pow2(e: i32) -> u32 {
    ((e as u32) * 78_913) >> 18
}

/// floor(log10(5^e)) for 0 <= e <= 2620.
fn log10_pow5(e: i32) -> u32 {
    ((e as u32) * 732_923) >> 20
}

fn pow5_factor(mut v: u64) -> u32 {
    let mut count = 0;
    while v > 0 && v % 5 == 0 {
        v /= 5;
        count += 1;
    }
    count
}

fn multiple_of_power_of_5(v: u64, p: u32) -> bool {
    pow5_factor(v) >= p
}

/// (m × mul) >> j, `mul` a 128-bit (low, high) pair, for 64 < j < 128 + 64.
fn mul_shift(m: u64, mul: (u64, u64), j: i32) -> u64 {
    let b0 = u128::from(m) * u128::from(mul.0);
    let b2 = u128::from(m) * u128::from(mul.1);
    (((b0 >> 64) + b2) >> (j - 64)) as u64
}

/// The shortest digits of a finite `x > 0`: `(d, e)` with `x ≈ d × 10^e` (`d` may end
/// in zeros).
pub(super) fn digits(x: f64) -> (u64, i32) {
    let bits = x.to_bits();
    let ieee_mantissa = bits & ((1u64 << MANTISSA_BITS) - 1);
    let ieee_exponent = ((bits >> MANTISSA_BITS) & 0x7ff) as i32;
    // x = m2 × 2^e2, shifted by 2 to leave room for the interval's bounds.
    let (e2, m2) = if ieee_exponent == 0 {
        (1 - EXPONENT_BIAS - MANTISSA_BITS as i32 - 2, ieee_mantissa)
    } else {
        (
            ieee_exponent - EXPONENT_BIAS - MANTISSA_BITS as i32 - 2,
            (1u64 << MANTISSA_BITS) | ieee_mantissa,
        )
    };
    let accept_bounds = m2 & 1 == 0;

    // The interval [mm, mp] around mv = 4 × m2: half a step each way, a quarter below
    // at a power of two (the step below is half as large). Rust's decoder does so for
    // every normal power of two, 2^-1022 included.
    let mv = 4 * m2;
    let mm_shift = u64::from(ieee_mantissa != 0);

    // mv, mp and mm × 2^e2 in base 10: vr, vp, vm × 10^e10, truncated.
    let (mut vr, mut vp, mut vm, e10);
    // Whether mm × 2^e2 is exactly vm × 10^e10 (Ryu also tracks whether vr is exact,
    // which only its round-half-even needs: see below).
    let mut vm_is_trailing_zeros = false;
    if e2 >= 0 {
        let q = log10_pow2(e2) - u32::from(e2 > 3);
        e10 = q as i32;
        let k = POW5_INV_BITCOUNT + pow5bits(q as i32) - 1;
        let i = -e2 + q as i32 + k;
        let mul = POW5_INV[q as usize];
        vr = mul_shift(4 * m2, mul, i);
        vp = mul_shift(4 * m2 + 2, mul, i);
        vm = mul_shift(4 * m2 - 1 - mm_shift, mul, i);
        if q <= 21 {
            // Only one of mp, mv and mm can be a multiple of 5, if any (mv: vr exact,
            // which does not matter here).
            if mv % 5 == 0 {
            } else if accept_bounds {
                vm_is_trailing_zeros = multiple_of_power_of_5(mv - 1 - mm_shift, q);
            } else {
                vp -= u64::from(multiple_of_power_of_5(mv + 2, q));
            }
        }
    } else {
        let q = log10_pow5(-e2) - u32::from(-e2 > 1);
        e10 = q as i32 + e2;
        let i = -e2 - q as i32;
        let k = pow5bits(i) - POW5_BITCOUNT;
        let j = q as i32 - k;
        let mul = POW5[i as usize];
        vr = mul_shift(4 * m2, mul, j);
        vp = mul_shift(4 * m2 + 2, mul, j);
        vm = mul_shift(4 * m2 - 1 - mm_shift, mul, j);
        if q <= 1 {
            // mv, mp and mm have at least q trailing zero bits: all three are exact.
            if accept_bounds {
                vm_is_trailing_zeros = mm_shift == 1;
            } else {
                vp -= 1;
            }
        }
    }

    // The shortest representation in the interval, and its rounding: remove the
    // most digits `c` for which vp / 10^c > vm / 10^c still holds (a condition that
    // stays false once false), found by trying 16, 8, 4, 2 and 1 more digits in turn;
    // Ryu removes them one at a time, fifteen steps for MJCF's short decimals.
    let mut removed = 0i32;
    let mut last_removed_digit = 0u64;
    for (p, k) in
        [(10_000_000_000_000_000u64, 16), (100_000_000, 8), (10_000, 4), (100, 2), (10, 1)]
    {
        if vp / p > vm / p {
            vm_is_trailing_zeros &= vm % p == 0;
            last_removed_digit = vr % p / (p / 10);
            vr /= p;
            vp /= p;
            vm /= p;
            removed += k;
        }
    }
    if vm_is_trailing_zeros {
        // The lower bound is exact and in the interval: its trailing zeros can go
        // too (rare).
        while vm % 10 == 0 {
            last_removed_digit = vr % 10;
            vr /= 10;
            vm /= 10;
            removed += 1;
        }
    }
    // Round up past the interval's lower end, or when the digits removed are at least
    // half. Ryu tracks whether vr is exact (`vr_is_trailing_zeros`) to round an exact
    // tie (5 then nothing) to even here; Rust rounds it up, which `>= 5` does, so
    // whether vr is exact does not matter for the rounding.
    let output = vr
        + u64::from(
            (vr == vm && (!accept_bounds || !vm_is_trailing_zeros)) || last_removed_digit >= 5,
        );
    (output, e10 + removed)
}
