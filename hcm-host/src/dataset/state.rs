//! A recorded sample as the integrator's rigid state (the residual's Eq 12 input and
//! the pose every rigid stage replays from).

use super::Sample;
use hcm_core::rigid::RigidState;
use nalgebra::{UnitQuaternion, Vector3};

/// Components of a rigid state: position (3), quaternion (4), velocity (3), angular
/// velocity (3).
pub const STATE_INPUTS: usize = 13;

/// The residual input of a recorded sample: [`RigidState`]'s components, ω turned from
/// the data's world frame into the body frame.
pub fn state_input(sample: &Sample) -> [f64; STATE_INPUTS] {
    let [w, x, y, z] = sample.orientation;
    let orientation = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z));
    let omega = orientation.inverse_transform_vector(&Vector3::from(sample.angular_velocity));
    let mut state = RigidState::new(
        Vector3::from(sample.position),
        orientation,
        Vector3::from(sample.velocity),
        omega,
    );
    // Keep the recorded quaternion itself (the integrator's, up to its drift).
    state.components[3..7].copy_from_slice(&sample.orientation);
    state.components
}
