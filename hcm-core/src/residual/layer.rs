//! One fully connected layer, z = W·x + b, and the two ways its weights are stored.
//!
//! The weights are held **column by column** (`weights[j][i]` multiplies input j into
//! output i): z is built as b + Σ_j x_j·W[:, j], so the inner loop is one contiguous
//! multiply-add over all OUT outputs, which the compiler runs in SIMD registers (four
//! `f32` per SSE register on x86_64), with one independent accumulator per output.
//! Each output still sums its inputs in order j = 0, 1, …, exactly as a row-by-row
//! dot product does: the layout changes the speed, not a single bit of the result, and
//! the result is the same on every target.
//!
//! The blob stores the weights row-major `[out][in]` (what the host trains); the
//! decoder transposes them once ([`Layer::from_rows`] does the same for a layer built
//! by hand).

use super::{BlobError, Quantisation};
use core::fmt::Debug;
use core::marker::PhantomData;

mod sealed {
    pub trait Sealed {}
    impl Sealed for super::F32Weights {}
    impl Sealed for super::Int8Weights {}
}

/// How a blob stores one layer's weights; implemented by [`F32Weights`] and
/// [`Int8Weights`] only (the blob format knows exactly these two).
///
/// Decoded, every layer holds `f32` weights and runs the same kernel: an int8 layer's
/// weight is its level times its row's scale, q·s, rounded to `f32` once at decoding.
/// int8 is a storage format — a quarter of the blob and of the flash that embeds it —
/// not an arithmetic: on the two targets hcm runs on, integer arithmetic is slower than
/// the `f32` kernel, not faster. On the Cortex-M4F an int8 product computed at run time
/// costs a load, a move to the FPU and a conversion before the same `vmla`
/// (4 instructions for the f32 kernel's 2; integer multiply-adds need the activations
/// quantised and the sums converted back, and the dual 16-bit `smlad` is out of reach
/// of stable Rust without `unsafe`); the x86-64 baseline (SSE2) has no int8 dot
/// product. Folded, an int8 network costs exactly what an f32 one does, and is never
/// slower (README, "The controller").
pub trait WeightFormat: Copy + Debug + PartialEq + sealed::Sealed {
    /// The blob tag of this format.
    const KIND: Quantisation;
    /// Bytes one weight takes in a blob.
    const WEIGHT_BYTES: usize;
    /// Whether a blob carries one `f32` scale per output row of each layer.
    const HAS_ROW_SCALE: bool;

    /// The weight (f32) or level (int8, as an exact `f32`) stored little-endian in
    /// `raw` (`WEIGHT_BYTES` long).
    fn weight_from_le(raw: &[u8]) -> Result<f32, BlobError>;

    /// A row scale read from a blob, checked (formats without one never read it).
    fn row_scale(scale: f32) -> Result<f32, BlobError>;
}

/// Full-precision weights: every weight an `f32`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct F32Weights;

/// Symmetric int8 weights: w = q·s_row with q ∈ [−127, 127] and one `f32` scale per
/// output row, folded into `f32` weights when decoded (see [`WeightFormat`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Int8Weights;

impl WeightFormat for F32Weights {
    const KIND: Quantisation = Quantisation::F32;
    const WEIGHT_BYTES: usize = 4;
    const HAS_ROW_SCALE: bool = false;

    fn weight_from_le(raw: &[u8]) -> Result<f32, BlobError> {
        let bytes: [u8; 4] = raw.try_into().map_err(|_| BlobError::Malformed)?;
        finite(f32::from_le_bytes(bytes))
    }

    fn row_scale(scale: f32) -> Result<f32, BlobError> {
        Ok(scale)
    }
}

impl WeightFormat for Int8Weights {
    const KIND: Quantisation = Quantisation::Int8;
    const WEIGHT_BYTES: usize = 1;
    const HAS_ROW_SCALE: bool = true;

    fn weight_from_le(raw: &[u8]) -> Result<f32, BlobError> {
        match raw {
            // −128 has no positive twin: the symmetric range is [−127, 127].
            [byte] if *byte != 0x80 => Ok(f32::from(i8::from_le_bytes([*byte]))),
            _ => Err(BlobError::Malformed),
        }
    }

    fn row_scale(scale: f32) -> Result<f32, BlobError> {
        finite(scale)
    }
}

/// `value` if finite, else [`BlobError::NonFiniteWeight`].
fn finite(value: f32) -> Result<f32, BlobError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(BlobError::NonFiniteWeight)
    }
}

