//! One fully connected `f32` layer, z = W·x + b, and the two weight formats of a
//! network's hidden → hidden layers ([`WeightFormat`]: `f32` here, int8 in
//! [`super::int8`]).
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

use super::int8::{Int8Layer, Q15Value};
use super::qtanh::quantised_tanh;
use super::{Activation, BlobError, Quantisation};
use core::fmt::Debug;

mod sealed {
    pub trait Sealed {}
    impl Sealed for super::F32Weights {}
    impl Sealed for super::Int8Weights {}
}

/// How a network stores and runs its hidden → hidden layers; implemented by
/// [`F32Weights`] and [`Int8Weights`] only (the blob format knows exactly these two).
///
/// The input layer and the linear output layer are `f32` [`Layer`]s in both (see
/// [`super::mlp`]). The formats differ in the width × width layers between, the bulk
/// of a network: `f32` weights and `f32` activations ([`Layer`]), or int8 levels with
/// a scale per row run in integers on 16-bit activations ([`Int8Layer`]: on a
/// Cortex-M4 two multiply-accumulates per `smlad` instruction, a quarter of the
/// flash).
pub trait WeightFormat: Copy + Debug + PartialEq + sealed::Sealed {
    /// The blob tag of this format.
    const KIND: Quantisation;

    /// A WIDTH → WIDTH hidden layer in this format.
    type Square<const WIDTH: usize>: Copy + Debug + PartialEq;

    /// A square layer whose weights and biases are all zero.
    fn zeroed_square<const WIDTH: usize>() -> Self::Square<WIDTH>;

    /// Reads a square layer from the front of a blob's layer bytes; the bytes read.
    fn read_square<const WIDTH: usize>(
        layer: &mut Self::Square<WIDTH>,
        bytes: &[u8],
    ) -> Result<usize, BlobError>;

    /// The last hidden layer's activations (`f32`) for the normalised inputs `x`:
    /// `input`, then every layer of `layers`, each followed by `activation`.
    fn hidden_pass<const IN: usize, const WIDTH: usize>(
        activation: Activation,
        input: &Layer<IN, WIDTH>,
        layers: &[Self::Square<WIDTH>],
        x: &[f32; IN],
    ) -> [f32; WIDTH];
}

/// Full-precision weights: every weight an `f32`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct F32Weights;

/// Symmetric int8 weights: w = q·σ_row with q ∈ [−127, 127] and one `f32` scale σ per
/// output row, run as integers ([`Int8Layer`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Int8Weights;

impl WeightFormat for F32Weights {
    const KIND: Quantisation = Quantisation::F32;
    type Square<const WIDTH: usize> = Layer<WIDTH, WIDTH>;

    fn zeroed_square<const WIDTH: usize>() -> Layer<WIDTH, WIDTH> {
        Layer::zeroed()
    }

    fn read_square<const WIDTH: usize>(
        layer: &mut Layer<WIDTH, WIDTH>,
        bytes: &[u8],
    ) -> Result<usize, BlobError> {
        layer.read(bytes)
    }

    #[inline]
    fn hidden_pass<const IN: usize, const WIDTH: usize>(
        activation: Activation,
        input: &Layer<IN, WIDTH>,
        layers: &[Layer<WIDTH, WIDTH>],
        x: &[f32; IN],
    ) -> [f32; WIDTH] {
        // tanh, the activation hcm trains, with its sixteen activations inlined into
        // the kernel (branch-free); the others through one out-of-line pass, so that
        // their kernels take no flash (a copy with sixteen ReLUs inlined was 600 B of
        // the ball's firmware image, another with the quantised tanh 1.5 kB).
        match activation {
            Activation::Tanh => f32_pass(input, layers, x, tanh_f32),
            Activation::Relu | Activation::QuantisedTanh => {
                plain_f32_pass(activation, input, layers, x)
            }
        }
    }
}

impl WeightFormat for Int8Weights {
    const KIND: Quantisation = Quantisation::Int8;
    type Square<const WIDTH: usize> = Int8Layer<WIDTH, WIDTH>;

