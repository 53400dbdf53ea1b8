//! A body's pose and velocities at one instant: what the contact geometry reads.

use nalgebra::{UnitQuaternion, Vector3};

/// A body's pose and velocities at one instant, world frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// Centre of mass (m).
    pub(crate) position: Vector3<f64>,
    /// Orientation, body → world (–).
    pub(crate) orientation: UnitQuaternion<f64>,
    /// Velocity of the centre of mass (m/s).
    pub(crate) velocity: Vector3<f64>,
    /// Angular velocity ω (rad/s, world frame).
    pub(crate) angular_velocity: Vector3<f64>,
}

impl Pose {
    /// Velocity (m/s) of the body's material point at `point` (m): v + ω × (point − p).
    #[inline]
    pub(crate) fn point_velocity(&self, point: &Vector3<f64>) -> Vector3<f64> {
        self.velocity + self.angular_velocity.cross(&(point - self.position))
    }
}
