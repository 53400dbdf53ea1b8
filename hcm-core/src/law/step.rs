//! The cubic STEP of MSC ADAMS, shared by IMPACT damping (Eq 9) and friction (Eq 11).

use crate::Real;

/// Cubic STEP from (x0, h0) to (x1, h1), Eq 9 (and Eq 11):
///
/// h0 for x ≤ x0, h1 for x ≥ x1, and in between h0 + (h1 − h0)·Δ²·(3 − 2Δ) with
/// Δ = (x − x0)/(x1 − x0). Continuous with zero slope at both ends.
///
/// Units are those of the caller (x: m for damping, m/s for friction; h: N·s/m or
/// dimensionless). If x1 ≤ x0 the STEP is a jump at x0 (h0 at x ≤ x0, h1 after); a
/// NaN `x` gives NaN.
#[inline]
pub fn step<T: Real>(x: T, x0: T, h0: T, x1: T, h1: T) -> T {
    if x <= x0 {
        h0
    } else if x >= x1 {
        h1
    } else {
        let delta = (x - x0) / (x1 - x0);
        h0 + (h1 - h0) * delta * delta * (T::of(3.0) - T::of(2.0) * delta)
    }
}

#[cfg(test)]
mod tests {
    use super::step;

    #[test]
    fn midpoint_is_the_mean() {
        assert_eq!(step(0.5_f64, 0.0, 1.0, 1.0, 3.0), 2.0);
    }

    #[test]
    fn degenerate_interval_is_a_jump() {
        assert_eq!(step(0.0_f32, 1.0, 5.0, 1.0, 7.0), 5.0);
        assert_eq!(step(1.0_f32, 1.0, 5.0, 1.0, 7.0), 5.0);
        assert_eq!(step(1.5_f32, 1.0, 5.0, 0.5, 7.0), 7.0);
    }

    #[test]
    fn nan_propagates() {
        assert!(step(f32::NAN, 0.0, 0.0, 1.0, 1.0).is_nan());
    }
}
