//! Three-vector arithmetic written out component by component, each in the order of
//! nalgebra's own operator (so to the same bits), for the geometry and the contact
//! model's per-point work. The controller's size-optimised build keeps nalgebra's
//! generic loops over the three components as loops, through copies on the stack:
//! several times the instructions of the arithmetic itself (Eq 1's wrench and its
//! sum over the peg's 4 points, written out: 18,221 → 16,885 instructions per peg
//! HCM).
//! Public for a controller's own per-point work around the core (the firmware's peg
//! manifold uses them).

use crate::Real;
use nalgebra::{UnitQuaternion, Vector3};

/// a · b, as nalgebra's `dot`: (aₓbₓ + a_y b_y) + a_z b_z.
pub fn dot<T: Real>(a: &Vector3<T>, b: &Vector3<T>) -> T {
    a.x * b.x + a.y * b.y + a.z * b.z
}

/// a × b, as nalgebra's `cross`.
pub fn cross<T: Real>(a: &Vector3<T>, b: &Vector3<T>) -> Vector3<T> {
    Vector3::new(
        a.y * b.z - a.z * b.y,
        a.z * b.x - a.x * b.z,
        a.x * b.y - a.y * b.x,
    )
}

/// a + b.
pub fn add<T: Real>(a: &Vector3<T>, b: &Vector3<T>) -> Vector3<T> {
    Vector3::new(a.x + b.x, a.y + b.y, a.z + b.z)
}

/// a − b.
pub fn sub<T: Real>(a: &Vector3<T>, b: &Vector3<T>) -> Vector3<T> {
    Vector3::new(a.x - b.x, a.y - b.y, a.z - b.z)
}

/// a · s.
pub fn scale<T: Real>(a: &Vector3<T>, s: T) -> Vector3<T> {
    Vector3::new(a.x * s, a.y * s, a.z * s)
}

/// a + b · s.
pub fn add_scaled<T: Real>(a: &Vector3<T>, b: &Vector3<T>, s: T) -> Vector3<T> {
    add(a, &scale(b, s))
}

/// −a.
pub fn neg<T: Real>(a: &Vector3<T>) -> Vector3<T> {
    Vector3::new(-a.x, -a.y, -a.z)
}

/// q·v·q⁻¹ (`v` rotated by `q`), as nalgebra's `UnitQuaternion * Vector3`: t = 2 (q⃗ × v),
/// then (t·w + q⃗ × t) + v. Its generic loops took 113 instructions more per peg
/// manifold on the Cortex-M4F.
pub fn rotate<T: Real>(q: &UnitQuaternion<T>, v: &Vector3<T>) -> Vector3<T> {
    let u = Vector3::new(q.i, q.j, q.k);
    let c = cross(&u, v);
    let two = T::one() + T::one();
    let t = Vector3::new(c.x * two, c.y * two, c.z * two);
    let d = cross(&u, &t);
    let w = q.w;
    Vector3::new(
        t.x * w + d.x + v.x,
        t.y * w + d.y + v.y,
        t.z * w + d.z + v.z,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each helper gives nalgebra's own operator's bits (what "as nalgebra's" claims).
    #[test]
    fn the_helpers_are_nalgebras_operators_bit_for_bit() {
        let bits = |v: Vector3<f32>| v.map(f32::to_bits);
        for k in 0..200_u16 {
            let x = |i: u16| (f32::from((k * 37 + i * 101) % 211) - 105.0) * 0.0137;
            let (a, b) = (
                Vector3::new(x(0), x(1), x(2)),
                Vector3::new(x(3), x(4), x(5)),
            );
            let q = UnitQuaternion::from_euler_angles(x(6), x(7), x(8));
            assert_eq!(dot(&a, &b).to_bits(), a.dot(&b).to_bits());
            assert_eq!(bits(cross(&a, &b)), bits(a.cross(&b)));
            assert_eq!(bits(add(&a, &b)), bits(a + b));
            assert_eq!(bits(sub(&a, &b)), bits(a - b));
            assert_eq!(bits(scale(&a, x(9))), bits(a * x(9)));
            assert_eq!(bits(neg(&a)), bits(-a));
            assert_eq!(bits(rotate(&q, &a)), bits(q * a), "{q:?} {a:?}");
        }
    }
}
