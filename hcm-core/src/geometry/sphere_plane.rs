//! A sphere (body 1) against a plane or half-space (body 2), e.g. a ball on the ground.

use super::{ContactGeometry, Material};
use crate::Real;
use nalgebra::Vector3;

/// Hertz stiffness of a sphere of `radius` r (m) on a flat body, Eq 3 with R2 → ∞:
/// k = 4/3 · E* · √r (N/m^1.5).
pub fn hertz_stiffness<T: Real>(sphere: &Material<T>, plane: &Material<T>, radius: T) -> T {
    super::hertz_stiffness(super::effective_modulus(sphere, plane), radius)
}

/// Overlap of a sphere (`center` (m), `radius` (m)) with the half-space behind the
/// plane through `plane_point` (m) with outward `plane_normal` (unit).
///
/// The normal of the result is `plane_normal` (plane → sphere); `depth` is negative
/// when the sphere is clear of the plane (the gap, with its sign flipped). One contact,
/// so `feature` is 0.
pub fn contact<T: Real>(
    center: &Vector3<T>,
    radius: T,
    plane_point: &Vector3<T>,
    plane_normal: &Vector3<T>,
) -> ContactGeometry<T> {
    let height = (center - plane_point).dot(plane_normal);
    let depth = radius - height;
    let half = T::of(0.5);
    ContactGeometry {
        depth,
        normal: *plane_normal,
        point: center - plane_normal * (radius - half * depth),
        feature: 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resting_ball_touches_at_its_lowest_point() {
        let c = contact(
            &Vector3::new(1.0, 2.0, 0.0127_f64),
            0.0127,
            &Vector3::zeros(),
            &Vector3::z(),
        );
        assert!(c.depth.abs() < 1e-15);
        assert!((c.point - Vector3::new(1.0, 2.0, 0.0)).norm() < 1e-15);
    }

    #[test]
    fn stiffness_is_eq3_with_an_infinite_second_radius() {
        let m = Material {
            youngs_modulus: 2.0e11_f64,
            poisson_ratio: 0.3,
        };
        let plane = hertz_stiffness(&m, &m, 0.01);
        let huge = super::super::sphere_sphere::hertz_stiffness(&m, &m, 0.01, 1e12);
        assert!((plane / huge - 1.0).abs() < 1e-9);
    }
}
