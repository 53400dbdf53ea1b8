//! # hcm-core — contact laws for the controller loop
//!
//! `#![no_std]`, no allocator, no `unsafe`: the contact laws of the hybrid contact
//! modeling (HCM) paper (Section 3.1), written once and generic over the float type
//! ([`Real`]: `f32` in a controller, `f64` in a stiff host simulation).
//!
//! ## Conventions (used everywhere in this crate)
//!
//! - Indentation δ (m) is **positive in contact**; δ ≤ 0 means the bodies are apart
//!   and every normal law returns exactly zero.
//! - Indentation rate δ̇ (m/s) is **positive while the bodies approach** (loading)
//!   and negative while they separate (unloading).
//! - The approach speed δ̇0 (m/s) is δ̇ at the instant the contact began; the laws
//!   that need it (Lankarani–Nikravesh, Flores) take it from the caller.
//! - The normal force magnitude f_n (N) is **positive when repulsive**. The common
//!   normal **n** is a unit vector pointing from body 2 towards body 1, so that body 1
//!   receives +f_n·**n** (Eq 1).
//! - All vectors given to one call are expressed in one common frame; rotating
//!   them into body frames is the caller's business.
//! - SI units throughout: m, s, kg, N, Pa.
//!
//! ## Totality
//!
//! Every public function returns a value for every input: NaN in any input
//! propagates to NaN in the result, results saturate at ±[`Real::MAX`] instead of
//! overflowing to infinity, and parameters outside their physical domain are
//! evaluated literally (use each law's `validate` to reject them up front).
//! Nothing panics.
//!
//! ## Example
//!
//! A steel ball (r = 12.7 mm) pressed 10 µm into concrete, approaching at 1.4 m/s,
//! under the Lankarani–Nikravesh law:
//!
//! ```
//! use hcm_core::geometry::{sphere_plane, Material};
//! use hcm_core::law::{Indentation, LankaraniNikravesh, NormalLaw};
//!
//! let steel = Material { youngs_modulus: 2.06e11_f32, poisson_ratio: 0.3 };
//! let concrete = Material { youngs_modulus: 2.5193e10_f32, poisson_ratio: 0.25 };
//! let stiffness = sphere_plane::hertz_stiffness(&steel, &concrete, 0.0127);
//! let law = LankaraniNikravesh { stiffness, exponent: 1.5, restitution: 0.93 };
//! let contact = Indentation { depth: 10e-6, rate: 1.4, approach_speed: 1.4 };
//! let force = law.normal_force(&contact);
//! assert!(force > 100.0 && force < 200.0); // newtons
//! assert_eq!(law.normal_force(&Indentation { depth: -1e-6, ..contact }), 0.0);
//! ```
#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod effect;
pub mod error;
pub mod friction;
pub mod geometry;
pub mod integrate;
/// Revolute-joint laws: spring, viscous and STEP-smoothed Coulomb torques (N·m).
pub mod joint;
pub mod law;
pub mod model;
mod real;
pub mod residual;
pub mod rigid;
pub mod vector;
pub mod wrench;

pub use error::LawError;
pub use real::Real;
