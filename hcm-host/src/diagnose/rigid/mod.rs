//! The force diagnosis of a rigid (3D) contact: given a model (PM2) and
//! data with the moving body's poses and a measured wrench, which effect of the 3D
//! [`catalogue`] the model lacks — judged on runs it was not fitted on, by the one
//! rule of every diagnosis ([`super::verdict`], with the runs as units and
//! [`Margins::RUNS`]).
//!
//! - **Rows**: every recorded sample with a measured force, in contact and in flight
//!   ([`RecordedContact::with_rows`]): a sensor's offset shows in flight.
//! - **Fits**: the model's own free parameters (a fitted base: the law, its exponent,
//!   the friction) and the candidate's, together, by least squares on the wrench at the
//!   recorded poses ([`least_squares`]), from the model's values and the candidate's
//!   neutral ones, and from a quarter of the way into the candidate's box.
//! - **Held out**: two folds by run (even and odd runs): each fitted on one, scored on
//!   the other; a run's score is its rows' mean squared weighted residual.
//! - **Rounds**: the rule names the candidate whose held-out gain over the model is at
//!   least 3 standard errors and [`MIN_GAIN`] of the model's score, and beats every
//!   rival by 3 standard errors unless it adds beyond it; a named cause joins the model
//!   and the search repeats, at most [`MAX_ROUNDS`] times. A tie is "ambiguous",
//!   nothing helping is "none" — never a guess.
//! - **Intervals**: the extended model fitted on every run ([`fit_samples`]): each
//!   parameter with the standard error that holds run scatter.

mod parameters;

use super::Family;
use super::{Catalogue, Effect, Scales, Site};
use crate::dataset::Evidence;
pub use parameters::{law_label, Extended};

use super::paired::Paired;
use super::rounds::{self, Outcome, Trials};
use super::verdict::{Decision, Margins};
use crate::dataset::Dataset;
use crate::identify::BoundsOverrides;
use crate::identify::{
    fit_samples, least_squares, RecordedContact, RigidIdentifyError, RigidParameters, SampleFit,
};
use crate::numerics::optimize::Parameters;
use crate::progress::{in_stage, Progress, Stage};
use crate::scenario::Model;
use hcm_core::law::LawKind;
use rayon::prelude::*;
use serde::Serialize;

/// Least held-out gain that helps, as a share of the model's held-out score (–). The
/// score of a stiff contact whose runs scatter is their scatter, hundreds of times the
/// sensor's noise: a 0.6 N offset of a block landing on a block at 1.4 kN (t = 38 on
/// held-out runs) gained 0.4 % of it, and 1 % (the motion diagnosis' floor) left it
/// unnamed.
pub const MIN_GAIN: f64 = 0.001;
/// Largest RMS difference of two fitted models' wrenches over the held-out rows, as a
/// share of the measured force's RMS, for them to be one model (–): the fits' own
/// convergence, not a closeness the data cannot resolve. Measured by `hcm diagnose` of
/// a Hertz PM2 (24 runs, seed 7): Hertz + hysteresis damping against Hunt–Crossley on
/// the ball, 1.9e-4 (one model: Hunt–Crossley is Hertz plus that damping);
/// Lankarani–Nikravesh against Flores on the block, 1.9e-10 (their damping
/// coefficients are two functions of a fitted restitution); the first pair with a
/// viscous friction hidden as well, 1.4e-3 — left ambiguous.
pub const SAME_MODEL: f64 = 1e-3;
/// Causes named one after another, at most.
pub const MAX_ROUNDS: usize = 2;
/// Runs with contact each half needs, at least: the paired gain's standard error
/// needs several units.
pub const MIN_RUNS_PER_HALF: usize = 3;
/// Jacobians per fit.
const ITERATIONS: usize = 40;
/// Where in their box the effects' other starts lie (shares, on the scale searched):
/// an effect the base's parameters half absorb (a sensor's lag looks like a stiffer,
/// less damped contact) is found from near its value, not from its neutral one.
const INTO_BOX: [f64; 2] = [0.02, 0.25];

