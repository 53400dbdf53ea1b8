//! Diagnosis from motion alone: what a tossed or sliding body's simulation
//! gets wrong when the data hold its poses and no force.
//!
//! The tosses are split as the identification from motion splits them (even toss
//! numbers train, odd ones are held out: [`crate::identify::motion::split_tosses`]).
//! Every candidate of the [`catalogue`] — the friction law's coefficient, its shape
//! (Coulomb), viscous friction, torsional and rolling resistance, the table's height
//! and tilt, the tracker's length scale, the body's inertia — is fitted on the training tosses with the
//! user's model otherwise fixed ([`fit`]), and judged on the held-out tosses by its
//! paired gain over the user's model, toss by toss ([`Paired`]). A toss's score is its
//! mean position error (%) plus mean rotation error (°), plus, where the data hold a
//! force channel, its mean force error (% of the body's weight). The decision is the
//! one rule of every diagnosis, [`super::verdict`], with the tosses as the units: a
//! candidate *helps* when its gain is at least [`GAIN_T`] standard errors above zero
//! and at least [`MIN_GAIN`] of the model's held-out score; the helping one with the
//! largest gain is named only if it also beats by [`RIVAL_T`] standard errors, on the
//! same tosses, every other helping candidate and every candidate whose mean gain is
//! larger than its own though less sure; otherwise the answer is "ambiguous" and names
//! none. A named cause is added to the model, and the search repeats on what is left
//! (at most [`MAX_ROUNDS`] causes). Nothing helping: the answer is "none".
//!
//! Then chance (`Family::Chance`): with the deterministic effects done, the model
//! forecasts by ensembles — its start state drawn as its fit says and the tracker's
//! noise on each member's frames, the reference — and each kind of run-to-run spread
//! (the contact's scatter, the start state's, the fixed body's height and tilt) is
//! fitted on a grid by the fair energy score of its ensembles and judged by the same
//! rule on the held-out tosses. Chances the held-out tosses cannot tell apart are one
//! forecast: the one gaining most is named, the others reported beside it. At most
//! [`MAX_CHANCES`] are named; none named, the extended model is the deterministic one.

mod fit;
mod rest;

pub use super::paired::Paired;
use super::rounds::{self, Outcome, Trials};
pub use super::verdict::GAIN_T;
use super::verdict::{Decision, Margins};
/// Standard errors the best candidate must beat each rival by on the held-out tosses
/// ([`Margins::TOSSES`]).
pub const RIVAL_T: f64 = Margins::TOSSES.rival_t;

use super::{apply_at, Catalogue, Effect, Scales, Site};
use crate::dataset::{Dataset, Evidence};
use crate::identify::{split_tosses, MotionParameters};
use crate::progress::{in_stage, Progress, Stage as ProgressStage};
use crate::replay::{TossError, TossSetup};
use crate::scenario::Model;
use fit::{Fitted, Part, Subject};
use serde::Serialize;

/// The least held-out gain that helps, as a fraction of the user's model's held-out
/// score (the first round's, also in later rounds): a significant but negligible
/// improvement is not a cause worth adding.
pub const MIN_GAIN: f64 = 0.01;
/// Causes named one after another, at most.
pub const MAX_ROUNDS: usize = 2;
/// Held-out tosses a diagnosis needs, at least.
pub const MIN_HELD_OUT: usize = 3;
/// Most chances named (–), one per round of the chance phase. One: on the real cube
/// tosses a second round on top of the first (the table's tilt) did not pass the rule —
/// the contact's scatter refitted with the tilt in place gained 0.449 ± 0.345 % + ° per
/// held-out toss (t 1.3; `hcm predict --members 32` of tilt and scatter 0.15 together:
/// bands 0.593 and 0.873 where the tilt alone holds 0.426 and 0.729), and the round
/// cost 332 s of the diagnose stage's 1212 s (`hcm reproduce cube-toss` on one 2-core
/// machine; 880 s without it, docs/real-data.md).
pub const MAX_CHANCES: usize = 1;

