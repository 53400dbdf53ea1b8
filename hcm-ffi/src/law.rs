//! The physics from C: a normal law (Eq 2–9) and the extended law (a law plus the
//! catalogued effects) as plain structs of integers and floats, and their force for
//! one contact.
//!
//! A law is a kind (`HCM_LAW_*`) and its parameters in the core's order
//! (`hcm_core::law::LawKind::parameters`), SI units; an effect likewise
//! (`HCM_EFFECT_*`). Evaluation is literal, as in the core: parameters outside their
//! physical domain give odd forces, not errors. Check them once, at configuration
//! time, with `hcm_law_validate` / `hcm_extended_law_validate`.

use crate::boundary::{checked_mut, guard, input};
use crate::HcmStatus;
use hcm_core::effect::{
    Adhesion, ContactEffect, ContactMemory, ExtendedLaw, HysteresisDamping, Plasticity,
    StiffnessExponent, ViscousDamping, MAX_EFFECTS,
};
use hcm_core::law::{AnyNormalLaw, Indentation, LawKind, NormalLaw, MAX_PARAMETERS};

/// Most parameters of one law or effect (the length of every `parameters` array).
pub const HCM_MAX_PARAMETERS: usize = 5;
/// Most effects one `HcmExtendedLaw` holds.
pub const HCM_MAX_EFFECTS: usize = 4;
const _: () = assert!(HCM_MAX_PARAMETERS == MAX_PARAMETERS && HCM_MAX_EFFECTS == MAX_EFFECTS);

/// Which normal law: one of the `HCM_LAW_*` constants.
pub type HcmLawKind = u32;
/// Hertz, Eq 2: stiffness k (N/m^n), exponent n (-).
pub const HCM_LAW_HERTZ: HcmLawKind = 0;
/// Lankarani–Nikravesh, Eq 4–5: stiffness k (N/m^n), exponent n (-), restitution ce (-).
pub const HCM_LAW_LANKARANI_NIKRAVESH: HcmLawKind = 1;
/// Variable stiffness, Eq 6–7: surface loading c (-), effective modulus E* (Pa),
/// radius r (m), damping λ (1/m), effective mass m_e (kg).
pub const HCM_LAW_VARIABLE_STIFFNESS: HcmLawKind = 2;
/// MSC ADAMS IMPACT, Eq 8–9: stiffness k (N/m^e), exponent e (-), maximum damping
/// d_max (N·s/m), depth of full damping δ_max (m).
pub const HCM_LAW_IMPACT: HcmLawKind = 3;
/// Hunt–Crossley: stiffness k (N/m^n), exponent n (-), damping factor χ (s/m).
pub const HCM_LAW_HUNT_CROSSLEY: HcmLawKind = 4;
/// Flores et al.: stiffness k (N/m^n), exponent n (-), restitution ce (-).
pub const HCM_LAW_FLORES: HcmLawKind = 5;

/// Which contact effect: one of the `HCM_EFFECT_*` constants.
pub type HcmEffectKind = u32;
/// Viscous damping c·δ̇: coefficient c (N·s/m).
pub const HCM_EFFECT_VISCOUS_DAMPING: HcmEffectKind = 0;
/// Hysteresis damping c·δ^p·δ̇: coefficient c (N·s/m^(1+p)), exponent p (-).
pub const HCM_EFFECT_HYSTERESIS_DAMPING: HcmEffectKind = 1;
/// Stiffness exponent change: Δ (-), reference depth δ_ref (m).
pub const HCM_EFFECT_STIFFNESS_EXPONENT: HcmEffectKind = 2;
/// Adhesion −a: pull-off force a (N).
pub const HCM_EFFECT_ADHESION: HcmEffectKind = 3;
/// Plasticity: permanent ratio ρ = δ_p/δ_max (-); reads `HcmContact::max_depth`.
pub const HCM_EFFECT_PLASTICITY: HcmEffectKind = 4;

/// A normal law and its parameters.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HcmLaw {
    /// `HCM_LAW_*`.
    pub kind: HcmLawKind,
    /// The law's parameters in the order its `HCM_LAW_*` constant lists, SI units;
    /// the entries after the law's count are ignored.
    pub parameters: [f32; HCM_MAX_PARAMETERS],
}

/// A contact effect and its parameters.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HcmEffect {
    /// `HCM_EFFECT_*`.
    pub kind: HcmEffectKind,
    /// The effect's parameters in the order its `HCM_EFFECT_*` constant lists; the
    /// entries after the effect's count are ignored.
    pub parameters: [f32; HCM_MAX_PARAMETERS],
}