    fn zeroed_square<const WIDTH: usize>() -> Int8Layer<WIDTH, WIDTH> {
        Int8Layer::zeroed()
    }

    fn read_square<const WIDTH: usize>(
        layer: &mut Int8Layer<WIDTH, WIDTH>,
        bytes: &[u8],
    ) -> Result<usize, BlobError> {
        layer.read(bytes)
    }

    /// The input layer in `f32`, its activations through the quantised tanh (Q15),
    /// the int8 layers in integers, the last activations back to `f32` (exactly: the
    /// unit 2⁻¹⁵ is a power of two). An int8 network runs the quantised tanh whatever
    /// its `activation` says: the decoder refuses an int8 blob of another activation,
    /// and hcm trains int8 twins with it (see [`Int8Layer`]).
    #[inline(never)]
    fn hidden_pass<const IN: usize, const WIDTH: usize>(
        _activation: Activation,
        input: &Layer<IN, WIDTH>,
        layers: &[Int8Layer<WIDTH, WIDTH>],
        x: &[f32; IN],
    ) -> [f32; WIDTH] {
        // One array returned on every path, first the input layer's sums, then the
        // last layer's values: built in the caller's slot, not copied there.
        let mut hidden = input.forward(x);
        // From a reference, not `hidden.map(…)`: that took `hidden` by value, a
        // 128-byte copy for the peg (and zeroing `a` first cost the ball 29
        // instructions).
        let mut a: [i16; WIDTH] = core::array::from_fn(|i| quantised_tanh(hidden[i]));
        let Some((last, first)) = layers.split_last() else {
            for (value, &a) in hidden.iter_mut().zip(&a) {
                *value = <f32 as Q15Value>::from_q15(a);
            }
            return hidden;
        };
        // Between the first and the last int8 layer, two buffers, their roles swapped
        // by reference after each layer (the second only made when there is such a
        // layer).
        let mut b;
        let from: &[i16; WIDTH] = if first.is_empty() {
            &a
        } else {
            b = a;
            let (mut from, mut to) = (&mut a, &mut b);
            for layer in first {
                layer.forward_into(from, to);
                core::mem::swap(&mut from, &mut to);
            }
            from
        };
        // The last layer writes its `f32` values straight into `hidden` (no pass
        // converting them after, no buffer of its own).
        last.forward_into(from, &mut hidden);
        hidden
    }
}

/// An `f32` network's pass with the activation applied after each layer's sums are
/// stored (see [`F32Weights::hidden_pass`]).
#[inline(never)]
fn plain_f32_pass<const IN: usize, const WIDTH: usize>(
    activation: Activation,
    input: &Layer<IN, WIDTH>,
    layers: &[Layer<WIDTH, WIDTH>],
    x: &[f32; IN],
) -> [f32; WIDTH] {
    let mut hidden = input.forward(x);
    for layer in layers {
        hidden.iter_mut().for_each(|z| *z = activation.apply(*z));
        hidden = layer.forward(&hidden);
    }
    hidden.iter_mut().for_each(|z| *z = activation.apply(*z));
    hidden
}

/// `input` then every layer of `layers`, each followed by `activation`, in `f32`.
#[inline]
fn f32_pass<const IN: usize, const WIDTH: usize>(
    input: &Layer<IN, WIDTH>,
    layers: &[Layer<WIDTH, WIDTH>],
    x: &[f32; IN],
    activation: impl Fn(f32) -> f32 + Copy,
) -> [f32; WIDTH] {
    // Two arrays taking turns, each layer's result built in place: reassigning one
    // array from a layer that reads it went through a temporary and a 128-byte copy per
    // layer for the peg's 32-wide network.
    let mut a = input.forward_activated(x, activation);
    let mut layers = layers.iter();
    loop {
        let Some(layer) = layers.next() else {
            return a;
        };
        let b = layer.forward_activated(&a, activation);
        let Some(layer) = layers.next() else {
            return b;
        };
        a = layer.forward_activated(&b, activation);
    }
}

