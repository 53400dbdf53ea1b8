//! Resistance of a contact to the bodies' relative rotation: a couple, not a force.

use crate::error::{require_non_negative, require_positive};
use crate::{LawError, Real};
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

/// Torsional resistance: a couple about the normal opposing the bodies' relative spin
/// about it, τ = −a_t·|f_n|·ω_n/√(ω_n² + ω_t²)·**n**, with ω_n = **ω**·**n** the
/// relative spin (rad/s): smooth, zero at zero spin, a_t·|f_n| once |ω_n| ≫ ω_t (a
/// regularised dry couple, as Eq 11 regularises dry friction).
///
/// A contact patch of finite size spinning on a surface: dry friction over the patch
/// gives a couple of about μ·f_n times the patch's mean radius, which a point contact
/// law does not have.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TorsionalResistance<T> {
    /// Couple per unit normal force a_t (m): μ times the patch's effective radius.
    pub arm: T,
    /// Spin rate ω_t (rad/s) below which the couple fades (to 71 % at ω_t).
    pub spin_rate: T,
}

/// Rolling resistance: a couple opposing the bodies' relative rotation about axes in
/// the tangent plane, τ = −a_r·|f_n|·**ω_r**/√(|**ω_r**|² + ω_0²), with **ω_r** = **ω** −
/// (**ω**·**n**)·**n** (rad/s), regularised as [`TorsionalResistance`].
///
/// Hysteresis in the material ahead of and behind a rolling contact shifts the normal
/// pressure forwards; its moment about the contact opposes rolling.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RollingResistance<T> {
    /// Couple per unit normal force a_r (m): how far forward the pressure centre moves.
    pub arm: T,
    /// Rolling rate ω_0 (rad/s) below which the couple fades (to 71 % at ω_0).
    pub roll_rate: T,
}

crate::law::map_fields!(TorsionalResistance { arm, spin_rate });
crate::law::map_fields!(RollingResistance { arm, roll_rate });

/// −a·|f_n|·**ω**/√(|**ω**|² + ω_0²): a couple of magnitude up to a·|f_n| opposing
/// **ω**, smooth through zero rotation, where it vanishes; NaN in gives NaN out.
/// Out of line: one copy serves both couples (flash on a controller).
#[inline(never)]
fn opposing_couple<T: Real>(
    rotation: &Vector3<T>,
    arm: T,
    full_rate: T,
    normal_force: T,
) -> Vector3<T> {
    let scale = (rotation.norm_squared() + full_rate * full_rate).square_root();
    // Saturated before it multiplies: no rotation stays no couple, even at f_n = ∞.
    rotation * (-arm * normal_force.abs() / scale).saturate()
}

impl<T: Real> TorsionalResistance<T> {
    /// The catalogue name.
    pub const NAME: &'static str = "torsional_resistance";

    /// Couple on body 1 (N·m) for relative angular velocity `omega` (rad/s, body 1
    /// minus body 2), unit `normal` and normal force f_n (N).
    #[inline]
    pub fn couple(&self, omega: &Vector3<T>, normal: &Vector3<T>, normal_force: T) -> Vector3<T> {
        let spin = normal * omega.dot(normal);
        opposing_couple(&spin, self.arm, self.spin_rate, normal_force)
    }

    /// Checks a_t ≥ 0 and ω_t > 0, both finite.
    pub fn validate(&self) -> Result<(), LawError> {
        require_non_negative(self.arm, "torsional_resistance.arm")?;
        require_positive(self.spin_rate, "torsional_resistance.spin_rate")
    }
}

impl<T: Real> RollingResistance<T> {
    /// The catalogue name.
    pub const NAME: &'static str = "rolling_resistance";

    /// Couple on body 1 (N·m), as [`TorsionalResistance::couple`], against the
    /// rotation about tangent axes.
    #[inline]
    pub fn couple(&self, omega: &Vector3<T>, normal: &Vector3<T>, normal_force: T) -> Vector3<T> {
        let rolling = omega - normal * omega.dot(normal);
        opposing_couple(&rolling, self.arm, self.roll_rate, normal_force)
    }

    /// Checks a_r ≥ 0 and ω_0 > 0, both finite.
    pub fn validate(&self) -> Result<(), LawError> {
        require_non_negative(self.arm, "rolling_resistance.arm")?;
        require_positive(self.roll_rate, "rolling_resistance.roll_rate")
    }
}