/// What the diagnosis is asked.
#[derive(Clone, Debug)]
pub struct RigidDiagnoseSettings {
    /// The contact.
    pub contact: usize,
    /// Whether the model's own parameters are re-fitted with each candidate (a PM2
    /// from `hcm identify`), or held as given (a model written by hand).
    pub fitted_base: bool,
    /// The scenario's `[identify.bounds]`.
    pub overrides: BoundsOverrides,
    /// The effects tried (those judged from a wrench).
    pub catalogue: Catalogue,
}

/// One candidate of one round.
#[derive(Clone, Debug, Serialize)]
pub struct CandidateScore {
    /// Catalogue name.
    pub name: &'static str,
    /// Its family.
    pub family: Family,
    /// Held-out gain over the round's model (its score minus the candidate's; the
    /// scores' unit: mean squared weighted residual per row).
    pub gain: Paired,
    /// Whether it helps.
    pub helps: bool,
}

/// One round.
#[derive(Clone, Debug, Serialize)]
pub struct RigidRound {
    /// The round's model's mean held-out score.
    pub score: f64,
    /// The candidates, in catalogue order.
    pub candidates: Vec<CandidateScore>,
    /// The cause named.
    pub named: Option<&'static str>,
    /// Candidates it could not tell apart.
    pub ambiguous: Vec<&'static str>,
    /// Tied candidates whose fits are one model with the named one (the same wrench at
    /// every row within [`SAME_MODEL`]): another way to write the cause, not a rival.
    pub same_as: Vec<&'static str>,
}

/// What the diagnosis found.
#[derive(Clone, Debug, Serialize)]
pub struct RigidDiagnosis {
    /// Runs judged.
    pub runs: usize,
    /// Recorded rows of the contact judged, over every run.
    pub rows: usize,
    /// The rounds.
    pub rounds: Vec<RigidRound>,
    /// Causes named, in order.
    pub named: Vec<&'static str>,
    /// Candidates of the last round it could not tell apart.
    pub ambiguous: Vec<&'static str>,
    /// The extended model fitted on every run: parameters ± standard errors.
    #[serde(skip)]
    pub fit: SampleFit,
    /// Held-out gain of the extended model over the given one.
    pub total_gain: Option<Paired>,
    /// The in-contact residual RMS left (N) and the sensor's RMS in flight (N).
    pub left: (f64, f64),
    /// One sentence for people.
    pub answer: String,
}

/// Diagnoses contact `settings.contact` of `base` on `data` (see the module docs),
/// reporting [`Stage::Diagnose`] to `progress`, one step per candidate fitted.
pub fn diagnose_rigid(
    base: &Model,
    data: &Dataset,
    settings: &RigidDiagnoseSettings,
    progress: &dyn Progress,
) -> Result<RigidDiagnosis, RigidIdentifyError> {
    let c = settings.contact;
    let recorded = RecordedContact::with_rows(base, data, c, true)?;
    enough_runs(data, &recorded)?;
    let exponent = base.contacts[c].law().get("exponent").unwrap_or(1.5);
    let scales = Scales::of(&recorded, exponent);
    let base_parameters = if settings.fitted_base {
        let mut p = RigidParameters::new(base, c, &settings.overrides)?
            .with_exponent(base, &settings.overrides)?;
        scales.contact.apply(base, c, &mut p);
        Some(p)
    } else {
        None
    };
    let model = Extended {
        base: base_parameters,
        contact: c,
        effects: Vec::new(),
        law: None,
    };
    let judge = Judge::new(base, &recorded, data.runs.len());
    let catalogue = candidates(base, settings);
    let mut search = Search::new(
        (&judge, &scales, &catalogue),
        &settings.overrides,
        model,
        progress,
    );
    let steps = (catalogue.len() * MAX_ROUNDS) as u64;
    let Ok(()) = in_stage(progress, Stage::Diagnose, steps, || {
        rounds::search(&mut search, Margins::RUNS, MAX_ROUNDS)
    });
    let Search {
        model,
        rounds,
        named,
        ambiguous,
        first,
        ..
    } = search;
    let fit = fit_samples(
        base,
        &recorded.part(|_| true),
        &model,
        &crate::progress::Silent,
    )?;
    let total_gain = match (&first, named.is_empty()) {
        (Some(f), false) => judge.scores(&model).map(|s| Paired::of(f, &s)),
        _ => None,
    };
    let left = leftover(&recorded, &fit.model);
    let same: Vec<String> = (rounds.iter())
        .filter_map(|r| Some((r.named?, &r.same_as)).filter(|(_, s)| !s.is_empty()))
        .map(|(n, same)| format!("{n} is {}", same.join(", ")))
        .collect();
    let answer = answer(&named, &ambiguous, left, &same);
    Ok(RigidDiagnosis {
        runs: judge.runs,
        rows: recorded.samples.len(),
        rounds,
        named,
        ambiguous,
        fit,
        total_gain,
        left,
        answer,
    })
}

