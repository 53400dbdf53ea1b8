//! Event location: where a function of the solution changes sign inside a step.

use super::{DenseOutput, OdeState};
use crate::Real;

/// Samples of g taken across the step to find the first sign change before refining.
const SCAN_INTERVALS: u32 = 8;
/// Upper bound on refinement iterations (one evaluation of g each). A forced bisection
/// at least every third iteration halves the bracket, so this resolves a 1 s step to
/// below 1e-40 s; the loop stops far earlier, at the tolerance or the float spacing.
const MAX_REFINEMENTS: u32 = 400;

/// Finds where `g(t, y(t))` changes sign inside the last step [previous_time, time] of `stepper`,
/// using the dense output; returns the time (s) of the first crossing located to within
/// `time_tolerance` (s) (bracketing: Illinois-modified regula falsi with a bisection fallback,
/// always keeping a bracket, so it converges to ≤ 1e-12 s when asked). Returns None when g has
/// the same strict sign at both ends (a double crossing inside one step is not seen — document it;
/// the system's step_limit exists to prevent it). A crossing counts when g(previous) and g(time) have
/// different signs, or g(time) == 0 while g(previous) != 0. `scratch` is working space.
///
/// `g` is the caller's event function (e.g. a gap in m) of time (s) and state; it is
/// called at the two ends of the step with the stored states and inside it with dense
/// output (4th-order for [`Dopri5`](super::Dopri5), 3rd for [`Rodas4`](super::Rodas4)), so the crossing is that
/// of the interpolant, within about the integration tolerance of the true solution.
///
/// - **Which side.** The returned time t* is on the far side of the crossing: g at t*
///   (with `dense_output(t*)`) has the sign g has at `time()`, or is exactly 0, and the
///   crossing lies in [t* − `time_tolerance`, t*]. Restarting from
///   (t*, `dense_output(t*)`) therefore does not report the same crossing again.
/// - **First crossing.** When g changes sign at both ends, it is first sampled at 7
///   interior points and the earliest sub-interval with a sign change is refined, so of
///   several crossings the first is found unless two of them fall inside one sample
///   interval (1/8 of the step).
/// - **Not seen.** An even number of crossings inside one step (g leaves and returns to
///   the same sign), a touch of zero without a sign change, and a g that starts at
///   exactly 0 (just after a restart on the event surface). Limit the step
///   ([`OdeSystem::step_limit`](super::OdeSystem::step_limit)) so that an event cannot
///   begin and end inside one step.
/// - **Tolerance.** Refinement stops when the bracket is ≤ `time_tolerance` or cannot
///   be split in floating point; a NaN or negative tolerance therefore refines to the
///   float spacing of the time.
/// - **NaN.** A NaN g at either end gives `None`; a NaN inside the step is skipped
///   while sampling, and during refinement ends it with the current far end of the
///   bracket.
///
/// `scratch` (any state of the right length) receives dense-output states; its
/// content on return is unspecified.
pub fn locate_crossing<T: Real, S: OdeState<T>>(
    stepper: &impl DenseOutput<T, S>,
    mut g: impl FnMut(T, &S) -> T,
    time_tolerance: T,
    scratch: &mut S,
) -> Option<T> {
    let (start, end) = (stepper.previous_time(), stepper.time());
    let g_start = g(start, stepper.previous_state());
    let g_end = g(end, stepper.state());
    if !crosses(g_start, g_end) {
        return None;
    }
    if start.is_nan() || end.is_nan() {
        return None;
    }
    if end <= start {
        return Some(end);
    }

    // The first sample interval [a, b] over which g changes sign (or reaches 0 at b).
    let (mut a, mut g_a) = (start, g_start);
    let (mut b, mut g_b) = (end, g_end);
    for i in 1..SCAN_INTERVALS {
        let t = start
            + (end - start) * (T::of_count(i as usize) / T::of_count(SCAN_INTERVALS as usize));
        stepper.dense_output(t, scratch);
        let g_t = g(t, scratch);
        if g_t.is_nan() {
            continue;
        }
        if g_t == T::zero() {
            return Some(t);
        }
        if (g_t > T::zero()) != (g_a > T::zero()) {
            (b, g_b) = (t, g_t);
            break;
        }
        (a, g_a) = (t, g_t);
    }
    if g_b == T::zero() {
        return Some(b);
    }

    // Illinois: regula falsi, halving the value kept at an end that survives twice in
    // a row; bisection after two iterations that did not halve the bracket.
    let half = T::of(0.5);
    let mut last_moved: Option<bool> = None; // Some(true): b moved last; Some(false): a.
    let mut slow = 0_u32;
    for _ in 0..MAX_REFINEMENTS {
        let width = b - a;
        if width <= time_tolerance {
            break;
        }
        let mut t = if slow >= 2 {
            a + width * half
        } else {
            b - g_b * (width / (g_b - g_a))
        };
        if !strictly_between(t, a, b) {
            t = a + width * half;
            if !strictly_between(t, a, b) {
                break; // No float strictly between a and b.
            }
        }
        stepper.dense_output(t, scratch);
        let g_t = g(t, scratch);
        if g_t.is_nan() {
            break;
        }
        if g_t == T::zero() {
            return Some(t);
        }
        if (g_t > T::zero()) == (g_b > T::zero()) {
            (b, g_b) = (t, g_t);
            if last_moved == Some(true) {
                g_a *= half;
            }
            last_moved = Some(true);
        } else {
            (a, g_a) = (t, g_t);
            if last_moved == Some(false) {
                g_b *= half;
            }
            last_moved = Some(false);
        }
        slow = if b - a > width * half { slow + 1 } else { 0 };
    }
    Some(b)
}

