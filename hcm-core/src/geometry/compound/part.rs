//! A part of a fixed compound prepared once: what [`super::contacts`] would work out
//! for it at every call (its frame, axis-aligned bounds, validity and the separating-
//! axis test's per-box sums), kept by the caller or built at compile time.

use crate::geometry::box_box::{Frame, Shape};
use crate::geometry::Cuboid;
use crate::Real;
use nalgebra::Vector3;

/// One box of a fixed compound with its per-box work done: [`Part::of`] at run time
/// for any float type, [`Part::of_f32`] in a `const` for `f32` (a table in flash,
/// bit for bit the same). [`super::prepared_contacts`] takes a slice of them.
#[derive(Clone, Copy, Debug)]
pub struct Part<T: Real> {
    /// The box's frame and the sums the separating-axis test uses against any box.
    pub(super) shape: Shape<T>,
    /// Half extents of its axis-aligned bounding box (m).
    pub(super) bounds: Vector3<T>,
    /// Whether every number is finite and every half extent ≥ 0: an invalid part
    /// touches nothing.
    pub(super) valid: bool,
}

impl<T: Real> Part<T> {
    /// `cuboid` (in the compound's common frame) prepared. Any numbers: a box that is
    /// not finite or has a negative half extent is kept as one that touches nothing.
    pub fn of(cuboid: &Cuboid<T>) -> Self {
        let frame = Frame::unchecked(cuboid);
        Part {
            bounds: frame.bounds(),
            valid: frame.valid(),
            shape: Shape::of(frame),
        }
    }
}

impl Part<f32> {
    /// [`Part::of`] for `f32` in a `const`: the same operations in the same order, so
    /// the same bits (a test compares them), evaluated by the compiler.
    pub const fn of_f32(cuboid: Cuboid<f32>) -> Self {
        let mut cuboid = cuboid;
        let [[i, j, k, w]] = cuboid.orientation.as_mut_unchecked().as_vector().data.0;
        let [h] = cuboid.half_extents.data.0;
        let [center] = cuboid.center.data.0;
        let two = 1.0_f32 + 1.0;
        let (ww, ii, jj, kk) = (w * w, i * i, j * j, k * k);
        let (ij, wk, wj) = (i * j * two, w * k * two, w * j * two);
        let (ik, jk, wi) = (i * k * two, j * k * two, w * i * two);
        let a = [ww + ii - jj - kk, wk + ij, ik - wj];
        let b = [ij - wk, ww - ii + jj - kk, wi + jk];
        let c = [wj + ik, jk - wi, ww - ii - jj + kk];
        let [p, q, r] = h;
        let nothing = zero_sum(&center)
            + (p * 0.0 + q * 0.0 + r * 0.0)
            + zero_sum(&a)
            + zero_sum(&b)
            + zero_sum(&c);
        let (ab, ac, bc) = (dot(&a, &b), dot(&a, &c), dot(&b, &c));
        let (aa, bb, cc) = (dot(&a, &a), dot(&b, &b), dot(&c, &c));
        Part {
            shape: Shape {
                frame: Frame {
                    center: vector(center),
                    axes: [vector(a), vector(b), vector(c)],
                    half: h,
                },
                own: [
                    p * aa.abs() + q * ab.abs() + r * ac.abs(),
                    p * ab.abs() + q * bb.abs() + r * bc.abs(),
                    p * ac.abs() + q * bc.abs() + r * cc.abs(),
                ],
                size: p + q + r,
                skew: (aa - 1.0).abs()
                    + (bb - 1.0).abs()
                    + (cc - 1.0).abs()
                    + ab.abs()
                    + ac.abs()
                    + bc.abs(),
            },
            bounds: Vector3::new(
                a[0].abs() * p + b[0].abs() * q + c[0].abs() * r,
                a[1].abs() * p + b[1].abs() * q + c[1].abs() * r,
                a[2].abs() * p + b[2].abs() * q + c[2].abs() * r,
            ),
            valid: nothing == 0.0 && p >= 0.0 && q >= 0.0 && r >= 0.0,
        }
    }
}

/// u · v, in nalgebra's order.
const fn dot(u: &[f32; 3], v: &[f32; 3]) -> f32 {
    u[0] * v[0] + u[1] * v[1] + u[2] * v[2]
}

/// Σ vᵢ · 0: 0 (or −0) when every component is finite, else NaN ([`Frame::valid`]).
const fn zero_sum(v: &[f32; 3]) -> f32 {
    v[0] * 0.0 + v[1] * 0.0 + v[2] * 0.0
}

