//! Cubic Hermite interpolation between two samples that carry a value and its rate,
//! and the zero crossing of that cubic: how a δ = 0 instant is recovered from
//! sampled (δ, δ̇) without rounding to a sample.

use crate::Real;

/// Value at fraction `s` ∈ [0, 1] of an interval of length `h` (s) of the cubic
/// matching (y0, y0') at its start and (y1, y1') at its end (units of y; y' per s).
#[inline]
pub fn cubic_hermite<T: Real>(h: T, (y0, rate0): (T, T), (y1, rate1): (T, T), s: T) -> T {
    let (two, three) = (T::of(2.0), T::of(3.0));
    let (s2, s3) = (s * s, s * s * s);
    (two * s3 - three * s2 + T::one()) * y0
        + (s3 - two * s2 + s) * h * rate0
        + (three * s2 - two * s3) * y1
        + (s3 - s2) * h * rate1
}

/// The fraction s ∈ [0, 1] where that cubic crosses zero, by 64 bisections (exact
/// to the float's resolution) on the assumption that y0 and y1 have opposite signs
/// (otherwise it returns an end of the interval). NaN inputs give a NaN-free
/// fraction in [0, 1]; the caller's values then decide what it means.
pub fn hermite_zero<T: Real>(h: T, start: (T, T), end: (T, T)) -> T {
    let rising = end.0 > start.0;
    let (mut lo, mut hi) = (T::zero(), T::one());
    let half = T::of(0.5);
    for _ in 0..64 {
        let mid = half * (lo + hi);
        if (cubic_hermite(h, start, end, mid) > T::zero()) == rising {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    half * (lo + hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reproduces_a_cubic_exactly() {
        // y = t³ − t on [0.5, 1.5]: its zero at t = 1 is found from end data alone.
        let y = |t: f64| t * t * t - t;
        let dy = |t: f64| 3.0 * t * t - 1.0;
        let s = hermite_zero(1.0, (y(0.5), dy(0.5)), (y(1.5), dy(1.5)));
        assert!((0.5 + s - 1.0).abs() < 1e-15);
        assert!(
            (cubic_hermite(1.0, (y(0.5), dy(0.5)), (y(1.5), dy(1.5)), 0.3) - y(0.8)).abs() < 1e-15
        );
    }
}