/// What the rounds may add to contact `settings.contact` of `base`: the catalogue's
/// effects judged from a wrench that change it (and are not freed by a fitted base's own
/// fit), then, on a fitted base, every other law of the core.
fn candidates(base: &Model, settings: &RigidDiagnoseSettings) -> Vec<Candidate> {
    let (site, fitted) = (Site::of(base, settings.contact), settings.fitted_base);
    let own_law = base.contacts[settings.contact].law().kind();
    (settings.catalogue.for_evidence(Evidence::Wrench))
        .filter(|e| e.applies(base, site) && !(fitted && e.within_base_fit(base, site)))
        .map(Candidate::Effect)
        .chain(
            (LawKind::ALL.iter().copied())
                .filter(|k| fitted && *k != own_law)
                .map(Candidate::Law),
        )
        .collect()
}

/// What a round may add: an effect of the catalogue, or another law in the model's
/// place (the normal-law family; with a fitted base only, at most one swap).
#[derive(Clone, Copy, Debug)]
enum Candidate {
    Effect(&'static dyn Effect),
    Law(LawKind),
}

impl Candidate {
    fn name(self) -> &'static str {
        match self {
            Candidate::Effect(e) => e.name(),
            Candidate::Law(k) => law_label(k),
        }
    }

    fn family(self) -> Family {
        match self {
            Candidate::Effect(e) => e.family(),
            Candidate::Law(_) => Family::Normal,
        }
    }

    /// Its line of a round: its held-out `gain` and whether it `helps`.
    fn scored(self, gain: Paired, helps: bool) -> CandidateScore {
        CandidateScore {
            name: self.name(),
            family: self.family(),
            gain,
            helps,
        }
    }
}

/// An error unless each half of the runs (even, odd) has [`MIN_RUNS_PER_HALF`] runs
/// with rows of `recorded`.
fn enough_runs(data: &Dataset, recorded: &RecordedContact) -> Result<(), RigidIdentifyError> {
    for fold in 0..2 {
        let runs = (0..data.runs.len())
            .filter(|r| r % 2 == fold && recorded.samples.iter().any(|s| s.run == *r))
            .count();
        if runs < MIN_RUNS_PER_HALF {
            return Err(RigidIdentifyError::Setup(format!(
                "the diagnosis fits on half the runs and judges on the other half, run by \
                     run: it needs at least {} runs with measured contact ({MIN_RUNS_PER_HALF} \
                     even, {MIN_RUNS_PER_HALF} odd); the data have {} — record more runs",
                2 * MIN_RUNS_PER_HALF,
                data.runs.len()
            )));
        }
    }
    Ok(())
}

