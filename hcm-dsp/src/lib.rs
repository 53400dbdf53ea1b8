//! # hcm-dsp — the Cortex-M4 instructions hcm-core needs beyond safe Rust
//!
//! hcm-core keeps `#![forbid(unsafe_code)]`; two things it needs cannot be reached from
//! safe, stable Rust on its controller, so the few instructions live here, written out
//! in inline assembly behind the `dsp` feature, each with a portable twin that gives
//! the same results on every target:
//!
//! - [`mac4`], the dual 16-bit multiply-accumulate of the int8 network (LLVM maps
//!   plain code to `smlad` only at `opt-level = 3`, with a 64-bit accumulator, and never
//!   from int8 weights; the `core::arch::arm` intrinsics are unstable);
//! - [`sqrt_f32`], the FPU's `vsqrt.f32` (`f32::sqrt` is `std`'s; a `no_std` build
//!   links the `libm` crate's software `sqrtf` instead).
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
//!
//! [`sqrt_f32`] on a hard-float Cortex-M (`dsp` feature, `target_abi = "eabihf"`) is one
//! `vsqrt.f32` (14 cycles on a Cortex-M4F), where the `libm` crate's `sqrtf` is 224 B
//! of integer code plus a 256 B table. Both round correctly (IEEE 754 `squareRoot`),
//! so they agree bit for bit on every input but NaN: see [`sqrt_f32`].

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

/// `sum` + a₀·b₀ + a₁·b₁ for the signed 16-bit lanes a₀ = bits 0–15 and a₁ = bits
/// 16–31 of `a` (likewise b of `b`), wrapping: `smlad` on a Cortex-M4 with the `dsp`
/// feature (one instruction; the compiler's multiply, multiply-accumulate and the lane
/// extractions take four or more), the same integers elsewhere.
#[inline(always)]
pub fn dual_mac(sum: i32, a: u32, b: u32) -> i32 {
    #[cfg(all(feature = "dsp", target_arch = "arm"))]
    {
        dsp::dual_mac(sum, a, b)
    }
    #[cfg(not(all(feature = "dsp", target_arch = "arm")))]
    {
        portable::dual_mac(sum, a, b)
    }
}

/// The sums of four rows over their whole groups of four inputs: for each row r,
/// Σ over k < `IN` − `IN` % 4 of its weights (stored in [`interleave`]'s order, group
/// by group) times `activations[k]`, wrapping. Inputs past the last whole group are the
/// caller's (none when `IN` is a multiple of 4).
///
/// On a Cortex-M4 with the `dsp` feature it is one loop written out in assembly: per
/// group of four inputs, 24 instructions for the 16 multiply-accumulates of the four
/// rows (two loads of activation pairs, four of weight words with the row offsets as
/// immediates, eight `sxtb16`, eight `smlad`, the loop's compare and branch). The
/// compiler's loop over [`mac4`] took 31: it kept moving pointers between registers
/// and counting a separate index. Measured and not kept: both pairs in one
/// `ldm` (23 instructions; peg residual −64), since `ldm` faults on an address that is
/// not a multiple of 4 and `&[i16; IN]` only promises 2, where `ldr` may be unaligned.
#[inline(always)]
pub fn four_row_sums<const IN: usize>(rows: &[[i8; IN]; 4], activations: &[i16; IN]) -> [i32; 4] {
    #[cfg(all(feature = "dsp", target_arch = "arm"))]
    {
        dsp::four_row_sums(rows, activations)
    }
    #[cfg(not(all(feature = "dsp", target_arch = "arm")))]
    {
        portable::four_row_sums(rows, activations)
    }
}

/// One block of 16 outputs of a column-major `f32` layer (`weights[j][i]` multiplies
/// input j into output i): for each lane k, `sums[k]` += `weights[j][first + k]`·`x[j]`
/// for j = 0, 1, … below the shorter of `weights` and `x`, in that order, each product
/// rounded and then added (as `s += w * x`, no fused multiply-add): the same bits on
/// every target. Nothing changes when the block does not fit (`first + 16 > OUT`).
///
/// On a hard-float Cortex-M with the `dsp` feature it is a loop written out in
/// assembly: per input, one load of x, two `vldm` of eight weights, sixteen `vmla.f32`
/// (multiply, round, add, round: not fused) and the loop's add, compare and branch, 22
/// instructions for 16 multiply-adds where the compiler's loop took 37 (each weight
/// loaded by a `vldr` of its own).
#[inline(always)]
pub fn block_sums<const OUT: usize>(
    sums: &mut [f32; 16],
    weights: &[[f32; OUT]],
    first: usize,
    x: &[f32],
) {
    #[cfg(all(feature = "dsp", target_arch = "arm", target_abi = "eabihf"))]
    {
        fpu::block_sums(sums, weights, first, x)
    }
    #[cfg(not(all(feature = "dsp", target_arch = "arm", target_abi = "eabihf")))]
    {
        portable::block_sums(sums, weights, first, x)
    }
}

