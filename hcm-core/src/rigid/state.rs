//! The 13-component state of one rigid body, as the integrator sees it.

use crate::integrate::OdeState;
use crate::Real;
use nalgebra::{Quaternion, UnitQuaternion, Vector3};

/// Position, orientation, velocity and angular velocity of a rigid body.
///
/// Components (the order the integrator sees): position p (m, world) 0–2, orientation
/// quaternion q = (w, x, y, z) (dimensionless, body → world, unit) 3–6, velocity v
/// (m/s, world) 7–9, angular velocity ω (rad/s, **body frame**) 10–12.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RigidState<T: Real> {
    /// The components p, q, v, ω in the order above.
    pub components: [T; 13],
}

impl<T: Real> RigidState<T> {
    /// A state from position p (m, world), orientation (body → world), velocity v (m/s,
    /// world) and angular velocity ω (rad/s, body frame).
    pub fn new(
        position: Vector3<T>,
        orientation: UnitQuaternion<T>,
        velocity: Vector3<T>,
        body_angular_velocity: Vector3<T>,
    ) -> Self {
        let q = orientation.quaternion();
        let mut components = [T::zero(); 13];
        components[0..3].copy_from_slice(position.as_slice());
        components[3..7].copy_from_slice(&[q.w, q.i, q.j, q.k]);
        components[7..10].copy_from_slice(velocity.as_slice());
        components[10..13].copy_from_slice(body_angular_velocity.as_slice());
        RigidState { components }
    }

    /// Position p of the centre of mass (m, world).
    pub fn position(&self) -> Vector3<T> {
        self.vector(0)
    }

    /// Orientation quaternion q as stored (dimensionless; unit up to integration drift).
    pub fn quaternion(&self) -> Quaternion<T> {
        let c = &self.components;
        Quaternion::new(c[3], c[4], c[5], c[6])
    }

    /// Orientation (body → world): q/‖q‖. A zero or non-finite q gives NaN, no panic.
    pub fn orientation(&self) -> UnitQuaternion<T> {
        let c = &self.components;
        let (w, i, j, k) = (c[3], c[4], c[5], c[6]);
        // ‖q‖ as nalgebra's `Quaternion::norm` sums its coordinates (i, j, k, w):
        // √((i² + k²) + (j² + w²)), written out (its generic code cost the controller
        // 30 instructions more per call).
        let norm = ((i * i + k * k) + (j * j + w * w)).square_root();
        // Dividing by exactly 1 changes nothing: skipped (the common case while a
        // body does not turn).
        let q = if norm == T::one() {
            Quaternion::new(w, i, j, k)
        } else {
            Quaternion::new(w / norm, i / norm, j / norm, k / norm)
        };
        UnitQuaternion::new_unchecked(q)
    }

    /// Velocity v of the centre of mass (m/s, world).
    pub fn velocity(&self) -> Vector3<T> {
        self.vector(7)
    }

    /// Angular velocity ω (rad/s, body frame).
    pub fn body_angular_velocity(&self) -> Vector3<T> {
        self.vector(10)
    }

    /// Angular velocity R·ω (rad/s, world frame).
    pub fn world_angular_velocity(&self) -> Vector3<T> {
        self.orientation() * self.body_angular_velocity()
    }

    /// Sets ω from a world-frame angular velocity (rad/s) with the current orientation.
    pub fn set_world_angular_velocity(&mut self, world: &Vector3<T>) {
        let body = self.orientation().inverse_transform_vector(world);
        self.components[10..13].copy_from_slice(body.as_slice());
    }

    /// Scales q to unit norm (a zero or non-finite q becomes NaN, no panic).
    pub fn normalise(&mut self) {
        let q = self.orientation();
        let q = q.quaternion();
        self.components[3..7].copy_from_slice(&[q.w, q.i, q.j, q.k]);
    }

    /// |‖q‖ − 1|: how far the stored quaternion is from unit (dimensionless).
    pub fn quaternion_drift(&self) -> T {
        (self.quaternion().norm_squared().square_root() - T::one()).abs()
    }

    fn vector(&self, first: usize) -> Vector3<T> {
        let c = &self.components;
        Vector3::new(c[first], c[first + 1], c[first + 2])
    }
}

impl<T: Real> OdeState<T> for RigidState<T> {
    #[inline]
    fn components(&self) -> &[T] {
        &self.components
    }

    #[inline]
    fn components_mut(&mut self) -> &mut [T] {
        &mut self.components
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_accessors_read_back_what_new_stored() {
        let q = UnitQuaternion::from_euler_angles(0.35, -0.26, 0.1);
        let state = RigidState::new(
            Vector3::new(0.0, 0.0, 0.15),
            q,
            Vector3::new(0.5, 0.0, -1.0),
            Vector3::new(2.0, -3.0, 1.0),
        );
        assert_eq!(state.position(), Vector3::new(0.0, 0.0, 0.15));
        assert_eq!(state.velocity(), Vector3::new(0.5, 0.0, -1.0));
        assert_eq!(state.body_angular_velocity(), Vector3::new(2.0, -3.0, 1.0));
        assert!(state.orientation().angle_to(&q) < 1e-15);
        let mut converted = state;
        let world = Vector3::new(2.0, -3.0, 1.0);
        converted.set_world_angular_velocity(&world);
        assert!((converted.world_angular_velocity() - world).norm() < 1e-15);
        assert!((converted.body_angular_velocity() - world).norm() > 0.1);
    }

    #[test]
    fn normalise_makes_q_unit_and_a_zero_q_nan_without_panic() {
        let mut state = RigidState::<f64> {
            components: [0.0; 13],
        };
        state.components[3..7].copy_from_slice(&[2.0, 0.0, 0.0, 2.0]);
        state.normalise();
        assert!(state.quaternion_drift() < 1e-15);
        assert!((state.components[3] - 0.5_f64.sqrt()).abs() < 1e-15);
        state.components[3..7].copy_from_slice(&[0.0; 4]);
        state.normalise();
        assert!(state.components[3].is_nan());
    }
}