/// One candidate of one round.
#[derive(Clone, Debug, Serialize)]
pub struct CandidateResult {
    /// Catalogue name.
    pub name: &'static str,
    /// Its family (`friction`, `resistance`, `measurement`).
    pub(crate) family: &'static str,
    /// Fitted parameters (name, value), units of the catalogue.
    pub parameters: Vec<(String, f64)>,
    /// Training fitness (% + °), the model's with this change.
    pub(crate) training: f64,
    /// Mean held-out score (% + °).
    pub(crate) held_out: f64,
    /// Held-out gain over the round's model: its score minus the candidate's.
    pub gain: Paired,
    /// The values the training tosses leave for it (95 %, paired): for chance, on its
    /// grid; for a named deterministic cause of one parameter, bisected.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub interval: Option<[f64; 2]>,
    /// Whether it helps (see the module's rule).
    pub helps: bool,
    /// Fitness evaluations its fit took.
    pub(crate) evaluations: usize,
}

/// One round: the candidates against the model as it stood.
#[derive(Clone, Debug, Serialize)]
pub struct Round {
    /// The round's model's training fitness (% + °).
    pub training: f64,
    /// The round's model's mean held-out score (% + °).
    pub held_out: f64,
    /// Every candidate, in catalogue order.
    pub candidates: Vec<CandidateResult>,
    /// The cause named in this round.
    pub(crate) named: Option<&'static str>,
    /// Candidates that explain the held-out data equally well (none named).
    pub(crate) ambiguous: Vec<&'static str>,
    /// Chances the named one could not be told from: spreads that forecast the
    /// held-out tosses as well (the named one gains most).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub same_as: Vec<&'static str>,
}

/// What the diagnosis found.
#[derive(Clone, Debug, Serialize)]
pub struct MotionDiagnosis {
    /// Tosses fitted on (the even toss numbers).
    pub training_tosses: usize,
    /// Tosses judged on (the odd toss numbers).
    pub held_out_tosses: usize,
    /// The rounds, in order.
    pub rounds: Vec<Round>,
    /// Causes named, in order, with their parameters.
    pub named: Vec<(String, Vec<(String, f64)>)>,
    /// When the search stopped at a tie: the candidates it could not tell apart.
    pub ambiguous: Vec<&'static str>,
    /// Held-out gain of the extended model (every named cause) over the user's.
    pub(crate) total_gain: Option<Paired>,
    /// One sentence for people.
    pub answer: String,
    /// The user's model with every named cause.
    #[serde(skip)]
    pub extended: Model,
    /// Wall-clock time of the chance phase (s; 0 where it did not run): what the
    /// spreads add to the deterministic search. Not written (a run's outputs are the
    /// same bits for the same inputs).
    #[serde(skip)]
    pub chance_seconds: f64,
}

impl MotionDiagnosis {
    /// Whether every cause it named is a chance (the extended model is then the base
    /// with a spread: a physics file of the base carries it whole).
    pub fn only_chance_named(&self) -> bool {
        let chance = |name: &str| (super::CHANCES.iter()).any(|e| e.name() == name);
        self.named.iter().all(|(name, _)| chance(name))
    }
}

