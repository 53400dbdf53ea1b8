//! Physical contact effects a diagnosis names and adds to a base normal law.
//!
//! A fitted base law (Hertz, Lankarani–Nikravesh, …) may miss an effect the measured
//! forces show: damping of another form, a different elastic exponent, adhesion,
//! permanent indentation. Each effect here is one small `Copy` value with its
//! parameters, a `name` (the catalogue name a diagnosis prints), a `validate`, its
//! force, and its parameters by name (`PARAMETERS`, [`ContactEffect::get`], …).
//! [`ExtendedLaw`] is a base law plus up to [`MAX_EFFECTS`] of them; it needs no
//! allocator, so the extended model runs in the controller as well.
//!
//! All but one effect add a term to the base force (N), exactly 0 for δ ≤ 0:
//!
//! | effect                | term                            |
//! |-----------------------|---------------------------------|
//! | [`ViscousDamping`]    | c·δ̇                            |
//! | [`HysteresisDamping`] | c·δ^p·δ̇                        |
//! | [`StiffnessExponent`] | f_el(δ)·((δ/δ_ref)^Δ − 1)        |
//! | [`Adhesion`]          | −a                              |
//!
//! [`Plasticity`] instead moves the indentation the base law sees while unloading,
//! which is why the extended law reads a [`ContactMemory`]. [`AirDrag`] acts on a
//! body in flight, not at a contact, and is not a [`ContactEffect`].

mod adhesion;
mod air_drag;
mod hysteresis_damping;
mod named;
mod plasticity;
mod stiffness_exponent;
mod viscous_damping;

pub use adhesion::Adhesion;
pub use air_drag::AirDrag;
pub use hysteresis_damping::HysteresisDamping;
pub use plasticity::Plasticity;
pub use stiffness_exponent::StiffnessExponent;
pub use viscous_damping::ViscousDamping;

use crate::law::{AnyNormalLaw, Indentation, NormalLaw};
use crate::{LawError, Real};
use serde::{Deserialize, Serialize};

/// Most effects one [`ExtendedLaw`] holds.
pub const MAX_EFFECTS: usize = 4;

/// Any of the contact effects, chosen at run time (like [`AnyNormalLaw`]).
///
/// Serialised externally tagged (`{ viscous_damping = { coefficient = 3.0 } }`),
/// the tag being the effect's [`name`](ContactEffect::name).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ContactEffect<T> {
    /// Kelvin–Voigt damping c·δ̇.
    ViscousDamping(ViscousDamping<T>),
    /// Hunt–Crossley-type damping c·δ^p·δ̇.
    HysteresisDamping(HysteresisDamping<T>),
    /// Elastic exponent changed by Δ about δ_ref.
    StiffnessExponent(StiffnessExponent<T>),
    /// DMT-type constant attraction −a.
    Adhesion(Adhesion<T>),
    /// Permanent indentation ρ·δ_max on unloading.
    Plasticity(Plasticity<T>),
}

impl<T: Real> ContactEffect<T> {
    /// The catalogue name (`"viscous_damping"`, …), the same as the serde tag.
    pub fn name(&self) -> &'static str {
        match self {
            ContactEffect::ViscousDamping(effect) => effect.name(),
            ContactEffect::HysteresisDamping(effect) => effect.name(),
            ContactEffect::StiffnessExponent(effect) => effect.name(),
            ContactEffect::Adhesion(effect) => effect.name(),
            ContactEffect::Plasticity(effect) => effect.name(),
        }
    }

    /// `Ok` if every parameter is in its physical domain, otherwise the first one
    /// that is not (named `effect.field`, e.g. `"adhesion.pull_off_force"`).
    pub fn validate(&self) -> Result<(), LawError> {
        match self {
            ContactEffect::ViscousDamping(effect) => effect.validate(),
            ContactEffect::HysteresisDamping(effect) => effect.validate(),
            ContactEffect::StiffnessExponent(effect) => effect.validate(),
            ContactEffect::Adhesion(effect) => effect.validate(),
            ContactEffect::Plasticity(effect) => effect.validate(),
        }
    }

    /// The term (N) this effect adds to `base` in state `contact`; exactly 0 for
    /// δ ≤ 0, and always 0 for [`Plasticity`], which transforms the state instead.
    #[inline]
    pub fn additive_force(&self, base: &AnyNormalLaw<T>, contact: &Indentation<T>) -> T {
        match self {
            ContactEffect::ViscousDamping(effect) => effect.force(contact),
            ContactEffect::HysteresisDamping(effect) => effect.force(contact),
            ContactEffect::StiffnessExponent(effect) => {
                effect.force(contact.depth, base.elastic_force(contact.depth))
            }
            ContactEffect::Adhesion(effect) => effect.force(contact),
            ContactEffect::Plasticity(_) => T::zero(),
        }
    }

    /// The same effect in another float type (f64 → f32 rounds each parameter).
    pub fn cast<U: Real>(self) -> ContactEffect<U> {
        self.map(Real::cast)
    }
}