/// √`x`, correctly rounded (IEEE 754 `squareRoot`, the unit of `x` to the power ½):
/// `vsqrt.f32` on a hard-float Arm core with the `dsp` feature, [`portable::sqrt_f32`]
/// elsewhere.
///
/// Every non-NaN input gives the same bits on every target: +0 → +0, −0 → −0, +∞ → +∞,
/// and x < 0 (−∞ included) → NaN. NaN bits may differ, NaN-ness never: for x < 0 the
/// Cortex-M4F and `libm`'s software give the default NaN `0x7fc0_0000`, x86-64's
/// `sqrtss` gives `0xffc0_0000`; a NaN input comes back quieted with its sign and
/// payload from `vsqrt.f32` (with the reset `FPSCR.DN = 0`), `sqrtss` and AArch64's
/// `fsqrt`, as `0x7fc0_0000` from `libm`'s software.
#[inline(always)]
pub fn sqrt_f32(x: f32) -> f32 {
    #[cfg(all(feature = "dsp", target_arch = "arm", target_abi = "eabihf"))]
    {
        fpu::sqrt_f32(x)
    }
    #[cfg(not(all(feature = "dsp", target_arch = "arm", target_abi = "eabihf")))]
    {
        portable::sqrt_f32(x)
    }
}

/// The same arithmetic in plain Rust, on every target: the reference the instructions
/// are held to.
pub mod portable {
    /// [`super::sqrt_f32`] without the FPU instruction: the `libm` crate's `sqrtf`
    /// (itself `sqrtss` on x86-64 and `fsqrt` on AArch64, software elsewhere).
    #[inline(always)]
    pub fn sqrt_f32(x: f32) -> f32 {
        libm::sqrtf(x)
    }

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

    /// [`super::block_sums`] in plain Rust.
    #[inline(always)]
    pub fn block_sums<const OUT: usize>(
        sums: &mut [f32; 16],
        weights: &[[f32; OUT]],
        first: usize,
        x: &[f32],
    ) {
        let Some(last) = first.checked_add(16).filter(|&last| last <= OUT) else {
            return;
        };
        let mut a = *sums;
        for (column, &x) in weights.iter().zip(x) {
            if let Some(w) = column.get(first..last) {
                for (a, &w) in a.iter_mut().zip(w) {
                    *a += w * x;
                }
            }
        }
        *sums = a;
    }

    /// [`super::dual_mac`] without the instruction.
    #[inline(always)]
    pub fn dual_mac(sum: i32, a: u32, b: u32) -> i32 {
        smlad(sum, lanes(a), b)
    }

