//! A cuboid (body 1) against a plane or half-space (body 2), e.g. a cube on the ground.

use super::{ContactGeometry, Contacts, Cuboid};
use crate::model::MAX_POINTS;
use crate::Real;
use nalgebra::Vector3;

/// The vertices of `cuboid` behind the plane through `plane_point` (m) with outward
/// `plane_normal` (unit), one contact per vertex, in vertex order ([`Cuboid::vertex`]).
///
/// Each contact has depth δ = −(signed distance of the vertex from the plane) (m), > 0
/// (a vertex exactly on the plane is not a contact), the normal `plane_normal`
/// (plane → box), and its point at the vertex itself: there the force acts and the
/// slip is measured. A face flat on the plane gives four contacts, an edge two, a
/// corner one; a box entirely behind the plane all eight. NaN inputs give no contacts.
/// `feature` is the vertex index (0..8), stable while that corner stays in contact.
pub fn contacts<T: Real>(
    cuboid: &Cuboid<T>,
    plane_point: &Vector3<T>,
    plane_normal: &Vector3<T>,
) -> Contacts<T> {
    rounded_contacts(cuboid, T::zero(), plane_point, plane_normal)
}

/// [`contacts`] of a box whose edges and corners are rounded to `rounding` (m, ≥ 0):
/// the box `core` (its half extents the outer box's less the rounding) swept by a
/// sphere of that radius. Against a plane its deepest points are always on the corner
/// spheres (a face flat on the plane lies between four of them), so each corner of
/// `core` is a contact where its sphere reaches behind the plane: depth
/// δ = `rounding` − (the corner's signed distance from the plane) (m), its point on
/// the sphere's surface, `rounding` behind the corner along −`plane_normal`. As the
/// box rolls over an edge, the point travels round it instead of pivoting on a
/// knife-edge. `rounding` = 0 is the sharp box of [`contacts`], bit for bit.
pub fn rounded_contacts<T: Real>(
    core: &Cuboid<T>,
    rounding: T,
    plane_point: &Vector3<T>,
    plane_normal: &Vector3<T>,
) -> Contacts<T> {
    let mut found = Contacts::new();
    for index in 0..MAX_POINTS {
        let vertex = core.vertex(index);
        let depth = rounding - (vertex - plane_point).dot(plane_normal);
        if depth > T::zero() {
            let point = if rounding > T::zero() {
                vertex - plane_normal * rounding
            } else {
                vertex
            };
            // At most eight vertices into a capacity of eight: the push cannot fail.
            let _ = found.push(ContactGeometry {
                depth,
                normal: *plane_normal,
                point,
                // `index` < 8: the cast is exact.
                feature: index as u32,
            });
        }
    }
    found
}

