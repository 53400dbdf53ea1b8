//! Normal contact laws: f_n(δ, δ̇) for one contact (paper Section 3.1, Eq 2–9).
//!
//! One law per file. Each is a small `Copy` value holding its parameters, implements
//! [`NormalLaw`], and has a `validate` that says which parameter is out of its domain.
//! Each lists its parameters (`PARAMETERS`: name, unit, meaning) and reads and
//! writes them by name or as a fixed-size array, with no serialisation;
//! [`LawKind`] is the one list of the laws' names.
//!
//! ## Holding "some law"
//!
//! Two ways, for two callers:
//! - the [`NormalLaw`] trait, for code that is generic over the law and wants static
//!   dispatch in its hot loop (a simulator monomorphised per law);
//! - the [`AnyNormalLaw`] enum, for code that picks the law at run time (a
//!   controller reading its configuration, a scenario file, the identification loop).
//!
//! The enum, not `dyn NormalLaw`, is the run-time form because a controller has no
//! allocator for a `Box`, a trait object cannot be `Copy`, serialised into a weights
//! blob or compared, and the set of laws is closed and known here; a `match` over six
//! variants costs less than an indirect call.

mod flores;
mod hertz;
mod hunt_crossley;
mod impact;
mod kind;
mod lankarani_nikravesh;
mod named;
mod parameters;
mod step;
mod variable_stiffness;

pub use flores::Flores;
pub use hertz::Hertz;
pub use hunt_crossley::HuntCrossley;
pub use impact::Impact;
pub use kind::LawKind;
pub use lankarani_nikravesh::LankaraniNikravesh;
pub(crate) use parameters::law_parameters;
pub use parameters::{ParameterInfo, ParameterValues, MAX_PARAMETERS};
pub use step::step;
pub use variable_stiffness::VariableStiffness;

use crate::{LawError, Real};
use serde::{Deserialize, Serialize};

/// The state of one contact that a normal law reads.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Indentation<T> {
    /// Indentation δ (m), > 0 in contact.
    pub depth: T,
    /// Indentation rate δ̇ (m/s), > 0 while approaching.
    pub rate: T,
    /// Approach speed δ̇0 (m/s): the indentation rate when this contact began. Only
    /// Lankarani–Nikravesh and Flores read it.
    pub approach_speed: T,
}

/// A normal contact law: the normal force magnitude for a given indentation state.
pub trait NormalLaw<T: Real>: Copy {
    /// Normal force magnitude f_n (N), > 0 repulsive.
    ///
    /// Exactly zero when δ ≤ 0. NaN in the state or the parameters gives NaN; the
    /// result saturates at ±[`Real::MAX`]. Only [`Impact`] clamps tension to zero;
    /// the others are evaluated as printed and may pull slightly near separation.
    fn normal_force(&self, contact: &Indentation<T>) -> T;

    /// `Ok` if every parameter is in its physical domain, otherwise the first one
    /// that is not.
    fn validate(&self) -> Result<(), LawError>;
}

/// Any of the normal laws of this module, chosen at run time.
///
/// Serialised externally tagged (`{ lankarani_nikravesh = { … } }`) so that it
/// decodes without an allocator.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AnyNormalLaw<T> {
    /// Hertz, Eq 2.
    Hertz(Hertz<T>),
    /// Lankarani–Nikravesh, Eq 4–5.
    LankaraniNikravesh(LankaraniNikravesh<T>),
    /// Variable stiffness, Eq 6–7.
    VariableStiffness(VariableStiffness<T>),
    /// MSC ADAMS IMPACT, Eq 8–9.
    Impact(Impact<T>),
    /// Hunt–Crossley.
    HuntCrossley(HuntCrossley<T>),
    /// Flores et al.
    Flores(Flores<T>),
}

impl<T: Real> AnyNormalLaw<T> {
    /// Elastic (non-dissipative) part of the force (N) at indentation δ (m): the
    /// force at δ̇ = 0 — k·δ^n (Hertz, Lankarani–Nikravesh, Hunt–Crossley, Flores),
    /// k(δ)·δ (variable stiffness, Eq 6–7), k·δ^e (IMPACT). Exactly 0 for δ ≤ 0;
    /// NaN propagates; saturates at [`Real::MAX`].
    #[inline]
    pub fn elastic_force(&self, depth: T) -> T {
        match self {
            AnyNormalLaw::Hertz(law) => Hertz::elastic_force(law.stiffness, law.exponent, depth),
            AnyNormalLaw::LankaraniNikravesh(law) => law.elastic_force(depth),
            AnyNormalLaw::VariableStiffness(law) => law.elastic_force(depth),
            AnyNormalLaw::Impact(law) => law.elastic_force(depth),
            AnyNormalLaw::HuntCrossley(law) => law.elastic_force(depth),
            AnyNormalLaw::Flores(law) => law.elastic_force(depth),
        }
    }
}