    /// [`super::four_row_sums`] through [`mac4`], a group of four inputs at a time, each
    /// group's two activation pairs formed once for the four rows.
    #[inline(always)]
    pub fn four_row_sums<const IN: usize>(
        rows: &[[i8; IN]; 4],
        activations: &[i16; IN],
    ) -> [i32; 4] {
        let word = |row: &[i8; IN], k: usize| match row.get(k..k + 4) {
            Some(&[a, b, c, d]) => u32::from_le_bytes([a as u8, b as u8, c as u8, d as u8]),
            _ => 0,
        };
        let pair = |k: usize| match activations.get(k..k + 2) {
            Some(&[a, b]) => u32::from(a as u16) | u32::from(b as u16) << 16,
            _ => 0,
        };
        let mut sums = [0_i32; 4];
        let mut k = 0;
        while k + 4 <= IN {
            let (p01, p23) = (pair(k), pair(k + 2));
            for (sum, row) in sums.iter_mut().zip(rows) {
                *sum = mac4(*sum, word(row, k), p01, p23);
            }
            k += 4;
        }
        sums
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

    /// [`super::dual_mac`] in one instruction.
    #[inline(always)]
    pub fn dual_mac(sum: i32, a: u32, b: u32) -> i32 {
        let total: i32;
        // SAFETY: register-only arithmetic, as in `mac4`. The result has a register
        // of its own, so a constant `sum` stays in its register across calls.
        unsafe {
            asm!(
                "smlad {total}, {a}, {b}, {sum}",
                total = lateout(reg) total,
                sum = in(reg) sum,
                a = in(reg) a,
                b = in(reg) b,
                options(pure, nomem, nostack, preserves_flags),
            );
        }
        total
    }

    /// [`super::four_row_sums`]: one pass over the groups of four inputs, the four
    /// rows' words read at fixed offsets (`IN`, 2·`IN`, 3·`IN` bytes) from the first
    /// row's, which the last load of each pass advances.
    #[inline(always)]
    pub fn four_row_sums<const IN: usize>(
        rows: &[[i8; IN]; 4],
        activations: &[i16; IN],
    ) -> [i32; 4] {
        let groups = IN / 4;
        let (mut s0, mut s1, mut s2, mut s3) = (0_i32, 0_i32, 0_i32, 0_i32);
        if groups == 0 {
            return [0; 4];
        }
        let activations = activations.as_ptr();
        // SAFETY: the loop runs `groups` ≥ 1 times; pass g reads activations 4g..4g+4
        // (two words at `x`, which starts at `activations` and ends at `end`) and
        // bytes 4g..4g+4 of each row (at `w` + r·`IN`, `w` starting at the first row),
        // all within the two arrays since 4·`groups` ≤ `IN`. `ldr` of a word at any
        // address is allowed on Armv7-M (unaligned access is not trapped by default,
        // and the rows are 4-byte aligned when `IN` is a multiple of 4). It writes only
        // the registers it names and the flags (no `preserves_flags`).
        unsafe {
            asm!(
                "2:",
                "ldr {a01}, [{x}], #4",
                "ldr {a23}, [{x}], #4",
                "ldr {word}, [{w}, #{row_1}]",
                "sxtb16 {lanes}, {word}",
                "smlad {s1}, {lanes}, {a01}, {s1}",
                "sxtb16 {lanes}, {word}, ror #8",
                "smlad {s1}, {lanes}, {a23}, {s1}",
                "ldr {word}, [{w}, #{row_2}]",
                "sxtb16 {lanes}, {word}",
                "smlad {s2}, {lanes}, {a01}, {s2}",
                "sxtb16 {lanes}, {word}, ror #8",
                "smlad {s2}, {lanes}, {a23}, {s2}",
                "ldr {word}, [{w}, #{row_3}]",
                "sxtb16 {lanes}, {word}",
                "smlad {s3}, {lanes}, {a01}, {s3}",
                "sxtb16 {lanes}, {word}, ror #8",
                "smlad {s3}, {lanes}, {a23}, {s3}",
                "ldr {word}, [{w}], #4",
                "sxtb16 {lanes}, {word}",
                "smlad {s0}, {lanes}, {a01}, {s0}",
                "sxtb16 {lanes}, {word}, ror #8",
                "smlad {s0}, {lanes}, {a23}, {s0}",
                "cmp {x}, {end}",
                "bne 2b",
                x = inout(reg) activations => _,
                w = inout(reg) rows.as_ptr().cast::<u8>() => _,
                end = in(reg) activations.wrapping_add(4 * groups),
                row_1 = const IN,
                row_2 = const 2 * IN,
                row_3 = const 3 * IN,
                s0 = inout(reg) s0,
                s1 = inout(reg) s1,
                s2 = inout(reg) s2,
                s3 = inout(reg) s3,
                a01 = out(reg) _,
                a23 = out(reg) _,
                word = out(reg) _,
                lanes = out(reg) _,
                options(pure, readonly, nostack),
            );
        }
        [s0, s1, s2, s3]
    }
}

/// The FPU's square root (VFPv2 and later, on every hard-float Cortex-M).
///
/// Rust 1.95 refuses the FPU's registers as `asm!` operands or clobbers (`sreg`, even
/// `s0` by name) on `thumbv7em-none-eabihf`: it asks for the `vfp2` target feature,
/// which that target's single-precision FPU (LLVM's `vfp2sp`) does not carry
/// (rust-lang/rust#161826). So the instruction sits in a two-instruction function of
/// its own, called with the hard-float ABI (argument and result in `s0`, which the
/// caller already treats as clobbered). Measured against an inline block that moves
/// the operand through a core register and borrows `s0` (five instructions): the
/// same instructions per peg HCM (17,872 against 17,879), 36 B less flash per peg image and
/// 148 B less for the ball's.
#[cfg(all(feature = "dsp", target_arch = "arm", target_abi = "eabihf"))]
mod fpu {
    core::arch::global_asm!(
        ".pushsection .text.hcm_dsp_vsqrt_f32,\"ax\",%progbits",
        // The assembler sees only the module's own directives, not the target's FPU:
        // name the Cortex-M4F's (a subset of every later Cortex-M FPU's).
        ".fpu fpv4-sp-d16",
        ".global hcm_dsp_vsqrt_f32",
        ".type hcm_dsp_vsqrt_f32, %function",
        ".thumb_func",
        "hcm_dsp_vsqrt_f32:",
        "vsqrt.f32 s0, s0",
        "bx lr",
        ".size hcm_dsp_vsqrt_f32, . - hcm_dsp_vsqrt_f32",
        ".popsection",
    );

