//! The core's box–box contact (`hcm_core::geometry::box_box`) against an independent
//! implementation, the `parry3d` crate (f64): its separating-axis routines
//! (`query::sat::cuboid_cuboid_*`) and its contact manifold
//! (`contact_manifold_cuboid_cuboid`), on random poses of two random boxes (half
//! extents 10–100 mm, centres within ±80 mm, uniformly random orientations) until
//! [`OVERLAPPING`] poses overlap. Run with `--nocapture` for the counts (seed 1313:
//! 10 000 overlapping — 6872 face, 3128 edge–edge contacts, 1786 of the face ones on a
//! face axis preferred over a nearly tied edge axis, 5086 manifolds compared point by
//! point — and 3608 separated). Not parry's `query::contact`: it dispatches a cuboid
//! pair to GJK/EPA, whose depth was 0.9 mm off the exact value on one of these poses.
//!
//! Every overlapping pose (parry's separation < 0):
//! - `separation` equals parry's (the largest separation over the 15 axes) within
//!   [`DEPTH_TOLERANCE`];
//! - the manifold is not empty; every point has δ > 0, no deeper than the penetration
//!   along its normal, and lies within δ/2 + [`DEPTH_TOLERANCE`] of each box (half-way
//!   across the overlap);
//! - the normal is parry's within [`ANGLE_TOLERANCE`], from the same kind of axis —
//!   or, the one legitimate difference, parry's axis is an edge pair that beats our face
//!   axis by less than the face preference (ODE's factor 1.05): then our face axis's
//!   penetration lies between parry's and 1.05 × parry's and is the least over the six
//!   face axes (these poses are counted and printed; their points get the checks above);
//! - with the same face axis, the points are parry's penetrating manifold points one for
//!   one: the same positions (the middle of parry's point pair) and depths within
//!   [`DEPTH_TOLERANCE`]; with the same edge axis, the depth is parry's penetration.
//!
//! Every separated pose: no contacts, and `separation` is > 0 and at most parry's
//! distance (a lower bound).

use hcm_core::geometry::{box_box, ContactGeometry, Cuboid};
use nalgebra::{UnitQuaternion, Vector3};
use parry3d_f64::glamx::{DPose3, DQuat, DVec3};
use parry3d_f64::query::details::contact_manifold_cuboid_cuboid;
use parry3d_f64::query::{self, sat, ContactManifold, PointQuery};
use parry3d_f64::shape::Cuboid as ParryCuboid;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Overlapping poses to check.
const OVERLAPPING: usize = 10_000;
/// Largest difference of depths, separations and positions allowed (m).
const DEPTH_TOLERANCE: f64 = 1e-9;
/// Largest angle between the two normals allowed (rad).
const ANGLE_TOLERANCE: f64 = 1e-9;
/// How much less an edge axis must penetrate to be preferred over a face (ODE's).
const FACE_PREFERENCE: f64 = 1.05;
/// Bit of the feature id marking an edge–edge contact (the module's encoding).
const EDGE_EDGE: u32 = 1 << 13;

fn dvec(v: &Vector3<f64>) -> DVec3 {
    DVec3::new(v.x, v.y, v.z)
}

fn vector(v: DVec3) -> Vector3<f64> {
    Vector3::new(v.x, v.y, v.z)
}

fn pose(cuboid: &Cuboid<f64>) -> DPose3 {
    let q = cuboid.orientation.quaternion();
    DPose3::from_parts(dvec(&cuboid.center), DQuat::from_xyzw(q.i, q.j, q.k, q.w))
}

fn shape(cuboid: &Cuboid<f64>) -> ParryCuboid {
    ParryCuboid::new(dvec(&cuboid.half_extents))
}

/// A box with half extents in 10–100 mm, its centre within ±80 mm of the origin, in a
/// uniformly random orientation (a quaternion drawn uniformly from the unit 4-ball by
/// rejection, then normalised).
fn random_cuboid(rng: &mut ChaCha8Rng) -> Cuboid<f64> {
    let q = loop {
        let q = nalgebra::Quaternion::new(
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
        );
        let norm: f64 = q.norm();
        if norm > 0.1 && norm <= 1.0 {
            break q;
        }
    };
    Cuboid {
        half_extents: Vector3::from_fn(|_, _| rng.random_range(0.01..0.1)),
        center: Vector3::from_fn(|_, _| rng.random_range(-0.08..0.08)),
        orientation: UnitQuaternion::from_quaternion(q),
    }
}