impl<T: Copy> AnyNormalLaw<T> {
    /// The same law with every parameter passed through `f` (e.g. a float cast).
    pub fn map<U>(self, f: impl Fn(T) -> U) -> AnyNormalLaw<U> {
        match self {
            AnyNormalLaw::Hertz(law) => AnyNormalLaw::Hertz(law.map(f)),
            AnyNormalLaw::LankaraniNikravesh(law) => AnyNormalLaw::LankaraniNikravesh(law.map(f)),
            AnyNormalLaw::VariableStiffness(law) => AnyNormalLaw::VariableStiffness(law.map(f)),
            AnyNormalLaw::Impact(law) => AnyNormalLaw::Impact(law.map(f)),
            AnyNormalLaw::HuntCrossley(law) => AnyNormalLaw::HuntCrossley(law.map(f)),
            AnyNormalLaw::Flores(law) => AnyNormalLaw::Flores(law.map(f)),
        }
    }
}

impl<T: Real> AnyNormalLaw<T> {
    /// The same law in another float type (f64 → f32 rounds each parameter).
    pub fn cast<U: Real>(self) -> AnyNormalLaw<U> {
        self.map(Real::cast)
    }
}

impl<T: Real> NormalLaw<T> for AnyNormalLaw<T> {
    #[inline]
    fn normal_force(&self, contact: &Indentation<T>) -> T {
        match self {
            AnyNormalLaw::Hertz(law) => law.normal_force(contact),
            AnyNormalLaw::LankaraniNikravesh(law) => law.normal_force(contact),
            AnyNormalLaw::VariableStiffness(law) => law.normal_force(contact),
            AnyNormalLaw::Impact(law) => law.normal_force(contact),
            AnyNormalLaw::HuntCrossley(law) => law.normal_force(contact),
            AnyNormalLaw::Flores(law) => law.normal_force(contact),
        }
    }

    fn validate(&self) -> Result<(), LawError> {
        match self {
            AnyNormalLaw::Hertz(law) => law.validate(),
            AnyNormalLaw::LankaraniNikravesh(law) => law.validate(),
            AnyNormalLaw::VariableStiffness(law) => law.validate(),
            AnyNormalLaw::Impact(law) => law.validate(),
            AnyNormalLaw::HuntCrossley(law) => law.validate(),
            AnyNormalLaw::Flores(law) => law.validate(),
        }
    }
}

/// `map` for a law struct: the same law with every field passed through `f`.
macro_rules! map_fields {
    ($law:ident { $($field:ident),* }) => {
        impl<T: Copy> $law<T> {
            /// The same law with every parameter passed through `f` (e.g. a float cast).
            pub fn map<U>(self, f: impl Fn(T) -> U) -> $law<U> {
                $law { $($field: f(self.$field)),* }
            }
        }
    };
}
pub(crate) use map_fields;

macro_rules! into_any {
    ($($law:ident),*) => {$(
        impl<T> From<$law<T>> for AnyNormalLaw<T> {
            fn from(law: $law<T>) -> Self {
                AnyNormalLaw::$law(law)
            }
        }
    )*};
}
into_any!(
    Hertz,
    LankaraniNikravesh,
    VariableStiffness,
    Impact,
    HuntCrossley,
    Flores
);

/// True unless δ ≤ 0: NaN counts as "in contact" so that it reaches the formula and
/// propagates instead of silently becoming a zero force.
#[inline]
pub(crate) fn touching<T: Real>(depth: T) -> bool {
    depth > T::zero() || depth.is_nan()
}

/// χ = `coefficient` / δ̇0 (s/m), the velocity scale of the hysteresis laws
/// (LN, Flores). δ̇0 ≤ 0 or +∞ means no damping (χ = 0); NaN propagates.
#[inline]
pub(crate) fn per_approach_speed<T: Real>(coefficient: T, approach_speed: T) -> T {
    if approach_speed.is_nan() {
        approach_speed
    } else if approach_speed > T::zero() && approach_speed < T::MAX {
        (coefficient / approach_speed).saturate()
    } else {
        T::zero()
    }
}
