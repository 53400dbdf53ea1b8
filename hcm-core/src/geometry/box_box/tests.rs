use super::*;
use core::f64::consts::{FRAC_PI_4, SQRT_2};
use nalgebra::{UnitQuaternion, Vector3};

const HALF: f64 = 0.05;

fn cube(center: Vector3<f64>, orientation: UnitQuaternion<f64>) -> Cuboid<f64> {
    Cuboid {
        half_extents: Vector3::repeat(HALF),
        center,
        orientation,
    }
}

/// A 0.4 × 0.4 × 0.1 m slab with its top face at z = 0.05 m.
fn slab() -> Cuboid<f64> {
    Cuboid {
        half_extents: Vector3::new(0.2, 0.2, 0.05),
        center: Vector3::zeros(),
        orientation: UnitQuaternion::identity(),
    }
}

fn assert_all(found: &Contacts<f64>, count: usize, depth: f64, normal: Vector3<f64>) {
    assert_eq!(found.len(), count, "{found:?}");
    for c in found {
        assert!((c.depth - depth).abs() < 1e-12, "{c:?}");
        assert!((c.normal - normal).norm() < 1e-12, "{c:?}");
    }
}

fn assert_distinct(found: &Contacts<f64>) {
    for (i, a) in found.iter().enumerate() {
        assert!(
            found[i + 1..].iter().all(|b| b.feature != a.feature),
            "{found:?}"
        );
    }
}

#[test]
fn cube_resting_on_a_slab_touches_at_its_four_bottom_corners() {
    let resting = cube(
        Vector3::new(0.01, -0.02, 0.1 - 1e-3),
        UnitQuaternion::identity(),
    );
    let found = contacts(&resting, &slab());
    assert_all(&found, 4, 1e-3, Vector3::z());
    assert_distinct(&found);
    for c in &found {
        // Half-way across the 1 mm overlap, under a corner of the cube.
        assert!((c.point.z - (0.05 - 0.5e-3)).abs() < 1e-12, "{c:?}");
        assert!(((c.point.x - 0.01).abs() - HALF).abs() < 1e-12, "{c:?}");
        assert!(((c.point.y + 0.02).abs() - HALF).abs() < 1e-12, "{c:?}");
        // Reference: the cube's −z face (5) on box 1; incident: the slab's +z face (4);
        // each point a corner of the reference face, two side planes (lines 4–7).
        assert_eq!(c.feature >> 6, 4 | 5 << 3, "{c:?}");
        assert!(c.feature & 0o70 >= 0o40 && c.feature & 0o7 >= 4, "{c:?}");
    }
    assert!((separation(&resting, &slab()) + 1e-3).abs() < 1e-12);
}

#[test]
fn features_stay_while_the_cube_slides_and_presses() {
    let before = cube(
        Vector3::new(0.0, 0.0, 0.1 - 1e-3),
        UnitQuaternion::identity(),
    );
    let after = cube(
        Vector3::new(3e-3, -1e-3, 0.1 - 2e-3),
        UnitQuaternion::identity(),
    );
    let features = |c: &Cuboid<f64>| {
        let found = contacts(c, &slab());
        found
            .iter()
            .map(|c| c.feature)
            .collect::<heapless::Vec<u32, 8>>()
    };
    assert_eq!(features(&before), features(&after));
}

#[test]
fn swapping_the_boxes_flips_the_normal() {
    let resting = cube(
        Vector3::new(0.0, 0.0, 0.1 - 1e-3),
        UnitQuaternion::identity(),
    );
    let found = contacts(&slab(), &resting);
    assert_all(&found, 4, 1e-3, -Vector3::z());
    // A tie between the two z faces goes to box 1, now the slab: its +z face (4) is
    // the reference, the cube's −z face (5) incident, each point an incident vertex
    // (two of the incident face's edges, lines 0–3).
    for c in &found {
        assert_eq!(c.feature >> 6, 5 | 4 << 3, "{c:?}");
        assert!(c.feature & 0o70 < 0o40 && c.feature & 0o7 < 4, "{c:?}");
    }
}

