use super::sat::{Frame, Shape};
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

/// A xorshift generator of numbers in [0, 1), enough to spread poses.
struct Poses(u64);

impl Poses {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1_u64 << 53) as f64
    }

    fn within(&mut self, limit: f64) -> f64 {
        limit * (2.0 * self.next() - 1.0)
    }

    /// A box 10–200 mm across within 80 mm of the origin, turned at random, barely
    /// turned (then some edge pairs are parallel and some edge axes copy face axes) or
    /// not at all, its quaternion a little off unit length now and then.
    fn cuboid<T: Real>(&mut self) -> Cuboid<T> {
        let small = [1.0, 1e-3, 1e-7, 0.0][(self.next() * 4.0) as usize];
        let (i, j, k) = match (self.next() * 3.0) as usize {
            0 => (self.within(1.0), self.within(1.0), self.within(1.0)),
            1 => (self.within(0.1) * small, self.within(0.1), 0.0),
            _ => (0.0, 0.0, 0.0),
        };
        let q = nalgebra::Quaternion::new(1.0, i, j, k);
        let q = q / q.norm() * [1.0, 1.0, 1.0 + 1e-6, 1.0 - 1e-4][(self.next() * 4.0) as usize];
        Cuboid {
            half_extents: Vector3::from_fn(|_, _| T::of(0.005 + 0.095 * self.next())),
            center: Vector3::from_fn(|_, _| T::of(self.within(0.08))),
            orientation: UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(
                T::of(q.w),
                T::of(q.i),
                T::of(q.j),
                T::of(q.k),
            )),
        }
    }
}

/// The axis the contact is built on when all 15 axes are computed exactly (no screen),
/// the first of equals of each kind: as [`sat::plan`] must choose it.
fn plan_unscreened<T: Real>(one: &Frame<T>, two: &Frame<T>) -> Option<sat::Plan<T>> {
    let (mut face, mut edge): (Option<sat::Axis<T>>, Option<sat::Axis<T>>) = (None, None);
    for index in 0..15 {
        let Some(axis) = sat::candidate(one, two, index) else {
            continue;
        };
        if axis.separation >= T::zero() || axis.separation.is_nan() {
            return None;
        }
        let best = if index < 6 { &mut face } else { &mut edge };
        if best.is_none_or(|b| axis.separation > b.separation) {
            *best = Some(axis);
        }
    }
    let face = face?;
    Some(match edge {
        Some(e) if e.separation * T::of(sat::FACE_PREFERENCE) > face.separation => {
            sat::Plan::Edge(e)
        }
        _ => sat::Plan::Face(face),
    })
}

/// `plan`'s axis as comparable bits: kind, origin, normal and separation.
fn plan_bits<T: Real>(plan: Option<sat::Plan<T>>) -> Option<(bool, sat::Origin, [u64; 4])> {
    let (edge, axis) = match plan? {
        sat::Plan::Face(axis) => (false, axis),
        sat::Plan::Edge(axis) => (true, axis),
    };
    let n = &axis.normal;
    // A face separation may differ in the sign of a zero only: compare its value.
    let separation = if edge {
        axis.separation.to_f64().to_bits()
    } else {
        (axis.separation.to_f64() + 0.0).to_bits()
    };
    let bits = [n.x, n.y, n.z].map(|x| x.to_f64().to_bits());
    Some((edge, axis.origin, [bits[0], bits[1], bits[2], separation]))
}

/// Pairs of random boxes, half of them moved until they barely overlap (0–1 mm, 0–10 µm
/// or 0–0.1 µm deep), the choice of axis with the screen against that without, bit
/// for bit, in `T`.
fn screen_keeps_the_choice<T: Real>(seed: u64) {
    let mut poses = Poses(seed);
    let (mut overlapping, mut edges) = (0, 0);
    for n in 0..20_000 {
        let (one, mut two) = (poses.cuboid::<T>(), poses.cuboid::<T>());
        if n % 2 == 1 {
            // Bisect the shift of box 2 towards box 1 at which they start to overlap.
            let d = two.center - one.center;
            let (mut lo, mut hi) = (T::zero(), T::one());
            for _ in 0..60 {
                let mid = (lo + hi) * T::of(0.5);
                let moved = Cuboid {
                    center: two.center - d * mid,
                    ..two
                };
                if separation(&one, &moved) < T::zero() {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            let deeper = [1e-3, 1e-5, 1e-7][n % 3] * poses.next();
            two.center -= d * hi + d.normalize() * T::of(deeper);
        }
        let (Some(a), Some(b)) = (Frame::of(&one), Frame::of(&two)) else {
            continue;
        };
        let screened = plan_bits(sat::plan(&Shape::of(a), &Shape::of(b)));
        assert_eq!(
            screened,
            plan_bits(plan_unscreened(&a, &b)),
            "{one:?} {two:?}"
        );
        overlapping += usize::from(screened.is_some());
        edges += usize::from(screened.is_some_and(|p| p.0));
    }
    // The poses reach both kinds of contact.
    assert!(overlapping > 8_000 && edges > 500, "{overlapping} {edges}");
}

#[test]
fn screening_edge_axes_changes_no_choice_f64() {
    screen_keeps_the_choice::<f64>(0x9E37_79B9_7F4A_7C15);
}

#[test]
fn screening_edge_axes_changes_no_choice_f32() {
    screen_keeps_the_choice::<f32>(0x2545_F491_4F6C_DD1D);
}
