//! Velocity-based friction with STEP transitions (MSC ADAMS style), Eq 10–11.

use crate::error::{require_non_negative, require_positive};
use crate::law::step;
use crate::{vector, LawError, Real};
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

/// Velocity-based friction, Eq 10–11:
/// f_f = −μ(v)·|f_n|·**v**/v with **v** the slip velocity (tangential part only) and
///
/// μ(v) = step(v, 0, 0, v_s, μ_s) for v < v_s,
///        step(v, v_s, μ_s, v_d, μ_d) for v_s ≤ v ≤ v_d,
///        μ_d for v > v_d.
///
/// μ(0) = 0 and μ is continuous, so the force goes smoothly to zero at zero slip: the
/// v/‖v‖ guard of Eq 10 (misprint 4 of the reference) returns a zero force there.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct VelocityStepFriction<T> {
    /// Static friction coefficient μ_s (dimensionless).
    pub static_coefficient: T,
    /// Dynamic friction coefficient μ_d (dimensionless).
    pub dynamic_coefficient: T,
    /// Stiction transition speed v_s (m/s), where μ peaks at μ_s.
    pub stiction_speed: T,
    /// Friction transition speed v_d (m/s), above which μ = μ_d.
    pub dynamic_speed: T,
}

crate::law::map_fields!(VelocityStepFriction {
    static_coefficient,
    dynamic_coefficient,
    stiction_speed,
    dynamic_speed
});

impl<T: Real> VelocityStepFriction<T> {
    /// Friction coefficient μ(v) of Eq 11 at slip speed v (m/s), dimensionless.
    ///
    /// Even in v (uses |v|). Bounded by max(μ_s, μ_d) for any v; NaN gives NaN.
    #[inline]
    pub fn coefficient(&self, slip_speed: T) -> T {
        let v = slip_speed.abs();
        if v < self.stiction_speed {
            step(
                v,
                T::zero(),
                T::zero(),
                self.stiction_speed,
                self.static_coefficient,
            )
        } else {
            let (vs, vd) = (self.stiction_speed, self.dynamic_speed);
            step(v, vs, self.static_coefficient, vd, self.dynamic_coefficient)
        }
    }

    /// Friction force f_f (N) of Eq 10 on body 1.
    ///
    /// `relative_velocity` (m/s) is the velocity of body 1's contact point relative to
    /// body 2's; its component along `normal` (unit, body 2 → body 1) is removed first,
    /// so the result is always perpendicular to the normal. `normal_force` f_n (N)
    /// enters by magnitude. Zero slip (or a slip speed that is not finite) gives a zero
    /// force; NaN in the velocity or force gives NaN components.
    pub fn force(
        &self,
        relative_velocity: &Vector3<T>,
        normal: &Vector3<T>,
        normal_force: T,
    ) -> Vector3<T> {
        // Written out per component (`crate::vector`, nalgebra's operation order, the
        // same bits): nalgebra's generic loops took the controller several times the
        // arithmetic.
        let along = vector::dot(relative_velocity, normal);
        let slip = vector::sub(relative_velocity, &vector::scale(normal, along));
        // ‖slip‖ as nalgebra's `norm`: √((x² + y²) + z²).
        let speed = vector::dot(&slip, &slip).square_root();
        if speed.is_nan() || normal_force.is_nan() {
            return Vector3::repeat(speed + normal_force);
        }
        match speed.positive() {
            Some(speed) => {
                let magnitude = (self.coefficient(speed) * normal_force.abs()).saturate();
                vector::scale(&slip, -magnitude / speed)
            }
            None => Vector3::zeros(),
        }
    }

    /// Checks μ_s, μ_d ≥ 0 and 0 < v_s ≤ v_d.
    pub fn validate(&self) -> Result<(), LawError> {
        require_non_negative(self.static_coefficient, "static_coefficient")?;
        require_non_negative(self.dynamic_coefficient, "dynamic_coefficient")?;
        require_positive(self.stiction_speed, "stiction_speed")?;
        require_positive(self.dynamic_speed, "dynamic_speed")?;
        if self.dynamic_speed < self.stiction_speed {
            return Err(LawError::OutOfRange {
                parameter: "dynamic_speed",
                allowed: "[stiction_speed, ∞)",
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn adams_defaults() -> VelocityStepFriction<f64> {
        VelocityStepFriction {
            static_coefficient: 0.3,
            dynamic_coefficient: 0.1,
            stiction_speed: 1e-4,
            dynamic_speed: 1e-2,
        }
    }

    #[test]
    fn zero_slip_gives_zero_force() {
        let f = adams_defaults().force(&Vector3::zeros(), &Vector3::z(), 100.0);
        assert_eq!(f, Vector3::zeros());
    }

    #[test]
    fn normal_velocity_is_not_slip() {
        let f = adams_defaults().force(&Vector3::new(0.0, 0.0, -3.0), &Vector3::z(), 100.0);
        assert_eq!(f, Vector3::zeros());
    }

    #[test]
    fn peaks_at_the_stiction_speed() {
        let law = adams_defaults();
        assert_eq!(law.coefficient(1e-4), 0.3);
        assert_eq!(law.coefficient(1.0), 0.1);
        assert!(law.coefficient(5e-5) < 0.3 && law.coefficient(5e-5) > 0.0);
    }
}