/// One fully connected layer with `IN` inputs and `OUT` outputs: z = W·x + b; `Q`
/// records how its blob stored the weights.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layer<const IN: usize, const OUT: usize, Q: WeightFormat = F32Weights> {
    /// Weights column by column, `[in][out]`: `weights[j][i]` multiplies input j into
    /// output i (dimensionless: the layer works on normalised values). For int8, q·s.
    pub weights: [[f32; OUT]; IN],
    /// Bias, one per output.
    pub bias: [f32; OUT],
    /// The storage format the weights came from.
    pub format: PhantomData<Q>,
}

impl<const IN: usize, const OUT: usize, Q: WeightFormat> Layer<IN, OUT, Q> {
    /// A layer whose weights and biases are all zero.
    pub const fn zeroed() -> Self {
        Layer {
            weights: [[0.0; OUT]; IN],
            bias: [0.0; OUT],
            format: PhantomData,
        }
    }

    /// The layer with weights given row by row, `rows[i][j]` multiplying input j
    /// into output i (the usual matrix W).
    pub fn from_rows(rows: [[f32; IN]; OUT], bias: [f32; OUT]) -> Self {
        Layer {
            weights: core::array::from_fn(|j| core::array::from_fn(|i| rows[i][j])),
            bias,
            format: PhantomData,
        }
    }

    /// Row i of W: the weights of output i, one per input.
    pub fn row(&self, output: usize) -> Option<[f32; IN]> {
        (output < OUT).then(|| self.weights.map(|column| column[output]))
    }

    /// z = W·x + b, before any activation.
    ///
    /// Outputs are summed sixteen at a time in sixteen named accumulators, over every
    /// input, then stored: written out so, the sums stay in registers even where the
    /// compiler does not unroll loops (`opt-level = "s"`, the firmware's), and one
    /// multiply-add costs a load and a `vmla` on a Cortex-M4F instead of a load, a
    /// load, a `vmla` and a store; sixteen rather than eight halve the loop's counting
    /// per multiply-add (the residual's widths, 16, 32 and 48, are multiples of it).
    /// Each sum starts from its bias (no separate pass to add it). Outputs beyond a
    /// multiple of sixteen (the remainder: a 6-output wrench layer) are summed one by
    /// one in the same order, so every output gets the same bits whichever path
    /// computes it.
    #[inline]
    pub fn forward(&self, x: &[f32; IN]) -> [f32; OUT] {
        self.forward_activated(x, |z| z)
    }

    /// a(W·x + b): [`Layer::forward`] with the activation `a` applied to each output
    /// while its sum is still in a register (on the Cortex-M4F a store, a load and a
    /// separate loop less per neuron).
    #[inline]
    pub fn forward_activated(&self, x: &[f32; IN], activation: impl Fn(f32) -> f32) -> [f32; OUT] {
        affine(&self.weights, &self.bias, x, activation)
    }
}

impl<const IN: usize, const OUT: usize> Layer<IN, OUT, Int8Weights> {
    /// The int8 layer with levels q given row by row (`levels[i][j]` for input j into
    /// output i) and one scale per output row (dimensionless): weights q·s in `f32`,
    /// exactly what decoding the blob gives.
    pub fn from_levels(levels: [[i8; IN]; OUT], scales: [f32; OUT], bias: [f32; OUT]) -> Self {
        let rows = core::array::from_fn(|i| levels[i].map(|q| f32::from(q) * scales[i]));
        Layer::from_rows(rows, bias)
    }
}

/// The activation of a block's sums, stored in `block` (same bits either way).
///
/// On a bare-metal controller (`target_os = "none"`: no SIMD, one FPU) each sum is
/// activated while still in a register — sixteen inlined activations, a store, a load
/// and a loop pass less per neuron (−140 instructions per 3-16-16-1 evaluation on the
/// Cortex-M4F). Elsewhere the sums are stored first and activated in one loop over
/// the block, which the compiler runs four or eight neurons at a time in SIMD
/// registers (inlined per sum, the x86-64 host evaluated them one by one: 2.4× slower).
#[inline(always)]
fn activate_block(block: &mut [f32], sums: [f32; BLOCK], activation: &impl Fn(f32) -> f32) {
    #[cfg(target_os = "none")]
    {
        // Written out: `sums.map(activation)` stays a loop at `opt-level = "s"`.
        let [a0, a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11, a12, a13, a14, a15] = sums;
        block.copy_from_slice(&[
            activation(a0),
            activation(a1),
            activation(a2),
            activation(a3),
            activation(a4),
            activation(a5),
            activation(a6),
            activation(a7),
            activation(a8),
            activation(a9),
            activation(a10),
            activation(a11),
            activation(a12),
            activation(a13),
            activation(a14),
            activation(a15),
        ]);
    }
    #[cfg(not(target_os = "none"))]
    {
        block.copy_from_slice(&sums);
        for value in block {
            *value = activation(*value);
        }
    }
}

