//! A moving shape (body 1) against a fixed compound body (body 2) made of boxes, e.g. a
//! peg in a block with a rectangular hole (four walls and a bottom).

use super::{box_box, sphere_box, ContactGeometry, Contacts, Cuboid};
use crate::Real;
use nalgebra::Vector3;

mod part;
pub use part::Part;

/// Bits of a feature id left to the part's own generator; the part index sits above.
pub const PART_SHIFT: u32 = 16;

/// The contacts of `moving` with every part of a compound (each `parts[i]` in the common
/// frame), merged into one manifold. Each point keeps its part's depth δ (m), normal
/// (unit, part → moving box) and point (m); its feature id is the part's
/// ([`box_box::contacts`]) with the part index (modulo 2¹⁶) in bits 16–31, so it stays
/// unique and stable. When the parts give more than 8 points, the 8 deepest are kept:
/// a new point replaces the shallowest kept one if it is strictly deeper (ties keep the
/// earlier part), so the result is deterministic, in part order except for replacements.
pub fn contacts<T: Real>(moving: &Cuboid<T>, parts: &[Cuboid<T>]) -> Contacts<T> {
    let mut found = Contacts::new();
    // Not finite or a negative half extent: no part touches it (as box_box::contacts).
    if let Some(frame) = box_box::Frame::of(moving) {
        merge(&frame, parts, &mut found);
    }
    // The one return: the vector is built in place, not copied out.
    found
}

/// [`contacts`] against parts prepared once ([`Part`]): the same points, bit for bit,
/// without redoing each part's frame, bounds, validity and sums at every call (the
/// peg's block of five boxes: 6,126 → 5,307 instructions per manifold).
pub fn prepared_contacts<T: Real>(moving: &Cuboid<T>, parts: &[Part<T>]) -> Contacts<T> {
    let mut found = Contacts::new();
    if let Some(frame) = box_box::Frame::of(moving) {
        merge_prepared(&frame, parts, &mut found);
    }
    found
}

/// [`contacts`] of the moving box's `frame`, into the empty `found`.
#[inline(never)]
fn merge<T: Real>(frame: &box_box::Frame<T>, parts: &[Cuboid<T>], found: &mut Contacts<T>) {
    let reach = frame.bounds();
    let one = box_box::Shape::of(*frame);
    for (index, part) in parts.iter().enumerate() {
        // A part whose axis-aligned bounds miss the moving box's cannot touch it: the
        // cheap test spares the 15-axis one for the far walls of a hole. One not
        // finite touches nothing either.
        let two = box_box::Frame::unchecked(part);
        if misses(&frame.center, &reach, &two.center, &two.bounds()) || !two.valid() {
            continue;
        }
        box_box::each_contact(&one, &box_box::Shape::of(two), &mut |contact| {
            keep_deepest(found, tagged(&contact, index));
        });
    }
}

/// [`prepared_contacts`] of the moving box's `frame`, into the empty `found`: as
/// [`merge`], each part's work read from it.
#[inline(never)]
fn merge_prepared<T: Real>(frame: &box_box::Frame<T>, parts: &[Part<T>], found: &mut Contacts<T>) {
    let reach = frame.bounds();
    let one = box_box::Shape::of(*frame);
    for (index, part) in parts.iter().enumerate() {
        let two = &part.shape;
        if !part.valid || misses(&frame.center, &reach, &two.frame.center, &part.bounds) {
            continue;
        }
        box_box::each_contact(&one, two, &mut |contact| {
            keep_deepest(found, tagged(&contact, index));
        });
    }
}

/// The contacts of a sphere (`center` (m), `radius` (m); body 1) with every part: one
/// point per part it penetrates ([`sphere_box::contact`], δ > 0 (m)), feature id the
/// part index in bits 16–31, the deepest 8 kept as in [`contacts`]. NaN gives none.
pub fn sphere_contacts<T: Real>(
    center: &Vector3<T>,
    radius: T,
    parts: &[Cuboid<T>],
) -> Contacts<T> {
    let mut found = Contacts::new();
    for (index, part) in parts.iter().enumerate() {
        let contact = sphere_box::contact(center, radius, part);
        if contact.depth > T::zero() {
            keep_deepest(&mut found, tagged(&contact, index));
        }
    }
    found
}