/// The rounds of one diagnosis: its fixed inputs, the model extended so far and the
/// current round's candidates.
struct Search<'a> {
    judge: &'a Judge<'a>,
    scales: &'a Scales,
    catalogue: &'a [Candidate],
    overrides: &'a BoundsOverrides,
    progress: &'a dyn Progress,
    /// The base with the causes named so far.
    model: Extended,
    /// The fit of the last cause named, the next round's seed.
    seed: Option<Folds>,
    /// The first round's reference scores.
    first: Option<Vec<f64>>,
    rounds: Vec<RigidRound>,
    named: Vec<&'static str>,
    ambiguous: Vec<&'static str>,
    /// This round's reference score (mean), open candidates and their fits.
    score: f64,
    left: Vec<(Candidate, Extended)>,
    fits: Vec<Option<Folds>>,
}

/// The seed a candidate's fit starts from beside its own starts: the reference's fit
/// for an effect (its genes a prefix of the candidate's), none for another law (whose
/// genes mean other parameters).
fn seed_of(candidate: Candidate, reference: &Folds) -> Option<&Folds> {
    matches!(candidate, Candidate::Effect(_)).then_some(reference)
}

impl<'a> Search<'a> {
    /// The search of `model`'s extensions, nothing tried yet.
    fn new(
        (judge, scales, catalogue): (&'a Judge<'a>, &'a Scales, &'a [Candidate]),
        overrides: &'a BoundsOverrides,
        model: Extended,
        progress: &'a dyn Progress,
    ) -> Search<'a> {
        Search {
            judge,
            scales,
            catalogue,
            overrides,
            progress,
            model,
            seed: None,
            first: None,
            rounds: Vec::new(),
            named: Vec::new(),
            ambiguous: Vec::new(),
            score: f64::NAN,
            left: Vec::new(),
            fits: Vec::new(),
        }
    }

    /// Whether `candidate` may still join the model: an effect not in it yet, another
    /// law than its own when none has been swapped in.
    fn open(&self, candidate: Candidate) -> bool {
        match candidate {
            Candidate::Effect(e) => !(self.model.effects.iter()).any(|(n, _)| n.name() == e.name()),
            Candidate::Law(_) => self.model.law.is_none(),
        }
    }

    /// `model` with `candidate` added, or `None` where it cannot join (a law that
    /// cannot stand in).
    fn extend(&self, model: &Extended, candidate: Candidate) -> Option<Extended> {
        match candidate {
            Candidate::Effect(e) => Some(model.with(e, self.scales)),
            Candidate::Law(k) => model.with_law(self.judge.base, k, self.overrides, self.scales),
        }
    }

    /// Every candidate still open to the model, extended, and its fit on the folds (the
    /// reference's fit `fitted` as an effect's seed); `done` (steps so far, steps in
    /// all) counts on in the progress. In parallel, collected in catalogue order: the
    /// same answer whatever the thread count.
    fn fit_candidates(
        &self,
        fitted: &Folds,
        (done, steps): (usize, u64),
    ) -> (Vec<(Candidate, Extended)>, Vec<Option<Folds>>) {
        let left: Vec<(Candidate, Extended)> = (self.catalogue.iter().copied())
            .filter(|c| self.open(*c))
            .filter_map(|c| Some((c, self.extend(&self.model, c)?)))
            .collect();
        let done = std::sync::atomic::AtomicUsize::new(done);
        let fits = (left.par_iter())
            .map(|(c, extended)| {
                let fit = self.judge.fit_folds(extended, seed_of(*c, fitted));
                let k = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                self.progress.advance(k as u64 + 1, steps);
                fit
            })
            .collect();
        (left, fits)
    }
}