/// tanh of one `f32` pre-activation; a function item, so every network and layer
/// shares the same instance of [`Layer::forward_activated`]. `#[inline]`: without it,
/// another crate (the host's simulator, a benchmark) calls it once per neuron.
#[inline]
fn tanh_f32(z: f32) -> f32 {
    Activation::Tanh.apply(z)
}

/// One fully connected layer with `IN` inputs and `OUT` outputs and `f32` weights:
/// z = W·x + b.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layer<const IN: usize, const OUT: usize> {
    /// Weights column by column, `[in][out]`: `weights[j][i]` multiplies input j into
    /// output i (dimensionless: the layer works on normalised values).
    pub weights: [[f32; OUT]; IN],
    /// Bias, one per output.
    pub bias: [f32; OUT],
}

impl<const IN: usize, const OUT: usize> Layer<IN, OUT> {
    /// A layer whose weights and biases are all zero.
    pub const fn zeroed() -> Self {
        Layer {
            weights: [[0.0; OUT]; IN],
            bias: [0.0; OUT],
        }
    }

    /// The layer with weights given row by row, `rows[i][j]` multiplying input j
    /// into output i (the usual matrix W).
    pub fn from_rows(rows: [[f32; IN]; OUT], bias: [f32; OUT]) -> Self {
        Layer {
            weights: core::array::from_fn(|j| core::array::from_fn(|i| rows[i][j])),
            bias,
        }
    }

