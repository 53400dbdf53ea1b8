//! The maximum normal force of a contact within one solver step, found on the
//! dense output rather than only at step ends.

use super::state::StateVector;
use super::system::ContactSystem;
use hcm_core::integrate::Dopri5;
use hcm_core::law::{Indentation, NormalLaw};

/// Samples per step before refining.
const GRID: usize = 8;
/// Golden-section iterations: shrinks the bracket by 0.618^40 ≈ 4e-9.
const REFINEMENTS: usize = 40;

/// Largest f_n (N) of contact `c` over [start, end] of the stepper's last step.
pub fn max_normal_force(
    system: &ContactSystem,
    stepper: &Dopri5<f64, StateVector>,
    c: usize,
    start: f64,
    end: f64,
) -> f64 {
    let mut y = stepper.state().clone();
    let mut force = |t: f64| {
        stepper.dense_output(t, &mut y);
        let k = system.kinematics(&y.0, c);
        let state = Indentation {
            depth: k.depth,
            rate: k.rate,
            approach_speed: system.modes.approach_speed[c],
        };
        system.model.contacts[c].law.normal_force(&state)
    };
    let h = (end - start) / GRID as f64;
    let (mut best_i, mut best) = (0, f64::NEG_INFINITY);
    for i in 0..=GRID {
        let f = force(start + h * i as f64);
        if f > best {
            (best_i, best) = (i, f);
        }
    }
    // Golden-section search on the bracket around the best grid point.
    let (mut a, mut b) = (
        start + h * best_i.saturating_sub(1) as f64,
        start + h * (best_i + 1).min(GRID) as f64,
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
    best.max(f1).max(f2)
}