/// Outputs summed together in registers (see [`Layer::forward`]).
const BLOCK: usize = 16;

/// a(W·x + b) for one layer, its weights column by column (see [`Layer::forward`]).
///
/// The input count is a slice length, not a const generic, and the storage format is
/// not a parameter: every layer with the same output count and activation — a 3-16
/// input layer, a 16-16 hidden layer, f32 or int8 — shares one copy of this code,
/// which keeps the sixteen activations inlined per block within the firmware's flash.
#[inline(never)]
fn affine<const OUT: usize, A: Fn(f32) -> f32>(
    weights: &[[f32; OUT]],
    bias: &[f32; OUT],
    x: &[f32],
    activation: A,
) -> [f32; OUT] {
    // Every element is overwritten; starting from a copy of the bias rather than zeros
    // spares a call to `memset` (40 instructions for 16 outputs on the Cortex-M4F).
    let mut z = *bias;
    let mut first = 0;
    while let (
        Some(block),
        Some(&[b0, b1, b2, b3, b4, b5, b6, b7, b8, b9, b10, b11, b12, b13, b14, b15]),
    ) = (
        z.get_mut(first..first + BLOCK),
        bias.get(first..first + BLOCK),
    ) {
        let (mut a0, mut a1, mut a2, mut a3) = (b0, b1, b2, b3);
        let (mut a4, mut a5, mut a6, mut a7) = (b4, b5, b6, b7);
        let (mut a8, mut a9, mut a10, mut a11) = (b8, b9, b10, b11);
        let (mut a12, mut a13, mut a14, mut a15) = (b12, b13, b14, b15);
        for (column, &x) in weights.iter().zip(x) {
            if let Some(&[w0, w1, w2, w3, w4, w5, w6, w7, w8, w9, w10, w11, w12, w13, w14, w15]) =
                column.get(first..first + BLOCK)
            {
                a0 += w0 * x;
                a1 += w1 * x;
                a2 += w2 * x;
                a3 += w3 * x;
                a4 += w4 * x;
                a5 += w5 * x;
                a6 += w6 * x;
                a7 += w7 * x;
                a8 += w8 * x;
                a9 += w9 * x;
                a10 += w10 * x;
                a11 += w11 * x;
                a12 += w12 * x;
                a13 += w13 * x;
                a14 += w14 * x;
                a15 += w15 * x;
            }
        }
        let sums = [
            a0, a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11, a12, a13, a14, a15,
        ];
        activate_block(block, sums, &activation);
        first += BLOCK;
    }
    // Then four at a time (a 6-output wrench layer: 4 + 2), then two, then one: the
    // remainder kept in named registers too (issue 31: one by one, the peg's 32-6
    // output layer took 8 instructions per multiply-add on the Cortex-M4F). Each sum
    // still starts from its bias and adds its inputs in order: the same bits.
    while let (Some(block), Some(&[b0, b1, b2, b3])) =
        (z.get_mut(first..first + 4), bias.get(first..first + 4))
    {
        let (mut a0, mut a1, mut a2, mut a3) = (b0, b1, b2, b3);
        for (column, &x) in weights.iter().zip(x) {
            if let Some(&[w0, w1, w2, w3]) = column.get(first..first + 4) {
                a0 += w0 * x;
                a1 += w1 * x;
                a2 += w2 * x;
                a3 += w3 * x;
            }
        }
        block.copy_from_slice(&[
            activation(a0),
            activation(a1),
            activation(a2),
            activation(a3),
        ]);
        first += 4;
    }
    while let (Some(block), Some(&[b0, b1])) =
        (z.get_mut(first..first + 2), bias.get(first..first + 2))
    {
        let (mut a0, mut a1) = (b0, b1);
        for (column, &x) in weights.iter().zip(x) {
            if let Some(&[w0, w1]) = column.get(first..first + 2) {
                a0 += w0 * x;
                a1 += w1 * x;
            }
        }
        block.copy_from_slice(&[activation(a0), activation(a1)]);
        first += 2;
    }
    // Indexed by a range below OUT, so every `get` is known to succeed (an
    // `enumerate().skip(first)` walked the first outputs again, one by one).
    for output in first..OUT {
        let (Some(z), Some(&bias)) = (z.get_mut(output), bias.get(output)) else {
            break;
        };
        let mut sum = bias;
        for (column, &x) in weights.iter().zip(x) {
            if let Some(&w) = column.get(output) {
                sum += w * x;
            }
        }
        *z = activation(sum);
    }
    z
}
