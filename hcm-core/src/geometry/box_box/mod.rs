//! Two cuboids (box 1 and box 2), e.g. a box stacked on a box or a peg against the wall
//! of a block.
//!
//! A separating-axis test over the 15 axes of two boxes (3 face normals each, 9 cross
//! products of edge directions) finds the axis of least penetration; the contact is
//! then built on it, as ODE's `dBoxBox`, MuJoCo's box–box and parry's cuboid–cuboid
//! manifold do:
//!
//! - **face axis** (a face of the *reference* box): the face of the other
//!   (*incident*) box most opposed to it is clipped against the reference face's four
//!   side planes; every clipped vertex below the reference face is a point, ≤ 8;
//! - **edge axis**: one point between the closest points of the two edges.
//!
//! An edge axis wins only when it penetrates 5 % less than the best face axis (ODE's
//! factor): near-ties give the face's several points, which hold a resting box steady.
//!
//! The face axes share their dot products; the edge axes go through a screen
//! (`filter.rs`) that leaves out, without a square root, every edge axis it can prove
//! neither separates the boxes nor wins; the rest are computed exactly, so the result
//! is bit for bit that of testing the 15 axes one by one.
//!
//! # Feature ids
//! `feature` names what made a point, so it stays the same while the configuration
//! persists (faces as 2·axis + 1 if on the box's − side, 0..6; bits from 0):
//! - face contact: bits 0–5 the two boundary lines the point lies on, as
//!   8·low + high with lines 0–3 the incident face's edges (its vertices in cyclic
//!   order, edge k from vertex k to k + 1) and 4–7 the reference face's side planes
//!   (its next axis + and −, then the one after + and −): an incident vertex is two
//!   edges, a clipped crossing an edge and a side plane, a reference corner two side
//!   planes; bits 6–8 the incident face, bits 9–11 the reference face, bit 12 set when
//!   box 2 holds the reference face;
//! - edge–edge contact: bit 13 set, bits 0–3 the edge of box 1 and bits 4–7 that of
//!   box 2, each 4·axis + 1 (on the + side of the next axis) + 2 (of the one after).

mod clip;
mod edge;
mod filter;
mod sat;
#[cfg(test)]
mod tests;

use super::{ContactGeometry, Contacts, Cuboid};
use crate::{vector, Real};
use clip::Reference;
pub(crate) use sat::{Frame, Shape};
use sat::{Origin, Plan};

/// Where `box_1` and `box_2` overlap: up to 8 points, each with its own depth δ > 0
/// (m), the common normal (unit, from box 2 to box 1) and the point (m) half-way across
/// the overlap along the normal. Separated or exactly touching boxes give none, and so
/// does NaN or ±∞ anywhere or a negative half extent (no panic). See the module doc for
/// the choice of axis and the feature ids.
pub fn contacts<T: Real>(box_1: &Cuboid<T>, box_2: &Cuboid<T>) -> Contacts<T> {
    let mut found = Contacts::new();
    if let (Some(one), Some(two)) = (Frame::of(box_1), Frame::of(box_2)) {
        // At most 8 points into a capacity of 8: no push fails.
        each_contact(&Shape::of(one), &Shape::of(two), &mut |contact| {
            let _ = found.push(contact);
        });
    }
    found
}

/// [`contacts`] of box 1 and box 2, already [`Shape`]s (a compound's parts share the
/// moving box's, and a prepared part brings its own), each point handed to
/// `emit` in order.
pub(crate) fn each_contact<T: Real>(
    one: &Shape<T>,
    two: &Shape<T>,
    emit: &mut impl FnMut(ContactGeometry<T>),
) {
    let edge = match sat::plan(one, two) {
        None => return,
        Some(Plan::Edge(axis)) => axis,
        Some(Plan::Face(axis)) => {
            if face_contacts(&one.frame, &two.frame, &axis, emit) {
                return;
            }
            // The clipped face lies entirely above the reference face (a near-tie
            // with an edge): the single point of the best edge axis.
            match sat::best_edge(&one.frame, &two.frame) {
                Some(axis) => axis,
                None => return,
            }
        }
    };
    if let Origin::Edges { axis_1, axis_2 } = edge.origin {
        emit(edge::edge_contact(
            &one.frame,
            &two.frame,
            &edge,
            (axis_1, axis_2),
        ));
    }
}

/// The separating-axis test's signed value (m): the largest separation of the boxes'
/// shadows over the valid axes. < 0 when they overlap, then minus the penetration
/// depth along the best axis; > 0 when they are apart, then a lower bound on their
/// distance. Continuous in the poses (a maximum of continuous functions) except where
/// an edge pair crosses the parallel threshold (sin θ = 1e-6), so a simulator can find
/// touch-down and lift-off by root finding. NaN when a box is not finite or has a
/// negative half extent.
pub fn separation<T: Real>(box_1: &Cuboid<T>, box_2: &Cuboid<T>) -> T {
    match (Frame::of(box_1), Frame::of(box_2)) {
        (Some(one), Some(two)) => sat::max_separation(&one, &two),
        // 0/0: the NaN of either float type.
        _ => T::zero() / T::zero(),
    }
}

/// The face contact on face `axis`, its reference box its owner; whether it had points.
fn face_contacts<T: Real>(
    one: &Frame<T>,
    two: &Frame<T>,
    axis: &sat::Axis<T>,
    emit: &mut impl FnMut(ContactGeometry<T>),
) -> bool {
    let Origin::Face { second, axis: face } = axis.origin else {
        return false;
    };
    // The normal points from box 2 to box 1: box 1's reference face faces −n.
    let (reference, incident, outward) = if second {
        (two, one, axis.normal)
    } else {
        (one, two, vector::neg(&axis.normal))
    };
    let reference = Reference {
        frame: reference,
        axis: face,
        outward,
    };
    clip::face_contacts(&reference, incident, &axis.normal, second, emit)
}
