//! One integrator step that keeps the orientation quaternion unit.

use super::RigidState;
use crate::integrate::{Dopri5, IntegrationError, OdeSystem};
use crate::Real;

/// Renormalises q when |‖q‖ − 1| exceeds this many machine epsilons of `T`
/// (dimensionless): a few ulps, so a step that did not drift is not followed by a
/// restart (and keeps its FSAL evaluation).
const DRIFT_ULPS: f64 = 4.0;

/// [`Dopri5::step`] towards `until` (s), first renormalising the quaternion of the
/// current state if it drifted from unit.
///
/// The projection happens *before* the step (through [`Dopri5::restart`], which costs
/// one derivative evaluation), so after the call the dense output of the step just
/// taken is intact for event location. The state it leaves carries the drift of one
/// step only: O(tolerance), far below the drift a run without projection accumulates.
///
/// # Errors
///
/// Those of [`Dopri5::step`]; the stepper stays at its last accepted point.
pub fn step_unit<T: Real>(
    stepper: &mut Dopri5<T, RigidState<T>>,
    system: &mut impl OdeSystem<T, RigidState<T>>,
    until: T,
) -> Result<(), IntegrationError> {
    let state = stepper.state();
    if state.quaternion_drift() > T::of(DRIFT_ULPS) * T::default_epsilon() {
        let mut unit = *state;
        unit.normalise();
        let time = stepper.time();
        stepper.restart(system, time, unit);
    }
    stepper.step(system, until)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::Settings;
    use crate::rigid::{ConstantLoad, RigidBody};
    use nalgebra::{Matrix3, UnitQuaternion, Vector3};

    #[test]
    fn a_drifted_quaternion_is_made_unit_before_the_step() {
        let body = RigidBody::new(1.0, Matrix3::identity(), Vector3::zeros());
        let mut system = ConstantLoad {
            body,
            force: Vector3::zeros(),
            torque: Vector3::zeros(),
        };
        let mut start = RigidState::new(
            Vector3::zeros(),
            UnitQuaternion::identity(),
            Vector3::zeros(),
            Vector3::new(0.0, 0.0, 1.0),
        );
        start.components[3] = 1.5;
        let settings = Settings::new(1e-12, 1e-14);
        let mut stepper = Dopri5::new(&mut system, 0.0, start, settings);
        step_unit(&mut stepper, &mut system, 0.1).unwrap();
        assert!(stepper.previous_state().quaternion_drift() < 1e-15);
        assert!(stepper.state().quaternion_drift() < 1e-12);
        assert!(stepper.time() > 0.0);
    }

    #[test]
    fn an_f32_spin_stays_unit_to_a_few_f32_ulps() {
        let body = RigidBody::new(1.0_f32, Matrix3::identity(), Vector3::zeros());
        let mut system = ConstantLoad {
            body,
            force: Vector3::zeros(),
            torque: Vector3::zeros(),
        };
        let start = RigidState::new(
            Vector3::zeros(),
            UnitQuaternion::identity(),
            Vector3::zeros(),
            Vector3::new(0.3, -2.0, 1.0),
        );
        let mut stepper = Dopri5::new(&mut system, 0.0, start, Settings::new(1e-5, 1e-6));
        while stepper.time() < 10.0 {
            step_unit(&mut stepper, &mut system, 10.0).unwrap();
        }
        assert!(stepper.state().quaternion_drift() < 1e-5);
        // A sphere-like body keeps ω: no gyroscopic torque when I = 1.
        let omega = stepper.state().body_angular_velocity();
        assert!((omega - Vector3::new(0.3, -2.0, 1.0)).norm() < 1e-6);
    }

    #[test]
    fn a_zero_quaternion_ends_in_an_error_not_a_panic() {
        let body = RigidBody::new(1.0, Matrix3::identity(), Vector3::zeros());
        let mut system = ConstantLoad {
            body,
            force: Vector3::zeros(),
            torque: Vector3::zeros(),
        };
        let start = RigidState {
            components: [0.0; 13],
        };
        let mut stepper = Dopri5::new(&mut system, 0.0, start, Settings::new(1e-9, 1e-9));
        assert!(step_unit(&mut stepper, &mut system, 1.0).is_err());
    }
}