impl rounds::Judge for Search<'_> {
    type Error = std::convert::Infallible;

    fn trials(&mut self, round: usize) -> Result<Option<Trials>, Self::Error> {
        let judge = self.judge;
        let Some(mut fitted) = judge.fit_folds(&self.model, self.seed.as_ref()) else {
            return Ok(None);
        };
        let steps = (self.catalogue.len() * MAX_ROUNDS) as u64;
        let (left, fits) = self.fit_candidates(&fitted, (round * self.catalogue.len(), steps));
        let nested: Vec<Option<Folds>> = (left.iter().zip(&fits))
            .map(|((c, _), f)| f.clone().filter(|_| matches!(c, Candidate::Effect(_))))
            .collect();
        judge.improve(&self.model, &mut fitted, &nested);
        let reference = judge.held_out(&self.model, &fitted);
        if round == 0 {
            self.first = Some(reference.clone());
        }
        let scores = (left.iter().zip(&fits))
            .map(|((_, extended), f)| f.as_ref().map(|f| judge.held_out(extended, f)))
            .collect();
        (self.score, self.left, self.fits) = (mean(&reference), left, fits);
        Ok(Some(Trials {
            floor: MIN_GAIN * self.score,
            reference,
            scores,
        }))
    }

    fn both(&self, a: usize, b: usize) -> Option<Vec<f64>> {
        let pair = self.extend(&self.left[a].1, self.left[b].0)?;
        let seed =
            (self.fits[a].as_ref()).filter(|_| matches!(self.left[b].0, Candidate::Effect(_)));
        let fit = self.judge.fit_folds(&pair, seed)?;
        Some(self.judge.held_out(&pair, &fit))
    }

    fn one_model(&self, tied: &[usize]) -> Option<(usize, Vec<&'static str>)> {
        if !self.judge.one_model(&self.left, &self.fits, tied) {
            return None;
        }
        let i = tied.iter().copied().min().unwrap_or(0);
        let others = tied.iter().filter(|&&j| j != i);
        Some((i, others.map(|&j| self.left[j].0.name()).collect()))
    }

    fn record(&mut self, decision: &Decision, outcome: &Outcome) {
        let mut this = RigidRound {
            score: self.score,
            candidates: (self.left.iter().zip(&decision.gains).zip(&decision.helps))
                .map(|(((c, _), g), h)| c.scored(*g, *h))
                .collect(),
            named: None,
            ambiguous: Vec::new(),
            same_as: Vec::new(),
        };
        match outcome {
            Outcome::Named(i, same_as) => {
                self.seed.clone_from(&self.fits[*i]);
                this.named = Some(self.left[*i].0.name());
                this.same_as.clone_from(same_as);
                self.named.push(self.left[*i].0.name());
                self.model = self.left[*i].1.clone();
            }
            Outcome::Ambiguous(tied) => {
                this.ambiguous = tied.iter().map(|&i| self.left[i].0.name()).collect();
                self.ambiguous.clone_from(&this.ambiguous);
            }
            Outcome::Nothing => {}
        }
        self.rounds.push(this);
    }
}

/// The in-contact residual RMS (N) of `model` and the measured force's RMS about its
/// mean in flight (N): what no cause explained beside the sensor's own noise.
fn leftover(recorded: &RecordedContact, model: &Model) -> (f64, f64) {
    let read = recorded.readings(model);
    let (mut contact, mut nc) = (0.0, 0usize);
    let mut flight: Vec<[f64; 3]> = Vec::new();
    for (s, r) in recorded.samples.iter().zip(&read) {
        if s.points.is_empty() {
            flight.push([s.measured[0], s.measured[1], s.measured[2]]);
        } else {
            contact += (0..3).map(|k| (s.measured[k] - r[k]).powi(2)).sum::<f64>();
            nc += 1;
        }
    }
    let n = flight.len().max(1) as f64;
    let centre: [f64; 3] = core::array::from_fn(|k| flight.iter().map(|f| f[k]).sum::<f64>() / n);
    let spread = flight
        .iter()
        .map(|f| (0..3).map(|k| (f[k] - centre[k]).powi(2)).sum::<f64>())
        .sum::<f64>()
        / n;
    let rms = |sum: f64, n: usize| {
        if n == 0 {
            f64::NAN
        } else {
            (sum / n as f64).sqrt()
        }
    };
    (
        rms(contact, nc),
        if flight.is_empty() {
            f64::NAN
        } else {
            spread.sqrt()
        },
    )
}

