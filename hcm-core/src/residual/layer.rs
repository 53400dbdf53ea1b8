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

mod sealed {
    pub trait Sealed {}
    impl Sealed for super::F32Weights {}
    impl Sealed for super::Int8Weights {}
}

/// How one layer stores its weights; implemented by [`F32Weights`] and
/// [`Int8Weights`] only (the blob format knows exactly these two).
pub trait WeightFormat: Copy + Debug + PartialEq + sealed::Sealed {
    /// One stored weight.
    type Weight: Copy + Debug + PartialEq;
    /// One stored per-output-row scale (`()` when there is none).
    type RowScale: Copy + Debug + PartialEq;
    /// The blob tag of this format.
    const KIND: Quantisation;
    /// A zero weight.
    const ZERO: Self::Weight;
    /// The row scale that leaves a row unchanged.
    const UNIT: Self::RowScale;
    /// Bytes one weight takes in a blob.
    const WEIGHT_BYTES: usize;
    /// Whether a blob carries one `f32` scale per output row of each layer.
    const HAS_ROW_SCALE: bool;

    /// The value an output's accumulator starts from: its bias where the sum needs no
    /// scaling (f32), else 0.
    fn start(bias: f32) -> f32;

    /// The pre-activation z of an output from its accumulated sum (started at
    /// [`WeightFormat::start`]), its bias and its row scale.
    fn finish(sum: f32, bias: f32, scale: Self::RowScale) -> f32;

    /// One weight as the `f32` that [`Layer::forward`] multiplies.
    fn widen(weight: Self::Weight) -> f32;

    /// The weight stored little-endian in `raw` (`WEIGHT_BYTES` long).
    fn weight_from_le(raw: &[u8]) -> Result<Self::Weight, BlobError>;

    /// The row scale read from a blob (ignored by formats without one).
    fn row_scale(scale: f32) -> Result<Self::RowScale, BlobError>;
}

/// Full-precision weights: every weight an `f32`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct F32Weights;

/// Symmetric int8 weights: w ≈ q·scale_row with q ∈ [−127, 127] and one `f32` scale
/// per output row; products are accumulated in `f32` and scaled once per row.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Int8Weights;

impl WeightFormat for F32Weights {
    type Weight = f32;
    type RowScale = ();
    const KIND: Quantisation = Quantisation::F32;
    const ZERO: f32 = 0.0;
    const UNIT: () = ();
    const WEIGHT_BYTES: usize = 4;
    const HAS_ROW_SCALE: bool = false;

    #[inline(always)]
    fn widen(weight: f32) -> f32 {
        weight
    }

    #[inline(always)]
    fn start(bias: f32) -> f32 {
        bias
    }

    #[inline(always)]
    fn finish(sum: f32, _bias: f32, _scale: ()) -> f32 {
        sum
    }

    fn weight_from_le(raw: &[u8]) -> Result<f32, BlobError> {
        let bytes: [u8; 4] = raw.try_into().map_err(|_| BlobError::Malformed)?;
        finite(f32::from_le_bytes(bytes))
    }

    fn row_scale(_scale: f32) -> Result<(), BlobError> {
        Ok(())
    }
}

impl WeightFormat for Int8Weights {
    type Weight = i8;
    type RowScale = f32;
    const KIND: Quantisation = Quantisation::Int8;
    const ZERO: i8 = 0;
    const UNIT: f32 = 1.0;
    const WEIGHT_BYTES: usize = 1;
    const HAS_ROW_SCALE: bool = true;

    #[inline(always)]
    fn start(_bias: f32) -> f32 {
        0.0
    }

    #[inline(always)]
    fn finish(sum: f32, bias: f32, scale: f32) -> f32 {
        bias + sum * scale
    }

    #[inline(always)]
    fn widen(weight: i8) -> f32 {
        f32::from(weight)
    }