/// The vector of `v`.
const fn vector(v: [f32; 3]) -> Vector3<f32> {
    Vector3::new(v[0], v[1], v[2])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::compound::{contacts, prepared_contacts};
    use nalgebra::UnitQuaternion;

    /// Every number of a part as bits, for bitwise comparison.
    fn bits(part: &Part<f32>) -> [u32; 25] {
        let s = &part.shape;
        let f = &s.frame;
        let [a, b, c] = &f.axes;
        let v = [
            f.center.x,
            f.center.y,
            f.center.z,
            a.x,
            a.y,
            a.z,
            b.x,
            b.y,
            b.z,
            c.x,
            c.y,
            c.z,
            f.half[0],
            f.half[1],
            f.half[2],
            s.own[0],
            s.own[1],
            s.own[2],
            s.size,
            s.skew,
            part.bounds.x,
            part.bounds.y,
            part.bounds.z,
        ];
        let mut out = [u32::from(part.valid); 25];
        for (o, x) in out.iter_mut().zip(v) {
            *o = x.to_bits();
        }
        out
    }

    fn cuboid(half: [f32; 3], center: [f32; 3], euler: [f32; 3]) -> Cuboid<f32> {
        Cuboid {
            half_extents: Vector3::from(half),
            center: Vector3::from(center),
            orientation: UnitQuaternion::from_euler_angles(euler[0], euler[1], euler[2]),
        }
    }

    #[test]
    fn const_part_is_the_run_time_one_bit_for_bit() {
        let boxes = [
            cuboid([0.03, 0.03, 0.005], [0.0, 0.0, -0.005], [0.0; 3]),
            cuboid([0.009, 0.03, 0.025], [0.021, 0.0, 0.025], [0.3, -0.7, 1.1]),
            cuboid([1.5, 0.25, 3.0], [-2.0, 7.0, 0.1], [2.9, 0.01, -1.3]),
            cuboid([-1.0, 1.0, 1.0], [0.0; 3], [0.0; 3]),
            cuboid([1.0; 3], [f32::NAN, 0.0, 0.0], [0.0; 3]),
            cuboid([1.0, f32::INFINITY, 1.0], [0.0; 3], [0.5; 3]),
        ];
        for b in &boxes {
            assert_eq!(bits(&Part::of_f32(*b)), bits(&Part::of(b)), "{b:?}");
        }
        // Evaluated by the compiler, as in a `static`.
        const TURNED: Cuboid<f32> = Cuboid {
            half_extents: Vector3::new(0.5, 0.25, 2.0),
            center: Vector3::new(0.1, -0.3, 7.0),
            orientation: UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(
                0.8, 0.36, -0.48, 0.0,
            )),
        };
        const PART: Part<f32> = Part::of_f32(TURNED);
        assert_eq!(bits(&PART), bits(&Part::of(&TURNED)));
        assert!(Part::of_f32(boxes[1]).valid && !Part::of_f32(boxes[3]).valid);
        assert!(!Part::of_f32(boxes[4]).valid && !Part::of_f32(boxes[5]).valid);
    }

    #[test]
    fn prepared_contacts_are_contacts() {
        let parts = [
            cuboid([0.03, 0.03, 0.005], [0.0, 0.0, -0.005], [0.0; 3]),
            cuboid([0.009, 0.03, 0.025], [0.021, 0.0, 0.025], [0.0; 3]),
            cuboid([0.009, 0.03, 0.025], [-0.021, 0.0, 0.025], [0.0; 3]),
            cuboid([0.012, 0.009, 0.025], [0.0, 0.021, 0.025], [0.02, 0.0, 0.0]),
            cuboid([1.0; 3], [f32::NAN, 0.0, 0.0], [0.0; 3]),
        ];
        let prepared = parts.map(Part::of_f32);
        for (i, euler) in [[0.0, 0.0, 0.0], [0.05, -0.02, 0.3], [0.4, 0.1, -0.2]]
            .into_iter()
            .enumerate()
        {
            let x = 0.0005 * i as f32;
            let peg = cuboid([0.01, 0.01, 0.04], [0.011 + x, 0.009, 0.038], euler);
            let (a, b) = (contacts(&peg, &parts), prepared_contacts(&peg, &prepared));
            assert!(!a.is_empty());
            assert_eq!(a.len(), b.len());
            for (p, q) in a.iter().zip(&b) {
                assert_eq!(p.feature, q.feature);
                assert_eq!(p.depth.to_bits(), q.depth.to_bits());
                assert_eq!(p.point.map(f32::to_bits), q.point.map(f32::to_bits));
                assert_eq!(p.normal.map(f32::to_bits), q.normal.map(f32::to_bits));
            }
        }
    }
}
