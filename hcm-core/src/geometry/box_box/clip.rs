//! A face contact: the incident face of one box clipped against the side planes of the
//! reference face of the other (Sutherland–Hodgman), each clipped vertex below the
//! reference face a contact point.

use super::sat::Frame;
use crate::geometry::ContactGeometry;
use crate::vector::{add, add_scaled, dot, scale, sub};
use crate::Real;
use nalgebra::Vector3;

/// A vertex of the clipped polygon (position in m) and the two boundary lines it lies
/// on, the one arriving at it and the one leaving it in the polygon's order: 0–3 the
/// incident face's edges, 4–7 the reference face's side planes. A vertex of the
/// incident face lies on two of its edges, a crossing on an edge and a side plane, a
/// corner of the reference face inside the incident face on two side planes.
#[derive(Clone, Copy, Debug)]
struct Corner<T: Real> {
    point: Vector3<T>,
    /// (point − reference centre) · the tangent axis being clipped against (m), kept
    /// for the second plane of the pair.
    along: T,
    arriving: u8,
    leaving: u8,
}

/// A convex quad clipped by four planes gains at most one vertex per plane: ≤ 8.
type Polygon<T> = heapless::Vec<Corner<T>, 8>;

/// The reference face: face `axis` of box `frame` whose outward normal is `outward`.
pub(super) struct Reference<'a, T: Real> {
    pub frame: &'a Frame<T>,
    pub axis: usize,
    pub outward: Vector3<T>,
}

/// The points of a face contact, each with the common `normal` (–, box 2 → box 1),
/// its depth δ below the reference face (m, > 0), its point half-way between the
/// incident surface and the reference face (m) and the feature id of
/// [`super`]'s encoding, with `tag` (reference box and faces) in bits 6–12, handed to
/// `emit` in the polygon's order. Whether there was any.
pub(super) fn face_contacts<T: Real>(
    reference: &Reference<'_, T>,
    incident: &Frame<T>,
    normal: &Vector3<T>,
    reference_is_2: bool,
    emit: &mut impl FnMut(ContactGeometry<T>),
) -> bool {
    let [mut polygon, mut spare] = [Polygon::new(), Polygon::new()];
    let (mut polygon, mut spare) = (&mut polygon, &mut spare);
    let incident_face = incident_face(incident, &reference.outward, polygon);
    let (frame, outward) = (reference.frame, &reference.outward);
    for pair in 0..2 {
        // Side planes 2·pair (+ side) and 2·pair + 1 (− side) of one tangent axis.
        let tangent = (reference.axis + 1 + pair) % 3;
        let axis = &frame.axes[tangent];
        for corner in polygon.iter_mut() {
            corner.along = dot(&sub(&corner.point, &frame.center), axis);
        }
        for plane in 2 * pair..2 * pair + 2 {
            let negative = plane % 2 == 1;
            let side = Side {
                center: &frame.center,
                axis,
                sign: if negative { -T::one() } else { T::one() },
                half: frame.half[tangent],
                negative,
                // plane < 4: the cast is exact.
                line: 4 + plane as u8,
            };
            // A plane with every corner inside leaves the polygon as it is.
            if polygon.iter().all(|c| side.beyond(c) <= T::zero()) {
                continue;
            }
            clip(polygon, spare, &side);
            core::mem::swap(&mut polygon, &mut spare);
        }
    }
    let face_center = add_scaled(&frame.center, outward, frame.half[reference.axis]);
    let negative = dot(&frame.axes[reference.axis], outward) < T::zero();
    let tag = incident_face << 6
        | face_index(reference.axis, negative) << 9
        | u32::from(reference_is_2) << 12;
    let mut any = false;
    for corner in polygon.iter() {
        let depth = dot(&sub(&face_center, &corner.point), outward);
        if depth > T::zero() {
            let (low, high) = if corner.arriving < corner.leaving {
                (corner.arriving, corner.leaving)
            } else {
                (corner.leaving, corner.arriving)
            };
            emit(ContactGeometry {
                depth,
                normal: *normal,
                point: add_scaled(&corner.point, outward, T::of(0.5) * depth),
                feature: tag | u32::from(low * 8 + high),
            });
            any = true;
        }
    }
    any
}