/// Whether a < t < b (false for a NaN t).
fn strictly_between<T: Real>(t: T, a: T, b: T) -> bool {
    t > a && t < b
}

/// Whether g goes from `g_start` to `g_end` across zero: from non-zero to the other
/// sign or to exactly zero. NaN at either end is no crossing.
fn crosses<T: Real>(g_start: T, g_end: T) -> bool {
    if g_start.is_nan() || g_end.is_nan() || g_start == T::zero() {
        return false;
    }
    g_end == T::zero() || (g_start > T::zero()) != (g_end > T::zero())
}

#[cfg(test)]
mod tests {
    use super::super::{Dopri5, OdeSystem, Settings};
    use super::*;

    /// y' = 1: y(t) = y0 + t, so dense output is exact.
    struct Clock;
    impl OdeSystem<f64, [f64; 1]> for Clock {
        fn derivative(&mut self, _: f64, _: &[f64; 1], dy: &mut [f64; 1]) {
            *dy = [1.0];
        }
    }

    fn one_step(until: f64) -> Dopri5<f64, [f64; 1]> {
        let mut settings = Settings::new(1e-10, 1e-10);
        settings.initial_step = until;
        let mut stepper = Dopri5::new(&mut Clock, 0.0, [0.0], settings);
        stepper.step(&mut Clock, until).unwrap();
        assert_eq!(stepper.time(), until);
        stepper
    }

    #[test]
    fn the_crossing_rule() {
        assert!(crosses(1.0, -1.0) && crosses(-1.0, 1.0) && crosses(2.0, 0.0));
        assert!(!crosses(0.0, 1.0) && !crosses(1.0, 2.0) && !crosses(-1.0, -0.5));
        assert!(!crosses(f64::NAN, 1.0) && !crosses(1.0, f64::NAN));
    }

    #[test]
    fn finds_the_first_of_three_crossings_on_the_far_side() {
        let stepper = one_step(1.0);
        let mut scratch = [0.0];
        // Roots at 0.2, 0.5, 0.8 (a step sign-changes at both ends).
        let g = |_: f64, y: &[f64; 1]| (y[0] - 0.2) * (y[0] - 0.5) * (y[0] - 0.8);
        let found = locate_crossing(&stepper, g, 1e-14, &mut scratch).unwrap();
        assert!((found - 0.2).abs() <= 1e-14, "{found}");
        assert!(found >= 0.2 - 1e-16);
    }

    #[test]
    fn converges_in_time_for_a_flat_function_and_keeps_a_bracket() {
        let stepper = one_step(1.0);
        let mut scratch = [0.0];
        // Flat near its root at 0.3 (regula falsi alone stalls on it).
        let g = |_: f64, y: &[f64; 1]| (y[0] - 0.3).powi(3) + 1e-3 * (y[0] - 0.3);
        let found = locate_crossing(&stepper, g, 1e-13, &mut scratch).unwrap();
        assert!((found - 0.3).abs() <= 1e-13, "{found}");
        assert!(g(found, &[found]) >= 0.0);
    }

    #[test]
    fn no_crossing_when_the_ends_agree_or_start_at_zero_or_nan() {
        let stepper = one_step(1.0);
        let mut scratch = [0.0];
        let double = |_: f64, y: &[f64; 1]| (y[0] - 0.4) * (y[0] - 0.6);
        assert_eq!(locate_crossing(&stepper, double, 1e-12, &mut scratch), None);
        let from_zero = |_: f64, y: &[f64; 1]| y[0];
        assert_eq!(
            locate_crossing(&stepper, from_zero, 1e-12, &mut scratch),
            None
        );
        let nan = |_: f64, _: &[f64; 1]| f64::NAN;
        assert_eq!(locate_crossing(&stepper, nan, 1e-12, &mut scratch), None);
    }

    #[test]
    fn a_zero_at_the_end_is_the_end_and_a_nan_tolerance_still_terminates() {
        let stepper = one_step(1.0);
        let mut scratch = [0.0];
        let at_end = |t: f64, _: &[f64; 1]| 1.0 - t;
        assert_eq!(
            locate_crossing(&stepper, at_end, 1e-12, &mut scratch),
            Some(1.0)
        );
        let g = |_: f64, y: &[f64; 1]| y[0] - 1.0 / 3.0;
        let found = locate_crossing(&stepper, g, f64::NAN, &mut scratch).unwrap();
        assert!((found - 1.0 / 3.0).abs() <= 2.0 * f64::EPSILON, "{found}");
    }
}