    core::arch::global_asm!(
        ".pushsection .text.hcm_dsp_block_sums,\"ax\",%progbits",
        ".fpu fpv4-sp-d16",
        ".global hcm_dsp_block_sums",
        ".type hcm_dsp_block_sums, %function",
        ".thumb_func",
        // r0 the 16 sums (read, then written), r1 the block's first weight in column
        // 0, r2 the inputs, r3 one past the last input read, [sp] the column stride in
        // bytes. s16–s24 are the caller's (AAPCS): saved and restored.
        "hcm_dsp_block_sums:",
        "ldr r12, [sp]",
        "sub r12, r12, #32",
        "vpush {{s16-s24}}",
        "vldmia r0, {{s0-s15}}",
        "1:",
        "vldmia r2!, {{s24}}",
        "vldmia r1!, {{s16-s23}}",
        "vmla.f32 s0, s16, s24",
        "vmla.f32 s1, s17, s24",
        "vmla.f32 s2, s18, s24",
        "vmla.f32 s3, s19, s24",
        "vmla.f32 s4, s20, s24",
        "vmla.f32 s5, s21, s24",
        "vmla.f32 s6, s22, s24",
        "vmla.f32 s7, s23, s24",
        "vldmia r1, {{s16-s23}}",
        "vmla.f32 s8, s16, s24",
        "vmla.f32 s9, s17, s24",
        "vmla.f32 s10, s18, s24",
        "vmla.f32 s11, s19, s24",
        "vmla.f32 s12, s20, s24",
        "vmla.f32 s13, s21, s24",
        "vmla.f32 s14, s22, s24",
        "vmla.f32 s15, s23, s24",
        "add r1, r1, r12",
        "cmp r2, r3",
        "bne 1b",
        "vstmia r0, {{s0-s15}}",
        "vpop {{s16-s24}}",
        "bx lr",
        ".size hcm_dsp_block_sums, . - hcm_dsp_block_sums",
        ".popsection",
    );

    extern "C" {
        /// √x by `vsqrt.f32`: reads `s0` and writes it, nothing else.
        fn hcm_dsp_vsqrt_f32(x: f32) -> f32;

        /// The loop of [`super::block_sums`] over inputs `x` up to `x_end` (at least
        /// one), the columns `stride` bytes apart.
        fn hcm_dsp_block_sums(
            sums: *mut f32,
            weights: *const f32,
            x: *const f32,
            x_end: *const f32,
            stride: usize,
        );
    }

    /// [`super::block_sums`] through the loop above.
    #[inline(always)]
    pub fn block_sums<const OUT: usize>(
        sums: &mut [f32; 16],
        weights: &[[f32; OUT]],
        first: usize,
        x: &[f32],
    ) {
        let inputs = weights.len().min(x.len());
        if inputs == 0 || first.checked_add(16).is_none_or(|last| last > OUT) {
            return;
        }
        // SAFETY: the loop reads `inputs` ≥ 1 values of `x` and, for each, the 16
        // weights `first..first + 16` of that column, all within `weights` since
        // `first + 16 ≤ OUT` and the columns are `OUT` `f32`s apart; it writes the 16
        // sums and only the registers the hard-float ABI lets a callee clobber (the
        // s16–s24 it uses are saved and restored). Every `vldm`/`vstm` address is that
        // of an `f32`, so a multiple of 4, as those instructions require.
        unsafe {
            let x = x.as_ptr();
            hcm_dsp_block_sums(
                sums.as_mut_ptr(),
                weights.as_ptr().cast::<f32>().add(first),
                x,
                x.add(inputs),
                OUT * 4,
            );
        }
    }