/// The one sentence.
fn answer(
    named: &[&str],
    ambiguous: &[&str],
    (contact, flight): (f64, f64),
    same: &[String],
) -> String {
    let mut out = if named.is_empty() && ambiguous.is_empty() {
        "none: no candidate of the catalogue gains on held-out runs".to_owned()
    } else if named.is_empty() {
        format!(
            "ambiguous: {} explain the held-out runs alike",
            ambiguous.join(" or ")
        )
    } else {
        let mut s = format!("named: {}", named.join(" + "));
        if !ambiguous.is_empty() {
            s += &format!("; then ambiguous: {}", ambiguous.join(" or "));
        }
        s
    };
    out += &format!(
        ". Left in contact: {contact:.3e} N RMS (the sensor in flight: {flight:.3e} N RMS)"
    );
    if !same.is_empty() {
        out += &format!(" (one model written another way: {})", same.join("; "));
    }
    out
}

/// Mean of `v` (0 for none).
fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len().max(1) as f64
}

/// One model fitted on each fold's training half: genes and training cost per fold.
#[derive(Clone, Debug)]
struct Folds {
    genes: [Vec<f64>; 2],
    cost: [f64; 2],
}

/// Fits on one fold and scores the other.
struct Judge<'a> {
    base: &'a Model,
    /// Per fold: (training half, held-out half): fold f holds out the runs r % 2 = f.
    parts: [(RecordedContact, RecordedContact); 2],
    runs: usize,
}

