//! The separating-axis test for two boxes: the 15 candidate axes, the separation along
//! each, and the choice of the axis the contact is built on.

use super::filter::Pair;
use crate::geometry::Cuboid;
use crate::vector::{cross, dot, neg, sub};
use crate::Real;
use nalgebra::{UnitQuaternion, Vector3};

/// Below this |a × b| = sin θ (–) two edge directions count as parallel and their cross
/// product is no axis: its direction would be rounding noise. Skipping it costs at most
/// ~1e-6 × (the boxes' extents) (m) of separation, because the face axes of the two
/// boxes then span the missing direction to within that angle.
pub(super) const PARALLEL_EDGES: f64 = 1e-6;

/// An edge axis is chosen over the best face axis only if its penetration is below the
/// face's by this factor (–), ODE's `fudge_factor`: a face contact gives a manifold of
/// several points, an edge contact one, so near-ties resolve to the steadier face.
pub(super) const FACE_PREFERENCE: f64 = 1.05;

/// A box as the test needs it: centre (m), unit axes (–) and half extents (m), in the
/// common frame; all finite when [`Frame::of`] made it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Frame<T: Real> {
    pub center: Vector3<T>,
    pub axes: [Vector3<T>; 3],
    pub half: [T; 3],
}

impl<T: Real> Frame<T> {
    /// The frame of `cuboid`, or `None` when any of its numbers is not finite or a half
    /// extent is negative.
    pub fn of(cuboid: &Cuboid<T>) -> Option<Self> {
        let frame = Self::unchecked(cuboid);
        frame.valid().then_some(frame)
    }

    /// The frame of `cuboid` whatever its numbers; [`Frame::valid`] tells whether
    /// [`Frame::of`] would give it.
    pub fn unchecked(cuboid: &Cuboid<T>) -> Self {
        let h = &cuboid.half_extents;
        Frame {
            center: cuboid.center,
            axes: rotated_axes(&cuboid.orientation),
            half: [h.x, h.y, h.z],
        }
    }

    /// Whether every number is finite and every half extent ≥ 0.
    pub fn valid(&self) -> bool {
        // x · 0 is 0 (or −0) for a finite x and NaN for ±∞ or NaN: the sum is 0 only
        // if every number is finite (and cannot overflow).
        let zero = T::zero();
        let sum = |v: &Vector3<T>| v.x * zero + v.y * zero + v.z * zero;
        let [p, q, r] = self.half;
        let [a, b, c] = &self.axes;
        let nothing =
            sum(&self.center) + (p * zero + q * zero + r * zero) + sum(a) + sum(b) + sum(c);
        nothing == zero && p >= zero && q >= zero && r >= zero
    }

    /// Half extents (m) of the box's axis-aligned bounding box in the common frame, as
    /// [`Cuboid::world_half_extents`] gives them (the same operations, the same bits).
    pub fn bounds(&self) -> Vector3<T> {
        let [a, b, c] = &self.axes;
        let [p, q, r] = self.half;
        Vector3::new(
            a.x.abs() * p + b.x.abs() * q + c.x.abs() * r,
            a.y.abs() * p + b.y.abs() * q + c.y.abs() * r,
            a.z.abs() * p + b.z.abs() * q + c.z.abs() * r,
        )
    }

    /// Half the box's width along the unit `direction` (m): Σ hᵢ |aᵢ · u|.
    pub fn reach(&self, direction: &Vector3<T>) -> T {
        let [a, b, c] = &self.axes;
        let [p, q, r] = self.half;
        T::zero()
            + p * dot(a, direction).abs()
            + q * dot(b, direction).abs()
            + r * dot(c, direction).abs()
    }
}

/// The columns of `orientation`'s rotation matrix, with the operations of nalgebra's
/// `to_rotation_matrix` (so the same bits), but doubling by multiplying with 1 + 1
/// instead of converting the constant 2.0 from `f64` on every call.
fn rotated_axes<T: Real>(orientation: &UnitQuaternion<T>) -> [Vector3<T>; 3] {
    let (i, j, k, w) = (orientation.i, orientation.j, orientation.k, orientation.w);
    let two = T::one() + T::one();
    let (ww, ii, jj, kk) = (w * w, i * i, j * j, k * k);
    let (ij, wk, wj) = (i * j * two, w * k * two, w * j * two);
    let (ik, jk, wi) = (i * k * two, j * k * two, w * i * two);
    [
        Vector3::new(ww + ii - jj - kk, wk + ij, ik - wj),
        Vector3::new(ij - wk, ww - ii + jj - kk, wi + jk),
        Vector3::new(wj + ik, jk - wi, ww - ii - jj + kk),
    ]
}