/// Why a motion diagnosis could not run.
#[derive(Debug, thiserror::Error)]
pub enum MotionDiagnoseError {
    /// The scenario or the data do not describe tosses.
    #[error(transparent)]
    Toss(#[from] TossError),
    /// Too few tosses to judge on.
    #[error("{found} held-out tosses (odd toss numbers); a diagnosis from motion needs at least {MIN_HELD_OUT} and as many for training")]
    TooFewTosses {
        /// Held-out tosses the data hold.
        found: usize,
    },
    /// The user's model cannot replay the tosses.
    #[error("the model's replay of the {part} tosses failed; check it with `hcm predict`")]
    Replay {
        /// Which tosses failed to replay: `training` or `held-out`.
        part: &'static str,
    },
}

fn mean(values: &[f64]) -> f64 {
    values.iter().sum::<f64>() / values.len().max(1) as f64
}

/// A candidate fitted in one round: its fit and its held-out scores, toss by toss
/// (% + °; None where the replay failed).
type Fit = (&'static dyn Effect, Fitted, Option<Vec<f64>>);

/// What a round's candidates are fitted and judged on: the round's model and the
/// tosses read through it.
struct Stage<'a> {
    /// The round's model, its contact and fixed partner.
    subject: Subject<'a>,
    /// The training tosses, prepared from the round's model.
    training: Part<'a>,
    /// The held-out tosses, prepared from the round's model.
    held_out: Part<'a>,
    /// The body's mass and half width, which scale the candidates' bounds.
    scales: Scales,
}

/// Every open candidate fitted on the training tosses and judged on the held-out ones,
/// in catalogue order; `progress` advances to `k` of the candidates, with the round as its
/// status, before each fit.
fn fit_candidates(
    stage: &Stage<'_>,
    open: &[&'static dyn Effect],
    round: usize,
    progress: &dyn Progress,
) -> (Vec<CandidateResult>, Vec<Fit>) {
    let subject = &stage.subject;
    let mut results = Vec::new();
    let mut held_scores = Vec::new();
    for (k, &effect) in open.iter().enumerate() {
        progress.advance(k as u64, open.len() as u64);
        progress.status(&format!("round {}", round + 1));
        let bounds = effect.bounds(Evidence::Poses, &stage.scales);
        let neutral = effect.neutral(subject.model, subject.site);
        let fitted = fit::fit(subject, effect, &bounds, &neutral, &stage.training);
        let held = subject.scores(effect, &fitted.values, &stage.held_out);
        let result = judge(effect, &bounds, &fitted, held.as_deref());
        results.push(result);
        held_scores.push((effect, fitted, held));
    }
    (results, held_scores)
}

/// The search under way: the model with every cause named so far, the tosses as read
/// through it, and what the rounds found.
struct Search<'p> {
    /// What the user's model is: given, or fitted from these poses.
    base: MotionBase,
    /// The user's model with the causes named so far.
    current: Model,
    /// The training tosses (transformed by any measurement cause named).
    training: Dataset,
    /// The held-out tosses (likewise).
    held_out: Dataset,
    /// The body's contact with its fixed partner.
    site: Site,
    /// The body's mass and half width.
    scales: Scales,
    /// The effects tried (those judged from poses).
    catalogue: Catalogue,
    /// The rounds so far.
    rounds: Vec<Round>,
    /// Causes named, with their parameters.
    named: Vec<(String, Vec<(String, f64)>)>,
    /// The candidates the last round could not tell apart.
    ambiguous: Vec<&'static str>,
    /// The user's model's held-out scores, toss by toss (% + °).
    first_scores: Option<Vec<f64>>,
    /// The extended model's held-out scores after the last cause named.
    last_scores: Option<Vec<f64>>,
    /// Where each candidate's fit is reported.
    progress: &'p dyn Progress,
    /// Whether the search is in its chance phase: the deterministic effects done,
    /// the spreads tried on what is left.
    chance: bool,
    /// The model as the deterministic phase left it, while the chance phase judges
    /// its spreads against it with the start state drawn as its fit says: the
    /// extended model unless a chance is named.
    deterministic: Option<Model>,
    /// When the chance phase began.
    chance_started: Option<std::time::Instant>,
    /// The round under way and its candidates' fits.
    this: Option<Round>,
    held_scores: Vec<Fit>,
}

impl Search<'_> {
    /// The held-out scores of the current model with `first` as fitted, then `second`
    /// fitted on top of it on the training tosses (read through `first` where it is a
    /// measurement effect): the model with both, for the rule's test whether the best candidate (`second`) adds
    /// beyond a rival (`first`). None where `second` cannot change that model or a
    /// replay fails.
    fn stacked(&self, first: &Fit, second: &'static dyn Effect) -> Option<Vec<f64>> {
        let site = self.site;
        let (effect, fitted, _) = first;
        let mut model = self.current.clone();
        apply_at(*effect, &mut model, site, &fitted.values);
        if !second.applies(&model, site) {
            return None;
        }
        let read = |data: &Dataset| effect.read(data, &fitted.values);
        let training = read(&self.training).unwrap_or_else(|| self.training.clone());
        let held_out = read(&self.held_out).unwrap_or_else(|| self.held_out.clone());
        let (training, held_out) = (
            Part::new(&model, &training, fit::FIT_MEMBERS).ok()?,
            Part::new(&model, &held_out, fit::JUDGE_MEMBERS).ok()?,
        );
        let subject = Subject {
            model: &model,
            site,
        };
        let bounds = second.bounds(Evidence::Poses, &self.scales);
        let neutral = second.neutral(&model, site);
        let fitted = fit::fit(&subject, second, &bounds, &neutral, &training);
        subject.scores(second, &fitted.values, &held_out)
    }

