//! One candidate fitted on the training tosses, the user's model otherwise fixed. One
//! parameter: a coarse grid over its box (the replay's score is rough: a bounce moved by
//! one frame jumps it, so a local method alone may stop in a dent), then Brent's method
//! in the best grid point's bracket — the identification's scalar search. Two
//! parameters: the Nelder–Mead polish of the identification from motion, from the
//! neutral values.

use super::super::{apply_at, Effect, Site};
use crate::dataset::Dataset;
use crate::identify::MotionTarget;
use crate::numerics::optimize::minimize_scalar;
use crate::numerics::optimize::nelder_mead::polish;
use crate::numerics::optimize::Bound;
use crate::replay::TossError;
use crate::replay::{forecast_toss_paths, simulate_toss, PreparedToss, Spread};
use crate::scenario::Model;
use nalgebra::Vector3;
use rayon::prelude::*;

/// Grid points of a one-parameter candidate's box (–).
const GRID: usize = 9;
/// Tolerance of the scalar search on the box's fraction (–): a friction coefficient
/// off by 0.3 % moves a 0.3 m slide's end by 1 mm, about 1 % of the score, so the fit
/// has to be that fine — 1e-6 of a box spanning 25× is 3e-6 relative.
const FRACTION_TOLERANCE: f64 = 1e-6;
/// Polish evaluations of a two-parameter candidate (–).
const POLISH_2D: usize = 40;

/// Where a candidate is evaluated: the user's model, the contact and the fixed
/// partner (a table, a ramp…) it changes, and the data.
#[derive(Clone, Copy, Debug)]
pub struct Subject<'a> {
    /// The model the candidates change.
    pub(crate) model: &'a Model,
    /// The body's contact with the partner, and the partner's body.
    pub(crate) site: Site,
}

/// One part of the tosses (training or held out) as every candidate of a round reads
/// it: the data, and their windows, initial states and frame grids prepared once from
/// the round's model — never from a candidate, so a tilted table or another inertia is
/// judged on the same frames from the same starts as the model it changes.
pub struct Part<'a> {
    /// The tosses.
    pub(crate) data: &'a Dataset,
    /// Prepared from the round's model.
    pub(crate) target: MotionTarget<'a>,
    /// Members of the ensemble a model that varies is scored by here (–).
    pub(crate) members: usize,
    /// Every toss's score under the round's own model, once computed
    /// ([`Subject::base_scores`]): a chance's grid value that leaves the model as it is
    /// (its neutral) reads them instead of replaying the tosses again.
    pub(crate) base: Option<Vec<f64>>,
}

impl<'a> Part<'a> {
    /// `data` prepared for `model`, a model that varies scored by ensembles of
    /// `members`.
    pub fn new(model: &Model, data: &'a Dataset, members: usize) -> Result<Part<'a>, TossError> {
        Ok(Part {
            data,
            target: MotionTarget::new(model, data)?,
            members,
            base: None,
        })
    }
}

impl Subject<'_> {
    /// Every toss's score of `part` under the subject's own model (`None` if a replay
    /// fails).
    pub fn base_scores(&self, part: &Part<'_>) -> Option<Vec<f64>> {
        scores_of(&part.target, self.model, part.members)
    }

    /// Every toss's score of `part` under `effect` with `values` (`None` if the data
    /// cannot be read so, or a replay fails): see `toss_score`. A candidate that
    /// reads the data otherwise (a length scale) has them prepared afresh, from the
    /// subject's model.
    pub fn scores(&self, effect: &dyn Effect, values: &[f64], part: &Part<'_>) -> Option<Vec<f64>> {
        let mut model = self.model.clone();
        apply_at(effect, &mut model, self.site, values);
        match effect.read(part.data, values) {
            Some(read) => {
                let target = MotionTarget::new(self.model, &read).ok()?;
                scores_of(&target, &model, part.members)
            }
            None => scores_of(&part.target, &model, part.members),
        }
    }

