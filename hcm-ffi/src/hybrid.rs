//! The hybrid contact model from C: the physics (an extended law) plus a decoded
//! residual, for one contact (paper Section 3.2, Eq 12), through the core's
//! `ContactModel::normal_force`.

use crate::boundary::{checked_mut, guard, input};
use crate::law::{HcmContact, HcmExtendedLaw};
use crate::residual::{network, HcmResidual, Network, HCM_RESIDUAL_INPUTS};
use crate::HcmStatus;
use hcm_core::model::{ContactModel, Evaluated, Residual};
use hcm_core::residual::Envelope;

/// One evaluation of the hybrid model.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HcmHybridForce {
    /// Normal force f_n (N, > 0 repulsive): physics + residual correction when
    /// `residual_used`, else the physics alone; exactly 0 for δ ≤ 0.
    pub force: f32,
    /// The physics alone (N), for comparison.
    pub physics: f32,
    /// Whether the residual took part: in contact, and its input inside its envelope.
    pub residual_used: bool,
    /// Bit i set: residual input i (0: δ, 1: δ̇, 2: δ̇0) lies beyond the envelope's
    /// tolerated bounds [min_i − tolerance_i, max_i + tolerance_i] (or is NaN): the
    /// core's own rule, so with an input in contact, `residual_used` is 0 exactly when
    /// some bit is set.
    pub outside_envelope: u32,
}

/// The hybrid model's normal force at `contact`, into `*out`: `physics` plus the
/// residual `*residual` evaluated at [δ, δ̇, δ̇0], when in contact and inside the
/// residual's training envelope; the physics alone otherwise.
///
/// `HCM_STATUS_NOT_DECODED` if `*residual` was never decoded.
///
/// # Safety
/// `physics` must be null or point to an initialised `HcmExtendedLaw`; `residual`
/// null or an initialised `HcmResidual` (zeroed, or passed to `hcm_residual_decode`)
/// not written during the call; `out` null or writable memory for one
/// `HcmHybridForce`.
#[no_mangle]
pub unsafe extern "C" fn hcm_hybrid_force(
    physics: *const HcmExtendedLaw,
    residual: *const HcmResidual,
    contact: HcmContact,
    out: *mut HcmHybridForce,
) -> HcmStatus {
    guard(|| {
        // SAFETY: the caller's contract above.
        let law = unsafe { input(physics) }?.to_core()?;
        // SAFETY: the caller's contract above.
        let network = unsafe { network(residual) }?;
        let out = checked_mut(out)?;
        let value = match network {
            Network::F32(mlp) => evaluate(law, mlp, &mlp.envelope, &contact),
            Network::Int8(mlp) => evaluate(law, mlp, &mlp.envelope, &contact),
        };
        // SAFETY: non-null and aligned (checked), writable (contract).
        unsafe { out.write(value) };
        Ok(())
    })
}

/// `ContactModel::normal_force` of `law` with residual `residual`.
fn evaluate<R: Residual<f32>>(
    law: hcm_core::effect::ExtendedLaw<f32>,
    residual: &R,
    envelope: &Envelope<HCM_RESIDUAL_INPUTS>,
    contact: &HcmContact,
) -> HcmHybridForce {
    let model = ContactModel::physics(law).with_residual(residual);
    let input = [contact.depth, contact.rate, contact.approach_speed];
    let (indentation, memory) = (contact.indentation(), contact.memory());
    let (force, evaluated) = model.normal_force(&indentation, &memory, &input);
    HcmHybridForce {
        force,
        physics: model.physics_normal_force(&indentation, &memory),
        residual_used: evaluated == Evaluated::PhysicsAndResidual,
        outside_envelope: outside(envelope, &input),
    }
}

/// The bit mask of the inputs beyond `envelope`'s tolerated bounds (NaN counts as
/// beyond), from the core's [`Envelope::distances`]: bit i for input i (at most 32
/// inputs).
pub(crate) fn outside<const INPUTS: usize>(
    envelope: &Envelope<INPUTS>,
    input: &[f32; INPUTS],
) -> u32 {
    const { assert!(INPUTS <= 32) };
    envelope
        .distances(input)
        .iter()
        .enumerate()
        .filter(|(_, distance)| **distance != 0.0)
        .fold(0, |mask, (i, _)| mask | 1 << i)
}
