//! Rigid-body dynamics in 3D: Newton–Euler equations of the paper's Eq 22.
//!
//! A body of mass m (kg) and inertia tensor **I** (kg·m², about the centre of mass, in
//! the body frame) moves under a force **F** (N, world frame) and a torque **T** (N·m,
//! world frame, about the centre of mass) and gravity **g** (m/s², world frame):
//!
//! ```text
//! ṗ = v                          position p (m, world)
//! v̇ = F/m + g                    velocity v (m/s, world)
//! q̇ = ½·q ⊗ (0, ω)               unit quaternion q (body → world), ω in the body frame
//! I·ω̇ + ω × I·ω = Rᵀ·T           Euler's equations, body frame (R the rotation of q)
//! ```
//!
//! **Eq 22 misprint.** The paper writes m·v̇ = F + m·g and I·ω̇ + ω × I·ω = T with F and T
//! computed in the body frame; adding the world-frame m·g to a body-frame F is only
//! right while the body is unrotated. Here F and T are taken in the world frame (where
//! the contact wrench of Eq 1 is assembled) and T is rotated into the body frame before
//! Euler's equations; gravity is added in the world frame.
//!
//! **Why ω in the body frame.** The inertia tensor is constant there, so Euler's
//! equations need no rotated tensor and the derivative costs one 3×3 solve with a
//! matrix inverted once ([`RigidBody::new`]). Use [`RigidState::world_angular_velocity`]
//! and [`RigidState::set_world_angular_velocity`] to convert.
//!
//! **Keeping q unit.** [`Dopri5`](crate::integrate::Dopri5) has no projection hook, and
//! adding one would change the integrator every other system uses. [`step_unit`] wraps
//! [`Dopri5::step`](crate::integrate::Dopri5::step): before each step it renormalises q
//! (through [`Dopri5::restart`](crate::integrate::Dopri5::restart)) if its norm has
//! drifted, so the dense output of the step just taken stays available to the caller.
//! The derivative rotates with q/‖q‖, so the drift never enters the forces.

mod body;
mod load;
mod state;
mod step;

pub use body::RigidBody;
pub use load::ConstantLoad;
pub use state::RigidState;
pub use step::step_unit;