    /// Mean score over `part`'s tosses, +∞ if any replay fails.
    pub fn fitness(&self, effect: &dyn Effect, values: &[f64], part: &Part<'_>) -> f64 {
        mean_or_infinity(self.scores(effect, values, part).as_deref())
    }
}

/// The mean of `scores`, +∞ if there are none, a replay failed or it is not finite.
pub fn mean_or_infinity(scores: Option<&[f64]>) -> f64 {
    match scores {
        Some(scores) if !scores.is_empty() => {
            let mean = scores.iter().sum::<f64>() / scores.len() as f64;
            if mean.is_finite() {
                mean
            } else {
                f64::INFINITY
            }
        }
        _ => f64::INFINITY,
    }
}

/// Every toss's score of `target` under `model`, in parallel (`None` if a replay fails):
/// a model that varies ([`Model::varies`]) by its ensemble of `members` ([`chance_score`]),
/// any other by its replay ([`toss_score`]).
fn scores_of(target: &MotionTarget<'_>, model: &Model, members: usize) -> Option<Vec<f64>> {
    let weight = model.bodies[target.setup.body].mass * target.setup.gravity.norm();
    let varies = model.varies();
    let scores: Vec<Option<f64>> = (target.tosses.par_iter().enumerate())
        .map(|(index, toss)| match varies {
            true => chance_score(target, toss, model, (members, index as u64)),
            false => toss_score(target, toss, model, weight),
        })
        .collect();
    scores.into_iter().collect()
}

/// Members of the ensembles a model that varies is fitted by on the training tosses
/// (–): the fair score is unbiased whatever their number, and the same draws at every
/// grid value keep the differences between values smooth, so few suffice for the
/// search. Four, not eight: the chance phase of `hcm reproduce cube-toss` is mostly
/// these replays (docs/real-data.md, "What chance costs").
pub const FIT_MEMBERS: usize = 4;
/// Members of the ensembles it is judged by on the held-out tosses (–).
pub const JUDGE_MEMBERS: usize = 12;
/// Seed of their draws: toss k draws from stream k, so every candidate and every value
/// of one sees the same random numbers (a smooth score to search, a paired comparison).
const CHANCE_SEED: u64 = 0x5eed;

/// One toss's score under a `model` that varies: the fair energy score of its ensemble's
/// centres (% of the width) plus orientations (°) ([`crate::replay::PathForecast::fair_score`]),
/// `members` members from stream `stream` — with one member, the replay's
/// position plus rotation error, so a deterministic model and a spread compare on one
/// scale. A force channel is not scored here.
fn chance_score(
    target: &MotionTarget<'_>,
    toss: &PreparedToss<'_>,
    model: &Model,
    (members, stream): (usize, u64),
) -> Option<f64> {
    let spread = Spread::of_model(members, CHANCE_SEED);
    let paths = forecast_toss_paths(model, &target.setup, toss, &spread, stream)?;
    Some(paths.fair_score())
}

/// One toss's score under `model`: its mean position error (% of the width) plus mean
/// rotation error (°), as `hcm predict` scores it, plus — where the data have a force
/// channel — the mean force error over the frames that hold one, |F_pred − F| in % of
/// the body's weight `weight` (N): motion and force judged together.
fn toss_score(
    target: &MotionTarget<'_>,
    toss: &PreparedToss<'_>,
    model: &Model,
    weight: f64,
) -> Option<f64> {
    let prediction = simulate_toss(model, &target.setup, toss).ok()?;
    let measured = toss.primary().measured();
    let score = toss.score(&target.setup, &prediction).ok()?;
    let (mut force, mut frames) = (0.0, 0);
    for (recorded, predicted) in measured.iter().zip(&prediction.samples) {
        let f = Vector3::from(recorded.force);
        if f.iter().all(|x| x.is_finite()) {
            force += (Vector3::from(predicted.force) - f).norm();
            frames += 1;
        }
    }
    let force_error = if frames > 0 {
        100.0 * force / frames as f64 / weight
    } else {
        0.0
    };
    Some(score.position_error + score.rotation_error + force_error)
}

