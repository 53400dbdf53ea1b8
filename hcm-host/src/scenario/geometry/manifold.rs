//! Where a body pair touches, from the two bodies' poses: the manifold of up to
//! eight contact points (the core's generators), the pair's signed separation and, for
//! a pair touching on its line of centres, its indentation rate.

use super::Pose;
use crate::scenario::{Contact, Model, Part, Shape};
use hcm_core::geometry::{
    box_box, box_plane, compound, sphere_box, sphere_plane, sphere_sphere, ContactGeometry,
    Contacts, Cuboid,
};
use nalgebra::Vector3;

/// Most boxes of one compound body the simulator places per evaluation (a block with
/// a hole: four walls and a bottom).
const MAX_PARTS: usize = 16;

/// A body's shape placed at its pose, world frame. A short-lived stack value built
/// per evaluation: the compound's inline array avoids an allocation in the solver's
/// hot path, which is worth its size.
#[allow(clippy::large_enum_variant)]
enum Placed {
    Sphere(Vector3<f64>, f64),
    Plane(Vector3<f64>, Vector3<f64>),
    /// The box's core (its half extents less the rounding) and the rounding (m).
    Box(Cuboid<f64>, f64),
    Compound(heapless::Vec<Cuboid<f64>, MAX_PARTS>),
}

#[inline]
fn place(shape: &Shape, pose: &Pose) -> Placed {
    match shape {
        Shape::Sphere { radius } => Placed::Sphere(pose.position, *radius),
        Shape::Plane { normal, offset } => {
            let normal = pose.orientation * normal;
            Placed::Plane(pose.position + normal * *offset, normal)
        }
        Shape::Box {
            half_extents,
            rounding,
        } => Placed::Box(
            Cuboid {
                half_extents: half_extents.add_scalar(-rounding),
                center: pose.position,
                orientation: pose.orientation,
            },
            *rounding,
        ),
        Shape::Compound { parts } => Placed::Compound(
            parts
                .iter()
                .take(MAX_PARTS)
                .map(|part| place_part(part, pose))
                .collect(),
        ),
    }
}

fn place_part(part: &Part, pose: &Pose) -> Cuboid<f64> {
    Cuboid {
        half_extents: part.half_extents,
        center: pose.position + pose.orientation * part.position,
        orientation: pose.orientation * part.orientation,
    }
}

/// A sphere (`center` (m), `radius` (m)) against a box rounded to `rounding` (m) of
/// core `core`: the box is its core swept by a sphere of that radius, so the contact is
/// the core's with a sphere `rounding` larger, its point moved out to the rounded
/// surface along the normal. Exact for any rounding; 0 is the sharp box.
fn sphere_rounded_box(
    center: &Vector3<f64>,
    radius: f64,
    core: &Cuboid<f64>,
    rounding: f64,
) -> ContactGeometry<f64> {
    let mut g = sphere_box::contact(center, radius + rounding, core);
    if rounding > 0.0 {
        g.point += g.normal * rounding;
    }
    g
}

/// The contact points of `contact` with its bodies at `pose_1`, `pose_2`: each with
/// δ > 0 (m), the normal from body 2 to body 1, its point and a feature id stable
/// while the same features touch.
#[inline]
pub fn pair_contacts(
    model: &Model,
    contact: &Contact,
    pose_1: &Pose,
    pose_2: &Pose,
) -> Contacts<f64> {
    let one = place(&model.bodies[contact.body_1].shape, pose_1);
    let two = place(&model.bodies[contact.body_2].shape, pose_2);
    let single = |g: ContactGeometry<f64>| {
        let mut found = Contacts::new();
        if g.depth > 0.0 {
            let _ = found.push(g);
        }
        found
    };
    match (&one, &two) {
        (Placed::Sphere(c, r), Placed::Plane(p, n)) => single(sphere_plane::contact(c, *r, p, n)),
        (Placed::Sphere(c1, r1), Placed::Sphere(c2, r2)) => {
            single(sphere_sphere::contact(c1, *r1, c2, *r2))
        }
        (Placed::Sphere(c, r), Placed::Box(b, rounding)) => {
            single(sphere_rounded_box(c, *r, b, *rounding))
        }
        (Placed::Sphere(c, r), Placed::Compound(parts)) => compound::sphere_contacts(c, *r, parts),
        (Placed::Box(b, rounding), Placed::Plane(p, n)) => {
            box_plane::rounded_contacts(b, *rounding, p, n)
        }
        // resolve() refuses a rounded box against a box or a compound: both cores are
        // the boxes themselves.
        (Placed::Box(b1, _), Placed::Box(b2, _)) => box_box::contacts(b1, b2),
        (Placed::Box(b, _), Placed::Compound(parts)) => compound::contacts(b, parts),
        // resolve() accepts no other pair.
        _ => Contacts::new(),
    }
}