/// Face `axis` (0..3) on the negative side or not, as 0..6: 2·axis + (1 if negative).
pub(super) fn face_index(axis: usize, negative: bool) -> u32 {
    // axis < 3: the cast is exact.
    2 * axis as u32 + u32::from(negative)
}

/// The face of `incident` most opposed to the reference face's `outward` normal (–):
/// its four vertices in cyclic order, into the empty `polygon`, and its index
/// ([`face_index`]).
fn incident_face<T: Real>(
    incident: &Frame<T>,
    outward: &Vector3<T>,
    polygon: &mut Polygon<T>,
) -> u32 {
    let [a, b, c] = &incident.axes;
    // The axis most aligned with the normal, the first of equals.
    let (mut axis, mut along) = (0, dot(a, outward));
    let d = dot(b, outward);
    if d.abs() > along.abs() {
        (axis, along) = (1, d);
    }
    let d = dot(c, outward);
    if d.abs() > along.abs() {
        (axis, along) = (2, d);
    }
    let negative = along > T::zero();
    let sign = if negative { -T::one() } else { T::one() };
    let center = add_scaled(
        &incident.center,
        &incident.axes[axis],
        sign * incident.half[axis],
    );
    let (p, q) = ((axis + 1) % 3, (axis + 2) % 3);
    // The centre + the tangents times ±h: axis × (−h) is −(axis × h) exactly.
    let (u, v) = (
        scale(&incident.axes[p], incident.half[p]),
        scale(&incident.axes[q], incident.half[q]),
    );
    let (plus, minus) = (add(&center, &u), sub(&center, &u));
    // 4 vertices into a capacity of 8: no push fails.
    let mut push = |point, k: u8| {
        let _ = polygon.push(Corner {
            point,
            along: T::zero(),
            arriving: (k + 3) % 4,
            leaving: k,
        });
    };
    push(add(&plus, &v), 0);
    push(add(&minus, &v), 1);
    push(sub(&minus, &v), 2);
    push(sub(&plus, &v), 3);
    face_index(axis, negative)
}

/// One side plane of the reference face: across the unit tangent `axis` (–) of the
/// face's box (centre `center` (m), half extent `half` (m) along it), on its − side if
/// `negative` (then `sign` is −1, else +1); boundary line `line` (4–7). The sign and
/// half extent are looked up once per plane rather than at every corner (saving
/// 129 instructions per peg manifold).
struct Side<'a, T: Real> {
    center: &'a Vector3<T>,
    axis: &'a Vector3<T>,
    sign: T,
    half: T,
    negative: bool,
    line: u8,
}

impl<T: Real> Side<'_, T> {
    /// How far `corner` lies beyond the plane (m): > 0 outside the reference face. On
    /// the − side (p − c) · (−a) is −((p − c) · a) exactly (rounding is symmetric), and
    /// −1 × x is −x.
    fn beyond(&self, corner: &Corner<T>) -> T {
        corner.along * self.sign - self.half
    }
}

/// `polygon` cut by the side plane `side`, keeping the part inside the face, into
/// `clipped` (emptied first). Each corner's `along` must hold its coordinate on the
/// side's tangent axis; a corner made on the + side gets its own, for the − side next.
fn clip<T: Real>(polygon: &Polygon<T>, clipped: &mut Polygon<T>, side: &Side<'_, T>) {
    clipped.clear();
    let Some(last) = polygon.last() else {
        return;
    };
    let (mut from, mut from_beyond) = (last, side.beyond(last));
    for to in polygon {
        let to_beyond = side.beyond(to);
        let (from_in, to_in) = (from_beyond <= T::zero(), to_beyond <= T::zero());
        if from_in != to_in {
            // The signs differ, so the denominator is not zero.
            let s = from_beyond / (from_beyond - to_beyond);
            let point = add_scaled(&from.point, &sub(&to.point, &from.point), s);
            let along = if side.negative {
                T::zero()
            } else {
                dot(&sub(&point, side.center), side.axis)
            };
            let (arriving, leaving) = if from_in {
                (from.leaving, side.line)
            } else {
                (side.line, from.leaving)
            };
            let _ = clipped.push(Corner {
                point,
                along,
                arriving,
                leaving,
            });
        }
        if to_in {
            let _ = clipped.push(*to);
        }
        (from, from_beyond) = (to, to_beyond);
    }
}
