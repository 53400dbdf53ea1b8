//! One point of contact between two bodies: the state a contact law reads there.

use crate::effect::ContactMemory;
use crate::law::Indentation;
use crate::Real;
use nalgebra::Vector3;

/// Most contact points one body pair holds at once (a box face on a plane touches at
/// four corners; a box in a rectangular hole at up to eight).
pub const MAX_POINTS: usize = 8;

/// The contact points of one body pair, fixed-size (no allocator).
pub type Manifold<T> = heapless::Vec<ContactPoint<T>, MAX_POINTS>;

/// The state of one contact point, every vector in one common (world) frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactPoint<T> {
    /// Indentation δ (m), its rate δ̇ (m/s) and the approach speed δ̇0 (m/s) latched
    /// at this point's touch-down.
    pub indentation: Indentation<T>,
    /// What the point remembers of its current contact: δ_max (m).
    pub memory: ContactMemory<T>,
    /// Unit contact normal **n**, from body 2 towards body 1 (–).
    pub normal: Vector3<T>,
    /// Contact point (m), where both bodies' forces act.
    pub position: Vector3<T>,
    /// Velocity of body 1's material point at the contact relative to body 2's (m/s);
    /// its part along **n** is the approach, the rest is slip.
    pub relative_velocity: Vector3<T>,
    /// Angular velocity of body 1 relative to body 2, **ω**₁ − **ω**₂ (rad/s): what
    /// torsional and rolling resistance oppose.
    pub relative_angular_velocity: Vector3<T>,
}

impl<T: Real> ContactPoint<T> {
    /// A frictionless point: indentation and memory only, normal +z, at the origin,
    /// no slip. What a one-dimensional contact (a ball on a plane along z) needs.
    pub fn along_normal(indentation: Indentation<T>, memory: ContactMemory<T>) -> Self {
        ContactPoint {
            indentation,
            memory,
            normal: Vector3::z(),
            position: Vector3::zeros(),
            relative_velocity: Vector3::zeros(),
            relative_angular_velocity: Vector3::zeros(),
        }
    }
}

/// The force one contact point applies to body 1 (body 2 receives the opposite).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointForce<T: Real> {
    /// Normal force magnitude f_n (N), > 0 repulsive, along **n**.
    pub normal_force: T,
    /// Friction force **f_f** on body 1 (N), perpendicular to **n**: the dry law's,
    /// plus viscous friction.
    pub friction: Vector3<T>,
    /// Couple on body 1 (N·m) of torsional and rolling resistance (body 2 receives the
    /// opposite); zero without them.
    pub couple: Vector3<T>,
}

impl<T: Real> PointForce<T> {
    /// The total force on body 1 (N): f_n·**n** + **f_f**.
    pub fn on_body_1(&self, normal: &Vector3<T>) -> Vector3<T> {
        normal * self.normal_force + self.friction
    }
}
