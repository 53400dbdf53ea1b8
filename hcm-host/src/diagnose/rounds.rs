//! The one driver of a diagnosis' rounds, whatever the evidence: each round fits every
//! open candidate on the training units, scores it on the held-out units, applies the
//! rule ([`super::verdict`]) and names the chosen one (the model then carries it) or
//! stops. What differs between a wrench and poses — how a candidate is fitted and
//! scored, what a round records — is the [`Judge`]'s.

use super::verdict::{decide_with, Decision, Margins, Verdict};

/// One round's candidates as a judge fitted them.
pub(super) struct Trials {
    /// The model as it stands, scored unit by unit on the held-out units.
    pub reference: Vec<f64>,
    /// The least gain that counts (the scores' unit).
    pub floor: f64,
    /// Each open candidate's held-out scores (None where it could not be scored).
    pub scores: Vec<Option<Vec<f64>>>,
}

/// What a round decided.
pub(super) enum Outcome {
    /// The candidate at this index is named; the others are one model with it (their
    /// names).
    Named(usize, Vec<&'static str>),
    /// These candidates could not be told apart, best first: none is named.
    Ambiguous(Vec<usize>),
    /// No candidate helps.
    Nothing,
}

/// How one kind of evidence fits, scores and records candidates.
pub(super) trait Judge {
    /// What stops a search.
    type Error;
    /// Round `round`'s open candidates fitted on the training units and scored on the
    /// held-out units; `None` ends the search (nothing can be fitted).
    fn trials(&mut self, round: usize) -> Result<Option<Trials>, Self::Error>;
    /// The held-out scores of the model with candidates `best` and `rival` together.
    fn both(&self, best: usize, rival: usize) -> Option<Vec<f64>>;
    /// Whether the tied candidates are one model written another way: the one to name
    /// and the others' names.
    fn one_model(&self, _tied: &[usize]) -> Option<(usize, Vec<&'static str>)> {
        None
    }
    /// Records the round (every candidate's gain, what was decided) and, where one is
    /// named, extends the model with it.
    fn record(&mut self, decision: &Decision, outcome: &Outcome);
    /// When a phase of the search ends (a round names nothing, or its rounds are
    /// spent): whether the judge has another kind of candidate to try next on the
    /// model as it stands (chance after the deterministic effects), with rounds of its
    /// own.
    fn next_phase(&mut self) -> bool {
        false
    }
}

/// Up to `max_rounds` rounds of `judge` under the rule's `margins` per phase
/// ([`Judge::next_phase`]).
pub(super) fn search<J: Judge>(
    judge: &mut J,
    margins: Margins,
    max_rounds: usize,
) -> Result<(), J::Error> {
    let (mut round, mut in_phase) = (0, 0);
    loop {
        if in_phase == max_rounds {
            if !judge.next_phase() {
                break;
            }
            in_phase = 0;
        }
        let Some(trials) = judge.trials(round)? else {
            if !judge.next_phase() {
                break;
            }
            in_phase = 0;
            continue;
        };
        (round, in_phase) = (round + 1, in_phase + 1);
        let scores: Vec<Option<&[f64]>> = trials.scores.iter().map(|s| s.as_deref()).collect();
        let both = |best: usize, rival: usize| judge.both(best, rival);
        let decision = decide_with(&trials.reference, &scores, (trials.floor, margins), both);
        let outcome = match &decision.verdict {
            Verdict::Named(i) => Outcome::Named(*i, Vec::new()),
            Verdict::Ambiguous(tied) => match judge.one_model(tied) {
                Some((i, same)) => Outcome::Named(i, same),
                None => Outcome::Ambiguous(tied.clone()),
            },
            Verdict::Nothing => Outcome::Nothing,
        };
        judge.record(&decision, &outcome);
        if !matches!(outcome, Outcome::Named(..)) {
            if !judge.next_phase() {
                break;
            }
            in_phase = 0;
        }
    }
    Ok(())
}
