//! The contact model of one body pair from C, in one call: the physics (an extended
//! law and a friction law) at up to `HCM_MAX_POINTS` touching points summed by Eq 1,
//! plus the wrench residual evaluated once for the pair — the core's
//! `ContactModel::pair_load`, so C gets the very bits Rust does.

use crate::boundary::{checked, checked_mut, guard, input};
use crate::hybrid::outside;
use crate::law::{HcmContact, HcmExtendedLaw, HCM_MAX_PARAMETERS};
use crate::wrench::{wrench_network, HcmWrenchResidual, WrenchNetwork, HCM_WRENCH_RESIDUAL_INPUTS};
use crate::HcmStatus;
use hcm_core::friction::VelocityStepFriction;
use hcm_core::model::{ContactModel, ContactPoint, Evaluated, Manifold, Residual, MAX_POINTS};
use hcm_core::residual::Envelope;
use nalgebra::Vector3;

/// Most contact points one `hcm_pair_load` call takes (a box in a rectangular hole
/// touches at up to eight).
pub const HCM_MAX_POINTS: usize = 8;
const _: () = assert!(HCM_MAX_POINTS == MAX_POINTS);

/// Which friction law: one of the `HCM_FRICTION_*` constants.
pub type HcmFrictionKind = u32;
/// No friction: every point pushes along its normal only.
pub const HCM_FRICTION_NONE: HcmFrictionKind = 0;
/// Velocity-based friction with STEP transitions (MSC ADAMS), Eq 10–11: static
/// coefficient μ_s (-), dynamic coefficient μ_d (-), stiction speed v_s (m/s), dynamic
/// speed v_d (m/s).
pub const HCM_FRICTION_STEP: HcmFrictionKind = 1;

/// A friction law and its parameters.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HcmFriction {
    /// `HCM_FRICTION_*`.
    pub kind: HcmFrictionKind,
    /// The law's parameters in the order its `HCM_FRICTION_*` constant lists, SI
    /// units; the entries after the law's count are ignored.
    pub parameters: [f32; HCM_MAX_PARAMETERS],
}

/// The physics of one body pair: the normal law with its effects at every point, and
/// the friction law from each point's slip and normal force.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HcmPairPhysics {
    /// The normal law and its effects.
    pub normal: HcmExtendedLaw,
    /// The friction law.
    pub friction: HcmFriction,
}

/// One contact point of a body pair, every vector in one common (world) frame.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HcmContactPoint {
    /// Indentation δ (m, > 0 in contact), its rate δ̇ (m/s, > 0 approaching), the
    /// approach speed δ̇0 (m/s) latched at this point's touch-down, and the deepest
    /// indentation δ_max (m) of this contact so far (read only by plasticity; 0 at
    /// touch-down).
    pub contact: HcmContact,
    /// Unit contact normal **n** (-), from body 2 towards body 1.
    pub normal: [f32; 3],
    /// Contact point (m), where both bodies' forces act.
    pub position: [f32; 3],
    /// Velocity (m/s) of body 1's material point at the contact relative to body 2's;
    /// its part perpendicular to **n** is the slip friction opposes.
    pub relative_velocity: [f32; 3],
    /// Angular velocity of body 1 relative to body 2 (rad/s).
    pub relative_angular_velocity: [f32; 3],
}

/// The loads of one body pair's contact on body 1 (body 2 receives the opposite
/// force).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HcmPairLoad {
    /// Force on body 1 (N), world frame: Σ (f_n·**n** + **f_f**) over the touching
    /// points, plus the residual's force when `residual_used`.
    pub force: [f32; 3],
    /// Torque on body 1 (N·m) about its reference point: Σ l × (f_n·**n** + **f_f**),
    /// plus the residual's torque when `residual_used`.
    pub torque: [f32; 3],
    /// Σ f_n over the touching points (N, > 0 repulsive).
    pub normal_force: f32,
    /// How many of the points touch (δ > 0, or δ NaN, which the core lets through so
    /// that it shows): those that contributed.
    pub points_used: u32,
    /// Whether the residual took part: some point touches, and the residual input lies
    /// inside its training envelope.
    pub residual_used: bool,
    /// Bit i set: residual input i lies beyond the envelope's tolerated bounds
    /// [min_i − tolerance_i, max_i + tolerance_i] (or is NaN): the core's own rule, so
    /// with a point touching, `residual_used` is 0 exactly when some bit is set.
    pub outside_envelope: u32,
}

