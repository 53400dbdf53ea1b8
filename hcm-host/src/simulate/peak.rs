//! The maximum normal force of a contact, found on the dense output rather than
//! only at step ends: a coarse grid in every step while in contact, then a
//! golden-section search only around the best grid point of the whole event.

use super::state::StateVector;
use super::system::ContactSystem;
use hcm_core::integrate::Dopri5;

/// Grid intervals per step.
const GRID: usize = 6;
/// Golden-section iterations: shrinks the bracket by 0.618^40 ≈ 4e-9.
const REFINEMENTS: usize = 40;

/// The best grid point of an event so far.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PeakCandidate {
    /// f_n there (N).
    pub force: f64,
    /// Its time (s).
    pub time: f64,
    /// Grid spacing of its step (s).
    pub spacing: f64,
    /// Index of the segment (solver step) holding it.
    pub segment: usize,
}

/// f_n (N) of contact `c` at `time` inside the stepper's last step.
fn force_at(
    system: &ContactSystem,
    stepper: &Dopri5<f64, StateVector>,
    c: usize,
    time: f64,
    y: &mut StateVector,
) -> f64 {
    stepper.dense_output(time, y);
    let k = system.kinematics(&y.0, c);
    system.contact_normal_force(&y.0, c, &k)
}

/// The largest f_n of contact `c` on a grid over [start, end] of the last step.
pub fn grid_max(
    system: &ContactSystem,
    stepper: &Dopri5<f64, StateVector>,
    c: usize,
    (start, end): (f64, f64),
    segment: usize,
) -> PeakCandidate {
    let mut y = stepper.state().clone();
    let spacing = (end - start) / GRID as f64;
    let mut best = PeakCandidate {
        force: f64::NEG_INFINITY,
        time: start,
        spacing,
        segment,
    };
    for i in 0..=GRID {
        let time = start + spacing * i as f64;
        let force = force_at(system, stepper, c, time, &mut y);
        if force > best.force {
            (best.force, best.time) = (force, time);
        }
    }
    best
}

/// Golden-section search for the peak within one grid spacing of `candidate`,
/// clamped to [start, end] of the step that holds it.
pub fn refine(
    system: &ContactSystem,
    stepper: &Dopri5<f64, StateVector>,
    c: usize,
    candidate: PeakCandidate,
    (start, end): (f64, f64),
) -> f64 {
    let mut y = stepper.state().clone();
    let mut force = |t: f64| force_at(system, stepper, c, t, &mut y);
    let (mut a, mut b) = (
        (candidate.time - candidate.spacing).max(start),
        (candidate.time + candidate.spacing).min(end),
    );
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    let (mut x1, mut x2) = (b - ratio * (b - a), a + ratio * (b - a));
    let (mut f1, mut f2) = (force(x1), force(x2));
    for _ in 0..REFINEMENTS {
        if f1 < f2 {
            a = x1;
            (x1, f1) = (x2, f2);
            x2 = a + ratio * (b - a);
            f2 = force(x2);
        } else {
            b = x2;
            (x2, f2) = (x1, f1);
            x1 = b - ratio * (b - a);
            f1 = force(x1);
        }
    }
    candidate.force.max(f1).max(f2)
}
