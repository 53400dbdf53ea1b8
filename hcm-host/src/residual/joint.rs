//! A joint's residual as the simulator uses it: the core's 2-16-16-1 network read from
//! the joint's own state [θ (rad), θ̇ (rad/s)], its output the torque on the child (N·m)
//! that the joint's law misses ([`hcm_core::joint::hybrid_torque`]), attached to a
//! joint of a model (`Model::with_residual`).

use super::{Stored, HIDDEN};
use hcm_core::joint::{hybrid_torque, JointLaw, JOINT_INPUTS};
use hcm_core::model::{Correction, Residual};
use hcm_core::residual::Excursion;

/// Hidden-layer width of a joint's residual.
pub const JOINT_WIDTH: usize = 16;

/// A decoded joint-torque network, f32 or int8.
#[derive(Clone, Debug)]
pub struct JointResidual(pub(crate) Stored<JOINT_INPUTS, JOINT_WIDTH, 1, HIDDEN>);

impl JointResidual {
    /// The hybrid torque on the child (N·m) of a joint of law `law` at angle `angle`
    /// (rad) and rate `rate` (rad/s): the core's sum, as a controller computes it.
    pub fn torque(&self, law: &JointLaw<f64>, angle: f64, rate: f64) -> f64 {
        hybrid_torque(law, self, angle, rate)
    }
}

/// Two joints' residuals are equal when they share the decoded weights (a model and
/// its clones); two decodings of one blob are not compared weight by weight.
impl PartialEq for JointResidual {
    fn eq(&self, other: &Self) -> bool {
        match (&self.0, &other.0) {
            (Stored::F32(a), Stored::F32(b)) => std::sync::Arc::ptr_eq(a, b),
            (Stored::Int8(a), Stored::Int8(b)) => std::sync::Arc::ptr_eq(a, b),
            _ => false,
        }
    }
}

/// The core's own evaluation (envelope, NaN, output meaning), as in a controller.
impl Residual<f64> for JointResidual {
    fn correction(&self, input: &[f64]) -> Option<Correction<f64>> {
        self.0.correction(input)
    }

    fn excursion(&self, input: &[f64]) -> Option<Excursion> {
        self.0.excursion(input)
    }
}
