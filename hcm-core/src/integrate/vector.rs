//! Component-wise arithmetic on ODE states shared by the steppers: stage sums, the
//! scaled RMS error norm of Hairer–Nørsett–Wanner (eq. II.4.11) and finiteness checks.

use super::OdeState;
use crate::Real;

/// True when `x` is neither NaN nor ±∞.
pub(super) fn is_finite<T: Real>(x: T) -> bool {
    x.abs() <= T::MAX
}

/// True when every component is finite (not NaN, not ±∞).
pub(super) fn all_finite<T: Real, S: OdeState<T>>(state: &S) -> bool {
    state.components().iter().all(|x| is_finite(*x))
}

/// Components of `out` ← Σ cᵢ·kᵢ, summed from 0 in the order of `terms`.
fn weighted_sum<T: Real, S: OdeState<T>>(out: &mut [T], terms: &[(T, &S)]) {
    out.fill(T::zero());
    for &(c, k) in terms {
        for (o, k) in out.iter_mut().zip(k.components()) {
            *o += c * *k;
        }
    }
}

/// Components of `out` ← h·Σ cᵢ·kᵢ.
pub(super) fn increment<T: Real, S: OdeState<T>>(out: &mut S, h: T, terms: &[(T, &S)]) {
    let out = out.components_mut();
    weighted_sum(out, terms);
    for o in out {
        *o = h * *o;
    }
}

/// `out` ← `base` + h·Σ cᵢ·kᵢ (the sum is formed first, then added once to `base`).
/// One pass fewer than copying `base` first: every component is written anyway, and
/// the steppers' states carry nothing else.
pub(super) fn combine<T: Real, S: OdeState<T>>(out: &mut S, base: &S, h: T, terms: &[(T, &S)]) {
    let out = out.components_mut();
    weighted_sum(out, terms);
    for (o, b) in out.iter_mut().zip(base.components()) {
        *o = *b + h * *o;
    }
}

/// RMS over components of v_i / sc_i, sc_i = atol + rtol·max(|y0_i|, |y1_i|)
/// (Hairer–Nørsett–Wanner eq. II.4.11). A zero v_i counts 0 even where sc_i = 0.
pub(super) fn scaled_rms<T: Real, S: OdeState<T>>(v: &S, y0: &S, y1: &S, rtol: T, atol: T) -> T {
    let mut sum = T::zero();
    let mut count = 0_usize;
    let ends = y0.components().iter().zip(y1.components());
    for (v, (a, b)) in v.components().iter().zip(ends) {
        let (a, b) = (a.abs(), b.abs());
        let scale = atol + rtol * if a > b { a } else { b };
        let ratio = if *v == T::zero() {
            T::zero()
        } else {
            *v / scale
        };
        sum += ratio * ratio;
        count += 1;
    }
    if count == 0 {
        T::zero()
    } else {
        (sum / T::of_count(count)).square_root()
    }
}

/// The error of an attempt (dimensionless, ≤ 1 to accept), or `None` when the error
/// estimate or the candidate state holds a NaN or ∞.
pub(super) fn error_norm<T: Real, S: OdeState<T>>(
    error: &S,
    y0: &S,
    y1: &S,
    rtol: T,
    atol: T,
) -> Option<T> {
    if !all_finite(error) || !all_finite(y1) {
        return None;
    }
    let norm = scaled_rms(error, y0, y1, rtol, atol);
    if norm.is_nan() {
        None
    } else {
        Some(norm)
    }
}
