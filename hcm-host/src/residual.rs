//! The residual network as the simulator uses it: the core's fixed-size model,
//! decoded from the exported blob, attached to one contact of a model. Inside its
//! training envelope it adds its force correction to the law's; outside it is
//! switched off (the paper's strategy for conditions without data).

use crate::train::Network;
use hcm_core::model::{ContactModel, Correction, Residual};
use hcm_core::residual::{decode, BlobError, F32Weights, Int8Weights, Mlp};
use std::sync::Arc;

/// Inputs of the 1D contact residual: δ (m), δ̇ (m/s), δ̇0 (m/s).
pub const INPUTS: usize = 3;
/// Hidden-layer width of the shipped residual architecture.
pub const WIDTH: usize = 16;
/// Hidden layers of the shipped residual architecture.
pub const HIDDEN: usize = 2;

/// A decoded residual network, in either weight storage.
#[derive(Clone, Debug)]
pub enum ContactResidual {
    /// f32 weights.
    F32(Arc<Mlp<INPUTS, WIDTH, 1, HIDDEN, F32Weights>>),
    /// int8 weights with per-row scales.
    Int8(Arc<Mlp<INPUTS, WIDTH, 1, HIDDEN, Int8Weights>>),
}

impl ContactResidual {
    /// Decodes a blob (f32 or int8) of the shipped architecture.
    pub fn decode(bytes: &[u8]) -> Result<ContactResidual, BlobError> {
        match decode::<INPUTS, WIDTH, 1, HIDDEN, F32Weights>(bytes) {
            Ok(mlp) => Ok(ContactResidual::F32(Arc::new(mlp))),
            Err(BlobError::WrongQuantisation { .. }) => {
                decode::<INPUTS, WIDTH, 1, HIDDEN, Int8Weights>(bytes)
                    .map(|m| ContactResidual::Int8(Arc::new(m)))
            }
            Err(e) => Err(e),
        }
    }

    /// The force correction (N) at (δ, δ̇, δ̇0), or None outside the envelope.
    pub fn correction(&self, depth: f64, rate: f64, approach_speed: f64) -> Option<f64> {
        match Residual::<f64>::correction(self, &[depth, rate, approach_speed]) {
            Some(Correction::NormalForce(force)) => Some(force),
            _ => None,
        }
    }
}

/// The core evaluates the decoded network as the contact model's learned part, the
/// same code path as in a controller.
impl Residual<f64> for ContactResidual {
    fn correction(&self, input: &[f64]) -> Option<Correction<f64>> {
        match self {
            ContactResidual::F32(m) => m.as_ref().correction(input),
            ContactResidual::Int8(m) => m.as_ref().correction(input),
        }
    }
}

/// A scenario's contact model on the host: physics (f64) with, once attached, the
/// decoded residual network.
pub type HostContactModel = ContactModel<f64, Option<ContactResidual>>;

/// Worst |core − host| of `decoded` against the host `network` it was exported from,
/// relative to the largest |host output|, over a 9×9×9 grid spanning the training
/// envelope (the points where the core runs the residual).
pub fn round_trip_error(network: &Network, decoded: &ContactResidual) -> f64 {
    let steps = 9;
    let axis = |i: usize, k: usize| {
        let (lo, hi) = (network.envelope_min[i], network.envelope_max[i]);
        lo + (hi - lo) * k as f64 / (steps - 1) as f64
    };
    let (mut worst, mut largest) = (0.0_f64, 0.0_f64);
    for a in 0..steps {
        for b in 0..steps {
            for c in 0..steps {
                let x = [axis(0, a), axis(1, b), axis(2, c)];
                let host = network.evaluate(&x)[0];
                largest = largest.max(host.abs());
                if let Some(core) = decoded.correction(x[0], x[1], x[2]) {
                    worst = worst.max((core - host).abs());
                }
            }
        }
    }
    worst / largest.max(f64::MIN_POSITIVE)
}