/// A frame with what the separating-axis test uses against every other box, worked
/// out once: its reach along its own axes, the sum of its half extents and how far its
/// axes are from orthonormal.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Shape<T: Real> {
    pub frame: Frame<T>,
    /// [`Frame::reach`] along each of its own axes (m).
    pub own: [T; 3],
    /// Σ hᵢ (m).
    pub size: T,
    /// Σ over the six entries of AᵀA − I (–): 0 for exactly orthonormal axes.
    pub skew: T,
}

impl<T: Real> Shape<T> {
    /// The shape of `frame`.
    pub fn of(frame: Frame<T>) -> Self {
        let [a, b, c] = &frame.axes;
        let (ab, ac, bc) = (dot(a, b), dot(a, c), dot(b, c));
        let (aa, bb, cc) = (dot(a, a), dot(b, b), dot(c, c));
        let [p, q, r] = frame.half;
        let one = T::one();
        // The same products and sums as `reach` (whose dot aᵢ · aₖ is aₖ · aᵢ bit for
        // bit), less its leading 0 +, which changes no comparison.
        let own = [
            p * aa.abs() + q * ab.abs() + r * ac.abs(),
            p * ab.abs() + q * bb.abs() + r * bc.abs(),
            p * ac.abs() + q * bc.abs() + r * cc.abs(),
        ];
        let skew =
            (aa - one).abs() + (bb - one).abs() + (cc - one).abs() + ab.abs() + ac.abs() + bc.abs();
        Shape {
            frame,
            own,
            size: p + q + r,
            skew,
        }
    }
}

/// Where an axis comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Origin {
    /// The normal of faces `axis` (0..3) of box 1 (`second` false) or box 2.
    Face { second: bool, axis: usize },
    /// The cross product of box 1's edge direction `axis_1` and box 2's `axis_2`.
    Edges { axis_1: usize, axis_2: usize },
}

/// One candidate axis and the boxes' separation along it.
#[derive(Clone, Copy, Debug)]
pub(super) struct Axis<T: Real> {
    pub origin: Origin,
    /// The axis as a unit normal (–) pointing from box 2 to box 1.
    pub normal: Vector3<T>,
    /// Gap between the boxes' shadows on the axis (m): < 0 when they overlap there.
    pub separation: T,
}

/// Candidate `index` (0..15): 0–2 box 1's faces, 3–5 box 2's, 6–14 the edge pairs
/// (box 1's direction (index − 6) / 3, box 2's (index − 6) % 3). `None` for an edge
/// pair closer to parallel than [`PARALLEL_EDGES`].
pub(super) fn candidate<T: Real>(one: &Frame<T>, two: &Frame<T>, index: usize) -> Option<Axis<T>> {
    let (second, axis) = (index >= 3, index % 3);
    match index {
        0..6 => Some(along(
            one,
            two,
            Origin::Face { second, axis },
            if second {
                two.axes[axis]
            } else {
                one.axes[axis]
            },
        )),
        _ => edge_axis(one, two, (index - 6) / 3 % 3, (index - 6) % 3),
    }
}

/// Edge axis `axis_1` × `axis_2` (box 1's edge direction and box 2's, 0..3 each) as
/// [`candidate`] numbers it 6 + 3 `axis_1` + `axis_2`.
pub(super) fn edge_axis<T: Real>(
    one: &Frame<T>,
    two: &Frame<T>,
    axis_1: usize,
    axis_2: usize,
) -> Option<Axis<T>> {
    let cross = cross(&one.axes[axis_1], &two.axes[axis_2]);
    let squared = dot(&cross, &cross);
    // Well below the threshold's square the square root is too (it rounds
    // monotonically): skip it. NaN goes on, to the test below.
    if squared < T::of(PARALLEL_EDGES * PARALLEL_EDGES * 0.99) {
        return None;
    }
    let sine = squared.square_root();
    if sine < T::of(PARALLEL_EDGES) || sine.is_nan() {
        return None;
    }
    let unit = Vector3::new(cross.x / sine, cross.y / sine, cross.z / sine);
    Some(along(one, two, Origin::Edges { axis_1, axis_2 }, unit))
}

