//! The contact-frame residual: one network evaluated at every touching point, from
//! what the point's contact law itself reads, its correction entering Eq 1 at that
//! point like the law's own force.
//!
//! Where the body-state residual of Eq 12 (13 inputs: position, quaternion,
//! velocity, angular velocity of the moving body) learns *where* and *how* the body
//! moved when the physics erred, this one learns *what the contact felt*: its inputs
//! do not change when the same contact happens at another place on the plate, in
//! another orientation of the body, or at another point of a box's face, so it may
//! act where the body-state network's envelope has switched it off.
//!
//! Inputs, per point ([`point_features`], `POINT_INPUTS` = 5):
//! - δ (m), the indentation;
//! - δ̇ (m/s), its rate;
//! - v_t (m/s, ≥ 0), the slip speed: |**v** − (**v**·**n**)**n**| of body 1's material
//!   point relative to body 2's;
//! - ω_n (rad/s, ≥ 0), the relative spin rate about the normal, |(**ω**₁ − **ω**₂)·**n**|;
//! - ω_t (rad/s, ≥ 0), the relative rolling rate, the tangential part's magnitude.
//!
//! The approach speed δ̇0 is left out on purpose: a faster impact than any trained
//! carries a δ̇0 outside the envelope over its whole contact, while its δ and δ̇
//! still pass through the trained range near the turn-around.
//!
//! Outputs, per point (`POINT_OUTPUTS` = 5): five coefficients of the point's own
//! indentation, friction and motion, so that a point which does not indent, slip,
//! spin or roll gets no correction of that kind and every correction is continuous in
//! the state, at touch-down and lift-off included:
//! - k_n (N/m): the normal force k_n·δ along **n**;
//! - r_f (–): the friction law's own force at the law's normal force, scaled by r_f
//!   (a friction coefficient off by r_f of itself, with the law's regularisation
//!   near sticking);
//! - c_t (N·s/m): the force c_t·**v**_t, **v**_t the slip velocity (negative opposes
//!   the slip, as viscous friction does);
//! - c_n (N·m·s/rad): the couple c_n·(**ω**·**n**)**n** about the normal;
//! - c_r (N·m·s/rad): the couple c_r·**ω**_t about the rolling axis.
//!
//! Why coefficients, measured: with the tangential outputs as forces along the unit
//! slip direction, the direction flipped wherever a ball (`examples/rig`) rolled
//! without slipping and the HCM's simulation stopped at its step limit on every
//! held-out run; with the normal output a force, a block coming to rest on four
//! corners (`tests/common/scenes/block_on_block.toml`) met a correction of its own
//! bias at δ = 0⁺, a jump it chattered on until the step limit; with a couple about a
//! fixed **n**, the network's bias turned the ball (rotation error 1.4° against PM2's
//! 0.08°). And why r_f: a wrong friction coefficient is a force of the law's size
//! along the slip at any slip speed, which c_t·**v**_t reaches only as c_t → ∞ near
//! sticking; without r_f, the ball of `tests/common/scenes/ball_on_plate.toml`
//! (PM2 Hertz against Hunt–Crossley data) kept 12 % of PM2's error in its force x.
//!
//! The normal correction enters before the friction law reads the normal force
//! ([`normal_correction`]), the others beside it ([`tangential_correction`] and the
//! friction scale in [`super::ContactModel::pair_load`]). The wrench is then linear in
//! the outputs at a given point (friction is linear in the normal force), so the host trains the network on the measured wrench of the
//! whole body — the sum over the points — with the wrench each unit output makes as
//! its lever.

use super::point::ContactPoint;
use super::residual::{Correction, Residual};
use crate::residual::{Excursion, Hidden, HiddenDepth, Mlp, WeightFormat};
use crate::Real;
use nalgebra::Vector3;

/// Inputs of the contact-frame residual: δ (m), δ̇ (m/s), v_t (m/s), ω_n (rad/s),
/// ω_t (rad/s).
pub const POINT_INPUTS: usize = 5;

/// Outputs of the contact-frame residual: k_n (N/m), r_f (–), c_t (N·s/m), c_n
/// (N·m·s/rad), c_r (N·m·s/rad).
pub const POINT_OUTPUTS: usize = 5;

/// The tangential part of `vector` at normal `normal` (unit), and its magnitude.
fn tangential<T: Real>(vector: &Vector3<T>, normal: &Vector3<T>) -> (Vector3<T>, T) {
    let along = vector - normal * vector.dot(normal);
    let size = along.norm_squared().square_root();
    (along, size)
}

/// The five contact-frame inputs of `point`: [δ (m), δ̇ (m/s), v_t (m/s), ω_n (rad/s),
/// ω_t (rad/s)] (see the module docs). NaN in the point's state gives NaN features,
/// which the network's envelope turns away.
pub fn point_features<T: Real>(point: &ContactPoint<T>) -> [T; POINT_INPUTS] {
    let n = &point.normal;
    let (_, slip) = tangential(&point.relative_velocity, n);
    let spin = point.relative_angular_velocity.dot(n).abs();
    let (_, roll) = tangential(&point.relative_angular_velocity, n);
    let i = &point.indentation;
    [i.depth, i.rate, slip, spin, roll]
}

