//! Two spheres, e.g. two balls or a ball and a strongly curved fingertip.

use super::{hertz_stiffness as stiffness_of, ContactGeometry, Material};
use crate::Real;
use nalgebra::Vector3;

/// Effective radius R = R1·R2 / (R1 + R2) (m) of Eq 3.
pub fn effective_radius<T: Real>(radius_1: T, radius_2: T) -> T {
    (radius_1 * radius_2 / (radius_1 + radius_2)).saturate()
}

/// Hertz stiffness of two spheres, Eq 3: k = 4/3 · E* · √(R1·R2/(R1 + R2)) (N/m^1.5).
pub fn hertz_stiffness<T: Real>(
    body_1: &Material<T>,
    body_2: &Material<T>,
    radius_1: T,
    radius_2: T,
) -> T {
    stiffness_of(
        super::effective_modulus(body_1, body_2),
        effective_radius(radius_1, radius_2),
    )
}

/// Overlap of sphere 1 (`center_1` (m), `radius_1` (m)) with sphere 2.
///
/// The normal points from centre 2 to centre 1. Coincident centres have no defined
/// normal: the result then uses +z, with the full depth r1 + r2. NaN centres give
/// +z and a NaN depth. One contact, so `feature` is 0.
pub fn contact<T: Real>(
    center_1: &Vector3<T>,
    radius_1: T,
    center_2: &Vector3<T>,
    radius_2: T,
) -> ContactGeometry<T> {
    let offset = center_1 - center_2;
    let distance = offset.norm_squared().square_root();
    let normal = if distance > T::zero() && distance < T::MAX {
        offset / distance
    } else {
        Vector3::z()
    };
    let depth = (radius_1 + radius_2 - distance).saturate();
    ContactGeometry {
        depth,
        normal,
        point: center_1 - normal * (radius_1 - T::of(0.5) * depth),
        feature: 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overlapping_spheres_share_a_midpoint() {
        let c = contact(
            &Vector3::new(0.0, 0.0, 1.9_f64),
            1.0,
            &Vector3::zeros(),
            1.0,
        );
        assert!((c.depth - 0.1).abs() < 1e-12);
        assert!((c.normal - Vector3::z()).norm() < 1e-12);
        assert!((c.point - Vector3::new(0.0, 0.0, 0.95)).norm() < 1e-12);
    }

    #[test]
    fn coincident_centres_do_not_panic() {
        let c = contact(&Vector3::zeros(), 1.0_f32, &Vector3::zeros(), 2.0);
        assert_eq!(c.depth, 3.0);
        assert_eq!(c.normal, Vector3::z());
    }
}
