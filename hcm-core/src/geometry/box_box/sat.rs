//! The separating-axis test for two boxes: the 15 candidate axes, the separation along
//! each, and the choice of the axis the contact is built on.

use crate::geometry::Cuboid;
use crate::Real;
use nalgebra::Vector3;

/// Below this |a × b| = sin θ (–) two edge directions count as parallel and their cross
/// product is no axis: its direction would be rounding noise. Skipping it costs at most
/// ~1e-6 × (the boxes' extents) (m) of separation, because the face axes of the two
/// boxes then span the missing direction to within that angle.
pub(super) const PARALLEL_EDGES: f64 = 1e-6;

/// An edge axis is chosen over the best face axis only if its penetration is below the
/// face's by this factor (–), ODE's `fudge_factor`: a face contact gives a manifold of
/// several points, an edge contact one, so near-ties resolve to the steadier face.
pub(super) const FACE_PREFERENCE: f64 = 1.05;

/// A box as the test needs it: centre (m), unit axes (–) and half extents (m), all
/// finite, in the common frame.
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
        let rotation = cuboid.orientation.to_rotation_matrix();
        let m = rotation.matrix();
        let axes = [0, 1, 2].map(|i| Vector3::new(m[(0, i)], m[(1, i)], m[(2, i)]));
        let half = [0, 1, 2].map(|i| cuboid.half_extents[i]);
        let finite = cuboid.center.iter().all(|x| x.is_finite())
            && axes.iter().flat_map(|a| a.iter()).all(|x| x.is_finite())
            && half.iter().all(|h| h.is_finite() && *h >= T::zero());
        finite.then_some(Frame {
            center: cuboid.center,
            axes,
            half,
        })
    }

    /// Half the box's width along the unit `direction` (m): Σ hᵢ |aᵢ · u|.
    pub fn reach(&self, direction: &Vector3<T>) -> T {
        (0..3).fold(T::zero(), |sum, i| {
            sum + self.half[i] * self.axes[i].dot(direction).abs()
        })
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
    let (origin, direction) = match index {
        0..3 => (
            Origin::Face {
                second: false,
                axis: index,
            },
            one.axes[index],
        ),
        3..6 => (
            Origin::Face {
                second: true,
                axis: index - 3,
            },
            two.axes[index - 3],
        ),
        _ => {
            let (axis_1, axis_2) = ((index - 6) / 3 % 3, (index - 6) % 3);
            let cross = one.axes[axis_1].cross(&two.axes[axis_2]);
            let sine = cross.norm();
            if sine < T::of(PARALLEL_EDGES) || sine.is_nan() {
                return None;
            }
            (Origin::Edges { axis_1, axis_2 }, cross / sine)
        }
    };
    let offset = (one.center - two.center).dot(&direction);
    let separation = offset.abs() - one.reach(&direction) - two.reach(&direction);
    let normal = if offset < T::zero() {
        -direction
    } else {
        direction
    };
    Some(Axis {
        origin,
        normal,
        separation,
    })
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

/// The axes of least penetration: the best face axis and the best edge axis.
pub(super) struct Choice<T: Real> {
    pub face: Axis<T>,
    /// `None` when every edge pair is parallel (the boxes' axes aligned).
    pub edge: Option<Axis<T>>,
}

impl<T: Real> Choice<T> {
    /// The edge axis, if it beats the face axis by the factor [`FACE_PREFERENCE`].
    pub fn winning_edge(&self) -> Option<Axis<T>> {
        self.edge
            .filter(|e| e.separation * T::of(FACE_PREFERENCE) > self.face.separation)
    }
}

/// The best axes of each kind; `None` when some axis separates the boxes (or they
/// touch exactly there) or a separation is NaN (an overflow).
pub(super) fn choose<T: Real>(one: &Frame<T>, two: &Frame<T>) -> Option<Choice<T>> {
    let mut face: Option<Axis<T>> = None;
    let mut edge: Option<Axis<T>> = None;
    for index in 0..15 {
        let Some(axis) = candidate(one, two, index) else {
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
    Some(Choice { face: face?, edge })
}
