//! One residual shape in either weight storage, as the core decodes it.

use hcm_core::model::point_residual::{point_features, point_outputs};
use hcm_core::model::{ContactPoint, Correction, Residual, POINT_INPUTS, POINT_OUTPUTS};
use hcm_core::residual::{
    decode, BlobError, Excursion, F32Weights, Hidden, HiddenDepth, Int8Weights, Mlp,
};
use std::sync::Arc;

/// A decoded network of one shape (`INPUTS`, hidden layers of `WIDTH`, `OUTPUTS`,
/// `HIDDEN` layers), f32 or int8 weights. Behind an [`Arc`]: a model holding it is
/// cloned per run and per candidate, the weights are not.
#[derive(Clone, Debug)]
pub enum Stored<const INPUTS: usize, const WIDTH: usize, const OUTPUTS: usize, const HIDDEN: usize>
where
    Hidden<HIDDEN>: HiddenDepth<WIDTH, F32Weights> + HiddenDepth<WIDTH, Int8Weights>,
{
    /// f32 weights.
    F32(Arc<Mlp<INPUTS, WIDTH, OUTPUTS, HIDDEN, F32Weights>>),
    /// int8 hidden → hidden weights with per-row scales.
    Int8(Arc<Mlp<INPUTS, WIDTH, OUTPUTS, HIDDEN, Int8Weights>>),
}

impl<const INPUTS: usize, const WIDTH: usize, const OUTPUTS: usize, const HIDDEN: usize>
    Stored<INPUTS, WIDTH, OUTPUTS, HIDDEN>
where
    Hidden<HIDDEN>: HiddenDepth<WIDTH, F32Weights> + HiddenDepth<WIDTH, Int8Weights>,
    Mlp<INPUTS, WIDTH, OUTPUTS, HIDDEN, F32Weights>: Send + Sync,
    Mlp<INPUTS, WIDTH, OUTPUTS, HIDDEN, Int8Weights>: Send + Sync,
{
    /// Decodes a blob of this shape, f32 or int8 (whichever the blob says).
    pub fn decode(bytes: &[u8]) -> Result<Self, BlobError> {
        match decode::<INPUTS, WIDTH, OUTPUTS, HIDDEN, F32Weights>(bytes) {
            Ok(mlp) => Ok(Stored::F32(Arc::new(mlp))),
            Err(BlobError::WrongQuantisation { .. }) => {
                decode::<INPUTS, WIDTH, OUTPUTS, HIDDEN, Int8Weights>(bytes)
                    .map(|m| Stored::Int8(Arc::new(m)))
            }
            Err(e) => Err(e),
        }
    }
}

/// The core's own evaluation: envelope, input length and output meaning as in a
/// controller (`hcm_core::model::residual`).
impl<const INPUTS: usize, const WIDTH: usize, const OUTPUTS: usize, const HIDDEN: usize>
    Residual<f64> for Stored<INPUTS, WIDTH, OUTPUTS, HIDDEN>
where
    Hidden<HIDDEN>: HiddenDepth<WIDTH, F32Weights> + HiddenDepth<WIDTH, Int8Weights>,
{
    fn correction(&self, input: &[f64]) -> Option<Correction<f64>> {
        match self {
            Stored::F32(m) => m.as_ref().correction(input),
            Stored::Int8(m) => m.as_ref().correction(input),
        }
    }

    fn excursion(&self, input: &[f64]) -> Option<Excursion> {
        match self {
            Stored::F32(m) => Residual::<f64>::excursion(m.as_ref(), input),
            Stored::Int8(m) => Residual::<f64>::excursion(m.as_ref(), input),
        }
    }
}

impl<const WIDTH: usize, const HIDDEN: usize> Stored<POINT_INPUTS, WIDTH, POINT_OUTPUTS, HIDDEN>
where
    Hidden<HIDDEN>: HiddenDepth<WIDTH, F32Weights> + HiddenDepth<WIDTH, Int8Weights>,
{
    /// A contact-frame network's outputs at one touching point, as the core's
    /// [`hcm_core::model::PerPoint`] computes them.
    pub fn point_correction(&self, point: &ContactPoint<f64>) -> Option<[f64; POINT_OUTPUTS]> {
        self.outputs(&point_features(point))
    }

    /// The network's five outputs at contact-frame `features`, or `None` outside its
    /// envelope (the core's evaluation).
    pub fn outputs(&self, features: &[f64; POINT_INPUTS]) -> Option<[f64; POINT_OUTPUTS]> {
        match self {
            Stored::F32(m) => point_outputs(m.as_ref(), features),
            Stored::Int8(m) => point_outputs(m.as_ref(), features),
        }
    }
}