/// The pair's signed separation (m): < 0 while they overlap (minus the deepest
/// penetration along the separating-axis estimate), > 0 apart (a lower bound on the
/// gap for boxes, the gap for spheres and planes). Continuous in the poses, so a
/// touch-down or lift-off of the pair is its zero crossing.
pub fn pair_separation(model: &Model, contact: &Contact, pose_1: &Pose, pose_2: &Pose) -> f64 {
    let one = place(&model.bodies[contact.body_1].shape, pose_1);
    let two = place(&model.bodies[contact.body_2].shape, pose_2);
    match (&one, &two) {
        (Placed::Sphere(c, r), Placed::Plane(p, n)) => -sphere_plane::contact(c, *r, p, n).depth,
        (Placed::Sphere(c1, r1), Placed::Sphere(c2, r2)) => {
            -sphere_sphere::contact(c1, *r1, c2, *r2).depth
        }
        (Placed::Sphere(c, r), Placed::Box(b, rounding)) => {
            -sphere_rounded_box(c, *r, b, *rounding).depth
        }
        (Placed::Sphere(c, r), Placed::Compound(parts)) => parts
            .iter()
            .map(|part| -sphere_box::contact(c, *r, part).depth)
            .fold(f64::INFINITY, |least, gap| {
                // NaN sticks (`f64::min` would drop it).
                if gap < least || gap.is_nan() {
                    gap
                } else {
                    least
                }
            }),
        (Placed::Box(b, rounding), Placed::Plane(p, n)) => {
            box_plane::separation(b, p, n) - rounding
        }
        (Placed::Box(b1, _), Placed::Box(b2, _)) => box_box::separation(b1, b2),
        (Placed::Box(b, _), Placed::Compound(parts)) => compound::separation(b, parts),
        _ => f64::NAN,
    }
}

/// The indentation rate δ̇ (m/s, > 0 approaching) of a pair that touches on its line of
/// centres — a sphere against a plane or a sphere — at its bodies' poses: minus the
/// velocity of body 1's contact point relative to body 2's along the normal (the closest
/// points' when apart). NaN for a pair with a box, whose points come and go.
pub fn pair_rate(model: &Model, contact: &Contact, pose_1: &Pose, pose_2: &Pose) -> f64 {
    let one = place(&model.bodies[contact.body_1].shape, pose_1);
    let two = place(&model.bodies[contact.body_2].shape, pose_2);
    let g = match (&one, &two) {
        (Placed::Sphere(c, r), Placed::Plane(p, n)) => sphere_plane::contact(c, *r, p, n),
        (Placed::Sphere(c1, r1), Placed::Sphere(c2, r2)) => {
            sphere_sphere::contact(c1, *r1, c2, *r2)
        }
        _ => return f64::NAN,
    };
    -(pose_1.point_velocity(&g.point) - pose_2.point_velocity(&g.point)).dot(&g.normal)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 0.1 m cube rounded to 10 mm, axis-aligned at the origin.
    fn rounded_cube() -> Cuboid<f64> {
        Cuboid {
            half_extents: Vector3::repeat(0.04),
            center: Vector3::zeros(),
            orientation: nalgebra::UnitQuaternion::identity(),
        }
    }

    #[test]
    fn a_sphere_meets_a_rounded_box_on_its_face_and_round_its_corner() {
        // Above the face's middle: the face is where the sharp box's was.
        let above = Vector3::new(0.0, 0.0, 0.059);
        let g = sphere_rounded_box(&above, 0.01, &rounded_cube(), 0.01);
        assert!((g.depth - 1e-3).abs() < 1e-12, "{g:?}");
        assert!((g.point.z - 0.0495).abs() < 1e-12, "{g:?}");
        // Off the corner along the diagonal: the corner sphere is √3·0.04 from the
        // centre, 0.01 + 0.01 of reach, where a sharp corner would already touch.
        let reach = 3f64.sqrt() * 0.04 + 0.02;
        let diagonal = Vector3::repeat(1.0).normalize();
        let g = sphere_rounded_box(&(diagonal * (reach - 1e-3)), 0.01, &rounded_cube(), 0.01);
        assert!((g.depth - 1e-3).abs() < 1e-12, "{g:?}");
        assert!((g.normal - diagonal).norm() < 1e-12, "{g:?}");
        let sharp = Cuboid {
            half_extents: Vector3::repeat(0.05),
            ..rounded_cube()
        };
        let clear = sphere_box::contact(&(diagonal * (reach + 5e-3)), 0.01, &sharp);
        assert!(
            clear.depth > 0.0,
            "the sharp corner reaches further: {clear:?}"
        );
    }
}
