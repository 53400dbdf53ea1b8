//! An edge–edge contact: one point between the closest points of the two crossing edges.

use super::sat::{Axis, Frame};
use crate::geometry::ContactGeometry;
use crate::vector::{add, add_scaled, dot, neg, scale, sub};
use crate::Real;
use nalgebra::Vector3;

/// Bit 13 of a feature id: the point is an edge–edge contact.
pub(super) const EDGE_EDGE: u32 = 1 << 13;

/// The contact on `axis`, the cross product of box 1's edge direction `axis_1` and box
/// 2's `axis_2` (0..3 each): depth δ = −(the axis's separation) (m), the point at the
/// middle of the closest points of the two edges (m), feature id `EDGE_EDGE | edge_1 |
/// edge_2 << 4` with edges numbered as in [`edge`].
pub(super) fn edge_contact<T: Real>(
    one: &Frame<T>,
    two: &Frame<T>,
    axis: &Axis<T>,
    (axis_1, axis_2): (usize, usize),
) -> ContactGeometry<T> {
    // Box 1's edge nearest box 2 lies towards −n, box 2's towards +n.
    let (middle_1, edge_1) = edge(one, axis_1, &neg(&axis.normal));
    let (middle_2, edge_2) = edge(two, axis_2, &axis.normal);
    let (direction_1, direction_2) = (one.axes[axis_1], two.axes[axis_2]);
    // Closest points of the two lines; 1 − c² = sin² θ ≥ PARALLEL_EDGES², not zero.
    let c = dot(&direction_1, &direction_2);
    let w = sub(&middle_1, &middle_2);
    let (d, e) = (dot(&direction_1, &w), dot(&direction_2, &w));
    let sine_squared = T::one() - c * c;
    let s = clamp((c * e - d) / sine_squared, one.half[axis_1]);
    let t = clamp((e - c * d) / sine_squared, two.half[axis_2]);
    let closest_1 = add_scaled(&middle_1, &direction_1, s);
    let closest_2 = add_scaled(&middle_2, &direction_2, t);
    ContactGeometry {
        depth: -axis.separation,
        normal: axis.normal,
        point: scale(&add(&closest_1, &closest_2), T::of(0.5)),
        feature: EDGE_EDGE | edge_1 | edge_2 << 4,
    }
}

/// The edge of `frame` along `axis` furthest towards `direction` (–): its middle (m)
/// and its number 4·axis + (1 if on the + side of the next axis) + (2 if on the + side
/// of the one after), 0..12.
fn edge<T: Real>(frame: &Frame<T>, axis: usize, direction: &Vector3<T>) -> (Vector3<T>, u32) {
    let mut middle = frame.center;
    // axis < 3: the cast is exact.
    let mut number = 4 * axis as u32;
    for (bit, other) in [(1, (axis + 1) % 3), (2, (axis + 2) % 3)] {
        let offset = scale(&frame.axes[other], frame.half[other]);
        if dot(&frame.axes[other], direction) >= T::zero() {
            middle = add(&middle, &offset);
            number |= bit;
        } else {
            middle = sub(&middle, &offset);
        }
    }
    (middle, number)
}

/// `s` (m) limited to the edge's half length `half` (m): the closest points of the lines
/// fall on the edges whenever the edge axis is the one of least penetration; the limit
/// keeps the point on the boxes otherwise.
fn clamp<T: Real>(s: T, half: T) -> T {
    if s > half {
        half
    } else if s < -half {
        -half
    } else {
        s
    }
}
