//! The tangential effects a contact may add to its dry friction law.

use super::{RollingResistance, TorsionalResistance, ViscousFriction};
use crate::{LawError, Real};
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

/// Tangential effects beside the dry friction of Eq 10–11, each at most once; all
/// absent by default. They act only at touching points (f_n ≠ 0), like friction.
///
/// Written in a scenario as `tangential = { viscous_friction = { coefficient = 0.5 },
/// torsional_resistance = { arm = 2e-3, spin_rate = 0.1 } }`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TangentialEffects<T> {
    /// Viscous friction −c_v·**v_t**.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub viscous_friction: Option<ViscousFriction<T>>,
    /// A couple against the relative spin about the normal.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub torsional_resistance: Option<TorsionalResistance<T>>,
    /// A couple against the relative rotation about tangent axes.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rolling_resistance: Option<RollingResistance<T>>,
}

impl<T> Default for TangentialEffects<T> {
    /// No effect.
    fn default() -> Self {
        TangentialEffects {
            viscous_friction: None,
            torsional_resistance: None,
            rolling_resistance: None,
        }
    }
}

impl<T: Real> TangentialEffects<T> {
    /// True when no effect is present.
    pub fn is_empty(&self) -> bool {
        self.viscous_friction.is_none()
            && self.torsional_resistance.is_none()
            && self.rolling_resistance.is_none()
    }

    /// The extra force on body 1 (N) at a point sliding with `slip` (m/s, tangential).
    #[inline]
    pub fn force(&self, slip: &Vector3<T>) -> Vector3<T> {
        self.viscous_friction
            .map_or_else(Vector3::zeros, |effect| effect.force(slip))
    }

    /// The couple on body 1 (N·m) at a point with normal force f_n (N), unit `normal`
    /// and relative angular velocity `omega` (rad/s).
    #[inline]
    pub fn couple(&self, omega: &Vector3<T>, normal: &Vector3<T>, normal_force: T) -> Vector3<T> {
        let mut couple = Vector3::zeros();
        if let Some(effect) = &self.torsional_resistance {
            couple += effect.couple(omega, normal, normal_force);
        }
        if let Some(effect) = &self.rolling_resistance {
            couple += effect.couple(omega, normal, normal_force);
        }
        couple
    }

    /// The extra friction force and the couple on body 1 (N, N·m) at a touching point:
    /// relative velocity `velocity` (m/s; its part along the unit `normal` is not
    /// slip), relative angular velocity `omega` (rad/s), normal force f_n (N).
    pub fn point_loads(
        &self,
        velocity: &Vector3<T>,
        omega: &Vector3<T>,
        normal: &Vector3<T>,
        normal_force: T,
    ) -> (Vector3<T>, Vector3<T>) {
        let slip = velocity - normal * velocity.dot(normal);
        (self.force(&slip), self.couple(omega, normal, normal_force))
    }

    /// `Ok` if every present effect's parameters are in their domains.
    pub fn validate(&self) -> Result<(), LawError> {
        self.viscous_friction.map_or(Ok(()), |e| e.validate())?;
        self.torsional_resistance.map_or(Ok(()), |e| e.validate())?;
        self.rolling_resistance.map_or(Ok(()), |e| e.validate())
    }
}

impl<T: Copy> TangentialEffects<T> {
    /// The same effects with every parameter passed through `f` (e.g. a float cast).
    pub fn map<U>(self, f: impl Fn(T) -> U + Copy) -> TangentialEffects<U> {
        TangentialEffects {
            viscous_friction: self.viscous_friction.map(|e| e.map(f)),
            torsional_resistance: self.torsional_resistance.map(|e| e.map(f)),
            rolling_resistance: self.rolling_resistance.map(|e| e.map(f)),
        }
    }
}