/// The motion part of the correction the outputs `outputs` = [k_n (N/m), r_f (–), c_t
/// (N·s/m), c_n (N·m·s/rad), c_r (N·m·s/rad)] make at `point` on body 1: (friction
/// c_t·**v**_t (N), couple c_n·(**ω**·**n**)**n** + c_r·**ω**_t (N·m)). Linear in the
/// outputs. The normal part, k_n·δ, is added to the law's normal force before the
/// friction law reads it ([`super::ContactModel::pair_load`]): a normal force that
/// was wrong made the friction wrong in proportion, and the correction carries that
/// through as the law would.
pub fn tangential_correction<T: Real>(
    point: &ContactPoint<T>,
    outputs: &[T; POINT_OUTPUTS],
) -> (Vector3<T>, Vector3<T>) {
    let n = &point.normal;
    let (slip, _) = tangential(&point.relative_velocity, n);
    let omega = &point.relative_angular_velocity;
    let (roll, _) = tangential(omega, n);
    let spin = n * omega.dot(n);
    let [_, _, slip_coefficient, spin_coefficient, roll_coefficient] = *outputs;
    (
        slip * slip_coefficient,
        spin * spin_coefficient + roll * roll_coefficient,
    )
}

/// The friction scale r_f (–) of the outputs `outputs`.
pub fn friction_scale<T: Real>(outputs: &[T; POINT_OUTPUTS]) -> T {
    outputs[1]
}

/// The normal-force correction k_n·δ (N) of the outputs `outputs` at `point`.
pub fn normal_correction<T: Real>(point: &ContactPoint<T>, outputs: &[T; POINT_OUTPUTS]) -> T {
    outputs[0] * point.indentation.depth
}

/// A network of the core's fixed size read as a contact-frame residual: evaluated at
/// every touching point from [`point_features`], its outputs applied as the module
/// docs say. Wrap a decoded blob of 5 inputs and 5 outputs in it:
///
/// ```no_run
/// use hcm_core::model::PerPoint;
/// use hcm_core::residual::{decode, F32Weights, Mlp};
///
/// # let blob: &[u8] = &[];
/// let residual: PerPoint<Mlp<5, 16, 5, 2, F32Weights>> = PerPoint(decode(blob)?);
/// # Ok::<(), hcm_core::residual::BlobError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct PerPoint<M>(pub M);

impl<const WIDTH: usize, const HIDDEN: usize, Q>
    PerPoint<Mlp<POINT_INPUTS, WIDTH, POINT_OUTPUTS, HIDDEN, Q>>
where
    Q: WeightFormat,
    Hidden<HIDDEN>: HiddenDepth<WIDTH, Q>,
{
    /// The five outputs at `features`, or `None` outside the envelope or on NaN.
    pub fn outputs<T: Real>(&self, features: &[T; POINT_INPUTS]) -> Option<[T; POINT_OUTPUTS]> {
        point_outputs(&self.0, features)
    }
}

/// The five outputs of `network` at `features` (normalised in `T`, evaluated in
/// `f32`), or `None` when a feature lies outside the training envelope or is NaN.
pub fn point_outputs<T: Real, const WIDTH: usize, const HIDDEN: usize, Q>(
    network: &Mlp<POINT_INPUTS, WIDTH, POINT_OUTPUTS, HIDDEN, Q>,
    features: &[T; POINT_INPUTS],
) -> Option<[T; POINT_OUTPUTS]>
where
    Q: WeightFormat,
    Hidden<HIDDEN>: HiddenDepth<WIDTH, Q>,
{
    let rounded = features.map(|f| f.to_f32());
    if !network.inside_envelope(&rounded) {
        return None;
    }
    let y = network.evaluate_normalised(&network.normalise(features));
    Some(y.map(T::of_f32))
}

/// Which feature of `features` left `network`'s envelope, if one did.
pub fn point_excursion<T: Real, const WIDTH: usize, const HIDDEN: usize, Q>(
    network: &Mlp<POINT_INPUTS, WIDTH, POINT_OUTPUTS, HIDDEN, Q>,
    features: &[T; POINT_INPUTS],
) -> Option<Excursion>
where
    Q: WeightFormat,
    Hidden<HIDDEN>: HiddenDepth<WIDTH, Q>,
{
    network.envelope.excursion(&features.map(|f| f.to_f32()))
}

/// The contact-frame residual as the contact model's learned part: nothing for the
/// pair as a whole, a correction at every touching point inside the envelope.
impl<T: Real, const WIDTH: usize, const HIDDEN: usize, Q> Residual<T>
    for PerPoint<Mlp<POINT_INPUTS, WIDTH, POINT_OUTPUTS, HIDDEN, Q>>
where
    Q: WeightFormat,
    Hidden<HIDDEN>: HiddenDepth<WIDTH, Q>,
{
    #[inline]
    fn correction(&self, _input: &[T]) -> Option<Correction<T>> {
        None
    }

    fn point_correction(&self, point: &ContactPoint<T>) -> Option<[T; POINT_OUTPUTS]> {
        point_outputs(&self.0, &point_features(point))
    }
}
