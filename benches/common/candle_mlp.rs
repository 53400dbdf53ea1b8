//! The core's residual network rebuilt in candle-core, for the benchmarks that compare
//! the two (`residual_evaluation`, `peg_hcm`): the same weights, normalisation and
//! envelope as CPU `f32` tensors, one input row per evaluation (matmul + bias, tanh on
//! the hidden layers). Shared by `#[path]`: a file directly in `benches/` would be a
//! benchmark of its own.

use candle_core::{Device, Tensor};
use hcm_core::residual::{Envelope, F32Weights, Hidden, HiddenDepth, Layer, Mlp};

/// A core network with `INPUTS` inputs and `OUTPUTS` outputs as candle tensors.
pub struct CandleMlp<const INPUTS: usize, const OUTPUTS: usize> {
    device: Device,
    input_mean: Tensor,
    input_scale: Tensor,
    /// (Wᵀ as (in, out), bias (out)), input → output.
    layers: Vec<(Tensor, Tensor)>,
    output_mean: Tensor,
    output_scale: Tensor,
    /// The core network's training envelope (raw input units).
    pub envelope: Envelope<INPUTS>,
}

impl<const INPUTS: usize, const OUTPUTS: usize> CandleMlp<INPUTS, OUTPUTS> {
    /// The tensors of the core's `f32` network `mlp` (a tanh network).
    pub fn from_core<const WIDTH: usize, const HIDDEN: usize>(
        mlp: &Mlp<INPUTS, WIDTH, OUTPUTS, HIDDEN, F32Weights>,
    ) -> candle_core::Result<Self>
    where
        Hidden<HIDDEN>: HiddenDepth<WIDTH, F32Weights, Layers: AsRef<[Layer<WIDTH, WIDTH>]>>,
    {
        let device = Device::Cpu;
        let vector = |values: &[f32]| Tensor::from_slice(values, values.len(), &device);
        let scaling = &mlp.normalisation;
        let mut layers = vec![layer(&mlp.input_layer, &device)?];
        for hidden in mlp.hidden_layers.as_ref() {
            layers.push(layer(hidden, &device)?);
        }
        layers.push(layer(&mlp.output_layer, &device)?);
        Ok(CandleMlp {
            input_mean: vector(&scaling.input_mean)?,
            input_scale: vector(&scaling.input_scale)?,
            layers,
            output_mean: vector(&scaling.output_mean)?,
            output_scale: vector(&scaling.output_scale)?,
            envelope: mlp.envelope,
            device,
        })
    }

    /// The network's outputs (raw units) for one raw input row.
    pub fn evaluate(&self, input: &[f32; INPUTS]) -> candle_core::Result<[f32; OUTPUTS]> {
        let x = Tensor::from_slice(input, (1, INPUTS), &self.device)?;
        let mut h = x
            .broadcast_sub(&self.input_mean)?
            .broadcast_div(&self.input_scale)?;
        let last = self.layers.len() - 1;
        for (index, (weights, bias)) in self.layers.iter().enumerate() {
            h = h.matmul(weights)?.broadcast_add(bias)?;
            if index < last {
                h = h.tanh()?;
            }
        }
        let y = h
            .broadcast_mul(&self.output_scale)?
            .broadcast_add(&self.output_mean)?
            .flatten_all()?
            .to_vec1::<f32>()?;
        let mut out = [0.0; OUTPUTS];
        out.copy_from_slice(&y);
        Ok(out)
    }
}

/// One core layer as (Wᵀ (in, out), bias (out)) tensors: the core stores W column by
/// column, which is Wᵀ row-major.
fn layer<const IN: usize, const OUT: usize>(
    layer: &Layer<IN, OUT>,
    device: &Device,
) -> candle_core::Result<(Tensor, Tensor)> {
    Ok((
        Tensor::from_slice(layer.weights.as_flattened(), (IN, OUT), device)?,
        Tensor::from_slice(&layer.bias, OUT, device)?,
    ))
}
