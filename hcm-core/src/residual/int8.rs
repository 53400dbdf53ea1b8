//! The int8 hidden layer: 8-bit weights times 16-bit activations, summed in 32-bit
//! integers, two multiply-accumulates per instruction on a Cortex-M4.
//!
//! ```text
//! s_i = Σ_j q_ij·a_j                  q_ij ∈ [−127, 127] (int8), a_j the Q activations (i16)
//! z_i = s_i·(σ_i·u) + b_i             σ_i the row's scale, u the activations' unit (f32)
//! a'_i = qtanh(z_i)                    the quantised tanh (i16, Q15)
//! ```
//!
//! The activations travel as Q15 integers a, value a·u with u = 2⁻¹⁵, from the
//! quantised tanh ([`super::qtanh`]), which goes from the `f32` pre-activation to the
//! integer directly: an int8 network runs that activation and no other (the decoder
//! refuses an int8 blob of another; training fits the int8 twin with it). u is a power
//! of two, so a·u and σ_i·u are exact.
//!
//! The sums are exact integers (at most 127·32 767 per product: within 2³¹ for up to
//! 516 inputs), so the order of the multiply-accumulates does not matter and the
//! kernel can take them four at a time through [`hcm_dsp::mac4`] — `sxtb16` and
//! `smlad` on a Cortex-M4 with the `dsp` feature (the firmware's), the same integers
//! in plain Rust elsewhere; four rows at a time share each pair of activations loaded
//! ([`hcm_dsp::four_row_sums`], on the Cortex-M4 a loop written out in assembly: 24
//! instructions per 16 multiply-accumulates where the compiler's took 31).
//! The levels are stored in `mac4`'s order ([`hcm_dsp::interleave`] on every group of
//! four inputs; a remainder of fewer than four kept in order).

use super::qtanh::{quantised_tanh_scaled, POSITIONS_PER_UNIT, Q15_ONE};
use super::BlobError;
use hcm_dsp::{four_row_sums, interleave, mac4};

/// An int8 layer with `IN` inputs and `OUT` outputs (see the module docs).
///
/// 4-byte aligned, so each row of levels (when `IN` is a multiple of 4) starts on a
/// word: the kernel reads four levels in one load.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(4))]
pub struct Int8Layer<const IN: usize, const OUT: usize> {
    /// Levels q ∈ [−127, 127], row by row (`[out][in]`), each whole group of four in
    /// [`hcm_dsp::interleave`]'s order (read them with [`Int8Layer::level`]).
    ///
    /// Tried and not kept: the four rows of a block stored word by word, one
    /// sequential pass per block (7,148 instructions per peg residual against 6,860:
    /// the four words loaded together spill the accumulators).
    levels: [[i8; IN]; OUT],
    /// Scale σ_i of each row (dimensionless): the weight is q·σ_i.
    scales: [f32; OUT],
    /// Bias b_i, one per output (dimensionless: the layer works on normalised values).
    bias: [f32; OUT],
    /// σ_i·u·P per row, P = [`POSITIONS_PER_UNIT`] (2¹⁷, the quantised tanh's
    /// table positions per unit of z): the factor from a row's sum straight to the
    /// position scale, worked out when the layer is made.
    gains: [f32; OUT],
    /// b_i·P per output, likewise.
    offsets: [f32; OUT],
}

impl<const IN: usize, const OUT: usize> Int8Layer<IN, OUT> {
    /// A layer whose levels, scales and biases are all zero.
    pub const fn zeroed() -> Self {
        Int8Layer {
            levels: [[0; IN]; OUT],
            scales: [0.0; OUT],
            bias: [0.0; OUT],
            gains: [0.0; OUT],
            offsets: [0.0; OUT],
        }
    }

    /// The layer with levels given row by row in natural order (`levels[i][j]` for
    /// input j into output i), a scale per row and a bias per output; a level of −128
    /// is read as −127 (the symmetric range).
    pub fn from_levels(levels: [[i8; IN]; OUT], scales: [f32; OUT], bias: [f32; OUT]) -> Self {
        let mut layer = Int8Layer {
            levels: [[0; IN]; OUT],
            scales,
            bias,
            gains: gains(&scales),
            offsets: offsets(&bias),
        };
        for (output, row) in levels.iter().enumerate() {
            for (input, &q) in row.iter().enumerate() {
                layer.set_level(output, input, q);
            }
        }
        layer
    }

