//! The core's box contact geometry (`hcm_core::geometry::{box_plane, sphere_box}`)
//! against an independent implementation, the `parry3d` crate (its f64 build), on
//! random poses: the same deepest depth and contact normal, and for a box on a plane
//! the same set of penetrating vertices.

use hcm_core::geometry::{box_plane, sphere_box, Cuboid};
use nalgebra::{UnitQuaternion, Vector3};
use parry3d_f64::glamx::{DPose3, DQuat, DVec3};
use parry3d_f64::query::{self, PointQuery};
use parry3d_f64::shape::{Ball, Cuboid as ParryCuboid, HalfSpace};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Random poses per shape pair.
const POSES: usize = 4000;
/// Largest difference of depths allowed (m).
const DEPTH_TOLERANCE: f64 = 1e-9;
/// Largest angle between the two normals allowed (rad).
const ANGLE_TOLERANCE: f64 = 1e-9;

fn dvec(v: &Vector3<f64>) -> DVec3 {
    DVec3::new(v.x, v.y, v.z)
}

fn pose(cuboid: &Cuboid<f64>) -> DPose3 {
    let q = cuboid.orientation.quaternion();
    DPose3::from_parts(dvec(&cuboid.center), DQuat::from_xyzw(q.i, q.j, q.k, q.w))
}

/// A uniformly random unit vector (–), by rejection from the unit ball.
fn unit_vector(rng: &mut ChaCha8Rng) -> Vector3<f64> {
    loop {
        let v = Vector3::from_fn(|_, _| rng.random_range(-1.0..1.0));
        let norm: f64 = v.norm();
        if norm > 0.1 && norm <= 1.0 {
            return v / norm;
        }
    }
}

/// A box with half extents in 10–100 mm, its centre within `spread` (m) of the
/// origin, in a uniformly random orientation.
fn random_cuboid(rng: &mut ChaCha8Rng, spread: f64) -> Cuboid<f64> {
    let axis = nalgebra::Unit::new_normalize(unit_vector(rng));
    let angle = rng.random_range(-core::f64::consts::PI..core::f64::consts::PI);
    Cuboid {
        half_extents: Vector3::from_fn(|_, _| rng.random_range(0.01..0.1)),
        center: Vector3::from_fn(|_, _| rng.random_range(-spread..spread)),
        orientation: UnitQuaternion::from_axis_angle(&axis, angle),
    }
}

fn angle_between(a: &Vector3<f64>, b: DVec3) -> f64 {
    let b = Vector3::new(b.x, b.y, b.z);
    a.cross(&b).norm().atan2(a.dot(&b))
}

#[test]
fn box_on_a_plane_agrees_with_parry() {
    let mut rng = ChaCha8Rng::seed_from_u64(13);
    let (mut touching, mut clear) = (0, 0);
    let mut by_count = [0; 9];
    for case in 0..POSES {
        let cuboid = random_cuboid(&mut rng, 0.1);
        let normal = unit_vector(&mut rng);
        // The plane within 110 % of the box's circumradius of its centre.
        let height = rng.random_range(-1.1..1.1) * cuboid.half_extents.norm();
        let plane_point = cuboid.center - normal * height;
        let ours = box_plane::contacts(&cuboid, &plane_point, &normal);

        let half_space = HalfSpace::new(dvec(&normal));
        let plane_pose = DPose3::from_translation(dvec(&plane_point));
        let shape = ParryCuboid::new(dvec(&cuboid.half_extents));
        // Half-space first: parry 0.31 gives a wrong contact for the order (box,
        // half-space) in a rotated pose (its dispatcher passes the pose of the
        // half-space relative to the box where the inverse is expected).
        let theirs = query::contact(&plane_pose, &half_space, &pose(&cuboid), &shape, 0.0)
            .expect("parry supports half-space–cuboid");

        // The penetrating vertices, as parry's half-space sees them, in vertex order.
        let inside: Vec<Vector3<f64>> = (0..8)
            .map(|i| cuboid.vertex(i))
            .filter(|v| half_space.contains_point(&plane_pose, dvec(v)))
            .collect();
        assert_eq!(ours.len(), inside.len(), "case {case}: {ours:?}");
        for (c, v) in ours.iter().zip(&inside) {
            assert_eq!(c.point, *v, "case {case}");
        }
        by_count[ours.len()] += 1;

        let deepest = ours
            .iter()
            .map(|c| c.depth)
            .fold(f64::NEG_INFINITY, f64::max);
        match theirs {
            Some(contact) if !ours.is_empty() => {
                touching += 1;
                assert!(
                    (deepest + contact.dist).abs() < DEPTH_TOLERANCE,
                    "case {case}: {deepest} {contact:?}"
                );
                // parry's normal1 points from the half-space to the box, as ours.
                let angle = angle_between(&ours[0].normal, contact.normal1);
                assert!(angle < ANGLE_TOLERANCE, "case {case}: {angle} rad");
            }
            Some(contact) => assert!(contact.dist >= -DEPTH_TOLERANCE, "case {case}: {contact:?}"),
            None => {
                clear += 1;
                assert!(ours.is_empty(), "case {case}");
            }
        }
    }
    println!("box–plane: {touching} touching, {clear} clear; poses by points 0..=8: {by_count:?}");
    assert!(
        touching > POSES / 2 && clear > POSES / 20,
        "{touching} / {clear}"
    );
    assert!(by_count[1..8].iter().all(|&n| n > 0), "{by_count:?}");
}

#[test]
fn sphere_on_a_box_agrees_with_parry() {
    let mut rng = ChaCha8Rng::seed_from_u64(31);
    let (mut outside, mut inside, mut clear) = (0, 0, 0);
    for case in 0..POSES {
        let cuboid = random_cuboid(&mut rng, 0.1);
        let radius = rng.random_range(0.005..0.05);
        let reach = cuboid.half_extents.add_scalar(radius);
        let local = reach.map(|r| rng.random_range(-1.2 * r..1.2 * r));
        let center = cuboid.to_world(&local);
        let ours = sphere_box::contact(&center, radius, &cuboid);

        let ball_pose = DPose3::from_translation(dvec(&center));
        let shape = ParryCuboid::new(dvec(&cuboid.half_extents));
        let theirs = query::contact(&ball_pose, &Ball::new(radius), &pose(&cuboid), &shape, 0.0)
            .expect("parry supports ball–cuboid");
        match theirs {
            Some(contact) => {
                let centre_inside = cuboid
                    .to_local(&center)
                    .iter()
                    .zip(cuboid.half_extents.iter())
                    .all(|(x, h)| x.abs() < *h);
                if centre_inside {
                    inside += 1;
                } else {
                    outside += 1;
                }
                assert!(
                    (ours.depth + contact.dist).abs() < DEPTH_TOLERANCE,
                    "case {case}"
                );
                // parry's normal1 points from the ball to the box.
                let angle = angle_between(&ours.normal, -contact.normal1);
                assert!(angle < ANGLE_TOLERANCE, "case {case}: {angle} rad");
            }
            None => {
                clear += 1;
                assert!(ours.depth < 0.0, "case {case}: {ours:?}");
            }
        }
    }
    println!("sphere–box: {outside} touching from outside, {inside} centre inside, {clear} clear");
    assert!(outside > POSES / 10 && inside > POSES / 20 && clear > POSES / 10);
}