impl<T: Copy> ContactEffect<T> {
    /// The same effect with every parameter passed through `f` (e.g. a float cast).
    pub fn map<U>(self, f: impl Fn(T) -> U) -> ContactEffect<U> {
        match self {
            ContactEffect::ViscousDamping(e) => ContactEffect::ViscousDamping(e.map(f)),
            ContactEffect::HysteresisDamping(e) => ContactEffect::HysteresisDamping(e.map(f)),
            ContactEffect::StiffnessExponent(e) => ContactEffect::StiffnessExponent(e.map(f)),
            ContactEffect::Adhesion(e) => ContactEffect::Adhesion(e.map(f)),
            ContactEffect::Plasticity(e) => ContactEffect::Plasticity(e.map(f)),
        }
    }
}

crate::law::into_variants!(
    ContactEffect:
    ViscousDamping,
    HysteresisDamping,
    StiffnessExponent,
    Adhesion,
    Plasticity
);

/// What an effect remembers of the current contact; the caller (the simulator or
/// the controller) keeps one per contact and passes it to every evaluation.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactMemory<T> {
    /// Deepest indentation δ_max (m) reached so far in the current contact.
    pub max_depth: T,
}

impl<T: Real> ContactMemory<T> {
    /// The memory at touch-down: no indentation yet (δ_max = 0 m).
    pub fn touch_down() -> Self {
        ContactMemory {
            max_depth: T::zero(),
        }
    }

    /// Records indentation δ (m) after a step: δ_max ← max(δ_max, δ). A NaN δ makes
    /// δ_max NaN for the rest of the contact, so it is not silently forgotten.
    #[inline]
    pub fn record(&mut self, depth: T) {
        if depth > self.max_depth || depth.is_nan() {
            self.max_depth = depth;
        }
    }
}

/// A base normal law with contact effects added: what `hcm diagnose` proposes.
///
/// f_n = f_base(δ_eff, δ̇) + Σ term_i(δ_eff, δ̇), with δ_eff the indentation after
/// [`Plasticity`] (δ itself without it). Every term sees the same shifted state as
/// the base, so with plasticity the whole contact force — damping and adhesion
/// included — ends at δ = δ_p. With no effects it is the base law exactly.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExtendedLaw<T> {
    /// The law the effects are added to.
    pub base: AnyNormalLaw<T>,
    /// The effects, at most one of each kind (see [`ExtendedLaw::validate`]).
    pub effects: heapless::Vec<ContactEffect<T>, MAX_EFFECTS>,
}

impl<T: Real> ExtendedLaw<T> {
    /// `base` with no effects.
    pub fn new(base: AnyNormalLaw<T>) -> Self {
        ExtendedLaw {
            base,
            effects: heapless::Vec::new(),
        }
    }

    /// Normal force magnitude f_n (N), > 0 repulsive, for contact state `state` and
    /// the contact's `memory` (read only by [`Plasticity`]).
    ///
    /// Effects of one kind listed twice (which `validate` rejects) are applied
    /// literally: terms add up, plasticity transforms compose in order. NaN in the
    /// state, memory or parameters gives NaN; partial sums saturate at ±[`Real::MAX`].
    pub fn normal_force(&self, state: &Indentation<T>, memory: &ContactMemory<T>) -> T {
        // The common case (no effects) is the base law itself: skip the folds.
        if self.effects.is_empty() {
            return self.base.normal_force(state);
        }
        let contact = self
            .effects
            .iter()
            .fold(*state, |contact, effect| match effect {
                ContactEffect::Plasticity(plasticity) => Indentation {
                    depth: plasticity.effective_depth(&contact, memory),
                    ..contact
                },
                _ => contact,
            });
        self.effects
            .iter()
            .fold(self.base.normal_force(&contact), |force, effect| {
                (force + effect.additive_force(&self.base, &contact)).saturate()
            })
    }

    /// `Ok` if the base law and every effect are in their physical domains and no
    /// kind of effect appears twice; otherwise the first problem. A repeated effect
    /// is reported as `OutOfRange` with the effect's name as the parameter.
    pub fn validate(&self) -> Result<(), LawError> {
        self.base.validate()?;
        for (i, effect) in self.effects.iter().enumerate() {
            effect.validate()?;
            if self.effects[..i].iter().any(|e| e.name() == effect.name()) {
                return Err(LawError::OutOfRange {
                    parameter: effect.name(),
                    allowed: "at most one entry of `effects`",
                });
            }
        }
        Ok(())
    }

    /// The same extended law in another float type (f64 → f32 rounds each parameter).
    pub fn cast<U: Real>(&self) -> ExtendedLaw<U> {
        let mut effects = heapless::Vec::new();
        for effect in &self.effects {
            // Same capacity on both sides: the push cannot fail.
            let _ = effects.push(effect.cast());
        }
        ExtendedLaw {
            base: self.base.cast(),
            effects,
        }
    }
}

impl<T: Real> From<AnyNormalLaw<T>> for ExtendedLaw<T> {
    fn from(base: AnyNormalLaw<T>) -> Self {
        ExtendedLaw::new(base)
    }
}

/// `term()`, saturated at ±[`Real::MAX`], while δ > 0; exactly 0 for δ ≤ 0. A NaN δ
/// gives NaN (not a plausible term), even for terms that do not read δ.
#[inline]
fn while_touching<T: Real>(depth: T, term: impl FnOnce() -> T) -> T {
    if depth.is_nan() {
        depth
    } else if depth > T::zero() {
        term().saturate()
    } else {
        T::zero()
    }
}