/// The boxes' penetration along the unit `axis` (m), the test's own projection.
fn penetration(one: &Cuboid<f64>, two: &Cuboid<f64>, axis: &Vector3<f64>) -> f64 {
    let reach = |c: &Cuboid<f64>| {
        (0..3)
            .map(|i| c.half_extents[i] * (c.orientation * Vector3::ith(i, 1.0)).dot(axis).abs())
            .sum::<f64>()
    };
    reach(one) + reach(two) - (one.center - two.center).dot(axis).abs()
}

fn angle_between(a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
    a.cross(b).norm().atan2(a.dot(b))
}

/// Our points and parry's manifold, one for one (order aside).
fn assert_same_points(case: usize, ours: &[ContactGeometry<f64>], theirs: &[(Vector3<f64>, f64)]) {
    assert_eq!(
        ours.len(),
        theirs.len(),
        "case {case}: {ours:?} vs {theirs:?}"
    );
    for c in ours {
        let matched = theirs.iter().any(|(point, depth)| {
            (c.point - point).norm() < DEPTH_TOLERANCE && (c.depth - depth).abs() < DEPTH_TOLERANCE
        });
        assert!(matched, "case {case}: {c:?} not in {theirs:?}");
    }
}

/// Every point: δ > 0, not deeper than the penetration along the normal, half-way
/// across the overlap (within δ/2 of each box).
fn assert_points_in_the_overlap(
    case: usize,
    one: &Cuboid<f64>,
    two: &Cuboid<f64>,
    ours: &[ContactGeometry<f64>],
) {
    let normal = ours[0].normal;
    let along_normal = penetration(one, two, &normal);
    for c in ours {
        assert_eq!(c.normal, normal, "case {case}");
        assert!(
            c.depth > 0.0 && c.depth <= along_normal + DEPTH_TOLERANCE,
            "case {case}: {c:?}"
        );
        for b in [one, two] {
            let gap = shape(b).distance_to_point(&pose(b), dvec(&c.point), true);
            assert!(
                gap <= 0.5 * c.depth + DEPTH_TOLERANCE,
                "case {case}: {gap} {c:?}"
            );
        }
    }
}

/// How many poses fell into each case.
#[derive(Debug, Default)]
struct Counts {
    separated: usize,
    face: usize,
    edge: usize,
    face_preferred: usize,
    manifolds_compared: usize,
    by_points: [usize; 9],
}

/// Parry's separating-axis test and contact manifold for one pose.
struct Parry {
    /// The largest separation over its axes (m).
    separation: f64,
    /// The manifold's normal (unit), turned to point from box 2 to box 1 as ours.
    normal: Vector3<f64>,
    /// Whether its axis is an edge pair.
    edge: bool,
    /// Its penetrating manifold points, as (middle of the point pair (m), depth (m)).
    points: Vec<(Vector3<f64>, f64)>,
}

fn parry(one: &Cuboid<f64>, two: &Cuboid<f64>) -> Parry {
    let (pose_1, pose_2, shape_1, shape_2) = (pose(one), pose(two), shape(one), shape(two));
    let pos12 = pose_1.inv_mul(&pose_2);
    let face_1 =
        sat::cuboid_cuboid_find_local_separating_normal_oneway(&shape_1, &shape_2, &pos12).0;
    let face_2 = sat::cuboid_cuboid_find_local_separating_normal_oneway(
        &shape_2,
        &shape_1,
        &pos12.inverse(),
    )
    .0;
    let edge = sat::cuboid_cuboid_find_local_separating_edge_twoway(&shape_1, &shape_2, &pos12).0;
    let mut manifold = ContactManifold::<(), ()>::new();
    contact_manifold_cuboid_cuboid(&pos12, &shape_1, &shape_2, 0.0, &mut manifold);
    let points = manifold
        .points
        .iter()
        .filter(|p| p.dist < 0.0)
        .map(|p| {
            let (p1, p2) = (
                pose_1.transform_point(p.local_p1),
                pose_2.transform_point(p.local_p2),
            );
            (vector((p1 + p2) * 0.5), -p.dist)
        })
        .collect();
    Parry {
        separation: face_1.max(face_2).max(edge),
        normal: -vector(pose_1.rotation * manifold.local_n1),
        // The manifold's rule: box 2's face if strictly best, else the edges if
        // strictly better than box 1's face.
        edge: !(face_2 > face_1 && face_2 > edge) && edge > face_1,
        points,
    }
}

