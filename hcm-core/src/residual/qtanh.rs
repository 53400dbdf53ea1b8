//! The quantised tanh: the activation of an int8 network, from an `f32`
//! pre-activation z straight to a 16-bit activation, by a table and a linear
//! interpolation in integers.
//!
//! ```text
//! p     = min(⌊|z|·32·4096⌋, 2²⁰ − 1)         (saturating conversion; NaN → 0)
//! i, f  = p >> 12, p & 4095                     segment [i/32, (i+1)/32) and 1/4096ths in it
//! a(|z|) = T[i] + ⌊((T[i+1] − T[i])·f + 2048) / 4096⌋
//! a(z)  = sign(z)·a(|z|)                         Q15: a / 32 768 ≈ tanh(z)
//! ```
//!
//! T\[k\] = round(tanh(k/32)·32 768), at most 32 767, for k = 0 … 256 (|z| up to 8;
//! beyond, the last segment's end, 32 767). From |z| = 5.9 on tanh rounds to the
//! largest Q15 value anyway, so a table to 6 holds the same function in 128 bytes less;
//! to 8 the positions are exactly the 20-bit numbers, clamped by one instruction. The
//! table is built at compile time ([`TABLE`]) from an `exp` written here as a
//! `const fn`.
//!
//! Why: the int8 kernel multiplies 16-bit activations ([`super::int8`]), so the
//! activation's output must be an integer; computing the rational tanh of
//! [`super::tanh`] in `f32` and rounding costs ~20 instructions and a rounding, where
//! this is a multiply, a conversion, one load of two table entries and one dual
//! multiply-accumulate. Its own error against tanh — at most 1.2e-4 over the real line
//! (1.18e-4 measured; interpolation between points 1/32 apart, plus the Q15 rounding;
//! `tests::error_against_tanh`) — does not
//! reach the network's output as an error: training evaluates this same function
//! ([`super::Activation::QuantisedTanh`]), so the int8 network is fitted to it.
//! Integers and one exactly specified conversion: the same bits on every target.

use hcm_dsp::dual_mac;

/// Table points per unit of z: segments 1/32 long.
const POINTS_PER_UNIT: u32 = 32;

/// Interpolation steps per segment (12 fraction bits: 4 096 steps of 7.6e-6 in z).
const FRACTION_BITS: u32 = 12;

/// Segments in the table: z from 0 to 8, so that the positions are the 20-bit numbers
/// (one `usat` clamps them on a Cortex-M4).
const SEGMENTS: usize = 256;

/// The Q15 scale: activation a stands for a / 32 768.
pub const Q15_ONE: f32 = 32_768.0;

/// The largest position p = ⌊|z|·32·4096⌋ read: 2²⁰ − 1.
const LAST_POSITION: i32 = ((SEGMENTS as i32) << FRACTION_BITS) - 1;

/// T\[k\] = round(tanh(k/32)·32 768), capped at 32 767, k = 0 … 256.
pub static TABLE: [i16; SEGMENTS + 1] = table();

/// The table positions per unit of z, 32·4 096 = 2¹⁷ (a power of two: z·P is exact).
pub const POSITIONS_PER_UNIT: f32 = (POINTS_PER_UNIT << FRACTION_BITS) as f32;

/// The quantised tanh of `z`, Q15 (see the module docs); NaN gives 0, ±∞ ±32 767.
#[inline]
pub fn quantised_tanh(z: f32) -> i16 {
    quantised_tanh_scaled(z * POSITIONS_PER_UNIT)
}

/// The quantised tanh of z given `scaled` = z·[`POSITIONS_PER_UNIT`] (the int8 layer
/// folds the factor into its scales and biases): the same bits as
/// [`quantised_tanh`]`(z)`, since |z·P| = |z|·P and z·P has z's sign.
#[inline]
pub fn quantised_tanh_scaled(scaled: f32) -> i16 {
    // The conversion to i32 saturates (NaN → 0; |z|·P ≥ 0), and the clamp to 20 bits
    // is one `usat` (three instructions as an unsigned minimum with a table to 6).
    let position = ((scaled.abs() as i32).clamp(0, LAST_POSITION)) as u32;
    // The index is at most 255: both reads succeed.
    let index = (position >> FRACTION_BITS) as usize;
    let fraction = position & ((1 << FRACTION_BITS) - 1);
    let low = TABLE.get(index).copied().unwrap_or(i16::MAX) as u16;
    let high = TABLE.get(index + 1).copied().unwrap_or(i16::MAX) as u16;
    // T[i] + ⌊((T[i+1] − T[i])·f + 2048) / 4096⌋ = ⌊(T[i]·(4096 − f) + T[i+1]·f + 2048)
    // / 4096⌋ (T[i]·4096 is a multiple of 4096): one dual multiply-accumulate of the
    // pair (T[i], T[i+1]) — adjacent, one load — with (4096 − f, f), both within i16
    // (f ≤ 4 095). The sum stays below 32 767·4 096 + 2 048, and so does the result
    // below 32 768: a value of the table's own range.
    let pair = u32::from(low) | u32::from(high) << 16;
    let weights = ((1 << FRACTION_BITS) - fraction) | fraction << 16;
    let magnitude = (dual_mac(1 << (FRACTION_BITS - 1), pair, weights) >> FRACTION_BITS) as i16;
    if scaled < 0.0 {
        -magnitude
    } else {
        magnitude
    }
}