    fn weight_from_le(raw: &[u8]) -> Result<i8, BlobError> {
        match raw {
            // −128 has no positive twin: the symmetric range is [−127, 127].
            [byte] if *byte != 0x80 => Ok(i8::from_le_bytes([*byte])),
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

/// One fully connected layer with `IN` inputs and `OUT` outputs: z = W·x + b.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layer<const IN: usize, const OUT: usize, Q: WeightFormat = F32Weights> {
    /// Weights column by column, `[in][out]`: `weights[j][i]` multiplies input j into
    /// output i (dimensionless: the layer works on normalised values).
    pub weights: [[Q::Weight; OUT]; IN],
    /// One scale per output row (int8 only; `()` for f32).
    pub row_scales: [Q::RowScale; OUT],
    /// Bias, one per output.
    pub bias: [f32; OUT],
}

impl<const IN: usize, const OUT: usize, Q: WeightFormat> Layer<IN, OUT, Q> {
    /// A layer whose weights and biases are all zero.
    pub const fn zeroed() -> Self {
        Layer {
            weights: [[Q::ZERO; OUT]; IN],
            row_scales: [Q::UNIT; OUT],
            bias: [0.0; OUT],
        }
    }

    /// The layer with weights given row by row, `rows[i][j]` multiplying input j
    /// into output i (the usual matrix W).
    pub fn from_rows(
        rows: [[Q::Weight; IN]; OUT],
        row_scales: [Q::RowScale; OUT],
        bias: [f32; OUT],
    ) -> Self {
        Layer {
            weights: core::array::from_fn(|j| core::array::from_fn(|i| rows[i][j])),
            row_scales,
            bias,
        }
    }

    /// Row i of W: the weights of output i, one per input.
    pub fn row(&self, output: usize) -> Option<[Q::Weight; IN]> {
        (output < OUT).then(|| self.weights.map(|column| column[output]))
    }

    /// z = W·x + b, before any activation.
    ///
    /// Outputs are summed eight at a time in eight named accumulators, over every
    /// input, then stored: written out so, the eight sums stay in registers even where
    /// the compiler does not unroll loops (`opt-level = "s"`, the firmware's), and one
    /// multiply-add costs a load and a `vmla` on a Cortex-M4F instead of a load, a
    /// load, a `vmla` and a store. With f32 weights each sum starts from its bias (no
    /// separate pass to add it: 16 × 9 instructions less per layer on the Cortex-M4F);
    /// int8 sums start from 0 and are scaled before the bias is added. Outputs beyond a
    /// multiple of eight (the remainder) are summed in the same order, so every output
    /// gets the same bits whichever path computes it.
    #[inline]
    pub fn forward(&self, x: &[f32; IN]) -> [f32; OUT] {
        let mut z = [0.0; OUT];
        let mut first = 0;
        while let (
            Some(block),
            Some(&[b0, b1, b2, b3, b4, b5, b6, b7]),
            Some(&[s0, s1, s2, s3, s4, s5, s6, s7]),
        ) = (
            z.get_mut(first..first + 8),
            self.bias.get(first..first + 8),
            self.row_scales.get(first..first + 8),
        ) {
            let (mut a0, mut a1, mut a2, mut a3) =
                (Q::start(b0), Q::start(b1), Q::start(b2), Q::start(b3));
            let (mut a4, mut a5, mut a6, mut a7) =
                (Q::start(b4), Q::start(b5), Q::start(b6), Q::start(b7));
            for (column, &x) in self.weights.iter().zip(x) {
                if let Some(&[w0, w1, w2, w3, w4, w5, w6, w7]) = column.get(first..first + 8) {
                    a0 += Q::widen(w0) * x;
                    a1 += Q::widen(w1) * x;
                    a2 += Q::widen(w2) * x;
                    a3 += Q::widen(w3) * x;
                    a4 += Q::widen(w4) * x;
                    a5 += Q::widen(w5) * x;
                    a6 += Q::widen(w6) * x;
                    a7 += Q::widen(w7) * x;
                }
            }
            block.copy_from_slice(&[
                Q::finish(a0, b0, s0),
                Q::finish(a1, b1, s1),
                Q::finish(a2, b2, s2),
                Q::finish(a3, b3, s3),
                Q::finish(a4, b4, s4),
                Q::finish(a5, b5, s5),
                Q::finish(a6, b6, s6),
                Q::finish(a7, b7, s7),
            ]);
            first += 8;
        }
        let remainder = z.iter_mut().zip(self.bias.iter().zip(&self.row_scales));
        for (output, (z, (&bias, &scale))) in remainder.enumerate().skip(first) {
            let mut sum = Q::start(bias);
            for (column, &x) in self.weights.iter().zip(x) {
                if let Some(&w) = column.get(output) {
                    sum += Q::widen(w) * x;
                }
            }
            *z = Q::finish(sum, bias, scale);
        }
        z
    }
}
