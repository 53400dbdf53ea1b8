//! Whether a rigid identification fitted anything (never a silent failure):
//! a fit that stops at its search box's edge, replays fewer events than the data have,
//! or misses an indicator by more than the runs scatter is said, with what to try.
//!
//! On `scenarios/cube_drop.toml` the genetic algorithm once returned a fitness of 1.0 —
//! the best candidate's replay made none of the data's events — and a stiffness at its
//! search bound, and `hcm identify` wrote the physics file without a word.

use super::fitness::{event_errors, replay_events};
use super::target::WrenchTarget;
use crate::indicators::WrenchIndicators;
use crate::numerics::optimize::Bound;
use crate::scenario::Model;

/// Share of a parameter's search interval (on the scale searched) within which it is
/// at the bound (–): the genetic algorithm clamps its genes to the box, so a best
/// pushed against a bound sits on it; 0.1 % leaves a small value of a wide linear
/// interval (IMPACT's damping 50 N·s/m in [0, 10⁴]) alone.
const AT_BOUND: f64 = 1e-3;

/// Least relative error of an indicator that is reported as not reproduced (–),
/// whatever the runs' scatter.
const MISS_FLOOR: f64 = 0.1;

/// Run-to-run standard deviations beyond which an indicator's error is reported (–).
const MISS_SPREADS: f64 = 3.0;

/// The warnings on a fit: genes `genes` searched in `bounds`, whose model
/// `candidate` (started like `target.model`) replays the target's events.
pub fn warnings(
    bounds: &[Bound],
    genes: &[f64],
    target: &WrenchTarget,
    candidate: &Model,
) -> Vec<String> {
    let mut out = at_bounds(bounds, genes);
    match replay_events(candidate, target.contact) {
        None => out.push(
            "the best candidate's replay fails to simulate: no parameter set was judged; \
             check the scenario's start and the data's pre-contact states"
                .to_owned(),
        ),
        Some(events) => out.extend(misses(target, &events)),
    }
    out
}

/// A warning per gene at (within [`AT_BOUND`] of) an end of its search interval.
pub(crate) fn at_bounds(bounds: &[Bound], genes: &[f64]) -> Vec<String> {
    bounds
        .iter()
        .zip(genes)
        .filter_map(|(b, &v)| {
            let at = b.fraction_of(v);
            let side = if at <= AT_BOUND {
                "lower"
            } else if at >= 1.0 - AT_BOUND {
                "upper"
            } else {
                return None;
            };
            Some(format!(
                "`{}` ended at its {side} search bound ({v:.4e}, searched in [{:.4e}, \
                 {:.4e}]): the data may want a value beyond it — widen the bound \
                 (`[identify.bounds.<law>]` in the scenario) or check the data against \
                 the scenario",
                b.name, b.lower, b.upper
            ))
        })
        .collect()
}

/// Warnings for the target's events the replay `events` (touch-down (s), indicators)
/// does not make, or makes with an indicator off by more than [`MISS_FLOOR`] and
/// [`MISS_SPREADS`] times the runs' own relative spread.
fn misses(target: &WrenchTarget, events: &[(f64, WrenchIndicators)]) -> Vec<String> {
    let wanted = target.events.len();
    if events.len() < wanted {
        return vec![format!(
            "the best candidate's replay makes {} of the {wanted} contact events the data \
             have: nothing the data measured was fitted — try more generations, wider \
             bounds, or check that the scenario's start reaches the contact",
            events.len()
        )];
    }
    let first = events.first().map_or(0.0, |e| e.0);
    let mut out = Vec::new();
    for (k, (goal, (touch_down, got))) in target.events.iter().zip(events).enumerate() {
        let errors = event_errors(goal, got, touch_down - first);
        let estimates = goal.statistics.estimates();
        for (i, (&error, name)) in errors.iter().zip(WrenchIndicators::NAMES).enumerate() {
            // The fifth error is the event's delay after the first, relative to its
            // duration: the first event's is 0 by construction.
            let spread = estimates[i].std / estimates[i].mean.abs();
            let bar = MISS_FLOOR.max(MISS_SPREADS * if spread.is_finite() { spread } else { 0.0 });
            if error.abs() > bar {
                // The delay's error is relative to the event's duration, whose own
                // scatter is the yardstick there.
                let (what, yardstick) = if i == 4 {
                    (
                        "start after the first (relative to its duration)",
                        "its duration scatters",
                    )
                } else {
                    (name.0, "the runs scatter")
                };
                out.push(format!(
                    "event {}: its {what} is off by {:+.1} % ({yardstick} by {:.1} %): the \
                     fit does not reproduce it",
                    k + 1,
                    100.0 * error,
                    100.0 * spread
                ));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bound(name: &str, lower: f64, upper: f64, log_scale: bool) -> Bound {
        Bound {
            name: name.to_owned(),
            lower,
            upper,
            log_scale,
        }
    }

    #[test]
    fn a_gene_at_either_end_of_its_interval_is_said_and_one_inside_is_not() {
        let bounds = [
            bound("stiffness", 1e6, 1e8, true),
            bound("mu_static", 0.1, 1.0, false),
            bound("damping", 0.0, 10.0, false),
        ];
        let warnings = at_bounds(&bounds, &[0.9999e8, 0.5, 0.0]);
        assert_eq!(warnings.len(), 2, "{warnings:?}");
        assert!(
            warnings[0].starts_with("`stiffness` ended at its upper"),
            "{warnings:?}"
        );
        assert!(
            warnings[1].starts_with("`damping` ended at its lower"),
            "{warnings:?}"
        );
        // On a log scale 1.1e6 is 2 % of the way from 1e6 to 1e8: inside; so is
        // 0.5 % of a linear interval.
        assert!(at_bounds(&bounds[..1], &[1.1e6]).is_empty());
        assert!(at_bounds(&bounds[2..], &[0.05]).is_empty());
        // Outside the box is at its bound too (a start the box excludes).
        assert_eq!(at_bounds(&bounds[..1], &[1e5]).len(), 1);
    }
}