    /// Reads the layer from the front of a blob's layer bytes — weights row-major
    /// (`[out][in]`, little-endian `f32`, finite), then the bias — and returns the
    /// bytes read; the weights are transposed into columns here.
    pub(crate) fn read(&mut self, bytes: &[u8]) -> Result<usize, BlobError> {
        let count = IN.checked_mul(OUT).and_then(|n| n.checked_add(OUT));
        let used = count
            .and_then(|n| n.checked_mul(4))
            .ok_or(BlobError::Malformed)?;
        let mut values = bytes
            .get(..used)
            .ok_or(BlobError::Malformed)?
            .chunks_exact(4)
            .map(|word| match *word {
                [a, b, c, d] => Some(f32::from_le_bytes([a, b, c, d])).filter(|v| v.is_finite()),
                _ => None,
            });
        for output in 0..OUT {
            for column in &mut self.weights {
                let value = values.next().flatten().ok_or(BlobError::NonFiniteWeight)?;
                if let Some(weight) = column.get_mut(output) {
                    *weight = value;
                }
            }
        }
        for bias in &mut self.bias {
            *bias = values.next().flatten().ok_or(BlobError::NonFiniteWeight)?;
        }
        Ok(used)
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

/// The outputs after the last whole [`BLOCK`] (fewer than 16: OUT mod 16 of them) in
/// one pass over the columns: lanes of 8, 4, 2 and 1 outputs, each taken or not by
/// the bits of OUT mod 16 (constants: the untaken lanes compile to nothing). Each
/// output still sums its inputs in order from its bias, so the bits are those of any
/// other pass. One pass instead of one per lane: the peg's 32 → 6 output layer went
/// from two passes over its 32 columns (4 outputs, then 2) to one: the peg's residual
/// 6,661 → 6,434 instructions in `f32`, 6,741 → 6,514 in int8, on the Cortex-M4F. Four
/// columns per turn of the loop: with few outputs, the loop's own counting was most of
/// a column's cost (the ball's residual 1,627 → 1,567 instructions in `f32`, 1,896 →
/// 1,836 in int8; the peg's 6,434 → 6,375 in `f32`).
#[inline(always)]
fn remainder<const OUT: usize>(
    weights: &[[f32; OUT]],
    bias: &[f32; OUT],
    x: &[f32],
    z: &mut [f32; OUT],
    activation: impl Fn(f32) -> f32,
) {
    let mut lanes = Lanes::new(bias);
    let (columns, last_columns) = weights.as_chunks::<4>();
    let (inputs, last_inputs) = x.as_chunks::<4>();
    for ([c0, c1, c2, c3], &[x0, x1, x2, x3]) in columns.iter().zip(inputs) {
        lanes.add(c0, x0);
        lanes.add(c1, x1);
        lanes.add(c2, x2);
        lanes.add(c3, x3);
    }
    for (column, &x) in last_columns.iter().zip(last_inputs) {
        lanes.add(column, x);
    }
    lanes.write(z, activation);
}

/// The sums of [`remainder`]'s lanes: 8, 4, 2 and 1 outputs from `O8`, `O4`, `O2`
/// and `O1`, each used or not by the bits of OUT mod 16. Written out lane by lane: at
/// the firmware's `opt-level = "s"` loops over the lanes stayed loops (4,536
/// instructions for the ball's residual against 1,627).
struct Lanes<const OUT: usize> {
    c: [f32; 8],
    d: [f32; 4],
    e: [f32; 2],
    f: f32,
}

impl<const OUT: usize> Lanes<OUT> {
    const REST: usize = OUT % BLOCK;
    const O8: usize = OUT - Self::REST;
    const O4: usize = Self::O8 + (Self::REST & 8);
    const O2: usize = Self::O4 + (Self::REST & 4);
    const O1: usize = Self::O2 + (Self::REST & 2);

    /// Each used lane starting from its outputs' biases.
    #[inline(always)]
    fn new(bias: &[f32; OUT]) -> Self {
        let rest = Self::REST;
        Lanes {
            c: match bias.get(Self::O8..Self::O8 + 8) {
                Some(&[b0, b1, b2, b3, b4, b5, b6, b7]) if rest & 8 != 0 => {
                    [b0, b1, b2, b3, b4, b5, b6, b7]
                }
                _ => [0.0; 8],
            },
            d: match bias.get(Self::O4..Self::O4 + 4) {
                Some(&[b0, b1, b2, b3]) if rest & 4 != 0 => [b0, b1, b2, b3],
                _ => [0.0; 4],
            },
            e: match bias.get(Self::O2..Self::O2 + 2) {
                Some(&[b0, b1]) if rest & 2 != 0 => [b0, b1],
                _ => [0.0; 2],
            },
            f: bias.get(Self::O1).copied().unwrap_or(0.0),
        }
    }

    /// Adds column `column` times its input `x` to every used lane.
    #[inline(always)]
    fn add(&mut self, column: &[f32; OUT], x: f32) {
        let rest = Self::REST;
        if let (Some(&[w0, w1, w2, w3, w4, w5, w6, w7]), true) =
            (column.get(Self::O8..Self::O8 + 8), rest & 8 != 0)
        {
            let [c0, c1, c2, c3, c4, c5, c6, c7] = self.c;
            self.c = [
                c0 + w0 * x,
                c1 + w1 * x,
                c2 + w2 * x,
                c3 + w3 * x,
                c4 + w4 * x,
                c5 + w5 * x,
                c6 + w6 * x,
                c7 + w7 * x,
            ];
        }
        if let (Some(&[w0, w1, w2, w3]), true) = (column.get(Self::O4..Self::O4 + 4), rest & 4 != 0)
        {
            let [d0, d1, d2, d3] = self.d;
            self.d = [d0 + w0 * x, d1 + w1 * x, d2 + w2 * x, d3 + w3 * x];
        }
        if let (Some(&[w0, w1]), true) = (column.get(Self::O2..Self::O2 + 2), rest & 2 != 0) {
            let [e0, e1] = self.e;
            self.e = [e0 + w0 * x, e1 + w1 * x];
        }
        if let (Some(&w0), true) = (column.get(Self::O1), rest & 1 != 0) {
            self.f += w0 * x;
        }
    }

    /// The used lanes' activations into their outputs of `z`.
    #[inline(always)]
    fn write(self, z: &mut [f32; OUT], activation: impl Fn(f32) -> f32) {
        let rest = Self::REST;
        if let (Some(out), true) = (z.get_mut(Self::O8..Self::O8 + 8), rest & 8 != 0) {
            out.copy_from_slice(&self.c.map(&activation));
        }
        if let (Some(out), true) = (z.get_mut(Self::O4..Self::O4 + 4), rest & 4 != 0) {
            out.copy_from_slice(&self.d.map(&activation));
        }
        if let (Some(out), true) = (z.get_mut(Self::O2..Self::O2 + 2), rest & 2 != 0) {
            out.copy_from_slice(&self.e.map(&activation));
        }
        if let (Some(out), true) = (z.get_mut(Self::O1), rest & 1 != 0) {
            *out = activation(self.f);
        }
    }
}

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
    // Every element is overwritten. Zeros, not a copy of the bias: for the peg's 32
    // outputs a `memset` costs less than a `memcpy` (its residual 6,236 → 6,094
    // instructions in f32, 6,418 → 6,347 in int8, on the Cortex-M4F); the ball's 16
    // cost the same either way.
    let mut z = [0.0; OUT];
    let mut first = 0;
    while let (Some(block), Some(&start)) = (
        z.get_mut(first..first + BLOCK),
        bias.get(first..).and_then(<[f32]>::first_chunk::<BLOCK>),
    ) {
        // The block's sixteen sums start from their biases and take the inputs in
        // order (`hcm_dsp::block_sums`: on the Cortex-M4F a loop of `vldm` and
        // `vmla.f32` written out, 22 instructions per 16 multiply-adds against the
        // compiler's 37; elsewhere plain Rust): the same bits on every target.
        let mut sums = start;
        hcm_dsp::block_sums(&mut sums, weights, first, x);
        activate_block(block, sums, &activation);
        first += BLOCK;
    }
    // Then four at a time (a 6-output wrench layer: 4 + 2), then two, then one: the
    // remainder kept in named registers too (one by one, the peg's 32-6
    // output layer took 8 instructions per multiply-add on the Cortex-M4F). Each sum
    // still starts from its bias and adds its inputs in order: the same bits.
    remainder(weights, bias, x, &mut z, activation);
    z
}

#[cfg(test)]
mod tests {
    use super::*;

