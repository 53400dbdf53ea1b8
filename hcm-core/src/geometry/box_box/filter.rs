//! The dot products two boxes' separating-axis test shares between its axes, the six
//! face separations from them, and a cheap screen of the nine edge axes.
//!
//! An edge axis aᵢ × bⱼ costs a square root and three divisions to normalise before
//! [`candidate`](super::sat::candidate) can measure the separation along it. Most edge
//! axes do not matter to the result: they neither separate the boxes nor beat the best
//! face by the factor [`FACE_PREFERENCE`]. The screen tells those apart without the
//! square root, from the products Rᵢⱼ = aᵢ · bⱼ (the edge axis's components in box 1's
//! axes are two of them, ODE's `dBoxBox` trick): the separation times |aᵢ × bⱼ| (m), its
//! error bounded from the float precision, the boxes' sizes and how far their axes are
//! from orthonormal. Only an axis the bound cannot decide is computed exactly, so the
//! choice, and every bit of the contact, is the one of testing all 15 axes exactly.

use super::sat::{Axis, Origin, Shape, FACE_PREFERENCE, PARALLEL_EDGES};
use crate::vector::{dot, neg, sub};
use crate::Real;
use nalgebra::Vector3;

/// Allowed error of a product Rᵢⱼ or a screen's coefficient, in units of the float
/// type's ε (–), and per unit of the boxes' summed orthonormality defect (–): the
/// rounding of the two ways to the separation (≈ 20 ε), and the triple products the
/// screen takes as ±Rᵢⱼ, off by ≈ 3.3 × the defect of each box's axes (≈ 3 ε more for
/// the rounding of the measured defect).
const ROUNDING: f64 = 48.0;
const SKEW: f64 = 8.0;

/// The square of [`FACE_PREFERENCE`] with 0.3 % to spare (–): 0.1 % the screen keeps
/// from the exact comparison, the rest for rounding in the screen's own products.
const LOSES: f64 = FACE_PREFERENCE * FACE_PREFERENCE / 1.003;

/// Sizes (m) above which the screen could overflow, and squared face separations (m²)
/// below which it could lose precision to subnormals: every edge axis is then exact.
const HUGE: f64 = 1e15;
const TINY: f64 = 1e-30;

/// The products and bounds the separating-axis test of box 1 (`one`) and box 2 (`two`)
/// shares between its 15 axes.
pub(super) struct Pair<'a, T: Real> {
    one: &'a Shape<T>,
    two: &'a Shape<T>,
    /// Rᵢⱼ = aᵢ · bⱼ (–), box 1's axis i with box 2's axis j.
    r: [[T; 3]; 3],
    /// |Rᵢⱼ| (–).
    size: [[T; 3]; 3],
    /// (centre 1 − centre 2) · aₖ (m).
    along_1: [T; 3],
    /// (centre 1 − centre 2) · bₖ (m).
    along_2: [T; 3],
    /// Box 1's reach along bₖ and box 2's along aₖ (m), as
    /// [`Frame::reach`](super::sat::Frame::reach) gives them (less its leading 0 +).
    reach_1: [T; 3],
    reach_2: [T; 3],
    /// Error bound (m) of a screened separation times |aᵢ × bⱼ|, against the exact one
    /// times the exact |aᵢ × bⱼ|.
    bound: T,
    /// Error bound (–) of the screen's |aᵢ × bⱼ|, squared and times 65.
    spread: T,
    /// Squared |aᵢ × bⱼ| (–) above which the exact edge axis is surely not parallel.
    valid: T,
    /// The best face separation, squared (m²).
    face_squared: T,
    /// False when the screen cannot bound its error (sizes too large or small, axes far
    /// from orthonormal, NaN): every edge axis is exact.
    usable: bool,
}

impl<'a, T: Real> Pair<'a, T> {
    /// The products and bounds of box 1 `one` and box 2 `two`.
    pub fn of(one: &'a Shape<T>, two: &'a Shape<T>) -> Self {
        let (a, b) = (&one.frame.axes, &two.frame.axes);
        let d = sub(&one.frame.center, &two.frame.center);
        let row = |a: &Vector3<T>| [dot(a, &b[0]), dot(a, &b[1]), dot(a, &b[2])];
        let r = [row(&a[0]), row(&a[1]), row(&a[2])];
        let size = |[x, y, z]: [T; 3]| [x.abs(), y.abs(), z.abs()];
        let size = [size(r[0]), size(r[1]), size(r[2])];
        let [p, q, t] = one.frame.half;
        let [x, y, z] = &size;
        let reach_1 = [
            p * x[0] + q * y[0] + t * z[0],
            p * x[1] + q * y[1] + t * z[1],
            p * x[2] + q * y[2] + t * z[2],
        ];
        let [p, q, t] = two.frame.half;
        let reach = |[x, y, z]: &[T; 3]| p * *x + q * *y + t * *z;
        let reach_2 = [reach(&size[0]), reach(&size[1]), reach(&size[2])];
        let delta = T::of(ROUNDING) * epsilon::<T>() + T::of(SKEW) * (one.skew + two.skew);
        let scale = d.x.abs() + d.y.abs() + d.z.abs() + one.size + two.size;
        let beta = delta + delta;
        let edge = T::of(PARALLEL_EDGES * 1.01) + beta;
        Pair {
            one,
            two,
            r,
            size,
            reach_1,
            reach_2,
            along_1: [dot(&d, &a[0]), dot(&d, &a[1]), dot(&d, &a[2])],
            along_2: [dot(&d, &b[0]), dot(&d, &b[1]), dot(&d, &b[2])],
            bound: beta * scale + T::of(TINY),
            spread: beta * beta * T::of(65.0),
            valid: edge * edge,
            face_squared: T::zero(),
            usable: scale < T::of(HUGE) && delta < T::of(1e-3),
        }
    }

