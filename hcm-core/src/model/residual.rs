//! The learned part of the contact model: what a residual returns and how.
//!
//! A residual r(x) is trained on what the physics gets wrong (paper Section 3.2,
//! Eq 12). Its input vector x is built by the caller (for the 1D examples
//! [δ (m), δ̇ (m/s), δ̇0 (m/s)]; for a rigid body its position, orientation
//! quaternion, velocity and angular velocity). It answers `None` where it must not
//! be trusted — outside its training envelope, on a NaN input, on an input of the
//! wrong length — and the model then falls back on the physics alone.

use super::point::ContactPoint;
use super::point_residual::POINT_OUTPUTS;
use crate::residual::{Excursion, HiddenDepth, Mlp, WeightFormat};
use crate::Real;
use nalgebra::Vector3;

/// What a residual adds to the physics of one body pair.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Correction<T: Real> {
    /// A normal-force correction (N), added to f_n along the normal of the pair's
    /// first contact point (the 1D examples: one output).
    NormalForce(T),
    /// A wrench on body 1 about its reference point (its centre of mass), world
    /// frame: force (N) and torque (N·m); body 2 receives the opposite (six outputs,
    /// Eq 12 for one body).
    Wrench {
        /// Force on body 1 (N).
        force: Vector3<T>,
        /// Torque on body 1 about its reference point (N·m).
        torque: Vector3<T>,
    },
    /// Independent wrenches on both bodies about their reference points, world frame
    /// (twelve outputs, Eq 12 for two moving bodies).
    PairWrench {
        /// Force on body 1 (N).
        force_1: Vector3<T>,
        /// Torque on body 1 (N·m).
        torque_1: Vector3<T>,
        /// Force on body 2 (N).
        force_2: Vector3<T>,
        /// Torque on body 2 (N·m).
        torque_2: Vector3<T>,
    },
}

/// A learned correction of the contact physics.
pub trait Residual<T: Real> {
    /// The correction at residual input `input`, or `None` where the residual is
    /// switched off (outside its envelope, NaN, wrong input length, no residual).
    fn correction(&self, input: &[T]) -> Option<Correction<T>>;

    /// Which input left the residual's training envelope and by how much, when that
    /// is why [`Residual::correction`] is `None`; `None` inside the envelope, for an
    /// input of the wrong length, and for a residual without an envelope.
    fn excursion(&self, _input: &[T]) -> Option<Excursion> {
        None
    }

    /// Its five outputs at one touching point — a contact-frame residual's
    /// ([`super::PerPoint`]), read from the point's own state, applied by
    /// [`super::point_residual`] — or `None`: switched off there, or a residual of the
    /// pair as a whole.
    fn point_correction(&self, _point: &ContactPoint<T>) -> Option<[T; POINT_OUTPUTS]> {
        None
    }
}

/// No learned part: the contact model is the physics alone.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NoResidual;

impl<T: Real> Residual<T> for NoResidual {
    #[inline]
    fn correction(&self, _input: &[T]) -> Option<Correction<T>> {
        None
    }
}

impl<T: Real, R: Residual<T>> Residual<T> for Option<R> {
    #[inline]
    fn correction(&self, input: &[T]) -> Option<Correction<T>> {
        self.as_ref().and_then(|r| r.correction(input))
    }

    #[inline]
    fn excursion(&self, input: &[T]) -> Option<Excursion> {
        self.as_ref().and_then(|r| r.excursion(input))
    }

    #[inline]
    fn point_correction(&self, point: &ContactPoint<T>) -> Option<[T; POINT_OUTPUTS]> {
        self.as_ref().and_then(|r| r.point_correction(point))
    }
}

impl<T: Real, R: Residual<T>> Residual<T> for &R {
    #[inline]
    fn correction(&self, input: &[T]) -> Option<Correction<T>> {
        (*self).correction(input)
    }

    #[inline]
    fn excursion(&self, input: &[T]) -> Option<Excursion> {
        (*self).excursion(input)
    }

    #[inline]
    fn point_correction(&self, point: &ContactPoint<T>) -> Option<[T; POINT_OUTPUTS]> {
        (*self).point_correction(point)
    }
}

/// The core's fixed-size network as a residual. Inputs are normalised in their own
/// type and then rounded to `f32`, the network's type; the envelope is checked on the
/// inputs rounded to `f32`. Its outputs mean, by their count: 6 → [`Correction::Wrench`]
/// (force x, y, z, then torque x, y, z), 12 → [`Correction::PairWrench`] (body 1's
/// force and torque, then body 2's), any other count → [`Correction::NormalForce`]
/// from the first output.
impl<T, const INPUTS: usize, const WIDTH: usize, const OUTPUTS: usize, const HIDDEN: usize, Q>
    Residual<T> for Mlp<INPUTS, WIDTH, OUTPUTS, HIDDEN, Q>
where
    T: Real,
    Q: WeightFormat,
    crate::residual::Hidden<HIDDEN>: HiddenDepth<WIDTH, Q>,
{
    fn correction(&self, input: &[T]) -> Option<Correction<T>> {
        let x = network_input(input)?;
        if !self.inside_envelope(&x) {
            return None;
        }
        // Normalised in T, before rounding to f32 (see Mlp::normalise); identical to
        // `evaluate(&x)` when T is f32.
        let raw: &[T; INPUTS] = input.try_into().ok()?;
        let y = self.evaluate_normalised(&self.normalise(raw));
        let at = |i: usize| y.get(i).copied().unwrap_or(0.0).cast::<T>();
        let vector = |i: usize| Vector3::new(at(i), at(i + 1), at(i + 2));
        Some(match OUTPUTS {
            6 => Correction::Wrench {
                force: vector(0),
                torque: vector(3),
            },
            12 => Correction::PairWrench {
                force_1: vector(0),
                torque_1: vector(3),
                force_2: vector(6),
                torque_2: vector(9),
            },
            _ => Correction::NormalForce(at(0)),
        })
    }

    fn excursion(&self, input: &[T]) -> Option<Excursion> {
        self.envelope.excursion(&network_input(input)?)
    }
}

/// `input` rounded to the network's `f32`, or `None` if it is not `INPUTS` long.
fn network_input<T: Real, const INPUTS: usize>(input: &[T]) -> Option<[f32; INPUTS]> {
    if input.len() != INPUTS {
        return None;
    }
    let mut x = [0.0_f32; INPUTS];
    for (x, value) in x.iter_mut().zip(input) {
        *x = value.to_f32();
    }
    Some(x)
}