/// The compound's separation from `moving` (m): the least over the parts of
/// [`box_box::separation`], < 0 when some part penetrates. A part whose axis-aligned
/// bounds miss the moving box's counts with the gap between the bounds instead (also a
/// positive lower bound on its distance, and cheaper), so the sign — what event
/// location reads — is that of the exact test. +[`Real::MAX`] for no parts, NaN if any
/// part's is NaN.
pub fn separation<T: Real>(moving: &Cuboid<T>, parts: &[Cuboid<T>]) -> T {
    let mut least = T::MAX;
    let reach = moving.world_half_extents();
    for part in parts {
        let bounds = bounds_gap(
            &moving.center,
            &reach,
            &part.center,
            &part.world_half_extents(),
        );
        let gap = if bounds > T::zero() {
            bounds
        } else {
            box_box::separation(moving, part)
        };
        if gap.is_nan() {
            return gap;
        }
        if gap < least {
            least = gap;
        }
    }
    least
}

/// The gap (m) between the axis-aligned bounding boxes of the moving box (centre
/// `center` (m), half extents along the common axes `reach` (m)) and a part (`part`,
/// `part_reach`, likewise): > 0 when they miss each other (then a lower bound on the two
/// boxes' distance), ≤ 0 when they overlap; NaN propagates.
fn bounds_gap<T: Real>(
    center: &Vector3<T>,
    reach: &Vector3<T>,
    part: &Vector3<T>,
    part_reach: &Vector3<T>,
) -> T {
    let gaps = axis_gaps(center, reach, part, part_reach);
    // `max` would skip a NaN: keep it, so that NaN input never passes as "apart".
    gaps.iter().fold(-T::MAX, |gap, &x| {
        if x.is_nan() || gap.is_nan() {
            x + gap
        } else {
            gap.max(x)
        }
    })
}

/// Whether the axis-aligned bounding box of the moving box (centre `center` (m), half
/// extents `reach` (m)) misses a part's (centre `c` (m), half extents `bounds` (m)):
/// [`bounds_gap`] > 0, without its maximum (any axis apart, none NaN: on the
/// controller the maximum's compares and selects cost the peg's manifold 148
/// instructions more).
fn misses<T: Real>(
    center: &Vector3<T>,
    reach: &Vector3<T>,
    c: &Vector3<T>,
    bounds: &Vector3<T>,
) -> bool {
    let [x, y, z] = axis_gaps(center, reach, c, bounds);
    // A NaN anywhere makes the gap NaN, which is not > 0.
    let zero = T::zero();
    !(x.is_nan() || y.is_nan() || z.is_nan()) && (x > zero || y > zero || z > zero)
}

/// The bounding boxes' gap along each common axis (m), |Δc| − reach − part's reach,
/// written out per axis (nalgebra's generic operators cost several times more on the
/// controller).
fn axis_gaps<T: Real>(
    center: &Vector3<T>,
    reach: &Vector3<T>,
    c: &Vector3<T>,
    bounds: &Vector3<T>,
) -> [T; 3] {
    [
        (center.x - c.x).abs() - reach.x - bounds.x,
        (center.y - c.y).abs() - reach.y - bounds.y,
        (center.z - c.z).abs() - reach.z - bounds.z,
    ]
}

/// `contact` with part `index` in the high bits of its feature id.
fn tagged<T: Real>(contact: &ContactGeometry<T>, index: usize) -> ContactGeometry<T> {
    // Keeping the low 16 bits of the index is the documented modulo 2¹⁶.
    let part = (index & 0xFFFF) as u32;
    ContactGeometry {
        feature: contact.feature | part << PART_SHIFT,
        ..*contact
    }
}

