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
    Box(Cuboid<f64>),
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
        Shape::Box { half_extents } => Placed::Box(Cuboid {
            half_extents: *half_extents,
            center: pose.position,
            orientation: pose.orientation,
        }),
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
        (Placed::Sphere(c, r), Placed::Box(b)) => single(sphere_box::contact(c, *r, b)),
        (Placed::Sphere(c, r), Placed::Compound(parts)) => compound::sphere_contacts(c, *r, parts),
        (Placed::Box(b), Placed::Plane(p, n)) => box_plane::contacts(b, p, n),
        (Placed::Box(b1), Placed::Box(b2)) => box_box::contacts(b1, b2),
        (Placed::Box(b), Placed::Compound(parts)) => compound::contacts(b, parts),
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
        (Placed::Sphere(c, r), Placed::Box(b)) => -sphere_box::contact(c, *r, b).depth,
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
        (Placed::Box(b), Placed::Plane(p, n)) => box_plane::separation(b, p, n),
        (Placed::Box(b1), Placed::Box(b2)) => box_box::separation(b1, b2),
        (Placed::Box(b), Placed::Compound(parts)) => compound::separation(b, parts),
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