    /// The layer from its levels as stored (`[out][in]`, each whole group of four in
    /// [`hcm_dsp::interleave`]'s order: what [`Int8Layer::stored_levels`] gives), a
    /// scale per row and a bias per output; a level of −128 is read as −127. `const`,
    /// so that a build step can write a decoded layer into a firmware image as a
    /// `static` (hcm-firmware's `build.rs`).
    pub const fn from_stored_levels(
        mut levels: [[i8; IN]; OUT],
        scales: [f32; OUT],
        bias: [f32; OUT],
    ) -> Self {
        let mut output = 0;
        while output < OUT {
            let mut input = 0;
            while input < IN {
                if levels[output][input] == i8::MIN {
                    levels[output][input] = -127;
                }
                input += 1;
            }
            output += 1;
        }
        Int8Layer {
            levels,
            scales,
            bias,
            gains: gains(&scales),
            offsets: offsets(&bias),
        }
    }

    /// The scale σ_i of each row (dimensionless).
    pub const fn scales(&self) -> &[f32; OUT] {
        &self.scales
    }

    /// The bias b_i of each output (dimensionless).
    pub const fn biases(&self) -> &[f32; OUT] {
        &self.bias
    }

    /// The levels as stored (see [`Int8Layer::from_stored_levels`]).
    pub const fn stored_levels(&self) -> &[[i8; IN]; OUT] {
        &self.levels
    }

    /// Where level (output, input) is stored within its row.
    fn slot(input: usize) -> usize {
        let whole = IN - IN % 4;
        if input < whole {
            let base = input - input % 4;
            base + usize::from(interleave([0, 1, 2, 3])[input % 4].unsigned_abs())
        } else {
            input
        }
    }

    /// The level q of output `output` for input `input`, or `None` outside the layer.
    pub fn level(&self, output: usize, input: usize) -> Option<i8> {
        (input < IN)
            .then(|| self.levels.get(output)?.get(Self::slot(input)).copied())
            .flatten()
    }

    /// Sets level (output, input) to `q` (−128 as −127); nothing outside the layer.
    pub fn set_level(&mut self, output: usize, input: usize, q: i8) {
        if input >= IN {
            return;
        }
        if let Some(slot) = self
            .levels
            .get_mut(output)
            .and_then(|row| row.get_mut(Self::slot(input)))
        {
            *slot = q.max(-127);
        }
    }

    /// Reads the layer from the front of a blob's layer bytes — levels row-major
    /// (one byte each, −128 refused), a little-endian `f32` scale per row (finite),
    /// a little-endian `f32` bias per output (finite) — and returns the bytes read.
    pub(crate) fn read(&mut self, bytes: &[u8]) -> Result<usize, BlobError> {
        let level_bytes = IN.checked_mul(OUT).ok_or(BlobError::Malformed)?;
        let (levels, rest) = bytes
            .split_at_checked(level_bytes)
            .ok_or(BlobError::Malformed)?;
        for (output, row) in levels.chunks_exact(IN.max(1)).take(OUT).enumerate() {
            for (input, &byte) in row.iter().enumerate() {
                // −128 has no positive twin: the symmetric range is [−127, 127].
                if byte == 0x80 {
                    return Err(BlobError::Malformed);
                }
                self.set_level(output, input, i8::from_le_bytes([byte]));
            }
        }
        let mut floats = rest.chunks_exact(4).map(|word| {
            let value = f32::from_le_bytes([word[0], word[1], word[2], word[3]]);
            if value.is_finite() {
                Ok(value)
            } else {
                Err(BlobError::NonFiniteWeight)
            }
        });
        for slot in self.scales.iter_mut().chain(self.bias.iter_mut()) {
            *slot = floats.next().ok_or(BlobError::Malformed)??;
        }
        self.gains = gains(&self.scales);
        self.offsets = offsets(&self.bias);
        Ok(level_bytes + 8 * OUT)
    }

