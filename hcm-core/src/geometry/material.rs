//! Elastic materials and their combined (effective) modulus.

use crate::Real;
use serde::{Deserialize, Serialize};

/// An isotropic linear-elastic material.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Material<T> {
    /// Young's modulus E (Pa).
    pub youngs_modulus: T,
    /// Poisson's ratio ν (dimensionless, −1 < ν < 0.5).
    pub poisson_ratio: T,
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
        // parameters.md: c·E* = 4.804e10 Pa with c = 2.
        let e_star: f64 = effective_modulus(&steel, &concrete);
        assert!((2.0 * e_star / 4.804e10 - 1.0).abs() < 1e-4, "{e_star}");
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