/// Signed distance (m) of the lowest vertex of `cuboid` from the plane through
/// `plane_point` (m) with outward `plane_normal` (unit): > 0 when the box is clear of
/// the plane, < 0 (minus the deepest indentation δ) when it penetrates. Continuous in
/// the pose, so a simulator can locate touch-down and lift-off by root finding. NaN in
/// any input gives NaN. For a box rounded to r (m), the separation of its `core`
/// less r.
pub fn separation<T: Real>(
    cuboid: &Cuboid<T>,
    plane_point: &Vector3<T>,
    plane_normal: &Vector3<T>,
) -> T {
    let mut lowest = T::MAX;
    for index in 0..MAX_POINTS {
        let height = (cuboid.vertex(index) - plane_point).dot(plane_normal);
        if height.is_nan() {
            return height;
        }
        if height < lowest {
            lowest = height;
        }
    }
    lowest
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::f64::consts::FRAC_PI_4;
    use heapless::Vec;
    use nalgebra::UnitQuaternion;

    const CUBE: f64 = 0.05;

    fn cube(center_z: f64, orientation: UnitQuaternion<f64>) -> Cuboid<f64> {
        Cuboid {
            half_extents: Vector3::repeat(CUBE),
            center: Vector3::new(0.2, -0.1, center_z),
            orientation,
        }
    }

    fn on_ground(cuboid: &Cuboid<f64>) -> Contacts<f64> {
        contacts(cuboid, &Vector3::zeros(), &Vector3::z())
    }

    fn assert_depths(found: &Contacts<f64>, count: usize, depth: f64) {
        assert_eq!(found.len(), count, "{found:?}");
        for c in found {
            assert!((c.depth - depth).abs() < 1e-12, "{c:?}");
            assert_eq!(c.normal, Vector3::z());
            assert!(
                (c.point.z + depth).abs() < 1e-12,
                "the point is the vertex: {c:?}"
            );
        }
    }

    #[test]
    fn flat_box_one_millimetre_deep_touches_at_four_corners() {
        let found = on_ground(&cube(CUBE - 1e-3, UnitQuaternion::identity()));
        assert_depths(&found, 4, 1e-3);
        let corners: [(f64, f64); 4] = [(0.15, -0.15), (0.25, -0.15), (0.15, -0.05), (0.25, -0.05)];
        for (c, (x, y)) in found.iter().zip(corners) {
            assert!((c.point.x - x).abs() < 1e-12 && (c.point.y - y).abs() < 1e-12);
        }
    }

    #[test]
    fn box_on_an_edge_touches_at_two_corners() {
        let tilt = UnitQuaternion::from_euler_angles(FRAC_PI_4, 0.0, 0.0);
        let found = on_ground(&cube(CUBE * 2.0_f64.sqrt() - 1e-3, tilt));
        assert_depths(&found, 2, 1e-3);
        // The edge is along x: its two ends.
        assert!((found[0].point.x - found[1].point.x).abs() > 0.099);
    }

    #[test]
    fn box_on_a_corner_touches_at_one() {
        // The body diagonal (1, 1, 1) turned onto −z.
        let down = UnitQuaternion::rotation_between(&Vector3::repeat(1.0), &-Vector3::z())
            .unwrap_or_else(UnitQuaternion::identity);
        let found = on_ground(&cube(CUBE * 3.0_f64.sqrt() - 2e-3, down));
        assert_depths(&found, 1, 2e-3);
    }

    #[test]
    fn tilted_plane_and_clear_box() {
        let normal = Vector3::new(1.0, 0.0, 1.0).normalize();
        let cuboid = Cuboid {
            half_extents: Vector3::new(0.1, 0.2, 0.3),
            center: Vector3::zeros(),
            orientation: UnitQuaternion::from_euler_angles(0.0, FRAC_PI_4, 0.0),
        };
        // Rotated by 45° about y, the box's −z face lies flat on a plane with normal
        // (1, 0, 1)/√2 through its centre shifted by 0.3 − 5 mm towards the box.
        let plane = -normal * (0.3 - 5e-3);
        let found = contacts(&cuboid, &plane, &normal);
        assert_eq!(found.len(), 4, "{found:?}");
        for c in &found {
            assert!((c.depth - 5e-3).abs() < 1e-12, "{c:?}");
        }
        assert!(contacts(&cuboid, &(-normal), &normal).is_empty());
    }

    #[test]
    fn features_are_the_vertex_indices() {
        let found = on_ground(&cube(CUBE - 1e-3, UnitQuaternion::identity()));
        let features: Vec<u32, 8> = found.iter().map(|c| c.feature).collect();
        // The four corners with a clear z bit (bit 2): the bottom face.
        assert_eq!(features.as_slice(), &[0, 1, 2, 3]);
    }

    #[test]
    fn separation_is_the_lowest_vertex_height() {
        let up = Vector3::z();
        let flat = cube(CUBE + 2e-3, UnitQuaternion::identity());
        assert!((separation(&flat, &Vector3::zeros(), &up) - 2e-3).abs() < 1e-12);
        let sunk = cube(CUBE - 1e-3, UnitQuaternion::identity());
        assert!((separation(&sunk, &Vector3::zeros(), &up) + 1e-3).abs() < 1e-12);
        let tilt = UnitQuaternion::from_euler_angles(FRAC_PI_4, 0.0, 0.0);
        let edge = cube(CUBE * 2.0_f64.sqrt() + 1e-3, tilt);
        assert!((separation(&edge, &Vector3::zeros(), &up) - 1e-3).abs() < 1e-12);
        assert!(separation(&edge, &Vector3::zeros(), &Vector3::repeat(f64::NAN)).is_nan());
    }

    #[test]
    fn box_sunk_below_the_plane_touches_at_all_eight() {
        assert_eq!(on_ground(&cube(-1.0, UnitQuaternion::identity())).len(), 8);
    }

    #[test]
    fn f32_as_a_controller_holds_it() {
        let cuboid = Cuboid {
            half_extents: Vector3::repeat(0.05_f32),
            center: Vector3::new(0.0, 0.0, 0.049),
            orientation: UnitQuaternion::identity(),
        };
        let found = contacts(&cuboid, &Vector3::zeros(), &Vector3::z());
        assert_eq!(found.len(), 4);
        assert!((found[0].depth - 1e-3).abs() < 1e-6);
    }

    #[test]
    fn nan_inputs_give_no_contacts_and_no_panic() {
        let nan = Vector3::repeat(f64::NAN);
        assert!(on_ground(&cube(f64::NAN, UnitQuaternion::identity())).is_empty());
        let cuboid = cube(0.0, UnitQuaternion::identity());
        assert!(contacts(&cuboid, &nan, &Vector3::z()).is_empty());
        assert!(contacts(&cuboid, &Vector3::zeros(), &nan).is_empty());
    }

    #[test]
    fn a_rounded_box_on_an_edge_touches_round_the_edge() {
        // Tilted 0.5 rad about x, the core's lowest edge 5.7 mm above the plane, within
        // reach of its 10 mm spheres: each point on a sphere, straight below its centre.
        let r = 0.01;
        let tilt = UnitQuaternion::from_euler_angles(0.5, 0.0, 0.0);
        let core = Cuboid {
            half_extents: Vector3::repeat(CUBE - r),
            center: Vector3::new(0.0, 0.0, 0.06),
            orientation: tilt,
        };
        let found = rounded_contacts(&core, r, &Vector3::zeros(), &Vector3::z());
        let lowest = (0..8)
            .map(|i| core.vertex(i).z)
            .fold(f64::INFINITY, f64::min);
        assert!(!found.is_empty());
        for c in &found {
            assert!((c.depth - (r - lowest)).abs() < 1e-12, "{c:?}");
            assert!((c.point.z - (lowest - r)).abs() < 1e-12, "{c:?}");
        }
        let sharp = contacts(&core, &Vector3::zeros(), &Vector3::z());
        assert!(sharp.is_empty(), "the core alone is clear: {sharp:?}");
    }

    #[test]
    fn rounding_zero_is_the_sharp_box() {
        let tilt = UnitQuaternion::from_euler_angles(0.3, -0.2, 0.9);
        let b = cube(0.05, tilt);
        let (a, z) = (
            on_ground(&b),
            rounded_contacts(&b, 0.0, &Vector3::zeros(), &Vector3::z()),
        );
        assert_eq!(a, z);
    }
}