    /// The integer sums s_i = Σ_j q_ij·a_j (see the module docs).
    pub fn sums(&self, activations: &[i16; IN]) -> [i32; OUT] {
        let mut sums = [0_i32; OUT];
        let (blocks, rest) = sums.as_chunks_mut::<4>();
        let (rows, last_rows) = self.levels.as_chunks::<4>();
        for (block, rows) in blocks.iter_mut().zip(rows) {
            *block = four_rows(rows, activations);
        }
        for (sum, row) in rest.iter_mut().zip(last_rows) {
            *sum = one_row(row, activations);
        }
        sums
    }

    /// a' = qtanh(z), z = s·(σ·u) + b: the layer's activations (Q15) from the
    /// activations `a` (Q15). Each block of four sums is activated while still in
    /// registers (no array of sums stored and read back).
    #[inline]
    pub fn forward(&self, activations: &[i16; IN]) -> [i16; OUT] {
        let mut out = [0_i16; OUT];
        self.forward_into(activations, &mut out);
        out
    }

    /// [`Int8Layer::forward`] into `out` (no array returned by copy: 360 instructions
    /// of `memcpy` per peg residual on the Cortex-M4F), each activation as an `i16`
    /// (Q15) or, for the last layer, straight as its `f32` value.
    #[inline(never)]
    pub fn forward_into<A: Q15Value>(&self, activations: &[i16; IN], out: &mut [A; OUT]) {
        // z·P = s·(σ·u·P) + b·P: P is a power of two, so this is the position scale
        // of z = s·(σ·u) + b bit for bit (see `gains`), one multiply less per output.
        let output = |sum: i32, gain: f32, offset: f32| {
            A::from_q15(quantised_tanh_scaled(sum as f32 * gain + offset))
        };
        let (blocks, rest) = out.as_chunks_mut::<4>();
        let (rows, last_rows) = self.levels.as_chunks::<4>();
        let (gains, last_gains) = self.gains.as_chunks::<4>();
        let (offsets, last_offsets) = self.offsets.as_chunks::<4>();
        for (((block, rows), gain), offset) in blocks.iter_mut().zip(rows).zip(gains).zip(offsets) {
            let [s0, s1, s2, s3] = four_rows(rows, activations);
            *block = [
                output(s0, gain[0], offset[0]),
                output(s1, gain[1], offset[1]),
                output(s2, gain[2], offset[2]),
                output(s3, gain[3], offset[3]),
            ];
        }
        for (((out, row), &gain), &offset) in rest
            .iter_mut()
            .zip(last_rows)
            .zip(last_gains)
            .zip(last_offsets)
        {
            *out = output(one_row(row, activations), gain, offset);
        }
    }
}

/// σ_i·u·P for each scale σ_i (see [`Int8Layer`]'s `gains`). σ·u is rounded as the
/// layer's formula rounds it, then scaled by the power of two P exactly: with the
/// offsets b·P, s·(σ·u·P) + b·P is (s·(σ·u) + b)·P bit for bit whenever the result is
/// a normal number (below that the position is 0 either way) and σ < 2¹²⁵ (beyond,
/// σ·u·P overflows).
const fn gains<const OUT: usize>(scales: &[f32; OUT]) -> [f32; OUT] {
    let mut gains = [0.0; OUT];
    let mut i = 0;
    while i < OUT {
        gains[i] = scales[i] * Q15_UNIT * POSITIONS_PER_UNIT;
        i += 1;
    }
    gains
}

/// b_i·P for each bias b_i (exact: P is a power of two; ±∞ past 2¹¹¹, where z·P
/// overflows too).
const fn offsets<const OUT: usize>(bias: &[f32; OUT]) -> [f32; OUT] {
    let mut offsets = [0.0; OUT];
    let mut i = 0;
    while i < OUT {
        offsets[i] = bias[i] * POSITIONS_PER_UNIT;
        i += 1;
    }
    offsets
}

/// What an [`Int8Layer`] writes its activations as: the Q15 integer the next int8
/// layer reads, or the `f32` value a·2⁻¹⁵ (exact) the `f32` output layer reads.
pub trait Q15Value: Copy {
    /// The value of the Q15 activation `a`.
    fn from_q15(a: i16) -> Self;
}

impl Q15Value for i16 {
    #[inline(always)]
    fn from_q15(a: i16) -> Self {
        a
    }
}

impl Q15Value for f32 {
    #[inline(always)]
    fn from_q15(a: i16) -> Self {
        f32::from(a) * Q15_UNIT
    }
}