/// One overlapping pose (parry's separation < 0).
fn check_overlap(
    case: usize,
    one: &Cuboid<f64>,
    two: &Cuboid<f64>,
    theirs: &Parry,
    counts: &mut Counts,
) {
    let separation = box_box::separation(one, two);
    assert!(
        (separation - theirs.separation).abs() < DEPTH_TOLERANCE,
        "case {case}: {separation}"
    );
    let ours = box_box::contacts(one, two);
    assert!(!ours.is_empty(), "case {case}: overlapping, no contacts");
    counts.by_points[ours.len()] += 1;
    assert_points_in_the_overlap(case, one, two, &ours);
    let is_edge = ours[0].feature & EDGE_EDGE != 0;
    if is_edge {
        counts.edge += 1;
    } else {
        counts.face += 1;
    }
    if angle_between(&ours[0].normal, &theirs.normal) < ANGLE_TOLERANCE {
        assert_eq!(is_edge, theirs.edge, "case {case}");
        if is_edge {
            assert!(
                (ours[0].depth + theirs.separation).abs() < DEPTH_TOLERANCE,
                "case {case}"
            );
        } else {
            counts.manifolds_compared += 1;
            assert_same_points(case, &ours, &theirs.points);
        }
        return;
    }
    // The face preference: our face axis against parry's edge axis.
    let (ours_deep, theirs_deep) = (penetration(one, two, &ours[0].normal), -theirs.separation);
    assert!(!is_edge && theirs.edge, "case {case}: the axes differ");
    assert!(
        ours_deep >= theirs_deep - DEPTH_TOLERANCE
            && ours_deep <= FACE_PREFERENCE * theirs_deep + DEPTH_TOLERANCE,
        "case {case}: {ours_deep} vs {theirs_deep}"
    );
    // And it is the best face axis: no face of either box penetrates less.
    let least_face = [one, two]
        .iter()
        .flat_map(|b| (0..3).map(|i| b.orientation * Vector3::ith(i, 1.0)))
        .map(|axis| penetration(one, two, &axis))
        .fold(f64::INFINITY, f64::min);
    assert!(
        (ours_deep - least_face).abs() < DEPTH_TOLERANCE,
        "case {case}: {ours_deep} {least_face}"
    );
    counts.face_preferred += 1;
}

#[test]
fn box_on_a_box_agrees_with_parry() {
    let mut rng = ChaCha8Rng::seed_from_u64(1313);
    let mut counts = Counts::default();
    let mut overlapping = 0;
    for case in 0.. {
        if overlapping == OVERLAPPING {
            break;
        }
        let (one, two) = (random_cuboid(&mut rng), random_cuboid(&mut rng));
        let theirs = parry(&one, &two);
        if theirs.separation < 0.0 {
            overlapping += 1;
            check_overlap(case, &one, &two, &theirs, &mut counts);
        } else {
            counts.separated += 1;
            assert!(box_box::contacts(&one, &two).is_empty(), "case {case}");
            let distance = query::distance(&pose(&one), &shape(&one), &pose(&two), &shape(&two))
                .expect("parry supports cuboid–cuboid")
                .distance;
            let separation = box_box::separation(&one, &two);
            assert!(
                separation > 0.0 && separation <= distance + DEPTH_TOLERANCE,
                "case {case}"
            );
        }
    }
    println!(
        "box–box: {overlapping} overlapping ({} face, {} edge–edge; {} face axes preferred \
         over a nearly tied edge axis, {} manifolds compared point by point), {} separated; \
         poses by points 0..=8: {:?}; tolerances {DEPTH_TOLERANCE:e} m, {ANGLE_TOLERANCE:e} rad",
        counts.face,
        counts.edge,
        counts.face_preferred,
        counts.manifolds_compared,
        counts.separated,
        counts.by_points
    );
    assert!(
        counts.edge > OVERLAPPING / 50 && counts.separated > OVERLAPPING / 10,
        "{counts:?}"
    );
    assert!(counts.manifolds_compared > OVERLAPPING / 2, "{counts:?}");
    assert!(
        counts.by_points[1..=8].iter().filter(|&&n| n > 0).count() >= 6,
        "{counts:?}"
    );
}