    /// Names candidate `index` of the round `this`: adds it to the model, reads the
    /// tosses through it where it is a measurement effect, and records the round.
    fn name(&mut self, mut this: Round, mut held_scores: Vec<Fit>, index: usize) {
        let (effect, fitted, held) = held_scores.swap_remove(index);
        if this.candidates[index].interval.is_none() {
            this.candidates[index].interval = self.interval(effect, &fitted);
        }
        this.named = Some(effect.name());
        self.named.push((
            effect.name().to_owned(),
            this.candidates[index].parameters.clone(),
        ));
        apply_at(effect, &mut self.current, self.site, &fitted.values);
        if let Some(read) = effect.read(&self.training, &fitted.values) {
            self.training = read;
        }
        if let Some(read) = effect.read(&self.held_out, &fitted.values) {
            self.held_out = read;
        }
        self.last_scores = held;
        self.rounds.push(this);
    }

    /// The interval of values the training tosses leave for a named deterministic
    /// cause of one parameter ([`fit::interval`]), against the round's model (before
    /// it is added); None for two parameters or where a replay fails.
    fn interval(&self, effect: &'static dyn Effect, fitted: &Fitted) -> Option<[f64; 2]> {
        let bounds = effect.bounds(Evidence::Poses, &self.scales);
        let ([bound], [best]) = (bounds.as_slice(), fitted.values.as_slice()) else {
            return None;
        };
        let training = Part::new(&self.current, &self.training, fit::FIT_MEMBERS).ok()?;
        let subject = Subject {
            model: &self.current,
            site: self.site,
        };
        fit::interval(&subject, effect, (bound, *best), &training)
    }

    /// How many chances were named.
    fn chances_named(&self) -> usize {
        let chance = |name: &str| {
            (self.catalogue.for_evidence(Evidence::Poses))
                .any(|e| e.stochastic() && e.name() == name)
        };
        self.named.iter().filter(|(name, _)| chance(name)).count()
    }

    /// Whether a chance was named.
    fn chance_named(&self) -> bool {
        self.chances_named() > 0
    }

    /// The diagnosis the search reached.
    fn diagnosis(self) -> MotionDiagnosis {
        let extended = match (self.chance_named(), &self.deterministic) {
            (false, Some(deterministic)) => deterministic.clone(),
            _ => self.current.clone(),
        };
        let total_gain = match (&self.first_scores, &self.last_scores) {
            (Some(first), Some(last)) => Some(Paired::of(first, last)),
            _ => None,
        };
        let same_as: Vec<(&str, &[&str])> = (self.rounds.iter())
            .filter_map(|r| Some((r.named?, r.same_as.as_slice())))
            .filter(|(_, same)| !same.is_empty())
            .collect();
        let intervals: Vec<Option<[f64; 2]>> = (self.named.iter())
            .map(|(name, _)| {
                let round = self.rounds.iter().find(|r| r.named == Some(name.as_str()));
                let candidate = round.and_then(|r| r.candidates.iter().find(|c| c.name == name));
                candidate.and_then(|c| c.interval)
            })
            .collect();
        let answer = answer(
            (&self.named, &intervals),
            &self.ambiguous,
            &same_as,
            total_gain.as_ref(),
        );
        MotionDiagnosis {
            training_tosses: self.training.runs.len(),
            held_out_tosses: self.held_out.runs.len(),
            rounds: self.rounds,
            named: self.named,
            ambiguous: self.ambiguous,
            total_gain,
            answer,
            extended,
            chance_seconds: (self.chance_started).map_or(0.0, |t| t.elapsed().as_secs_f64()),
        }
    }
}

