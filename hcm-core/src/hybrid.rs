//! The hybrid contact model (HCM): a physics normal law plus the learned residual,
//! f_n = f_law(δ, δ̇, δ̇0) + r(x) (paper Section 3.2).
//!
//! The residual r is trusted only where it was trained: when its input x leaves the
//! training envelope, the model "switches it off" and returns the law's force alone,
//! and says so ([`Evaluated::PhysicsOnly`]), so that a controller can count or flag
//! extrapolation instead of acting on it silently.
//!
//! The residual input vector is built by the caller (for the 1D contact examples it is
//! [δ (m), δ̇ (m/s), δ̇0 (m/s)]); the residual's first output is the normal-force
//! correction (N).

use crate::law::{touching, AnyNormalLaw, Indentation, NormalLaw};
use crate::residual::{F32Weights, Hidden, HiddenDepth, Mlp, WeightFormat};
use crate::Real;

/// Which parts of the hybrid model produced a force.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Evaluated {
    /// The residual input was inside the training envelope: law + residual.
    PhysicsAndResidual,
    /// Out of contact, or the residual input was outside the envelope (or NaN): the
    /// law's force alone.
    PhysicsOnly,
}

/// A physics normal law corrected by a residual network with `INPUTS` inputs,
/// `HIDDEN` hidden layers of `WIDTH` neurons and `OUTPUTS` outputs (the first is the
/// normal-force correction, N).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HybridContactModel<
    const INPUTS: usize,
    const WIDTH: usize,
    const OUTPUTS: usize,
    const HIDDEN: usize,
    Q: WeightFormat = F32Weights,
> where
    Hidden<HIDDEN>: HiddenDepth<WIDTH, Q>,
{
    /// The physics law, with its identified parameters.
    pub law: AnyNormalLaw<f32>,
    /// The residual trained on the law's error.
    pub residual: Mlp<INPUTS, WIDTH, OUTPUTS, HIDDEN, Q>,
}

impl<const INPUTS: usize, const WIDTH: usize, const OUTPUTS: usize, const HIDDEN: usize, Q>
    HybridContactModel<INPUTS, WIDTH, OUTPUTS, HIDDEN, Q>
where
    Q: WeightFormat,
    Hidden<HIDDEN>: HiddenDepth<WIDTH, Q>,
{
    /// Normal force magnitude f_n (N, > 0 repulsive) and what produced it.
    ///
    /// Exactly (0, `PhysicsOnly`) for δ ≤ 0. Inside the envelope: the law's force plus
    /// the residual's first output, saturated at ±`f32::MAX` (the sum is not clamped at
    /// zero: a correction may make the force slightly tensile, as the data said).
    /// Outside the envelope, or for a NaN residual input: exactly the law's force.
    /// NaN in `contact` propagates as in every law.
    pub fn normal_force(
        &self,
        contact: &Indentation<f32>,
        residual_input: &[f32; INPUTS],
    ) -> (f32, Evaluated) {
        if !touching(contact.depth) {
            return (0.0, Evaluated::PhysicsOnly);
        }
        let physics = self.law.normal_force(contact);
        if !self.residual.inside_envelope(residual_input) {
            return (physics, Evaluated::PhysicsOnly);
        }
        let correction = self
            .residual
            .evaluate(residual_input)
            .first()
            .copied()
            .unwrap_or(0.0);
        (
            (physics + correction).saturate(),
            Evaluated::PhysicsAndResidual,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::law::Hertz;
    use crate::residual::{Activation, Envelope, Mlp};

    /// A residual that returns 2 N + 1000·δ (N) on δ ∈ [0, 1 mm], |δ̇| ≤ 2 m/s.
    fn model() -> HybridContactModel<3, 1, 1, 1> {
        let mut residual: Mlp<3, 1, 1, 1> = Mlp::zeroed(Activation::Relu);
        residual.input_layer.weights = [[1000.0, 0.0, 0.0]];
        residual.output_layer.weights = [[1.0]];
        residual.output_layer.bias = [2.0];
        residual.envelope = Envelope {
            min: [0.0, -2.0, 0.0],
            max: [1e-3, 2.0, 2.0],
        };
        HybridContactModel {
            law: Hertz {
                stiffness: 1e9,
                exponent: 1.5,
            }
            .into(),
            residual,
        }
    }

    fn contact(depth: f32, rate: f32) -> (Indentation<f32>, [f32; 3]) {
        let state = Indentation {
            depth,
            rate,
            approach_speed: 1.0,
        };
        (state, [depth, rate, 1.0])
    }

    #[test]
    fn inside_the_envelope_adds_the_residual() {
        let model = model();
        let (state, input) = contact(1e-4, 0.5);
        let physics = model.law.normal_force(&state);
        let (force, evaluated) = model.normal_force(&state, &input);
        assert_eq!(evaluated, Evaluated::PhysicsAndResidual);
        assert!(
            (force - (physics + 2.1)).abs() < 1e-4,
            "{force} vs {physics}"
        );
    }

    #[test]
    fn outside_the_envelope_returns_exactly_the_law_force() {
        let model = model();
        for (depth, rate) in [(2e-3, 0.5), (1e-4, 3.0), (1e-4, f32::NAN)] {
            let (state, input) = contact(depth, rate);
            let (force, evaluated) = model.normal_force(&state, &input);
            assert_eq!(evaluated, Evaluated::PhysicsOnly);
            assert_eq!(
                force,
                model.law.normal_force(&state),
                "δ = {depth}, δ̇ = {rate}"
            );
        }
    }

    #[test]
    fn out_of_contact_is_zero_even_inside_the_envelope() {
        let model = model();
        // δ = 0 is inside the envelope, where the residual alone would give 2 N.
        for depth in [0.0, -1e-4] {
            let (state, input) = contact(depth, 0.5);
            assert_eq!(
                model.normal_force(&state, &input),
                (0.0, Evaluated::PhysicsOnly)
            );
        }
    }

    #[test]
    fn nan_depth_propagates() {
        let model = model();
        let (state, input) = contact(f32::NAN, 0.5);
        let (force, evaluated) = model.normal_force(&state, &input);
        assert!(force.is_nan());
        assert_eq!(evaluated, Evaluated::PhysicsOnly);
    }
}
