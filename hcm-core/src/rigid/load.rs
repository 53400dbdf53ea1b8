//! A rigid body under a constant world-frame load, as an ODE system.

use super::{RigidBody, RigidState};
use crate::integrate::OdeSystem;
use crate::Real;
use nalgebra::Vector3;

/// A [`RigidBody`] under a constant force **F** (N, world frame, at the centre of mass)
/// and torque **T** (N·m, world frame, about the centre of mass), plus gravity: the
/// torque-free and free-fall motions, and a constant motor torque.
///
/// Contact forces change with the state; a contact system evaluates them and calls
/// [`RigidBody::derivative`] the same way.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConstantLoad<T: Real> {
    /// The body.
    pub body: RigidBody<T>,
    /// Force **F** (N, world frame).
    pub force: Vector3<T>,
    /// Torque **T** (N·m, world frame, about the centre of mass).
    pub torque: Vector3<T>,
}

impl<T: Real> OdeSystem<T, RigidState<T>> for ConstantLoad<T> {
    fn derivative(&mut self, _time: T, state: &RigidState<T>, out: &mut RigidState<T>) {
        self.body.derivative(state, &self.force, &self.torque, out);
    }
}
