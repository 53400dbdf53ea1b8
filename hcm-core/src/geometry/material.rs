//! Elastic materials and their combined (effective) modulus.

use crate::error::require_positive;
use crate::{LawError, Real};
use serde::{Deserialize, Serialize};

/// An isotropic linear-elastic material.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Material<T> {
    /// Young's modulus E (Pa).
    pub youngs_modulus: T,
    /// Poisson's ratio ν (dimensionless, −1 < ν < 0.5).
    pub poisson_ratio: T,
}

impl<T: Real> Material<T> {
    /// The range of Poisson's ratio ν allowed, as [`LawError::OutOfRange`] shows it.
    pub const POISSON_RATIO_RANGE: &'static str = "(-1, 0.5)";

    /// Checks that the material is physically possible: E finite and > 0, and
    /// −1 < ν < 0.5 — the open range where an isotropic linear-elastic material is
    /// stable (positive bulk and shear moduli, K = E/(3(1 − 2ν)) and G = E/(2(1 + ν))).
    ///
    /// At ν = 0.5 (incompressible) and beyond, or at ν ≤ −1, the strain energy is not
    /// positive-definite; [`effective_modulus`] would still return a number, just not
    /// a meaningful one. NaN and ±∞ fail.
    pub fn validate(&self) -> Result<(), LawError> {
        require_positive(self.youngs_modulus, "youngs_modulus")?;
        let nu = self.poisson_ratio;
        if nu > -T::one() && nu < T::of(0.5) {
            Ok(())
        } else {
            Err(LawError::OutOfRange {
                parameter: "poisson_ratio",
                allowed: Self::POISSON_RATIO_RANGE,
            })
        }
    }
}

/// Effective modulus E* = E1·E2 / (E1·(1 − ν2²) + E2·(1 − ν1²)) (Pa), the material
/// factor shared by Eq 3 and Eq 7 (without Eq 3's 4/3).
///
/// Equivalent to 1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2. Two zero moduli give NaN; the
/// result saturates at ±[`Real::MAX`].
pub fn effective_modulus<T: Real>(body_1: &Material<T>, body_2: &Material<T>) -> T {
    let (e1, e2) = (body_1.youngs_modulus, body_2.youngs_modulus);
    let (nu1, nu2) = (body_1.poisson_ratio, body_2.poisson_ratio);
    let one = T::one();
    (e1 * e2 / (e1 * (one - nu2 * nu2) + e2 * (one - nu1 * nu1))).saturate()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steel_on_concrete_matches_the_reference() {
        let steel = Material {
            youngs_modulus: 2.06e11,
            poisson_ratio: 0.3,
        };
        let concrete = Material {
            youngs_modulus: 2.5193e10,
            poisson_ratio: 0.25,
        };
        // docs/reconstruction.md: c·E* = 4.804e10 Pa with c = 2.
        let e_star: f64 = effective_modulus(&steel, &concrete);
        assert!((2.0 * e_star / 4.804e10 - 1.0).abs() < 1e-4, "{e_star}");
    }

    #[test]
    fn validate_accepts_real_materials_and_refuses_impossible_ones() {
        let steel = Material {
            youngs_modulus: 2.06e11_f64,
            poisson_ratio: 0.3,
        };
        assert_eq!(steel.validate(), Ok(()));
        // Auxetic foams have ν < 0: possible down to (but not including) −1.
        let auxetic = Material {
            poisson_ratio: -0.9,
            ..steel
        };
        assert_eq!(auxetic.validate(), Ok(()));
        let poisson = LawError::OutOfRange {
            parameter: "poisson_ratio",
            allowed: "(-1, 0.5)",
        };
        for nu in [0.5, 0.6, -1.0, -1.5, f64::NAN, f64::INFINITY] {
            let material = Material {
                poisson_ratio: nu,
                ..steel
            };
            assert_eq!(material.validate(), Err(poisson), "ν = {nu}");
        }
        let modulus = LawError::NotPositive {
            parameter: "youngs_modulus",
        };
        for e in [0.0, -2.06e11, f64::NAN, f64::INFINITY] {
            let material = Material {
                youngs_modulus: e,
                ..steel
            };
            assert_eq!(material.validate(), Err(modulus), "E = {e}");
        }
        // f32, as a controller would hold it.
        let light = Material {
            youngs_modulus: 7.0e10_f32,
            poisson_ratio: 0.499,
        };
        assert_eq!(light.validate(), Ok(()));
    }

    #[test]
    fn symmetric_in_the_two_bodies() {
        let a = Material {
            youngs_modulus: 7.0e10_f64,
            poisson_ratio: 0.33,
        };
        let b = Material {
            youngs_modulus: 2.1e11_f64,
            poisson_ratio: 0.29,
        };
        assert_eq!(effective_modulus(&a, &b), effective_modulus(&b, &a));
    }
}
