//! Three-vector arithmetic written out component by component, each in the order of
//! nalgebra's own operator (so to the same bits), for the geometry and the contact
//! model's per-point work. The controller's size-optimised build keeps nalgebra's
//! generic loops over the three components as loops, through copies on the stack:
//! several times the instructions of the arithmetic itself (issue 31: Eq 1's wrench
//! and its sum over the peg's 4 points, 18,221 → 16,885 instructions per peg HCM).

use crate::Real;
use nalgebra::Vector3;

/// a · b, as nalgebra's `dot`: (aₓbₓ + a_y b_y) + a_z b_z.
pub(crate) fn dot<T: Real>(a: &Vector3<T>, b: &Vector3<T>) -> T {
    a.x * b.x + a.y * b.y + a.z * b.z
}

/// a × b, as nalgebra's `cross`.
pub(crate) fn cross<T: Real>(a: &Vector3<T>, b: &Vector3<T>) -> Vector3<T> {
    Vector3::new(
        a.y * b.z - a.z * b.y,
        a.z * b.x - a.x * b.z,
        a.x * b.y - a.y * b.x,
    )
}

/// a + b.
pub(crate) fn add<T: Real>(a: &Vector3<T>, b: &Vector3<T>) -> Vector3<T> {
    Vector3::new(a.x + b.x, a.y + b.y, a.z + b.z)
}

/// a − b.
pub(crate) fn sub<T: Real>(a: &Vector3<T>, b: &Vector3<T>) -> Vector3<T> {
    Vector3::new(a.x - b.x, a.y - b.y, a.z - b.z)
}

/// a · s.
pub(crate) fn scale<T: Real>(a: &Vector3<T>, s: T) -> Vector3<T> {
    Vector3::new(a.x * s, a.y * s, a.z * s)
}

/// a + b · s.
pub(crate) fn add_scaled<T: Real>(a: &Vector3<T>, b: &Vector3<T>, s: T) -> Vector3<T> {
    add(a, &scale(b, s))
}

/// −a.
pub(crate) fn neg<T: Real>(a: &Vector3<T>) -> Vector3<T> {
    Vector3::new(-a.x, -a.y, -a.z)
}