    /// [`super::sqrt_f32`] in one instruction (and a call).
    #[inline(always)]
    pub fn sqrt_f32(x: f32) -> f32 {
        // SAFETY: the function above touches `s0` alone (a caller-saved register
        // under the hard-float ABI), and `vsqrt.f32` exists on every core with an
        // FPU, which `target_abi = "eabihf"` promises. It sets FPSCR's cumulative
        // exception bits, as any float operation does.
        unsafe { hcm_dsp_vsqrt_f32(x) }
    }
}

#[cfg(test)]
mod tests {
    extern crate std;

    use super::{interleave, mac4, sqrt_f32};

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
    fn four_row_sums_cover_the_whole_groups_and_leave_the_rest() {
        // 10 inputs: two whole groups, two inputs past them that the sums leave out.
        let natural: [[i8; 10]; 4] = core::array::from_fn(|r| {
            core::array::from_fn(|k| ((r * 37 + k * 101) % 255) as i8 ^ -128)
        });
        let x: [i16; 10] = core::array::from_fn(|k| (k as i16 - 5) * 6_553 - 1);
        let stored = natural.map(|row| {
            let mut out = row;
            for g in 0..2 {
                let w = interleave([row[4 * g], row[4 * g + 1], row[4 * g + 2], row[4 * g + 3]]);
                out[4 * g..4 * g + 4].copy_from_slice(&w);
            }
            out
        });
        let sums = super::four_row_sums(&stored, &x);
        for (r, row) in natural.iter().enumerate() {
            let want: i64 = (0..8).map(|k| i64::from(row[k]) * i64::from(x[k])).sum();
            assert_eq!(i64::from(sums[r]), want, "row {r}");
        }
        assert_eq!(super::four_row_sums(&[[5_i8; 3]; 4], &[7_i16; 3]), [0; 4]);
    }

    #[test]
    fn interleave_is_its_own_inverse() {
        let w = [1, -2, 3, -4];
        assert_eq!(interleave(interleave(w)), w);
        assert_ne!(interleave(w), w);
    }

    /// √x correctly rounded, from `f64`: exact enough that rounding it to `f32` cannot
    /// double-round (53 ≥ 2·24 + 2 bits).
    fn reference(x: f32) -> f32 {
        f64::from(x).sqrt() as f32
    }

    #[test]
    fn square_roots_round_correctly_across_the_f32_range() {
        // Every 61st bit pattern (70 million), both signs: subnormals, normals, ∞.
        let mut checked = 0_u32;
        for bits in (0..=u32::MAX).step_by(61) {
            let x = f32::from_bits(bits);
            let (got, want) = (sqrt_f32(x), reference(x));
            if want.is_nan() {
                assert!(got.is_nan(), "sqrt({x:e}) = {got:e}, not NaN");
            } else {
                assert_eq!(got.to_bits(), want.to_bits(), "sqrt({x:e})");
            }
            checked += 1;
        }
        assert!(checked > 70_000_000);
    }

    #[test]
    fn square_roots_of_the_special_values() {
        let exact = [
            (0.0_f32, 0.0_f32),
            (-0.0, -0.0),
            (f32::INFINITY, f32::INFINITY),
            (1.0, 1.0),
            (4.0, 2.0),
            (f32::from_bits(1), f32::from_bits(0x1a35_04f3)),
            (f32::MAX, f32::from_bits(0x5f7f_ffff)),
        ];
        for (x, root) in exact {
            assert_eq!(sqrt_f32(x).to_bits(), root.to_bits(), "sqrt({x:e})");
        }
        for x in [
            -1.0_f32,
            -f32::MIN_POSITIVE,
            f32::NEG_INFINITY,
            f32::NAN,
            -f32::NAN,
        ] {
            assert!(sqrt_f32(x).is_nan(), "sqrt({x:e})");
        }
    }
}