impl rounds::Judge for Search<'_> {
    type Error = MotionDiagnoseError;

    /// Every open candidate fitted and judged against the current model.
    fn trials(&mut self, round: usize) -> Result<Option<Trials>, MotionDiagnoseError> {
        let site = self.site;
        let open: Vec<&'static dyn Effect> = (self.catalogue.for_evidence(Evidence::Poses))
            .filter(|e| e.stochastic() == self.chance)
            .filter(|e| !self.named.iter().any(|(n, _)| n == e.name()))
            .filter(|e| e.applies(&self.current, site))
            .filter(|e| self.base == MotionBase::Given || !e.within_base_fit(&self.current, site))
            .collect();
        // At most MAX_CHANCES: the spreads the held-out tosses choose, one per round
        // (the others one cannot be told from are reported beside it).
        let chances_spent = self.chance && self.chances_named() >= MAX_CHANCES;
        if open.is_empty() || chances_spent {
            return Ok(None);
        }
        let subject = Subject {
            model: &self.current,
            site,
        };
        let (mut training_part, held_part) = (
            Part::new(&self.current, &self.training, fit::FIT_MEMBERS)?,
            Part::new(&self.current, &self.held_out, fit::JUDGE_MEMBERS)?,
        );
        let base_held = subject
            .base_scores(&held_part)
            .ok_or(MotionDiagnoseError::Replay { part: "held-out" })?;
        training_part.base = subject.base_scores(&training_part);
        let base_training = fit::mean_or_infinity(training_part.base.as_deref());
        if !base_training.is_finite() {
            return Err(MotionDiagnoseError::Replay { part: "training" });
        }
        let floor = MIN_GAIN * mean(self.first_scores.get_or_insert_with(|| base_held.clone()));
        let stage = Stage {
            subject,
            training: training_part,
            held_out: held_part,
            scales: self.scales,
        };
        let (results, held_scores) = fit_candidates(&stage, &open, round, self.progress);
        let scores = held_scores.iter().map(|h| h.2.clone()).collect();
        self.this = Some(Round {
            training: base_training,
            held_out: mean(&base_held),
            candidates: results,
            named: None,
            ambiguous: Vec::new(),
            same_as: Vec::new(),
        });
        self.held_scores = held_scores;
        Ok(Some(Trials {
            reference: base_held,
            floor,
            scores,
        }))
    }

    /// The best fitted on top of the rival; none in the chance phase, where every rival
    /// is a chance and chances the held-out tosses cannot tell apart are one forecast
    /// ([`rounds::Judge::one_model`]) whatever the pair would add: the best is named
    /// either way, and the pair's fit (two grids, the rival refitted on top of the best)
    /// was a third of the real cube tosses' chance phase.
    fn both(&self, best: usize, rival: usize) -> Option<Vec<f64>> {
        if self.chance {
            return None;
        }
        self.stacked(&self.held_scores[rival], self.held_scores[best].0)
    }

    /// Chances tied with the best are one forecast: spreads from run to run the
    /// held-out tosses cannot tell apart. The best (the first of `tied`) is named, the
    /// others reported beside it; a tie with any deterministic effect stays ambiguous.
    fn one_model(&self, tied: &[usize]) -> Option<(usize, Vec<&'static str>)> {
        let chance = |&i: &usize| self.held_scores.get(i).is_some_and(|h| h.0.stochastic());
        if !self.chance || !tied.iter().all(chance) {
            return None;
        }
        let (&best, others) = tied.split_first()?;
        Some((
            best,
            others
                .iter()
                .map(|&i| self.held_scores[i].0.name())
                .collect(),
        ))
    }

    fn record(&mut self, decision: &Decision, outcome: &Outcome) {
        let Some(mut this) = self.this.take() else {
            return;
        };
        let scored = decision.gains.iter().zip(&decision.helps);
        for (r, (gain, helps)) in this.candidates.iter_mut().zip(scored) {
            (r.gain, r.helps) = (*gain, *helps);
        }
        match outcome {
            Outcome::Named(index, same_as) => {
                this.same_as.clone_from(same_as);
                let held_scores = std::mem::take(&mut self.held_scores);
                return self.name(this, held_scores, *index);
            }
            Outcome::Ambiguous(tied) => {
                this.ambiguous = tied.iter().map(|&i| this.candidates[i].name).collect();
            }
            Outcome::Nothing => {}
        }
        self.ambiguous.extend(&this.ambiguous);
        self.rounds.push(this);
    }

    /// Chance after the deterministic effects, once: from here on the model forecasts
    /// from start states drawn with their fits' covariance and what the tracker records
    /// of each member (`variation.start_state` and `tracker` 1 where they were 0), as
    /// any forecast of filmed frames from a filmed start must — not causes, the
    /// reference every spread is judged against.
    /// Not after an ambiguous round: a deterministic cause is there, only not which,
    /// and a spread would take up its misfit.
    fn next_phase(&mut self) -> bool {
        let chances = (self.catalogue.for_evidence(Evidence::Poses)).any(|e| e.stochastic());
        if !chances || !self.ambiguous.is_empty() || std::mem::replace(&mut self.chance, true) {
            return false;
        }
        self.deterministic = Some(self.current.clone());
        self.chance_started = Some(std::time::Instant::now());
        let variation = &mut self.current.scenario.variation;
        if variation.start_state == 0.0 {
            variation.start_state = 1.0;
        }
        if variation.tracker == 0.0 {
            variation.tracker = 1.0;
        }
        true
    }
}