/// The separation along the unit `direction` (–) from `origin`.
fn along<T: Real>(
    one: &Frame<T>,
    two: &Frame<T>,
    origin: Origin,
    direction: Vector3<T>,
) -> Axis<T> {
    let offset = dot(&sub(&one.center, &two.center), &direction);
    let separation = offset.abs() - one.reach(&direction) - two.reach(&direction);
    let normal = if offset < T::zero() {
        neg(&direction)
    } else {
        direction
    };
    Axis {
        origin,
        normal,
        separation,
    }
}

/// The largest separation over all valid axes (m): < 0 only when the boxes overlap.
pub(super) fn max_separation<T: Real>(one: &Frame<T>, two: &Frame<T>) -> T {
    let mut largest = -T::MAX;
    for axis in (0..15).filter_map(|index| candidate(one, two, index)) {
        if axis.separation.is_nan() {
            return axis.separation;
        }
        if axis.separation > largest {
            largest = axis.separation;
        }
    }
    largest
}

/// The axis a contact is built on.
pub(super) enum Plan<T: Real> {
    /// The face axis of least penetration: no edge axis beats it by the factor
    /// [`FACE_PREFERENCE`].
    Face(Axis<T>),
    /// The edge axis of least penetration, which beats every face axis by that factor.
    Edge(Axis<T>),
}

/// The axis to build the contact on; `None` when some axis separates the boxes (or they
/// touch exactly there) or a separation is NaN (an overflow). The choice is the one of
/// the 15 separations [`candidate`] computes, first the six face axes (exactly, from
/// dot products shared between the axes), then the edge axes, which
/// [`Pair::exact_edges`] screens: only those that might separate the boxes or win over
/// the face are computed exactly, with a square root each.
pub(super) fn plan<T: Real>(one: &Shape<T>, two: &Shape<T>) -> Option<Plan<T>> {
    let mut pair = Pair::of(one, two);
    let (mut best, mut face) = (0, (T::zero(), T::zero()));
    for index in 0..6 {
        let found = pair.face_separation(index);
        if found.0 >= T::zero() || found.0.is_nan() {
            return None;
        }
        // The first of equals.
        if index == 0 || found.0 > face.0 {
            (best, face) = (index, found);
        }
    }
    let face = pair.face(best, face);
    let screen = pair.set_face(face.separation);
    let mut edge: Option<Axis<T>> = None;
    for axis_1 in 0..3 {
        let exact = if screen { pair.exact_edges(axis_1) } else { 7 };
        for axis_2 in 0..3 {
            if exact & 1 << axis_2 == 0 {
                continue;
            }
            let Some(axis) = edge_axis(&one.frame, &two.frame, axis_1, axis_2) else {
                continue;
            };
            if axis.separation >= T::zero() || axis.separation.is_nan() {
                return None;
            }
            if edge.is_none_or(|b| axis.separation > b.separation) {
                edge = Some(axis);
            }
        }
    }
    // An edge screened out loses to the face, so it is not the best edge if one wins.
    Some(match edge {
        Some(e) if e.separation * T::of(FACE_PREFERENCE) > face.separation => Plan::Edge(e),
        _ => Plan::Face(face),
    })
}

/// The edge axis of least penetration over all valid edge pairs, each computed exactly
/// (the first of equals), for boxes no axis separates; `None` when all are parallel.
pub(super) fn best_edge<T: Real>(one: &Frame<T>, two: &Frame<T>) -> Option<Axis<T>> {
    let mut best: Option<Axis<T>> = None;
    for axis in (0..9).filter_map(|index| edge_axis(one, two, index / 3, index % 3)) {
        if best.is_none_or(|b| axis.separation > b.separation) {
            best = Some(axis);
        }
    }
    best
}