/// Four levels of a row as the word [`mac4`] reads (one load on a Cortex-M4).
#[inline(always)]
fn word(levels: &[i8; 4]) -> u32 {
    u32::from_le_bytes(levels.map(|q| q as u8))
}

/// Two activations as one word, the first in the low half (one load).
#[inline(always)]
fn pair(first: i16, second: i16) -> u32 {
    u32::from(first as u16) | (u32::from(second as u16) << 16)
}

/// The four levels of `row` from input `k` as the word [`mac4`] reads, 0 past the end.
#[inline(always)]
fn word_at<const IN: usize>(row: &[i8; IN], k: usize) -> u32 {
    match row.get(k..k + 4) {
        Some(&[a, b, c, d]) => word(&[a, b, c, d]),
        _ => 0,
    }
}

/// The activations k and k + 1 as one word, the first in the low half; 0 past the end.
#[inline(always)]
fn pair_at<const IN: usize>(activations: &[i16; IN], k: usize) -> u32 {
    match activations.get(k..k + 2) {
        Some(&[first, second]) => pair(first, second),
        _ => 0,
    }
}

/// The sums of four rows: each group of four activations loaded once for the four
/// ([`hcm_dsp::four_row_sums`], a loop written out for the Cortex-M4), then the inputs
/// past the last whole group.
#[inline(always)]
fn four_rows<const IN: usize>(rows: &[[i8; IN]; 4], activations: &[i16; IN]) -> [i32; 4] {
    let whole = IN - IN % 4;
    let sums = four_row_sums(rows, activations);
    if whole == IN {
        return sums;
    }
    let tail = activations.get(whole..).unwrap_or(&[]);
    let rest = |row: &[i8; IN]| remainder(row.get(whole..).unwrap_or(&[]), tail);
    let [r0, r1, r2, r3] = rows;
    let [s0, s1, s2, s3] = sums;
    [
        s0.wrapping_add(rest(r0)),
        s1.wrapping_add(rest(r1)),
        s2.wrapping_add(rest(r2)),
        s3.wrapping_add(rest(r3)),
    ]
}

/// The sum of one row (rows beyond a multiple of four).
fn one_row<const IN: usize>(row: &[i8; IN], activations: &[i16; IN]) -> i32 {
    let whole = IN - IN % 4;
    let mut sum = 0_i32;
    let mut k = 0;
    while k < whole {
        let (p01, p23) = (pair_at(activations, k), pair_at(activations, k + 2));
        sum = mac4(sum, word_at(row, k), p01, p23);
        k += 4;
    }
    let tail = activations.get(whole..).unwrap_or(&[]);
    sum.wrapping_add(remainder(row.get(whole..).unwrap_or(&[]), tail))
}

/// Σ q·a over the fewer than four inputs after the last whole group (natural order).
#[inline(always)]
fn remainder(levels: &[i8], activations: &[i16]) -> i32 {
    levels.iter().zip(activations).fold(0_i32, |sum, (&q, &a)| {
        sum.wrapping_add(i32::from(q) * i32::from(a))
    })
}

/// Q15's unit u = 2⁻¹⁵: the activation a stands for a·u.
pub const Q15_UNIT: f32 = 1.0 / Q15_ONE;

#[cfg(test)]
mod tests {
    use super::*;

    /// A layer with levels from a formula, every row scale 1/64.
    fn layer<const IN: usize, const OUT: usize>() -> ([[i8; IN]; OUT], Int8Layer<IN, OUT>) {
        let levels: [[i8; IN]; OUT] = core::array::from_fn(|i| {
            core::array::from_fn(|j| (((i * 37 + j * 91) % 255) as i32 - 127) as i8)
        });
        (
            levels,
            Int8Layer::from_levels(levels, [1.0 / 64.0; OUT], [0.0; OUT]),
        )
    }

