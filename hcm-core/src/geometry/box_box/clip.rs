//! A face contact: the incident face of one box clipped against the side planes of the
//! reference face of the other (Sutherland–Hodgman), each clipped vertex below the
//! reference face a contact point.

use super::sat::Frame;
use crate::geometry::{ContactGeometry, Contacts};
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
/// [`super`]'s encoding, with `tag` (reference box and faces) in bits 6–12.
pub(super) fn face_contacts<T: Real>(
    reference: &Reference<'_, T>,
    incident: &Frame<T>,
    normal: &Vector3<T>,
    reference_is_2: bool,
) -> Contacts<T> {
    let (incident_face, mut polygon) = incident_face(incident, &reference.outward);
    for plane in 0..4 {
        polygon = clip(&polygon, reference, plane);
    }
    let (frame, outward) = (reference.frame, &reference.outward);
    let face_center = frame.center + outward * frame.half[reference.axis];
    let negative = frame.axes[reference.axis].dot(outward) < T::zero();
    let tag = incident_face << 6
        | face_index(reference.axis, negative) << 9
        | u32::from(reference_is_2) << 12;
    let mut found = Contacts::new();
    for corner in &polygon {
        let depth = (face_center - corner.point).dot(outward);
        if depth > T::zero() {
            let (low, high) = if corner.arriving < corner.leaving {
                (corner.arriving, corner.leaving)
            } else {
                (corner.leaving, corner.arriving)
            };
            // At most 8 corners into a capacity of 8: the push cannot fail.
            let _ = found.push(ContactGeometry {
                depth,
                normal: *normal,
                point: corner.point + outward * (T::of(0.5) * depth),
                feature: tag | u32::from(low * 8 + high),
            });
        }
    }
    found
}

/// Face `axis` (0..3) on the negative side or not, as 0..6: 2·axis + (1 if negative).
pub(super) fn face_index(axis: usize, negative: bool) -> u32 {
    // axis < 3: the cast is exact.
    2 * axis as u32 + u32::from(negative)
}

/// The face of `incident` most opposed to the reference face's `outward` normal (–):
/// its index ([`face_index`]) and its four vertices in cyclic order.
fn incident_face<T: Real>(incident: &Frame<T>, outward: &Vector3<T>) -> (u32, Polygon<T>) {
    let alignment = |i: usize| incident.axes[i].dot(outward).abs();
    let axis = (1..3).fold(0, |best, i| {
        if alignment(i) > alignment(best) {
            i
        } else {
            best
        }
    });
    let negative = incident.axes[axis].dot(outward) > T::zero();
    let sign = if negative { -T::one() } else { T::one() };
    let center = incident.center + incident.axes[axis] * (sign * incident.half[axis]);
    let (p, q) = ((axis + 1) % 3, (axis + 2) % 3);
    let mut polygon = Polygon::new();
    for (k, (sp, sq)) in [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)]
        .into_iter()
        .enumerate()
    {
        let point = center
            + incident.axes[p] * (T::of(sp) * incident.half[p])
            + incident.axes[q] * (T::of(sq) * incident.half[q]);
        // k < 4: the casts are exact; 4 vertices into a capacity of 8.
        let _ = polygon.push(Corner {
            point,
            arriving: ((k + 3) % 4) as u8,
            leaving: k as u8,
        });
    }
    (face_index(axis, negative), polygon)
}

/// `polygon` cut by side plane `plane` (0..4: the reference face's tangent axes in
/// turn, + side then − side) of the reference face, keeping the part inside the face.
fn clip<T: Real>(polygon: &Polygon<T>, reference: &Reference<'_, T>, plane: usize) -> Polygon<T> {
    let frame = reference.frame;
    let tangent = (reference.axis + 1 + plane / 2) % 3;
    let side = if plane.is_multiple_of(2) {
        frame.axes[tangent]
    } else {
        -frame.axes[tangent]
    };
    // How far beyond the side plane (m): > 0 outside the reference face.
    let beyond = |p: &Vector3<T>| (p - frame.center).dot(&side) - frame.half[tangent];
    // plane < 4: the cast is exact.
    let line = 4 + plane as u8;
    let mut clipped = Polygon::new();
    let count = polygon.len();
    for (k, to) in polygon.iter().enumerate() {
        let from = &polygon[(k + count - 1) % count];
        let (from_beyond, to_beyond) = (beyond(&from.point), beyond(&to.point));
        let (from_in, to_in) = (from_beyond <= T::zero(), to_beyond <= T::zero());
        if from_in != to_in {
            // The signs differ, so the denominator is not zero.
            let s = from_beyond / (from_beyond - to_beyond);
            let point = from.point + (to.point - from.point) * s;
            let (arriving, leaving) = if from_in {
                (from.leaving, line)
            } else {
                (line, from.leaving)
            };
            let _ = clipped.push(Corner {
                point,
                arriving,
                leaving,
            });
        }
        if to_in {
            let _ = clipped.push(*to);
        }
    }
    clipped
}