impl HcmFriction {
    /// The core's friction law (`None`: frictionless); [`HcmStatus::BadParameter`] for
    /// an unknown kind.
    pub fn to_core(&self) -> Result<Option<VelocityStepFriction<f32>>, HcmStatus> {
        let [static_coefficient, dynamic_coefficient, stiction_speed, dynamic_speed, _] =
            self.parameters;
        match self.kind {
            HCM_FRICTION_NONE => Ok(None),
            HCM_FRICTION_STEP => Ok(Some(VelocityStepFriction {
                static_coefficient,
                dynamic_coefficient,
                stiction_speed,
                dynamic_speed,
            })),
            _ => Err(HcmStatus::BadParameter),
        }
    }
}

impl HcmPairPhysics {
    /// The core's contact model without a residual; [`HcmStatus::BadParameter`] for an
    /// unknown kind or more than `HCM_MAX_EFFECTS` effects.
    pub fn to_core(&self) -> Result<ContactModel<f32>, HcmStatus> {
        let model = ContactModel::physics(self.normal.to_core()?);
        Ok(match self.friction.to_core()? {
            Some(friction) => model.with_friction(friction),
            None => model,
        })
    }
}

impl HcmContactPoint {
    /// The core's contact point.
    pub fn to_core(&self) -> ContactPoint<f32> {
        ContactPoint {
            indentation: self.contact.indentation(),
            memory: self.contact.memory(),
            normal: Vector3::from(self.normal),
            position: Vector3::from(self.position),
            relative_velocity: Vector3::from(self.relative_velocity),
            relative_angular_velocity: Vector3::from(self.relative_angular_velocity),
        }
    }
}

/// `HCM_STATUS_OK` if the normal law, its effects and the friction law are in their
/// physical domains, `HCM_STATUS_OUT_OF_DOMAIN` if one is not (or one kind of effect
/// is listed twice), `HCM_STATUS_BAD_PARAMETER` for an unknown kind.
///
/// # Safety
/// `physics` must be null or point to an initialised `HcmPairPhysics`.
#[no_mangle]
pub unsafe extern "C" fn hcm_pair_physics_validate(physics: *const HcmPairPhysics) -> HcmStatus {
    guard(|| {
        // SAFETY: the caller's contract above.
        let model = unsafe { input(physics) }?.to_core()?;
        model.validate().map_err(|_| HcmStatus::OutOfDomain)
    })
}

/// The contact model of one body pair, into `*out`: `physics` at each of the `count`
/// points `points[0..count]` (the normal law with its effects, friction from the
/// point's slip), summed by Eq 1 with torques about `reference` (3 floats: body 1's
/// reference point, its centre of mass (m)), plus the wrench residual `*residual` at
/// `residual_input` (`HCM_WRENCH_RESIDUAL_INPUTS` floats), evaluated once, when some
/// point touches and the input lies inside the residual's training envelope. Through
/// the core's `ContactModel::pair_load`: the same bits as Rust.
///
/// No points touching: zero loads, physics only. Non-finite values are not refused:
/// they go through the core's rules (a NaN δ counts as touching and propagates; a NaN
/// or infinite residual input switches the residual off, its bit set in
/// `outside_envelope`). `HCM_STATUS_BAD_PARAMETER` for `count` > `HCM_MAX_POINTS` or an
/// unknown kind; `HCM_STATUS_NOT_DECODED` if `*residual` was never decoded.
///
/// # Safety
/// `physics` must be null or point to an initialised `HcmPairPhysics`; `residual` null
/// or an initialised `HcmWrenchResidual` (zeroed, or passed to
/// `hcm_wrench_residual_decode`) not written during the call; `points` null or `count`
/// initialised `HcmContactPoint`s; `reference` null or 3 initialised floats;
/// `residual_input` null or `HCM_WRENCH_RESIDUAL_INPUTS` initialised floats; `out`
/// null or writable memory for one `HcmPairLoad`.
#[no_mangle]
pub unsafe extern "C" fn hcm_pair_load(
    physics: *const HcmPairPhysics,
    residual: *const HcmWrenchResidual,
    points: *const HcmContactPoint,
    count: usize,
    reference: *const f32,
    residual_input: *const f32,
    out: *mut HcmPairLoad,
) -> HcmStatus {
    guard(|| {
        // SAFETY: the caller's contract above.
        let model = unsafe { input(physics) }?.to_core()?;
        // SAFETY: the caller's contract above.
        let network = unsafe { wrench_network(residual) }?;
        // SAFETY: the caller's contract above.
        let points = unsafe { manifold(points, count) }?;
        // SAFETY: the caller's contract above; an array of floats has a float's
        // alignment, which `input` checks.
        let reference = Vector3::from(*unsafe { input(reference.cast::<[f32; 3]>()) }?);
        // SAFETY: as for `reference`.
        let residual_input = unsafe { input(residual_input.cast()) }?;
        let out = checked_mut(out)?;
        let value = match network {
            WrenchNetwork::F32(mlp) => {
                let model = model.with_residual(mlp);
                evaluate(&model, &mlp.envelope, &points, &reference, residual_input)
            }
            WrenchNetwork::Int8(mlp) => {
                let model = model.with_residual(mlp);
                evaluate(&model, &mlp.envelope, &points, &reference, residual_input)
            }
        };
        // SAFETY: non-null and aligned (checked), writable (contract).
        unsafe { out.write(value) };
        Ok(())
    })
}