/// A base law plus up to `HCM_MAX_EFFECTS` effects (the core's `ExtendedLaw`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HcmExtendedLaw {
    /// The law the effects add to.
    pub base: HcmLaw,
    /// How many entries of `effects` apply, 0 to `HCM_MAX_EFFECTS`.
    pub effect_count: u32,
    /// The effects, in order; those after `effect_count` are ignored.
    pub effects: [HcmEffect; HCM_MAX_EFFECTS],
}

/// The state of one contact (paper conventions: δ > 0 in contact, δ̇ > 0 approaching).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HcmContact {
    /// Indentation δ (m).
    pub depth: f32,
    /// Indentation rate δ̇ (m/s).
    pub rate: f32,
    /// Approach speed δ̇0 (m/s): δ̇ when this contact began.
    pub approach_speed: f32,
    /// Deepest indentation δ_max (m) of this contact so far; read only by plasticity.
    pub max_depth: f32,
}

impl HcmLaw {
    /// The core's law; [`HcmStatus::BadParameter`] for an unknown kind.
    pub fn to_core(&self) -> Result<AnyNormalLaw<f32>, HcmStatus> {
        let kind = usize::try_from(self.kind)
            .ok()
            .and_then(|at| LawKind::ALL.get(at))
            .ok_or(HcmStatus::BadParameter)?;
        let values = self
            .parameters
            .get(..kind.parameters().len())
            .ok_or(HcmStatus::BadParameter)?;
        AnyNormalLaw::from_values(*kind, values).map_err(|_| HcmStatus::BadParameter)
    }
}

impl HcmEffect {
    /// The core's effect; [`HcmStatus::BadParameter`] for an unknown kind.
    pub fn to_core(&self) -> Result<ContactEffect<f32>, HcmStatus> {
        let [a, b, ..] = self.parameters;
        Ok(match self.kind {
            HCM_EFFECT_VISCOUS_DAMPING => ViscousDamping::from_array([a]).into(),
            HCM_EFFECT_HYSTERESIS_DAMPING => HysteresisDamping::from_array([a, b]).into(),
            HCM_EFFECT_STIFFNESS_EXPONENT => StiffnessExponent::from_array([a, b]).into(),
            HCM_EFFECT_ADHESION => Adhesion::from_array([a]).into(),
            HCM_EFFECT_PLASTICITY => Plasticity::from_array([a]).into(),
            _ => return Err(HcmStatus::BadParameter),
        })
    }
}

impl HcmExtendedLaw {
    /// The core's extended law; [`HcmStatus::BadParameter`] for an unknown kind or
    /// more than [`HCM_MAX_EFFECTS`] effects.
    pub fn to_core(&self) -> Result<ExtendedLaw<f32>, HcmStatus> {
        let count = usize::try_from(self.effect_count).map_err(|_| HcmStatus::BadParameter)?;
        let effects = self.effects.get(..count).ok_or(HcmStatus::BadParameter)?;
        let mut law = ExtendedLaw::new(self.base.to_core()?);
        for effect in effects {
            law.effects
                .push(effect.to_core()?)
                .map_err(|_| HcmStatus::BadParameter)?;
        }
        Ok(law)
    }
}

impl HcmContact {
    /// The core's indentation state.
    pub fn indentation(&self) -> Indentation<f32> {
        Indentation {
            depth: self.depth,
            rate: self.rate,
            approach_speed: self.approach_speed,
        }
    }

    /// The core's contact memory.
    pub fn memory(&self) -> ContactMemory<f32> {
        ContactMemory {
            max_depth: self.max_depth,
        }
    }
}

/// The normal force f_n (N, > 0 repulsive) of `law` at `contact`, into `*force`.
///
/// Exactly 0 for δ ≤ 0; NaN in gives NaN out. `HCM_STATUS_BAD_PARAMETER` for an
/// unknown law kind.
///
/// # Safety
/// `law` must be null or point to an initialised `HcmLaw`; `force` must be null or
/// point to writable memory for one `float`.
#[no_mangle]
pub unsafe extern "C" fn hcm_law_force(
    law: *const HcmLaw,
    contact: HcmContact,
    force: *mut f32,
) -> HcmStatus {
    guard(|| {
        // SAFETY: the caller's contract above.
        let law = unsafe { input(law) }?.to_core()?;
        let force = checked_mut(force)?;
        let value = law.normal_force(&contact.indentation());
        // SAFETY: `force` is non-null and aligned (checked) and writable (contract).
        unsafe { force.write(value) };
        Ok(())
    })
}