    fn check_sums<const IN: usize, const OUT: usize>() {
        let (levels, layer) = layer::<IN, OUT>();
        let activations: [i16; IN] =
            core::array::from_fn(|j| ((j as i32 * 7919) % 65_535 - 32_767) as i16);
        let sums = layer.sums(&activations);
        for (i, row) in levels.iter().enumerate() {
            let expected: i64 = row
                .iter()
                .zip(&activations)
                .map(|(&q, &a)| i64::from(q.max(-127)) * i64::from(a))
                .sum();
            assert_eq!(i64::from(sums[i]), expected, "row {i} of {IN}x{OUT}");
            for (j, &q) in row.iter().enumerate() {
                assert_eq!(layer.level(i, j), Some(q.max(-127)));
            }
        }
        assert_eq!(layer.level(OUT, 0), None);
        assert_eq!(layer.level(0, IN), None);
    }

    #[test]
    fn sums_are_the_exact_integer_dot_products_at_every_shape() {
        // Whole groups and blocks, remainders of inputs and of rows, and both.
        check_sums::<32, 32>();
        check_sums::<16, 16>();
        check_sums::<13, 7>();
        check_sums::<3, 5>();
        check_sums::<1, 1>();
        check_sums::<6, 9>();
    }

    #[test]
    fn folded_gains_and_offsets_give_the_formula_bit_for_bit() {
        use crate::residual::qtanh::quantised_tanh;
        // Scales from 1e-30 to 1e30, biases of both signs down to subnormal, sums
        // across the i32 range: s·(σ·u·P) + b·P lands on the same activation as
        // qtanh(s·(σ·u) + b).
        let mut checked = 0;
        for e in -60..=60 {
            let scale = 1.7_f32 * 10_f32.powf(e as f32 * 0.5);
            for bias in [0.0_f32, -0.0, 1e-40, -3.5e-3, 0.75, -2.5, 7.9, 1e20] {
                let gain = gains(&[scale])[0];
                let offset = offsets(&[bias])[0];
                for k in -40..=40 {
                    let sum = k * 53_687_091;
                    let want = quantised_tanh(sum as f32 * (scale * Q15_UNIT) + bias);
                    let got = quantised_tanh_scaled(sum as f32 * gain + offset);
                    assert_eq!(got, want, "σ {scale:e}, b {bias:e}, s {sum}");
                    checked += 1;
                }
            }
        }
        assert_eq!(checked, 121 * 8 * 81);
    }

    #[test]
    fn forward_is_the_quantised_tanh_of_the_scaled_sums() {
        use crate::residual::qtanh::quantised_tanh;
        let (levels, layer) = layer::<6, 5>();
        let bias = [0.5, -0.25, 0.0, 1.0, -1.0];
        let layer = Int8Layer::from_levels(levels, *layer.scales(), bias);
        let activations = [32_767, -32_767, 0, 16_384, -1, 7];
        let sums = layer.sums(&activations);
        let out = layer.forward(&activations);
        for i in 0..5 {
            let z = sums[i] as f32 * (layer.scales[i] * Q15_UNIT) + bias[i];
            assert_eq!(out[i], quantised_tanh(z), "output {i}");
            let value = f64::from(out[i]) / f64::from(Q15_ONE);
            assert!((value - f64::from(z).tanh()).abs() < 1.3e-4, "output {i}");
        }
    }

    #[test]
    fn a_blob_layer_reads_back_with_its_levels_scales_and_bias() {
        let mut bytes = std::vec::Vec::new();
        let rows: [[i8; 5]; 2] = [[1, -2, 3, -4, 5], [-127, 127, 0, 9, -9]];
        for row in rows {
            bytes.extend(row.map(|q| q as u8));
        }
        for x in [0.5_f32, 0.25, 1.0, -2.0] {
            bytes.extend(x.to_le_bytes());
        }
        bytes.push(7);
        let mut layer = Int8Layer::<5, 2>::zeroed();
        assert_eq!(layer.read(&bytes), Ok(bytes.len() - 1));
        assert_eq!(
            layer,
            Int8Layer::from_levels(rows, [0.5, 0.25], [1.0, -2.0])
        );
        let mut bad = bytes.clone();
        bad[3] = 0x80;
        assert_eq!(layer.read(&bad), Err(BlobError::Malformed));
        assert_eq!(layer.read(&bytes[..12]), Err(BlobError::Malformed));
        bytes[10..14].copy_from_slice(&f32::NAN.to_le_bytes());
        assert_eq!(layer.read(&bytes), Err(BlobError::NonFiniteWeight));
    }

    extern crate std;
}
