//! The one decision rule both diagnoses name a cause by, on held-out evidence.
//!
//! A diagnosis fits each candidate effect on some units — the runs of a force
//! diagnosis ([`super::held_out`], by folds), the tosses of a motion diagnosis
//! ([`super::motion`]) — and scores it, unit by unit, on units it was not fitted on
//! (lower is better: a run's RSS, a toss's error). Against the model as it stands
//! (`reference`), a candidate's *gain* is the paired difference of the scores
//! ([`Paired`]). The rule:
//!
//! 1. A candidate **helps** when its gain is at least [`GAIN_T`] standard errors above
//!    zero and at least `floor` (a significant but negligible gain is no cause).
//! 2. The helping candidate with the largest mean gain is the **best**.
//! 3. It is **named** when it beats, on the same units, by a margin of standard errors
//!    every other candidate that helps or whose mean gain is larger though less sure
//!    (a large gain carried by a few units may be the true cause, of which a small
//!    steady gain is only a shadow) — unless the best one **adds beyond** the rival:
//!    with the rival in the model, adding the best one still helps. The rival then does
//!    not explain the same gain (it is the best one's shadow, or a second cause the next
//!    step judges). Otherwise the answer is **ambiguous** between it and those rivals,
//!    and names none.
//!
//! Nothing helping: **nothing** is named.
//!
//! The margin is the rule's one calibration by evidence ([`Margins`]): 2 standard
//! errors on tosses, each candidate fitted on its own and all compared on held-out
//! tosses only; 3 on a force diagnosis' runs, where the candidate was first picked by
//! its in-sample criterion among every catalogued one on the same runs (the folds
//! reuse them), a selection the held-out comparison must outweigh. Measured: with 2 on
//! runs, two 3 % hysteresis dampings of the 100 kHz power table were named
//! `viscous_damping` (tests/diagnose/diagnose_power_table.rs); with 3 on tosses, a friction
//! coefficient × 1.5 judged on 5 held-out tosses (Student's t, 4 degrees of freedom)
//! and a restitution falling with the impact speed were left `ambiguous`
//! (tests/diagnose/diagnose_motion.rs).

use super::paired::Paired;

/// Standard errors a held-out gain must lie above zero to help (one-sided; about 1 in
/// 700 by chance for one candidate, 1 % two-sided for the 10–30 units a diagnosis fits).
pub const GAIN_T: f64 = 3.0;

/// The rule's thresholds for one kind of evidence (–, standard errors).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Margins {
    /// A gain helps from this many standard errors above zero.
    pub gain_t: f64,
    /// The best must beat each rival by this many standard errors to be named alone.
    pub rival_t: f64,
}

impl Margins {
    /// Held-out tosses of a motion diagnosis.
    pub const TOSSES: Margins = Margins {
        gain_t: GAIN_T,
        rival_t: 2.0,
    };
    /// Held-out runs of a force diagnosis, the candidate picked in-sample first.
    pub const RUNS: Margins = Margins {
        gain_t: GAIN_T,
        rival_t: 3.0,
    };
}

/// What the rule decided.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// The candidate at this index.
    Named(usize),
    /// The best candidate and the rivals it does not beat by the rival margin, best first.
    Ambiguous(Vec<usize>),
    /// No candidate helps.
    Nothing,
}

/// Every candidate's gain and whether it helps, and the verdict.
#[derive(Clone, Debug)]
pub struct Decision {
    /// Each candidate's held-out gain over the reference (the reference's unit).
    pub gains: Vec<Paired>,
    /// Whether each helps (rule 1).
    pub helps: Vec<bool>,
    /// The verdict (rules 2 and 3).
    pub verdict: Verdict,
}

/// The rule applied to `candidates`' held-out scores (None where a candidate could not
/// be scored: it never helps, never rivals) against `reference`'s on the same units,
/// with the least gain `floor` (the scores' unit) and `margins`, without the test
/// whether the best adds beyond a rival (every close rival stays a rival).
pub fn decide(
    reference: &[f64],
    candidates: &[Option<&[f64]>],
    (floor, margins): (f64, Margins),
) -> Decision {
    decide_with(reference, candidates, (floor, margins), |_, _| None)
}

/// Whether the best candidate adds beyond a rival, from the rival's held-out scores
/// and those of the model with both (`both`): a gain that helps (`margins.gain_t`).
pub fn adds_beyond(rival: &[f64], both: &[f64], margins: Margins) -> bool {
    Paired::of(rival, both).t() >= margins.gain_t
}