/// Adds `contact` to `found`, or, when full, puts it in place of the shallowest kept
/// point if it is strictly deeper.
fn keep_deepest<T: Real>(found: &mut Contacts<T>, contact: ContactGeometry<T>) {
    if let Err(contact) = found.push(contact) {
        let shallowest = (1..found.len()).fold(0, |least, i| {
            if found[i].depth < found[least].depth {
                i
            } else {
                least
            }
        });
        if let Some(kept) = found.get_mut(shallowest) {
            if contact.depth > kept.depth {
                *kept = contact;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::UnitQuaternion;

    fn block(half: [f64; 3], center: [f64; 3]) -> Cuboid<f64> {
        Cuboid {
            half_extents: Vector3::from(half),
            center: Vector3::from(center),
            orientation: UnitQuaternion::identity(),
        }
    }

    /// A block with a 0.1 m square hole, 0.1 m deep: a 20 mm bottom (top face at z = 0)
    /// and four 20 mm walls up to z = 0.1 m.
    fn block_with_a_hole() -> [Cuboid<f64>; 5] {
        [
            block([0.07, 0.07, 0.01], [0.0, 0.0, -0.01]),
            block([0.01, 0.07, 0.05], [0.06, 0.0, 0.05]),
            block([0.01, 0.07, 0.05], [-0.06, 0.0, 0.05]),
            block([0.05, 0.01, 0.05], [0.0, 0.06, 0.05]),
            block([0.05, 0.01, 0.05], [0.0, -0.06, 0.05]),
        ]
    }

    #[test]
    fn peg_on_the_bottom_and_against_a_wall_merges_both() {
        // A 40 mm square peg, 1 mm into the bottom and 0.5 mm into the +x wall.
        let peg = block([0.02, 0.02, 0.04], [0.0305, 0.0, 0.039]);
        let parts = block_with_a_hole();
        let found = contacts(&peg, &parts);
        assert_eq!(found.len(), 8, "{found:?}");
        let (bottom, wall): (heapless::Vec<_, 8>, heapless::Vec<_, 8>) = (
            found
                .iter()
                .filter(|c| c.feature >> PART_SHIFT == 0)
                .collect(),
            found
                .iter()
                .filter(|c| c.feature >> PART_SHIFT == 1)
                .collect(),
        );
        assert_eq!((bottom.len(), wall.len()), (4, 4));
        assert!(bottom
            .iter()
            .all(|c| (c.depth - 1e-3).abs() < 1e-12 && c.normal == Vector3::z()));
        assert!(wall
            .iter()
            .all(|c| (c.depth - 5e-4).abs() < 1e-12 && c.normal == -Vector3::x()));
        for (i, a) in found.iter().enumerate() {
            assert!(found[i + 1..].iter().all(|b| b.feature != a.feature));
        }
        assert!((separation(&peg, &parts) + 1e-3).abs() < 1e-12);
    }

    #[test]
    fn more_than_eight_points_keep_the_deepest_eight() {
        // Three narrow rails under a cube, 1, 2 and 3 mm deep: 12 points, 8 kept.
        let cube = block([0.05, 0.05, 0.05], [0.0, 0.0, 0.05]);
        let rails =
            [1e-3, 2e-3, 3e-3].map(|depth| block([0.01, 0.04, 0.01], [0.0, 0.0, depth - 0.01]));
        let rails = [
            Cuboid {
                center: rails[0].center + Vector3::x() * -0.03,
                ..rails[0]
            },
            rails[1],
            Cuboid {
                center: rails[2].center + Vector3::x() * 0.03,
                ..rails[2]
            },
        ];
        let found = contacts(&cube, &rails);
        assert_eq!(found.len(), 8, "{found:?}");
        for c in &found {
            let part = c.feature >> PART_SHIFT;
            assert!(part == 1 || part == 2, "{c:?}");
            assert!(
                (c.depth - 1e-3 * f64::from(part + 1)).abs() < 1e-12,
                "{c:?}"
            );
        }
        assert!((separation(&cube, &rails) + 3e-3).abs() < 1e-12);
    }

    #[test]
    fn ball_in_a_corner_of_the_hole_touches_bottom_and_wall() {
        let parts = block_with_a_hole();
        let found = sphere_contacts(&Vector3::new(0.0, -0.041, 0.0095), 0.01, &parts);
        assert_eq!(found.len(), 2, "{found:?}");
        assert_eq!(found[0].feature, 0);
        assert!((found[0].depth - 5e-4).abs() < 1e-12);
        assert_eq!(found[1].feature, 4 << PART_SHIFT);
        assert!((found[1].depth - 1e-3).abs() < 1e-12 && found[1].normal == Vector3::y());
    }

    #[test]
    fn no_parts_and_nan_parts() {
        let cube = block([0.05; 3], [0.0; 3]);
        assert!(contacts(&cube, &[]).is_empty());
        assert_eq!(separation(&cube, &[]), f64::MAX);
        let broken = block([0.05; 3], [f64::NAN, 0.0, 0.0]);
        assert!(contacts(&cube, &[broken]).is_empty());
        assert!(separation(&cube, &[cube, broken]).is_nan());
        assert!(sphere_contacts(&Vector3::zeros(), f64::NAN, &[cube]).is_empty());
    }
}