/// What the user's model is to the diagnosis.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum MotionBase {
    /// As the user wrote it: every candidate is a possible cause.
    #[default]
    Given,
    /// Fitted from these poses ([`crate::identify::identify_motion`], a physics file with a fit
    /// record): its own parameters are first polished on the training tosses (a
    /// Nelder–Mead of [`BASE_POLISH`] replays, kept where it trains better), and the
    /// candidates that fit frees ([`Effect::within_base_fit`]) are left out —
    /// their gain would be a better optimum of the base, not a missing effect.
    Fitted,
}

/// Replays of the training tosses the polish of a fitted base may spend (–).
pub const BASE_POLISH: usize = 40;

/// Diagnoses `model` against `data` (poses of one body tossed onto or sliding on fixed bodies),
/// reporting [`ProgressStage::Diagnose`] to `progress`: its steps are each round's
/// candidates, advanced before each candidate's fit, its status the round.
pub fn diagnose_motion(
    model: &Model,
    data: &Dataset,
    progress: &dyn Progress,
) -> Result<MotionDiagnosis, MotionDiagnoseError> {
    diagnose_motion_with(
        model,
        data,
        (MotionBase::Given, &Catalogue::default()),
        progress,
    )
}

/// [`diagnose_motion`] of a base that is `base` (given, or fitted from these poses),
/// trying the effects of `catalogue` judged from poses.
pub fn diagnose_motion_with(
    model: &Model,
    data: &Dataset,
    base: (MotionBase, &Catalogue),
    progress: &dyn Progress,
) -> Result<MotionDiagnosis, MotionDiagnoseError> {
    let (training, held_out) = split_tosses(data);
    in_stage(progress, ProgressStage::Diagnose, 0, || {
        search(model, training, held_out, base, progress)
    })
}

/// [`diagnose_motion`] on tosses already split into a `training` part (the candidates
/// are fitted on it) and a `held_out` one (their gain is judged on it).
pub fn diagnose_motion_split(
    model: &Model,
    training: Dataset,
    held_out: Dataset,
    catalogue: &Catalogue,
    progress: &dyn Progress,
) -> Result<MotionDiagnosis, MotionDiagnoseError> {
    in_stage(progress, ProgressStage::Diagnose, 0, || {
        search(
            model,
            training,
            held_out,
            (MotionBase::Given, catalogue),
            progress,
        )
    })
}

/// The rounds of [`diagnose_motion_split`].
fn search(
    model: &Model,
    training: Dataset,
    held_out: Dataset,
    (base, catalogue): (MotionBase, &Catalogue),
    progress: &dyn Progress,
) -> Result<MotionDiagnosis, MotionDiagnoseError> {
    let setup = TossSetup::new(model)?;
    let indices = MotionParameters::new(model, &setup)?;
    let found = held_out.runs.len().min(training.runs.len());
    if found < MIN_HELD_OUT {
        return Err(MotionDiagnoseError::TooFewTosses { found });
    }
    let current = match base {
        MotionBase::Given => model.clone(),
        MotionBase::Fitted => polished_base(model, &indices, &training)?,
    };
    let (rest_tilt, rest_height) = rest::rest_spreads(model, &setup, &training);
    let mut search = Search {
        base,
        current,
        training,
        held_out,
        site: Site {
            contact: indices.contact,
            partner: indices.partner,
        },
        scales: Scales {
            rest_tilt,
            rest_height,
            joint: model.joints.first().map(|j| j.scales(model)),
            ..Scales::of_body(model.bodies[setup.body].mass, setup.width / 2.0)
        },
        catalogue: catalogue.clone(),
        rounds: Vec::new(),
        named: Vec::new(),
        ambiguous: Vec::new(),
        first_scores: None,
        last_scores: None,
        progress,
        chance: false,
        deterministic: None,
        chance_started: None,
        this: None,
        held_scores: Vec::new(),
    };
    rounds::search(&mut search, Margins::TOSSES, MAX_ROUNDS)?;
    Ok(search.diagnosis())
}