/// The table, computed by the compiler (const `f64` arithmetic).
const fn table() -> [i16; SEGMENTS + 1] {
    let mut table = [0_i16; SEGMENTS + 1];
    let mut k = 0;
    while k <= SEGMENTS {
        let z = k as f64 / POINTS_PER_UNIT as f64;
        let e = exp(2.0 * z);
        let value = (e - 1.0) / (e + 1.0) * Q15_ONE as f64;
        // round half up (values are ≥ 0), capped at the largest i16.
        let rounded = (value + 0.5) as i64;
        table[k] = if rounded > i16::MAX as i64 {
            i16::MAX
        } else {
            rounded as i16
        };
        k += 1;
    }
    table
}

/// e^x for 0 ≤ x ≤ 16 in `const` context, to ~1e-15 relative: x = n·ln 2 + r with
/// |r| ≤ ln 2 / 2, e^r by its Taylor series to r²⁰/20!, times 2ⁿ.
const fn exp(x: f64) -> f64 {
    let ln2 = core::f64::consts::LN_2;
    let n = (x / ln2 + 0.5) as i32;
    let r = x - n as f64 * ln2;
    let mut sum = 1.0;
    let mut term = 1.0;
    let mut i = 1;
    while i <= 20 {
        term = term * r / i as f64;
        sum += term;
        i += 1;
    }
    let mut scale = 1.0;
    let mut j = 0;
    while j < n {
        scale *= 2.0;
        j += 1;
    }
    sum * scale
}

#[cfg(test)]
mod tests {
    extern crate std;

    use super::{exp, quantised_tanh, Q15_ONE, TABLE};

    #[test]
    fn const_exp_matches_libm() {
        for i in 0..=160 {
            let x = f64::from(i) * 0.1;
            let relative = (exp(x) - x.exp()).abs() / x.exp();
            assert!(relative < 1e-14, "exp({x}): {relative:e}");
        }
    }

    #[test]
    fn table_is_tanh_rounded() {
        for (k, &t) in TABLE.iter().enumerate() {
            let exact = (k as f64 / 32.0).tanh() * f64::from(Q15_ONE);
            assert!(
                (f64::from(t) - exact.min(32_767.0)).abs() <= 0.5,
                "T[{k}] = {t}"
            );
        }
        assert_eq!(TABLE[0], 0);
        assert_eq!(TABLE[192], i16::MAX);
        assert_eq!(TABLE[256], i16::MAX);
        // From 5.9 on tanh rounds to the largest value: the table may stop at 6.
        assert!((5.9_f64.tanh() * f64::from(Q15_ONE)).round() >= 32_767.0);
    }

    #[test]
    fn error_against_tanh() {
        let worst = (0..=80_000)
            .map(|i| i as f32 * 1.3e-4)
            .map(|z| {
                let q = f64::from(quantised_tanh(z)) / f64::from(Q15_ONE);
                (q - f64::from(z).tanh()).abs()
            })
            .fold(0.0_f64, f64::max);
        std::println!("quantised tanh error {worst:.2e}");
        assert!(worst < 1.25e-4, "{worst}");
    }

    /// The table to 8 clamped at 2²⁰ − 1 is the function the table to 6 clamped at
    /// 192·4096 − 1 was (its first definition), at every z.
    #[test]
    fn the_table_to_8_is_the_function_of_the_table_to_6() {
        let to_six = |z: f32| -> i16 {
            let p = ((z.abs() * 131_072.0) as u32).min(192 * 4096 - 1);
            let (i, f) = ((p >> 12) as usize, (p & 4095) as i32);
            let (low, high) = (i32::from(TABLE[i]), i32::from(TABLE[i + 1]));
            let value = (low + (((high - low) * f + 2048) >> 12)) as i16;
            if z < 0.0 {
                -value
            } else {
                value
            }
        };
        for i in -2_000_000..=2_000_000 {
            let z = i as f32 * 5e-6;
            assert_eq!(quantised_tanh(z), to_six(z), "at {z}");
        }
        for z in [
            5.99,
            6.0,
            7.99,
            8.0,
            8.5,
            16.0,
            1e9,
            f32::MAX,
            f32::INFINITY,
            f32::NAN,
        ] {
            assert_eq!(quantised_tanh(z), to_six(z), "at {z}");
            assert_eq!(quantised_tanh(-z), to_six(-z), "at -{z}");
        }
    }

    #[test]
    fn odd_monotone_saturating_and_total() {
        let mut previous = i16::MIN;
        for i in -100_000..=100_000 {
            let z = i as f32 * 1e-4;
            let q = quantised_tanh(z);
            assert_eq!(q, -quantised_tanh(-z), "odd at {z}");
            assert!(q >= previous, "monotone at {z}");
            previous = q;
        }
        assert_eq!(quantised_tanh(f32::NAN), 0);
        assert_eq!(quantised_tanh(f32::INFINITY), i16::MAX);
        assert_eq!(quantised_tanh(f32::NEG_INFINITY), -i16::MAX);
        assert_eq!(quantised_tanh(1e30), i16::MAX);
    }
}
