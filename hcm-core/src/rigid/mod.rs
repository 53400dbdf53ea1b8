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
//!
//! ## Example
//!
//! A body thrown upwards at 1 m/s, spinning at 2 rad/s about its z axis, after 0.1 s:
//!
//! ```
//! use hcm_core::integrate::{Dopri5, Settings};
//! use hcm_core::rigid::{step_unit, ConstantLoad, RigidBody, RigidState};
//! use nalgebra::{Matrix3, UnitQuaternion, Vector3};
//!
//! let inertia = Matrix3::from_diagonal(&Vector3::new(1e-3, 2e-3, 3e-3)); // kg·m²
//! let body = RigidBody::new(0.37_f64, inertia, Vector3::new(0.0, 0.0, -9.81));
//! let mut system = ConstantLoad { body, force: Vector3::zeros(), torque: Vector3::zeros() };
//! let start = RigidState::new(
//!     Vector3::zeros(),
//!     UnitQuaternion::identity(),
//!     Vector3::new(0.0, 0.0, 1.0),
//!     Vector3::new(0.0, 0.0, 2.0),
//! );
//! let mut stepper = Dopri5::new(&mut system, 0.0, start, Settings::new(1e-10, 1e-12));
//! while stepper.time() < 0.1 {
//!     step_unit(&mut stepper, &mut system, 0.1)?;
//! }
//! let state = stepper.state();
//! assert!((state.position().z - (0.1 - 0.5 * 9.81 * 0.01)).abs() < 1e-10);
//! assert!((state.orientation().angle() - 0.2).abs() < 1e-9); // 2 rad/s · 0.1 s
//! # Ok::<(), hcm_core::integrate::IntegrationError>(())
//! ```

mod body;
mod load;
mod state;
mod step;

pub use body::RigidBody;
pub use load::ConstantLoad;
pub use state::RigidState;
pub use step::step_unit;