/// A candidate's result from its fit and held-out scores (its gain and whether it
/// helps filled in by [`decided`]).
fn judge(
    effect: &dyn Effect,
    bounds: &[crate::numerics::optimize::Bound],
    fitted: &Fitted,
    held: Option<&[f64]>,
) -> CandidateResult {
    let parameters = (bounds.iter().zip(&fitted.values))
        .map(|(b, v)| (b.name.clone(), *v))
        .collect();
    CandidateResult {
        name: effect.name(),
        family: effect.family().name(),
        parameters,
        training: fitted.fitness,
        held_out: held.map_or(f64::INFINITY, mean),
        gain: Paired::of(&[], &[]),
        interval: fitted.interval,
        helps: false,
        evaluations: fitted.evaluations,
    }
}

/// A cause named, with its parameters (name, value).
type NamedCause = (String, Vec<(String, f64)>);

/// The answer in one sentence.
fn answer(
    (named, intervals): (&[NamedCause], &[Option<[f64; 2]>]),
    ambiguous: &[&'static str],
    same_as: &[(&str, &[&str])],
    total: Option<&Paired>,
) -> String {
    let mut parts = Vec::new();
    for ((name, parameters), interval) in named.iter().zip(intervals) {
        let mut values: Vec<String> = parameters
            .iter()
            .map(|(p, v)| format!("{p} = {v:.4e}"))
            .collect();
        if let Some([lo, hi]) = interval {
            values.push(format!("95 % {lo:.4e} to {hi:.4e}"));
        }
        let alike = (same_as.iter().find(|(n, _)| n == name)).map_or(String::new(), |(_, same)| {
            format!(
                "; a spread the held-out tosses do not tell from {}",
                same.join(" or ")
            )
        });
        parts.push(format!("{name} ({}{alike})", values.join(", ")));
    }
    let mut text = if parts.is_empty() {
        "none named".to_owned()
    } else {
        format!("named: {}", parts.join("; "))
    };
    if let Some(total) = total {
        text.push_str(&format!(
            "; held-out gain {:.3} (95 % {:.3} to {:.3}) % + ° per toss",
            total.mean, total.interval[0], total.interval[1]
        ));
    }
    if !ambiguous.is_empty() {
        text.push_str(&format!(
            "; then ambiguous ({}): the first helps, the others help or gain as much on \
             average, none clearly more, so none is named",
            ambiguous.join(" or ")
        ));
    } else if parts.is_empty() {
        text.push_str(": no candidate improves the held-out prediction significantly");
    }
    text
}

/// A fitted base polished over its own parameters on the `training` tosses: the better
/// of it and the polish's best.
fn polished_base(
    model: &Model,
    parameters: &MotionParameters,
    training: &Dataset,
) -> Result<Model, MotionDiagnoseError> {
    use crate::numerics::optimize::{nelder_mead, Parameters};
    let target = crate::identify::MotionTarget::new(model, training)?;
    let score =
        |genes: &[f64]| crate::identify::motion_fitness(&target, &parameters.apply(model, genes));
    let start = parameters.values(model);
    let start_fitness = score(&start);
    if !start_fitness.is_finite() {
        return Err(MotionDiagnoseError::Replay { part: "training" });
    }
    let bounds = parameters.bounds();
    let polished = nelder_mead::polish(
        &bounds,
        &start,
        start_fitness,
        BASE_POLISH,
        score,
        |_, _| {},
    );
    Ok(if polished.fitness < start_fitness {
        parameters.apply(model, &polished.best)
    } else {
        model.clone()
    })
}