    /// The separation (m) along face axis `index` (0..6, as
    /// [`candidate`](super::sat::candidate) numbers them) and its offset (m), the
    /// centres' distance along the face's axis, whose sign orients the normal: the
    /// same, bit for bit but for the sign of a zero separation.
    pub fn face_separation(&self, index: usize) -> (T, T) {
        let k = index % 3;
        let (offset, reach_1, reach_2) = if index >= 3 {
            (self.along_2[k], self.reach_1[k], self.two.own[k])
        } else {
            (self.along_1[k], self.one.own[k], self.reach_2[k])
        };
        (offset.abs() - reach_1 - reach_2, offset)
    }

    /// Face axis `index` (0..6) whose [`Pair::face_separation`] is `separation` (m) and
    /// whose offset is `offset` (m).
    pub fn face(&self, index: usize, (separation, offset): (T, T)) -> Axis<T> {
        let (second, axis) = (index >= 3, index % 3);
        let frame = if second { self.two } else { self.one };
        let direction = &frame.frame.axes[axis];
        Axis {
            origin: Origin::Face { second, axis },
            normal: if offset < T::zero() {
                neg(direction)
            } else {
                *direction
            },
            separation,
        }
    }

    /// Records the best face axis's separation `face` (m, < 0) for [`Pair::exact_edges`];
    /// whether the screen can be used.
    pub fn set_face(&mut self, face: T) -> bool {
        self.face_squared = face * face;
        self.usable && self.face_squared >= T::of(TINY)
    }

    /// The edge axes aᵢ × bⱼ of box 1's axis `i` that must be computed exactly, as bits
    /// j (box 2's axis) of the result: all but those [`Pair::screens_out`] leaves out.
    /// Only when [`Pair::set_face`] allows it.
    pub fn exact_edges(&self, i: usize) -> u32 {
        let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
        let edge = Edge {
            // aᵢ × bⱼ has components (−Rᵢ₂ⱼ, Rᵢ₁ⱼ) along box 1's axes i1, i2 (0 along
            // i); along box 2's axes j1, j2 it has Rᵢⱼ₂ and −Rᵢⱼ₁.
            u: &self.r[i2],
            v: &self.r[i1],
            size_u: &self.size[i2],
            size_v: &self.size[i1],
            size_w: &self.size[i],
            offset_u: self.along_1[i1],
            offset_v: self.along_1[i2],
            half_u: self.one.frame.half[i1],
            half_v: self.one.frame.half[i2],
        };
        // Box 2's axis j with the next two, written out so that each is a constant.
        u32::from(!self.screens_out(&edge, 0, 1, 2))
            | u32::from(!self.screens_out(&edge, 1, 2, 0)) << 1
            | u32::from(!self.screens_out(&edge, 2, 0, 1)) << 2
    }

    /// Whether edge axis aᵢ × bⱼ may be left out (box 1's axis i in `edge`, box 2's `j`
    /// followed by `j1`, `j2`): it surely is a valid axis along which the boxes overlap,
    /// and its penetration surely is not below the face's by the factor
    /// [`FACE_PREFERENCE`]. False whenever in doubt (NaN included).
    #[inline(always)]
    fn screens_out(&self, edge: &Edge<'_, T>, j: usize, j1: usize, j2: usize) -> bool {
        let (u, v) = (edge.u[j], edge.v[j]);
        let squared = u * u + v * v;
        let half = &self.two.frame.half;
        let offset = edge.offset_v * v - edge.offset_u * u;
        let separation = offset.abs()
            - (edge.half_u * edge.size_u[j] + edge.half_v * edge.size_v[j])
            - (half[j1] * edge.size_w[j2] + half[j2] * edge.size_w[j1]);
        // Penetration × |aᵢ × bⱼ| at least `least` (m); (|aᵢ × bⱼ| + β)² is at most
        // 65/64 of the screen's square plus 65 β².
        let least = -separation - self.bound;
        let width = squared * T::of(65.0 / 64.0) + self.spread;
        squared > self.valid
            && least > T::zero()
            && least * least * T::of(LOSES) >= self.face_squared * width
    }
}

/// The products of one box-1 axis i that the screen of its three edge axes uses.
struct Edge<'a, T: Real> {
    /// Rᵢ₂ⱼ and Rᵢ₁ⱼ over j (–), the edge axis's components along box 1's axes i1, i2
    /// (up to sign), and their sizes.
    u: &'a [T; 3],
    v: &'a [T; 3],
    size_u: &'a [T; 3],
    size_v: &'a [T; 3],
    /// |Rᵢⱼ| over j (–).
    size_w: &'a [T; 3],
    /// The centres' offset along box 1's axes i1 and i2 (m).
    offset_u: T,
    offset_v: T,
    /// Box 1's half extents along i1 and i2 (m).
    half_u: T,
    half_v: T,
}

/// ε (–) of the float type: `f32`'s when 1 + 2⁻⁵² rounds to 1, else `f64`'s.
fn epsilon<T: Real>() -> T {
    if T::of(1.0 + f64::EPSILON) == T::one() {
        T::of(f64::from(f32::EPSILON))
    } else {
        T::of(f64::EPSILON)
    }
}