/// The `count` points at `points` as the core's manifold; [`HcmStatus::BadParameter`]
/// for more than [`HCM_MAX_POINTS`].
///
/// # Safety
/// `points` must be null or point to `count` initialised `HcmContactPoint`s that stay
/// unchanged during the call. They are made of floats only: any bytes are valid.
unsafe fn manifold(
    points: *const HcmContactPoint,
    count: usize,
) -> Result<Manifold<f32>, HcmStatus> {
    if count > HCM_MAX_POINTS {
        return Err(HcmStatus::BadParameter);
    }
    let points = checked(points)?;
    // SAFETY: non-null and aligned (checked), `count` ≤ 8 initialised points by the
    // caller's contract (so the length in bytes is far below isize::MAX).
    let points = unsafe { core::slice::from_raw_parts(points, count) };
    let mut manifold = Manifold::new();
    for point in points {
        // At most HCM_MAX_POINTS == MAX_POINTS points (checked): the push succeeds.
        manifold
            .push(point.to_core())
            .map_err(|_| HcmStatus::BadParameter)?;
    }
    Ok(manifold)
}

/// `ContactModel::pair_load` of `model` on `points` (body 2's reference point at the
/// origin: body 1's loads do not depend on it), as C receives it.
fn evaluate<R: Residual<f32>>(
    model: &ContactModel<f32, R>,
    envelope: &Envelope<HCM_WRENCH_RESIDUAL_INPUTS>,
    points: &[ContactPoint<f32>],
    reference: &Vector3<f32>,
    input: &[f32; HCM_WRENCH_RESIDUAL_INPUTS],
) -> HcmPairLoad {
    let load = model.pair_load(points, reference, &Vector3::zeros(), input);
    let touching = |p: &&ContactPoint<f32>| {
        let depth = p.indentation.depth;
        depth > 0.0 || depth.is_nan()
    };
    // At most HCM_MAX_POINTS points: the cast is lossless.
    let points_used = points.iter().filter(touching).count() as u32;
    HcmPairLoad {
        force: load.wrench.force_1.into(),
        torque: load.wrench.torque_1.into(),
        normal_force: load.normal_force,
        points_used,
        residual_used: load.evaluated == Evaluated::PhysicsAndResidual,
        outside_envelope: outside(envelope, input),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn friction_kinds_map_to_the_core() {
        let step = HcmFriction {
            kind: HCM_FRICTION_STEP,
            parameters: [0.3, 0.1, 1e-3, 3e-3, 99.0],
        };
        let law = step.to_core().unwrap().unwrap();
        assert_eq!(law.static_coefficient, 0.3);
        assert_eq!(law.dynamic_coefficient, 0.1);
        assert_eq!(law.stiction_speed, 1e-3);
        assert_eq!(law.dynamic_speed, 3e-3);
        let none = HcmFriction {
            kind: HCM_FRICTION_NONE,
            ..step
        };
        assert_eq!(none.to_core(), Ok(None));
        let unknown = HcmFriction { kind: 2, ..step };
        assert_eq!(unknown.to_core(), Err(HcmStatus::BadParameter));
    }
}