/// A candidate's fit.
#[derive(Clone, Debug, PartialEq)]
pub struct Fitted {
    /// Its parameters (the bounds' units).
    pub(crate) values: Vec<f64>,
    /// Their training fitness (% + °).
    pub(crate) fitness: f64,
    /// Fitness evaluations (each a replay of every training toss).
    pub(crate) evaluations: usize,
    /// For chance, the lowest and highest values whose training scores are not worse
    /// than the best's at 95 % (paired over the tosses): the interval the data leave for
    /// the spread (on the grid: its step limits it).
    pub(crate) interval: Option<[f64; 2]>,
}

/// Fits `effect` to `training` in `bounds`, starting from `neutral`: one parameter by
/// `line_search`, two by the
/// polish from `neutral`. The neutral values win ties (no change unless it helps).
pub fn fit(
    subject: &Subject<'_>,
    effect: &dyn Effect,
    bounds: &[Bound],
    neutral: &[f64],
    training: &Part<'_>,
) -> Fitted {
    if let (true, [bound], [neutral]) = (effect.stochastic(), bounds, neutral) {
        return grid_fit(subject, effect, (bound, *neutral), training);
    }
    let score = |values: &[f64]| subject.fitness(effect, values, training);
    let start = score(neutral);
    let (values, fitness, evaluations) = match bounds {
        [bound] => line_search(bound, |x| score(&[x])),
        _ => {
            let p = polish(bounds, neutral, start, POLISH_2D, score, |_, _| {});
            (p.best, p.fitness, p.evaluations)
        }
    };
    if fitness < start {
        Fitted {
            values,
            fitness,
            evaluations: evaluations + 1,
            interval: None,
        }
    } else {
        Fitted {
            values: neutral.to_vec(),
            fitness: start,
            evaluations: evaluations + 1,
            interval: None,
        }
    }
}

/// Grid points of a chance candidate's box, its ends included (–): the fractions
/// k/(CHANCE_GRID − 1) of it.
const CHANCE_GRID: usize = 9;
/// Every how many grid points the coarse pass evaluates (–): 0, ¼, ½, ¾ and 1 of the box.
const COARSE_STEP: usize = 2;

/// A chance candidate fitted by its ensemble's training score on the grid of
/// [`CHANCE_GRID`] evenly spaced values of `bound`: the score of a few members is rough,
/// so a grid, not a local search, and the same draws at every value (common random
/// numbers). Coarse to fine: every [`COARSE_STEP`]th value first, then the two beside
/// the best of those — the full grid's resolution where the minimum is, with 7 of its 9
/// values replayed (6 where the `neutral` value, the box's first, reads the part's base
/// scores). The best value (the lowest on a tie) and the interval of the evaluated
/// values whose paired difference from it, toss by toss, has a 95 % interval
/// (Student's t) reaching 0.
fn grid_fit(
    subject: &Subject<'_>,
    effect: &dyn Effect,
    (bound, neutral): (&Bound, f64),
    training: &Part<'_>,
) -> Fitted {
    let value = |k: usize| bound.value_at(k as f64 / (CHANCE_GRID - 1) as f64);
    let mut scores: Vec<Option<Option<Vec<f64>>>> = vec![None; CHANCE_GRID];
    let mut evaluations = 0;
    let mut evaluate = |ks: &[usize], scores: &mut Vec<Option<Option<Vec<f64>>>>| {
        for &k in ks {
            if k >= CHANCE_GRID || scores[k].is_some() {
                continue;
            }
            scores[k] = Some(match (&training.base, value(k) == neutral) {
                (Some(base), true) => Some(base.clone()),
                _ => {
                    evaluations += 1;
                    subject.scores(effect, &[value(k)], training)
                }
            });
        }
    };
    let coarse: Vec<usize> = (0..CHANCE_GRID).step_by(COARSE_STEP).collect();
    evaluate(&coarse, &mut scores);
    let means = |scores: &[Option<Option<Vec<f64>>>]| -> Vec<f64> {
        (scores.iter())
            .map(|s| {
                s.as_ref()
                    .map_or(f64::INFINITY, |s| mean_or_infinity(s.as_deref()))
            })
            .collect()
    };
    let lowest = |means: &[f64]| {
        (0..CHANCE_GRID)
            .min_by(|&a, &b| means[a].total_cmp(&means[b]))
            .unwrap_or(0)
    };
    let best = lowest(&means(&scores));
    evaluate(&[best.saturating_sub(1), best + 1], &mut scores);
    let means = means(&scores);
    let best = lowest(&means);
    let within = |k: usize| match (&scores[k], &scores[best]) {
        (Some(Some(s)), Some(Some(b))) if k != best => super::Paired::of(s, b).interval[0] <= 0.0,
        (Some(Some(_)), Some(Some(_))) => true,
        _ => false,
    };
    let inside: Vec<f64> = (0..CHANCE_GRID).filter(|&k| within(k)).map(value).collect();
    let interval = match (inside.first(), inside.last()) {
        (Some(&lo), Some(&hi)) => Some([lo, hi]),
        _ => None,
    };
    Fitted {
        values: vec![value(best)],
        fitness: means[best],
        evaluations,
        interval,
    }
}