impl Judge<'_> {
    fn new<'a>(base: &'a Model, recorded: &RecordedContact, runs: usize) -> Judge<'a> {
        let part = |fold: usize| {
            (
                recorded.part(|r| r % 2 != fold),
                recorded.part(|r| r % 2 == fold),
            )
        };
        Judge {
            base,
            parts: [part(0), part(1)],
            runs,
        }
    }

    /// The held-out score of every run with rows (in run order) under `parameters`.
    fn scores(&self, parameters: &Extended) -> Option<Vec<f64>> {
        Some(self.held_out(parameters, &self.fit_folds(parameters, None)?))
    }

    /// Each run's held-out score under `parameters` fitted as `folds`: its rows' mean
    /// squared weighted residual, the run scored by the fit on the other half.
    fn held_out(&self, parameters: &Extended, folds: &Folds) -> Vec<f64> {
        let mut per_run = vec![f64::NAN; self.runs];
        for (fold, (_, held)) in self.parts.iter().enumerate() {
            let model = parameters.apply(self.base, &folds.genes[fold]);
            let mut out = vec![0.0; 6 * held.samples.len()];
            held.residuals(&model, &mut out);
            let mut sums = vec![(0.0, 0usize); self.runs];
            for (s, row) in held.samples.iter().zip(out.chunks_exact(6)) {
                sums[s.run].0 += row.iter().map(|x| x * x).sum::<f64>();
                sums[s.run].1 += 1;
            }
            for (r, (sum, n)) in sums.into_iter().enumerate() {
                if n > 0 {
                    per_run[r] = sum / n as f64;
                }
            }
        }
        per_run.into_iter().filter(|s| s.is_finite()).collect()
    }

    /// ½ Σ r² of `parameters` at `genes` on fold `fold`'s training half.
    fn cost(&self, parameters: &Extended, genes: &[f64], fold: usize) -> f64 {
        let training = &self.parts[fold].0;
        let mut out = vec![0.0; 6 * training.samples.len()];
        training.residuals(&parameters.apply(self.base, genes), &mut out);
        0.5 * out.iter().map(|x| x * x).sum::<f64>()
    }

    /// `parameters` fitted on each fold's training half: the best of the fits from the
    /// model's values with the effects neutral, with the effects [`INTO_BOX`] of the
    /// way into their box, and from `seed`'s genes of that fold (a nested model's fit,
    /// the extra effects neutral); `None` if a fold has no fit.
    fn fit_folds(&self, parameters: &Extended, seed: Option<&Folds>) -> Option<Folds> {
        let neutral = parameters.values(self.base);
        let bounds = parameters.bounds();
        let effect_len: usize = parameters.effects.iter().map(|(_, b)| b.len()).sum();
        let base_len = neutral.len() - effect_len;
        let mut starts = vec![neutral.clone()];
        if effect_len > 0 {
            for share in INTO_BOX {
                let mut start = neutral.clone();
                for (k, b) in bounds.iter().enumerate().skip(base_len) {
                    start[k] = b.value_at(share);
                }
                starts.push(start);
            }
        }
        let mut folds = Folds {
            genes: [Vec::new(), Vec::new()],
            cost: [f64::INFINITY; 2],
        };
        for fold in 0..2 {
            let mut own = starts.clone();
            if let Some(seed) = seed {
                let mut start = seed.genes[fold].clone();
                start.extend_from_slice(&neutral[start.len().min(neutral.len())..]);
                own.push(start);
            }
            let training = &self.parts[fold].0;
            let (genes, cost) = (own.iter())
                .filter_map(|s| least_squares(self.base, training, parameters, s, ITERATIONS))
                .min_by(|a, b| a.1.total_cmp(&b.1))?;
            (folds.genes[fold], folds.cost[fold]) = (genes, cost);
        }
        Some(folds)
    }

    /// Whether the candidates `tied` of `left`, fitted as `fits`, are one model: on
    /// every fold's held-out rows each predicts the first one's wrench within
    /// [`SAME_MODEL`] of the measured force's RMS.
    fn one_model(
        &self,
        left: &[(Candidate, Extended)],
        fits: &[Option<Folds>],
        tied: &[usize],
    ) -> bool {
        let readings = |i: usize| -> Option<Vec<Vec<[f64; 6]>>> {
            let fit = fits[i].as_ref()?;
            Some(
                (self.parts.iter().enumerate())
                    .map(|(fold, (_, held))| {
                        held.readings(&left[i].1.apply(self.base, &fit.genes[fold]))
                    })
                    .collect(),
            )
        };
        let Some(first) = tied.first().and_then(|&i| readings(i)) else {
            return false;
        };
        let scale = self.parts[0].1.force_scale.max(f64::MIN_POSITIVE);
        tied[1..].iter().all(|&j| {
            let Some(other) = readings(j) else {
                return false;
            };
            let (mut sum, mut n) = (0.0, 0usize);
            for (a, b) in first.iter().flatten().zip(other.iter().flatten()) {
                sum += (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>();
                n += 1;
            }
            let rms = (sum / n.max(1) as f64).sqrt();
            n > 0 && rms <= SAME_MODEL * scale
        })
    }

    /// `reference` improved by the candidates' fits: a candidate's genes without its
    /// own effect are a fit of the reference, and where one has a lower training cost
    /// than the reference's own fit it replaces it — so that no candidate gains by
    /// having found a better optimum of the model's own parameters.
    fn improve(&self, parameters: &Extended, reference: &mut Folds, fits: &[Option<Folds>]) {
        for fit in fits.iter().flatten() {
            for fold in 0..2 {
                let genes = &fit.genes[fold][..reference.genes[fold].len()];
                let cost = self.cost(parameters, genes, fold);
                if cost < reference.cost[fold] {
                    reference.genes[fold] = genes.to_vec();
                    reference.cost[fold] = cost;
                }
            }
        }
    }
}
