//! # hcm-dsp — two DSP instructions for the int8 residual kernel
//!
//! hcm-core keeps `#![forbid(unsafe_code)]`; the dual 16-bit multiply-accumulate it
//! needs for its int8 network cannot be reached from safe, stable Rust (LLVM maps
//! plain code to `smlad` only at `opt-level = 3`, with a 64-bit accumulator, and never
//! from int8 weights; the `core::arch::arm` intrinsics are unstable). So the few
//! instructions live here, written out in inline assembly behind the `dsp` feature,
//! with a portable twin that gives the same integers on every target.
//!
//! One call, [`mac4`], does four multiply-accumulates: the four int8 weights of one
//! 32-bit word against four 16-bit activations, added to a 32-bit sum. On a Cortex-M4
//! it is four instructions — two `sxtb16` (sign-extend bytes 0 and 2, then bytes 1 and
//! 3, into two 16-bit lanes) and two `smlad` (two 16×16 products added to the sum) —
//! where the portable form takes four loads, four multiplies and four adds.
//!
//! The byte order this asks of the weights ([`interleave`]): `sxtb16` takes bytes 0
//! and 2 of a word, so the word holding weights w0, w1, w2, w3 stores them as
//! `[w0, w2, w1, w3]`; then bytes 0/2 are (w0, w1) and bytes 1/3 are (w2, w3), which
//! meet the activation pairs (x0, x1) and (x2, x3) as they lie in memory.
//!
//! Sums wrap on overflow, as `smlad` does (it sets the Q flag and wraps). A sum of
//! n products of an int8 level (|q| ≤ 127) and an int16 activation (|x| ≤ 32 767)
//! stays within 4 161 409·n, below 2³¹ for n ≤ 516: hcm's layers (at most a few
//! dozen inputs) never come near.

#![no_std]
#![warn(missing_docs)]

/// The word order [`mac4`] reads four weights in: `[w0, w2, w1, w3]` for weights
/// `[w0, w1, w2, w3]` (see the crate docs). Its own inverse.
#[inline]
pub const fn interleave(w: [i8; 4]) -> [i8; 4] {
    [w[0], w[2], w[1], w[3]]
}

/// `sum` + w0·x0 + w1·x1 + w2·x2 + w3·x3, for the weights packed by [`interleave`] into
/// the little-endian `weights` word and the activations `pair_01` = x0 | x1 << 16 and
/// `pair_23` = x2 | x3 << 16 (each an `i16` as 16 bits). Wraps on overflow.
#[inline(always)]
pub fn mac4(sum: i32, weights: u32, pair_01: u32, pair_23: u32) -> i32 {
    #[cfg(all(feature = "dsp", target_arch = "arm"))]
    {
        dsp::mac4(sum, weights, pair_01, pair_23)
    }
    #[cfg(not(all(feature = "dsp", target_arch = "arm")))]
    {
        portable::mac4(sum, weights, pair_01, pair_23)
    }
}

/// The same arithmetic in plain Rust, on every target: the reference the instructions
/// are held to.
pub mod portable {
    /// The two 16-bit lanes of `sxtb16`: bytes 0 and 2 of `word`, sign-extended.
    #[inline(always)]
    fn sxtb16(word: u32) -> (i32, i32) {
        let [b0, _, b2, _] = word.to_le_bytes();
        (i32::from(b0 as i8), i32::from(b2 as i8))
    }

    /// The two signed 16-bit lanes of `pair`: bits 0–15 and 16–31.
    #[inline(always)]
    fn lanes(pair: u32) -> (i32, i32) {
        (
            i32::from(pair as u16 as i16),
            i32::from((pair >> 16) as u16 as i16),
        )
    }

    /// `smlad`: `sum` + low(a)·low(b) + high(a)·high(b), wrapping.
    #[inline(always)]
    fn smlad(sum: i32, a: (i32, i32), b: u32) -> i32 {
        let (b_low, b_high) = lanes(b);
        sum.wrapping_add(a.0 * b_low).wrapping_add(a.1 * b_high)
    }

    /// [`super::mac4`] without the DSP instructions.
    #[inline(always)]
    pub fn mac4(sum: i32, weights: u32, pair_01: u32, pair_23: u32) -> i32 {
        let sum = smlad(sum, sxtb16(weights), pair_01);
        smlad(sum, sxtb16(weights.rotate_right(8)), pair_23)
    }
}

/// The instructions themselves (Armv7E-M DSP extension).
#[cfg(all(feature = "dsp", target_arch = "arm"))]
mod dsp {
    use core::arch::asm;

    /// [`super::mac4`] in four instructions.
    #[inline(always)]
    pub fn mac4(mut sum: i32, weights: u32, pair_01: u32, pair_23: u32) -> i32 {
        // SAFETY: register-only arithmetic (no memory, no stack, no flags read by
        // the compiler): `sxtb16` and `smlad` exist on every Armv7E-M core, which
        // the `dsp` feature promises.
        unsafe {
            asm!(
                "sxtb16 {lanes}, {weights}",
                "smlad {sum}, {lanes}, {pair_01}, {sum}",
                "sxtb16 {lanes}, {weights}, ror #8",
                "smlad {sum}, {lanes}, {pair_23}, {sum}",
                sum = inout(reg) sum,
                weights = in(reg) weights,
                pair_01 = in(reg) pair_01,
                pair_23 = in(reg) pair_23,
                lanes = out(reg) _,
                options(pure, nomem, nostack),
            );
        }
        sum
    }
}

#[cfg(test)]
mod tests {
    use super::{interleave, mac4};

    /// The four products by hand, in i64.
    fn by_hand(sum: i32, w: [i8; 4], x: [i16; 4]) -> i64 {
        i64::from(sum)
            + w.iter()
                .zip(x)
                .map(|(&w, x)| i64::from(w) * i64::from(x))
                .sum::<i64>()
    }

    fn pack(w: [i8; 4], x: [i16; 4]) -> (u32, u32, u32) {
        let weights = u32::from_le_bytes(interleave(w).map(|b| b as u8));
        let pair = |a: i16, b: i16| u32::from(a as u16) | u32::from(b as u16) << 16;
        (weights, pair(x[0], x[1]), pair(x[2], x[3]))
    }

    #[test]
    fn four_products_at_the_extremes_and_in_between() {
        let levels = [-128_i8, -127, -1, 0, 1, 2, 63, 127];
        let values = [i16::MIN, -32_767, -1, 0, 1, 3, 12_345, i16::MAX];
        let mut checked = 0;
        for (i, &a) in levels.iter().enumerate() {
            for (j, &b) in values.iter().enumerate() {
                let w = [
                    a,
                    levels[(i + 3) % 8],
                    levels[(i + 5) % 8],
                    levels[(i + j) % 8],
                ];
                let x = [
                    b,
                    values[(j + 1) % 8],
                    values[(j + 6) % 8],
                    values[(i * j) % 8],
                ];
                for sum in [0, -7, 1 << 20] {
                    let (weights, p01, p23) = pack(w, x);
                    assert_eq!(i64::from(mac4(sum, weights, p01, p23)), by_hand(sum, w, x));
                    checked += 1;
                }
            }
        }
        assert_eq!(checked, 192);
    }

    #[test]
    fn interleave_is_its_own_inverse() {
        let w = [1, -2, 3, -4];
        assert_eq!(interleave(interleave(w)), w);
        assert_ne!(interleave(w), w);
    }
}