/// [`decide`] with the test whether the best adds beyond a rival: `both(best, rival)`
/// gives the held-out scores of the model with both candidates (None if it cannot),
/// asked only for the rivals the best one does not beat by the rival margin.
pub fn decide_with(
    reference: &[f64],
    candidates: &[Option<&[f64]>],
    (floor, margins): (f64, Margins),
    both: impl Fn(usize, usize) -> Option<Vec<f64>>,
) -> Decision {
    let gains: Vec<Paired> = (candidates.iter())
        .map(|c| c.map_or_else(|| Paired::of(&[], &[]), |s| Paired::of(reference, s)))
        .collect();
    let helps: Vec<bool> = (gains.iter())
        .map(|g| g.t() >= margins.gain_t && g.mean >= floor)
        .collect();
    let best = (0..candidates.len())
        .filter(|&i| helps[i])
        .max_by(|&a, &b| gains[a].mean.total_cmp(&gains[b].mean));
    let Some(best) = best else {
        return Decision {
            gains,
            helps,
            verdict: Verdict::Nothing,
        };
    };
    let best_scores = candidates[best].unwrap_or(&[]);
    let rivals: Vec<usize> = (0..candidates.len())
        .filter(|&i| i != best && (helps[i] || gains[i].mean > gains[best].mean))
        .filter(|&i| {
            let other = candidates[i].unwrap_or(&[]);
            Paired::of(other, best_scores).t() < margins.rival_t
                && !both(best, i).is_some_and(|b| adds_beyond(other, &b, margins))
        })
        .collect();
    let verdict = if rivals.is_empty() {
        Verdict::Named(best)
    } else {
        Verdict::Ambiguous(std::iter::once(best).chain(rivals).collect())
    };
    Decision {
        gains,
        helps,
        verdict,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Scores of 12 units: `level` plus a unit-by-unit wobble of ±`spread`.
    fn scores(level: f64, spread: f64, phase: usize) -> Vec<f64> {
        (0..12)
            .map(|k| {
                level
                    + spread
                        * if (k + phase).is_multiple_of(2) {
                            1.0
                        } else {
                            -1.0
                        }
            })
            .collect()
    }

    #[test]
    fn a_clear_winner_is_named_a_close_pair_is_ambiguous_and_no_gain_is_nothing() {
        let reference = scores(10.0, 0.5, 0);
        let strong = scores(5.0, 0.5, 1);
        let weak = scores(9.0, 0.5, 1);
        let none = scores(10.0, 0.5, 1);
        let d = decide(
            &reference,
            &[Some(&weak), Some(&strong), Some(&none)],
            (0.0, Margins::RUNS),
        );
        assert_eq!(d.verdict, Verdict::Named(1));
        assert_eq!(d.helps, [true, true, false]);
        // Two candidates whose scores differ by less than the units' spread: the best
        // first, then the rival.
        let twin = scores(5.2, 0.5, 0);
        let d = decide(
            &reference,
            &[Some(&twin), Some(&strong)],
            (0.0, Margins::RUNS),
        );
        assert_eq!(d.verdict, Verdict::Ambiguous(vec![1, 0]));
        // Nothing helps: none better than the reference, one not scored, one below
        // the floor.
        let d = decide(
            &reference,
            &[Some(&none), None, Some(&weak)],
            (2.0, Margins::RUNS),
        );
        assert_eq!(d.verdict, Verdict::Nothing);
        assert_eq!(d.helps, [false, false, false]);
    }

    #[test]
    fn the_best_is_named_over_a_close_rival_only_where_it_adds_beyond_it() {
        let reference = scores(10.0, 0.5, 0);
        let (best, rival) = (scores(5.0, 0.5, 1), scores(5.2, 0.5, 0));
        let candidates = [Some(best.as_slice()), Some(rival.as_slice())];
        // Together clearly better than the rival alone: the best adds beyond it.
        let together = scores(4.0, 0.1, 0);
        let d = decide_with(&reference, &candidates, (0.0, Margins::TOSSES), |_, _| {
            Some(together.clone())
        });
        assert_eq!(d.verdict, Verdict::Named(0));
        // Together no better than the rival: the rival explains the same gain.
        let d = decide_with(&reference, &candidates, (0.0, Margins::TOSSES), |_, _| {
            Some(rival.clone())
        });
        assert_eq!(d.verdict, Verdict::Ambiguous(vec![0, 1]));
        // Not asked (None): the close rival stays one.
        let d = decide_with(&reference, &candidates, (0.0, Margins::TOSSES), |_, _| None);
        assert_eq!(d.verdict, Verdict::Ambiguous(vec![0, 1]));
    }
}