#[test]
fn cube_turned_45_degrees_on_a_cube_touches_at_an_octagon() {
    let base = cube(Vector3::zeros(), UnitQuaternion::identity());
    let turn = UnitQuaternion::from_euler_angles(0.0, 0.0, FRAC_PI_4);
    let top = cube(Vector3::new(0.0, 0.0, 2.0 * HALF - 1e-3), turn);
    let found = contacts(&top, &base);
    assert_all(&found, 8, 1e-3, Vector3::z());
    assert_distinct(&found);
    // The octagon's vertices: the squares' edges cross 0.05 m from the centre on one
    // axis and (√2 − 1)·0.05 m on the other.
    let short = (SQRT_2 - 1.0) * HALF;
    for c in &found {
        let (x, y) = (c.point.x.abs(), c.point.y.abs());
        let on_edge = |a: f64, b: f64| (a - HALF).abs() < 1e-12 && (b - short).abs() < 1e-12;
        assert!(on_edge(x, y) || on_edge(y, x), "{c:?}");
    }
}

#[test]
fn crossed_edges_touch_at_one_point() {
    // The base stands on an edge along x, the top on an edge along y, 1 mm overlap.
    let base = cube(
        Vector3::zeros(),
        UnitQuaternion::from_euler_angles(FRAC_PI_4, 0.0, 0.0),
    );
    let top = cube(
        Vector3::new(0.0, 0.0, 2.0 * SQRT_2 * HALF - 1e-3),
        UnitQuaternion::from_euler_angles(0.0, FRAC_PI_4, 0.0),
    );
    let found = contacts(&top, &base);
    assert_all(&found, 1, 1e-3, Vector3::z());
    let expected = Vector3::new(0.0, 0.0, SQRT_2 * HALF - 0.5e-3);
    assert!((found[0].point - expected).norm() < 1e-12, "{found:?}");
    assert_ne!(found[0].feature & edge::EDGE_EDGE, 0);
    // Box 1's edge along y (axis 1), box 2's along x (axis 0).
    assert_eq!(found[0].feature & 0xC, 4);
    assert_eq!(found[0].feature >> 4 & 0xC, 0);
    assert!((separation(&top, &base) + 1e-3).abs() < 1e-12);
}

#[test]
fn separated_boxes_have_no_contacts_and_a_positive_separation() {
    let above = cube(
        Vector3::new(0.0, 0.0, 0.1 + 2e-3),
        UnitQuaternion::identity(),
    );
    assert!(contacts(&above, &slab()).is_empty());
    assert!((separation(&above, &slab()) - 2e-3).abs() < 1e-12);
    // Exactly touching: no depth, no contact.
    let touching = cube(Vector3::new(0.0, 0.0, 0.1), UnitQuaternion::identity());
    assert!(contacts(&touching, &slab()).is_empty());
}

#[test]
fn nan_infinity_and_negative_extents_give_nothing_and_no_panic() {
    let mut bad = slab();
    bad.center.x = f64::NAN;
    let resting = cube(Vector3::new(0.0, 0.0, 0.099), UnitQuaternion::identity());
    assert!(contacts(&resting, &bad).is_empty());
    assert!(separation(&resting, &bad).is_nan());
    bad.center.x = f64::INFINITY;
    assert!(contacts(&bad, &resting).is_empty());
    let mut hollow = slab();
    hollow.half_extents.y = -0.1;
    assert!(contacts(&resting, &hollow).is_empty());
    assert!(separation(&hollow, &resting).is_nan());
    let spun = Cuboid {
        orientation: UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(
            f64::NAN,
            0.0,
            0.0,
            0.0,
        )),
        ..resting
    };
    assert!(contacts(&spun, &slab()).is_empty());
}

#[test]
fn f32_as_a_controller_holds_it() {
    let resting = Cuboid {
        half_extents: Vector3::repeat(0.05_f32),
        center: Vector3::new(0.0, 0.0, 0.099),
        orientation: UnitQuaternion::from_euler_angles(0.0, 0.0, 0.3),
    };
    let base = Cuboid {
        half_extents: Vector3::new(0.2_f32, 0.2, 0.05),
        center: Vector3::zeros(),
        orientation: UnitQuaternion::identity(),
    };
    let found = contacts(&resting, &base);
    assert_eq!(found.len(), 4, "{found:?}");
    for c in &found {
        assert!((c.depth - 1e-3).abs() < 1e-6, "{c:?}");
        assert!((c.normal - Vector3::z()).norm() < 1e-6, "{c:?}");
    }
    assert!((separation(&resting, &base) + 1e-3).abs() < 1e-6);
}