/// Minimises `score` over `bound` on the fraction of its box (log(value) on a log
/// scale): the identification's scalar search, a grid of [`GRID`] points then Brent's
/// method between the best one's neighbours, to [`FRACTION_TOLERANCE`]. Returns the
/// value, its score and the evaluations made.
fn line_search(bound: &Bound, score: impl Fn(f64) -> f64) -> (Vec<f64>, f64, usize) {
    let mut evaluations = 0;
    let (at, fitness) = minimize_scalar(
        |u| {
            evaluations += 1;
            score(bound.value_at(u))
        },
        0.0,
        1.0,
        GRID,
        FRACTION_TOLERANCE,
    );
    (vec![bound.value_at(at)], fitness, evaluations)
}

/// Bisections of each side of a named cause's interval (–): its ends to 1/32 of the
/// stretch between the fitted value and the box's end.
const INTERVAL_STEPS: usize = 5;

/// The values of a one-parameter deterministic `effect` the training tosses do not
/// tell from the fitted `best` (its paired difference from `best`'s scores, toss by
/// toss, has a 95 % interval reaching 0, as [`grid_fit`] bounds a chance), bracketed:
/// on each side the box's end where that is not worse, else the nearest value of
/// [`INTERVAL_STEPS`] bisections of the fraction between `best` and the end that is —
/// the boundary lies between it and the last value that is not, so the interval holds
/// every value the tosses do not exclude (a step of 1/32 of the side wider at most).
/// None where a replay fails. 2 + 2·[`INTERVAL_STEPS`] replays of the training tosses
/// at most.
pub fn interval(
    subject: &Subject<'_>,
    effect: &dyn Effect,
    (bound, best): (&Bound, f64),
    training: &Part<'_>,
) -> Option<[f64; 2]> {
    let scores = |u: f64| subject.scores(effect, &[bound.value_at(u)], training);
    let at_best = scores(bound.fraction_of(best))?;
    let alike =
        |u: f64| scores(u).is_some_and(|s| super::Paired::of(&s, &at_best).interval[0] <= 0.0);
    let side = |end: f64| {
        let mut inside = bound.fraction_of(best);
        if alike(end) {
            return end;
        }
        let mut outside = end;
        for _ in 0..INTERVAL_STEPS {
            let middle = 0.5 * (inside + outside);
            if alike(middle) {
                inside = middle;
            } else {
                outside = middle;
            }
        }
        outside
    };
    Some([bound.value_at(side(0.0)), bound.value_at(side(1.0))])
}
