//! A sphere (body 1) against a cuboid (body 2), e.g. a ball on a block or a
//! fingertip on a box.

use super::{ContactGeometry, Cuboid};
use crate::Real;
use nalgebra::Vector3;

/// Overlap of a sphere (`center` (m), `radius` (m)) with `cuboid`.
///
/// Outside the box the normal runs from the closest point of the box to the centre;
/// with the centre inside (or on the surface), it is the outward normal of the face of
/// least penetration (ties: x before y before z, + before −), so the sphere is pushed
/// out the shortest way. Depth δ (m) is negative when the sphere is clear of the box;
/// the point is, as for [`super::sphere_plane`], the middle of the overlap along the
/// normal. NaN inputs give a NaN depth and no panic. One contact, so `feature` is 0.
pub fn contact<T: Real>(center: &Vector3<T>, radius: T, cuboid: &Cuboid<T>) -> ContactGeometry<T> {
    let local = cuboid.to_local(center);
    let closest = clamp_into(&local, &cuboid.half_extents);
    let offset = local - closest;
    let distance = offset.norm_squared().square_root();
    let (closest, normal, depth) = if distance > T::zero() && distance < T::MAX {
        (closest, offset / distance, radius - distance)
    } else {
        let (closest, normal, inside) = least_penetrated_face(&local, &cuboid.half_extents);
        (closest, normal, radius + inside)
    };
    let normal = cuboid.orientation * normal;
    ContactGeometry {
        depth,
        normal,
        point: cuboid.to_world(&closest) - normal * (T::of(0.5) * depth),
        feature: 0,
    }
}

/// `local` (m) moved onto the box of `half` extents (m), coordinate by coordinate.
fn clamp_into<T: Real>(local: &Vector3<T>, half: &Vector3<T>) -> Vector3<T> {
    local.zip_map(half, |x, h| {
        if x > h {
            h
        } else if x < -h {
            -h
        } else {
            x
        }
    })
}

/// For a centre `local` (m) inside the box of `half` extents (m): the face it is
/// closest to, as (its projection onto that face (m), the face's outward normal in the
/// box frame (–), the distance to the face (m)).
fn least_penetrated_face<T: Real>(
    local: &Vector3<T>,
    half: &Vector3<T>,
) -> (Vector3<T>, Vector3<T>, T) {
    let mut best = (0, T::one(), half.x - local.x);
    for axis in 0..3 {
        for sign in [T::one(), -T::one()] {
            let inside = half[axis] - sign * local[axis];
            if inside < best.2 {
                best = (axis, sign, inside);
            }
        }
    }
    let (axis, sign, inside) = best;
    let mut projection = *local;
    projection[axis] = sign * half[axis];
    let mut normal = Vector3::zeros();
    normal[axis] = sign;
    (projection, normal, inside)
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::f64::consts::FRAC_PI_4;
    use nalgebra::UnitQuaternion;

    fn block() -> Cuboid<f64> {
        Cuboid {
            half_extents: Vector3::new(0.1, 0.2, 0.3),
            center: Vector3::new(1.0, 0.0, 0.0),
            orientation: UnitQuaternion::identity(),
        }
    }

    fn assert_contact(c: &ContactGeometry<f64>, depth: f64, normal: Vector3<f64>) {
        assert!((c.depth - depth).abs() < 1e-12, "{c:?}");
        assert!((c.normal - normal).norm() < 1e-12, "{c:?}");
    }

    #[test]
    fn ball_on_the_top_face() {
        let c = contact(&Vector3::new(1.05, 0.1, 0.309), 0.01, &block());
        assert_contact(&c, 1e-3, Vector3::z());
        assert!((c.point - Vector3::new(1.05, 0.1, 0.2995)).norm() < 1e-12);
    }

    #[test]
    fn ball_on_an_edge_and_on_a_corner() {
        let edge = contact(&Vector3::new(1.11, 0.0, 0.31), 0.02, &block());
        let diagonal = Vector3::new(1.0, 0.0, 1.0).normalize();
        assert_contact(&edge, 0.02 - 0.01 * 2.0_f64.sqrt(), diagonal);
        let corner = contact(&Vector3::new(1.11, 0.21, 0.31), 0.02, &block());
        assert_contact(
            &corner,
            0.02 - 0.01 * 3.0_f64.sqrt(),
            Vector3::repeat(1.0).normalize(),
        );
    }

    #[test]
    fn clear_ball_has_a_negative_depth() {
        let c = contact(&Vector3::new(1.0, 0.0, -0.5), 0.1, &block());
        assert_contact(&c, -0.1, -Vector3::z());
    }

    #[test]
    fn centre_inside_is_pushed_out_through_the_nearest_face() {
        // 0.02 m from the +x face, 0.18 m from ±y, ≥ 0.28 m from ±z.
        let c = contact(&Vector3::new(1.08, 0.0, 0.0), 0.01, &block());
        assert_contact(&c, 0.03, Vector3::x());
        let c = contact(&Vector3::new(1.0, -0.15, 0.0), 0.01, &block());
        assert_contact(&c, 0.06, -Vector3::y());
        // On the surface exactly: the face it lies on.
        let c = contact(&Vector3::new(1.0, 0.0, -0.3), 0.01, &block());
        assert_contact(&c, 0.01, -Vector3::z());
    }

    #[test]
    fn rotated_box_rotates_the_normal() {
        let turned = Cuboid {
            orientation: UnitQuaternion::from_euler_angles(0.0, 0.0, FRAC_PI_4),
            ..block()
        };
        // The box's +x face now faces (1, 1, 0)/√2, 0.1 m from the centre.
        let out = Vector3::new(1.0, 1.0, 0.0).normalize();
        let c = contact(&(turned.center + out * 0.105), 0.01, &turned);
        assert_contact(&c, 5e-3, out);
        let c = contact(&(turned.center + out * 0.095), 0.01, &turned);
        assert_contact(&c, 0.015, out);
    }

    #[test]
    fn f32_ball_on_a_box() {
        let cuboid = Cuboid {
            half_extents: Vector3::repeat(0.05_f32),
            center: Vector3::zeros(),
            orientation: UnitQuaternion::identity(),
        };
        let c = contact(&Vector3::new(0.0, 0.0, 0.059), 0.01, &cuboid);
        assert!((c.depth - 1e-3).abs() < 1e-6);
        assert_eq!(c.normal, Vector3::z());
    }

    #[test]
    fn nan_inputs_give_a_nan_depth_and_no_panic() {
        let nan = Vector3::repeat(f64::NAN);
        assert!(contact(&nan, 0.01, &block()).depth.is_nan());
        assert!(contact(&Vector3::zeros(), f64::NAN, &block())
            .depth
            .is_nan());
        let hollow = Cuboid {
            half_extents: nan,
            ..block()
        };
        assert!(contact(&Vector3::zeros(), 0.01, &hollow).depth.is_nan());
    }
}