    /// z_i = b_i + Σ_j w_ij·x_j summed in order j = 0, 1, …, one output at a time.
    fn in_order<const IN: usize, const OUT: usize>(
        layer: &Layer<IN, OUT>,
        x: &[f32; IN],
    ) -> [f32; OUT] {
        core::array::from_fn(|i| {
            let mut sum = layer.bias[i];
            for (column, &x) in layer.weights.iter().zip(x) {
                sum += column[i] * x;
            }
            sum
        })
    }

    fn check<const IN: usize, const OUT: usize>() {
        // Values whose sums round differently in another order.
        let value = |k: usize| ((k * 7919 % 1000) as f32 - 500.0) * 1.37e-3 + 1e-7 * k as f32;
        let layer = Layer::<IN, OUT> {
            weights: core::array::from_fn(|j| core::array::from_fn(|i| value(i * 31 + j))),
            bias: core::array::from_fn(|i| value(i + 1000) * 1e3),
        };
        let x: [f32; IN] = core::array::from_fn(|j| value(j + 77) * 1e2);
        let got = layer.forward(&x);
        let expected = in_order(&layer, &x);
        for i in 0..OUT {
            assert_eq!(
                got[i].to_bits(),
                expected[i].to_bits(),
                "output {i} of {IN}x{OUT}"
            );
        }
        let activated = layer.forward_activated(&x, |z| z * 0.5 - 1.0);
        for i in 0..OUT {
            assert_eq!(
                activated[i],
                expected[i] * 0.5 - 1.0,
                "activated {i} of {IN}x{OUT}"
            );
        }
    }

    #[test]
    fn every_output_width_sums_each_output_in_input_order() {
        // Whole blocks of 16, and every remainder lane: 8, 4, 2, 1 and their sums.
        check::<13, 6>();
        check::<32, 6>();
        check::<3, 16>();
        check::<16, 1>();
        check::<5, 15>();
        check::<7, 31>();
        check::<4, 9>();
        check::<2, 3>();
        check::<1, 0>();
    }
}