/// The normal force f_n (N) of the extended `law` (base law + effects) at `contact`,
/// into `*force`: exactly 0 for δ ≤ 0, as the core's contact model.
///
/// # Safety
/// `law` must be null or point to an initialised `HcmExtendedLaw`; `force` must be
/// null or point to writable memory for one `float`.
#[no_mangle]
pub unsafe extern "C" fn hcm_extended_law_force(
    law: *const HcmExtendedLaw,
    contact: HcmContact,
    force: *mut f32,
) -> HcmStatus {
    guard(|| {
        // SAFETY: the caller's contract above.
        let law = unsafe { input(law) }?.to_core()?;
        let force = checked_mut(force)?;
        let model = hcm_core::model::ContactModel::physics(law);
        let value = model.physics_normal_force(&contact.indentation(), &contact.memory());
        // SAFETY: `force` is non-null and aligned (checked) and writable (contract).
        unsafe { force.write(value) };
        Ok(())
    })
}

/// `HCM_STATUS_OK` if every parameter of `law` is in its physical domain,
/// `HCM_STATUS_OUT_OF_DOMAIN` if one is not, `HCM_STATUS_BAD_PARAMETER` for an
/// unknown kind.
///
/// # Safety
/// `law` must be null or point to an initialised `HcmLaw`.
#[no_mangle]
pub unsafe extern "C" fn hcm_law_validate(law: *const HcmLaw) -> HcmStatus {
    guard(|| {
        // SAFETY: the caller's contract above.
        let law = unsafe { input(law) }?.to_core()?;
        law.validate().map_err(|_| HcmStatus::OutOfDomain)
    })
}

/// As `hcm_law_validate`, for the base law and every effect; one kind of effect
/// listed twice is `HCM_STATUS_OUT_OF_DOMAIN` too.
///
/// # Safety
/// `law` must be null or point to an initialised `HcmExtendedLaw`.
#[no_mangle]
pub unsafe extern "C" fn hcm_extended_law_validate(law: *const HcmExtendedLaw) -> HcmStatus {
    guard(|| {
        // SAFETY: the caller's contract above.
        let law = unsafe { input(law) }?.to_core()?;
        law.validate().map_err(|_| HcmStatus::OutOfDomain)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn law_constants_follow_the_core_catalogue() {
        let named = [
            (HCM_LAW_HERTZ, "hertz"),
            (HCM_LAW_LANKARANI_NIKRAVESH, "lankarani_nikravesh"),
            (HCM_LAW_VARIABLE_STIFFNESS, "variable_stiffness"),
            (HCM_LAW_IMPACT, "impact"),
            (HCM_LAW_HUNT_CROSSLEY, "hunt_crossley"),
            (HCM_LAW_FLORES, "flores"),
        ];
        assert_eq!(named.len(), LawKind::ALL.len());
        for (kind, name) in named {
            let law = HcmLaw {
                kind,
                parameters: [1.0, 1.5, 0.9, 0.5, 0.1],
            };
            assert_eq!(law.to_core().unwrap().name(), name);
        }
    }

    #[test]
    fn effect_constants_name_the_effects_and_their_parameters_in_order() {
        let named = [
            (HCM_EFFECT_VISCOUS_DAMPING, "viscous_damping"),
            (HCM_EFFECT_HYSTERESIS_DAMPING, "hysteresis_damping"),
            (HCM_EFFECT_STIFFNESS_EXPONENT, "stiffness_exponent"),
            (HCM_EFFECT_ADHESION, "adhesion"),
            (HCM_EFFECT_PLASTICITY, "plasticity"),
        ];
        for (kind, name) in named {
            let parameters = [1.0, 2.0, 3.0, 4.0, 5.0];
            let effect = HcmEffect { kind, parameters }.to_core().unwrap();
            assert_eq!(effect.name(), name);
            let count = effect.parameters().len();
            assert_eq!(effect.values().as_slice(), &parameters[..count], "{name}");
        }
    }

    #[test]
    fn unknown_kinds_and_too_many_effects_are_bad_parameters() {
        let law = HcmLaw {
            kind: 6,
            parameters: [1.0; 5],
        };
        assert_eq!(law.to_core(), Err(HcmStatus::BadParameter));
        let effect = HcmEffect {
            kind: 5,
            parameters: [1.0; 5],
        };
        assert_eq!(effect.to_core(), Err(HcmStatus::BadParameter));
        let mut extended = HcmExtendedLaw {
            base: HcmLaw { kind: 0, ..law },
            effect_count: 5,
            effects: [HcmEffect { kind: 0, ..effect }; HCM_MAX_EFFECTS],
        };
        assert_eq!(extended.to_core(), Err(HcmStatus::BadParameter));
        extended.effect_count = u32::MAX;
        assert_eq!(extended.to_core(), Err(HcmStatus::BadParameter));
        extended.effect_count = 4;
        assert_eq!(extended.to_core().map(|l| l.effects.len()), Ok(4));
    }
}
