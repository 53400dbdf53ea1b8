//! Chance in a force diagnosis (`Family::Chance`): what the deterministic law cannot
//! carry — its parameters scattering from run to run (Eq 18's `noise`: a ball that
//! lands on another spot of the plate, a batch of parts not quite alike), or a sensor
//! noisier than its noise floor says.
//!
//! The deterministic phase done, the model forecasts each run's force as an ensemble:
//! each member's law with its parameters drawn (`scenario::Draw::Member`, the same draw
//! a forecast member of any command makes), its force read by the fitted sensor along
//! the run's recorded motion, and the sensor's noise σ (N per sample) added. A run's
//! **score** is the fair CRPS of the three indicators the members give — the peak
//! force, the impulse ∫f dt and the energy the contact takes, ∫f·δ̇ dt — each in % of
//! its mean over the training runs, averaged over the three (%). With no spread the
//! ensemble is the deterministic model plus the sensor's noise: the reference every
//! chance is judged against, on the same scale.
//!
//! Candidates: each free parameter of the base law (those `hcm identify` fits)
//! scattering by a relative σ ∈ [0, [`SIGMA_MAX`]] (`<parameter>_scatter`), and the
//! sensor's noise × k ∈ [0, [`NOISE_MAX`]] (`sensor_noise`, neutral k = 1). Each is
//! fitted on the training runs over a grid (the score's minimum; its interval the grid
//! values whose training scores the best's does not beat at 95 %, paired), scored on
//! the held-out runs and judged by the one rule ([`super::verdict`]): 3 standard errors
//! of the paired gain, beating every rival by 2 unless it adds beyond it (the rival
//! refitted with it in place). One is named per round, on top of those named before,
//! up to [`MAX_CHANCES`]; chances the held-out runs cannot tell apart are one forecast
//! (the best named, the others beside it).

use super::paired::{t_975, Paired};
use super::rounds::{search, Judge, Outcome, Trials};
use super::sensor::Sensor;
use super::verdict::{Decision, Margins};
use super::ContactSamples;
use crate::numerics::scores::{central_band, fair_crps};
use crate::scenario::{draw_parameter, Draw};
use hcm_core::effect::ExtendedLaw;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use rayon::prelude::*;
use serde::Serialize;

/// Largest relative scatter σ of a parameter tried (–).
pub const SIGMA_MAX: f64 = 0.5;
/// Smallest nonzero σ on the grid (–): below it a scatter is no cause anyone measures.
const SIGMA_MIN: f64 = 0.002;
/// Largest factor on the sensor's noise σ tried (–).
pub const NOISE_MAX: f64 = 4.0;
/// Grid points of a candidate's search (–): 0 and 40 more (σ geometric from
/// [`SIGMA_MIN`] to [`SIGMA_MAX`], 15 % apart; k linear, 0.1 apart).
const GRID: usize = 41;
/// Members of the ensembles a spread is fitted by on the training runs (–).
const FIT_MEMBERS: usize = 16;
/// Members of the ensembles it is judged by on the held-out runs (–): ≥ 19, so the
/// type-6 bands of the coverage are calibrated.
pub const JUDGE_MEMBERS: usize = 32;
/// Most chances named together.
pub const MAX_CHANCES: usize = 3;
/// Seed of the members' draws: run r draws from stream r, whatever the candidate.
const SEED: u64 = 0x5ca7;
/// The least held-out gain that counts, as a share of the reference's score (–): a
/// significant gain of less than 1 % of the forecast's error is no cause.
const FLOOR_SHARE: f64 = 0.01;
/// The rule's margins: each candidate is fitted on the training runs alone and all are
/// compared on held-out runs only, as a motion diagnosis' candidates are.
const MARGINS: Margins = Margins::TOSSES;

/// One candidate spread.
#[derive(Clone, Debug, PartialEq)]
enum Candidate {
    /// A base-law parameter's relative scatter.
    Scatter(String),
    /// A factor on the sensor's noise σ.
    SensorNoise,
}

impl Candidate {
    fn name(&self) -> String {
        match self {
            Candidate::Scatter(p) => format!("{p}_scatter"),
            Candidate::SensorNoise => "sensor_noise".to_owned(),
        }
    }

    /// The name of its one parameter.
    fn parameter(&self) -> &'static str {
        match self {
            Candidate::Scatter(_) => "sigma",
            Candidate::SensorNoise => "factor",
        }
    }

    /// The grid it is fitted on.
    fn grid(&self) -> Vec<f64> {
        match self {
            Candidate::Scatter(_) => {
                let ratio = (SIGMA_MAX / SIGMA_MIN).powf(1.0 / (GRID - 2) as f64);
                let steps = (0..GRID - 1).map(|k| SIGMA_MIN * ratio.powi(k as i32));
                std::iter::once(0.0).chain(steps).collect()
            }
            Candidate::SensorNoise => (0..GRID)
                .map(|k| NOISE_MAX * k as f64 / (GRID - 1) as f64)
                .collect(),
        }
    }
}

/// What an ensemble spreads: relative σ per base-law parameter (in the order named)
/// and the factor on the sensor's noise.
#[derive(Clone, Debug, PartialEq)]
struct Spread {
    scatter: Vec<(String, f64)>,
    noise: f64,
}

impl Spread {
    /// The deterministic model with the sensor's noise.
    fn none() -> Spread {
        Spread {
            scatter: Vec::new(),
            noise: 1.0,
        }
    }

    /// This spread with `candidate` at `value` (replacing its earlier value).
    fn with(&self, candidate: &Candidate, value: f64) -> Spread {
        let mut spread = self.clone();
        match candidate {
            Candidate::Scatter(p) => match spread.scatter.iter_mut().find(|(q, _)| q == p) {
                Some(entry) => entry.1 = value,
                None => spread.scatter.push((p.clone(), value)),
            },
            Candidate::SensorNoise => spread.noise = value,
        }
        spread
    }

    /// Whether `candidate` is part of it already.
    fn holds(&self, candidate: &Candidate) -> bool {
        match candidate {
            Candidate::Scatter(p) => self.scatter.iter().any(|(q, _)| q == p),
            Candidate::SensorNoise => self.noise != 1.0,
        }
    }
}

/// One run as the forecast reads it.
struct RunCase {
    /// Its samples of the contact.
    samples: ContactSamples,
    /// The time each sample stands for in the indicators' sums (s), 0 outside contact.
    weights: Vec<f64>,
    /// Its measured indicators: peak force (N), impulse (N·s), energy taken (J).
    measured: [f64; 3],
    /// The run's index in the data set: its stream of random numbers.
    stream: u64,
}

/// The three indicators of `force` (N per sample) on `case`'s samples.
fn indicators(case: &RunCase, force: &[f64]) -> [f64; 3] {
    let s = &case.samples;
    let mut out = [f64::NEG_INFINITY, 0.0, 0.0];
    for (i, (&f, &w)) in force.iter().zip(&case.weights).enumerate() {
        if s.in_contact[i] {
            out[0] = out[0].max(f);
            out[1] += f * w;
            out[2] += f * s.rate[i] * w;
        }
    }
    if out[0] == f64::NEG_INFINITY {
        out[0] = 0.0;
    }
    out
}

/// The runs of `samples`, run r (its index among them) with the stream `streams[r]`
/// (its index in the data).
fn cases(samples: &ContactSamples, streams: &[usize]) -> Vec<RunCase> {
    (samples.run_ranges().into_iter())
        .map(|range| {
            let run = samples.run[range.start];
            let samples = samples.select(|r| r == run);
            let t = &samples.time;
            let n = t.len();
            let weights = (0..n)
                .map(|i| {
                    let (a, b) = (t[i.saturating_sub(1)], t[(i + 1).min(n - 1)]);
                    if samples.in_contact[i] {
                        0.5 * (b - a)
                    } else {
                        0.0
                    }
                })
                .collect();
            let mut case = RunCase {
                samples,
                weights,
                measured: [0.0; 3],
                stream: streams.get(run).copied().unwrap_or(run) as u64,
            };
            case.measured = indicators(&case, &case.samples.measured);
            case
        })
        .collect()
}

/// `law` with `scatter`'s parameters drawn as a forecast member draws them
/// ([`draw_parameter`]), one ζ each in order.
fn drawn_law(
    law: &ExtendedLaw<f64>,
    scatter: &[(String, f64)],
    rng: &mut ChaCha8Rng,
) -> ExtendedLaw<f64> {
    let mut drawn = law.clone();
    for (name, sigma) in scatter {
        let zeta: f64 = StandardNormal.sample(rng);
        // The candidates are the law's own parameters: no name is unknown.
        let _ = draw_parameter(&mut drawn, name, *sigma, zeta, Draw::Member);
    }
    drawn
}

/// The fixed inputs of the forecasts.
struct Forecaster<'a> {
    law: &'a ExtendedLaw<f64>,
    sensor: Sensor,
    /// The sensor's noise σ (N).
    sigma: f64,
    /// Each indicator's scale: its mean magnitude over the training runs.
    scales: [f64; 3],
}

impl Forecaster<'_> {
    /// Each indicator's `members` values for `case` under `spread`.
    fn members(&self, case: &RunCase, spread: &Spread, members: usize) -> [Vec<f64>; 3] {
        let mut rng = ChaCha8Rng::seed_from_u64(SEED);
        rng.set_stream(case.stream);
        let mut out: [Vec<f64>; 3] = Default::default();
        for _ in 0..members {
            let law = drawn_law(self.law, &spread.scatter, &mut rng);
            let mut force = self.sensor.reads(&case.samples, &law);
            let noise = spread.noise * self.sigma;
            for f in &mut force {
                let xi: f64 = StandardNormal.sample(&mut rng);
                *f += noise * xi;
            }
            for (k, value) in indicators(case, &force).into_iter().enumerate() {
                out[k].push(value);
            }
        }
        out
    }

    /// `case`'s score under `spread` (%).
    fn score(&self, case: &RunCase, spread: &Spread, members: usize) -> f64 {
        let members = self.members(case, spread, members);
        let parts = (0..3).map(|k| fair_crps(&members[k], case.measured[k]) / self.scales[k]);
        100.0 * parts.sum::<f64>() / 3.0
    }

    /// Every case's score, in parallel.
    fn scores(&self, cases: &[RunCase], spread: &Spread, members: usize) -> Vec<f64> {
        cases
            .par_iter()
            .map(|case| self.score(case, spread, members))
            .collect()
    }
}

/// One candidate as the training runs fitted it.
#[derive(Clone, Debug)]
struct Fitted {
    value: f64,
    interval: (f64, f64),
}

/// A candidate tried in one round.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ChanceTrial {
    /// `<parameter>_scatter` or `sensor_noise`.
    pub effect: String,
    /// Its fitted size: relative σ (–) or the factor on the sensor's noise (–).
    pub value: f64,
    /// The grid values the training runs leave for it (95 %, paired).
    pub interval: (f64, f64),
    /// Its held-out gain over the model as the round found it (% per run).
    pub gain: Paired,
    /// Whether it helps (rule 1).
    pub helps: bool,
}

/// One round of the chance phase.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ChanceRound {
    /// The model's held-out score as the round found it (% per run, mean).
    pub reference: f64,
    /// Every open candidate.
    pub trials: Vec<ChanceTrial>,
    /// What the round decided: the name, `ambiguous: …` or `none`.
    pub verdict: String,
}

/// A chance named.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NamedChance {
    /// `<parameter>_scatter` or `sensor_noise`.
    pub effect: String,
    /// The law parameter that scatters (None for the sensor's noise).
    pub law_parameter: Option<String>,
    /// `sigma` (relative, –) or `factor` (–).
    pub parameter: &'static str,
    /// Its fitted size.
    pub value: f64,
    /// Its interval (95 %, see the module).
    pub interval: (f64, f64),
    /// Its held-out gain (% per run).
    pub gain: Paired,
    /// Chances the held-out runs could not tell from it (one forecast).
    pub same_as: Vec<String>,
}

/// The chance phase's answer.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ForceChance {
    /// The chances named, in order.
    pub named: Vec<NamedChance>,
    /// Every round.
    pub rounds: Vec<ChanceRound>,
    /// Members of the held-out forecasts (–).
    pub members: usize,
    /// Held-out runs judged.
    pub held_out: usize,
    /// The held-out score of the deterministic model with the sensor's noise, and of
    /// the extended model with its named chances (% per run, mean).
    pub scores: (f64, f64),
    /// The extended model's gain over the deterministic one, paired per held-out run.
    pub gain: Paired,
    /// The shares of held-out indicators (3 per run) inside the extended model's 50 %
    /// and 90 % bands.
    pub coverage: [f64; 2],
    /// The same for the deterministic model with the sensor's noise.
    pub coverage_reference: [f64; 2],
}

impl ForceChance {
    /// The named chances as a contact's `noise` table (parameter, relative σ).
    pub fn noise(&self) -> Vec<(String, f64)> {
        (self.named.iter())
            .filter_map(|n| n.law_parameter.clone().map(|p| (p, n.value)))
            .collect()
    }
}

/// The search's state: the runs, the forecaster, the spread named so far.
struct ChanceJudge<'a> {
    training: Vec<RunCase>,
    held_out: Vec<RunCase>,
    forecaster: Forecaster<'a>,
    candidates: Vec<Candidate>,
    spread: Spread,
    /// The current round's open candidates, fits and held-out scores.
    open: Vec<(Candidate, Fitted, Vec<f64>)>,
    reference: f64,
    rounds: Vec<ChanceRound>,
    named: Vec<NamedChance>,
}

impl ChanceJudge<'_> {
    /// `candidate` fitted on the training runs with `spread` in place.
    fn fit(&self, candidate: &Candidate, spread: &Spread) -> Fitted {
        let grid = candidate.grid();
        let scores: Vec<Vec<f64>> = (grid.iter())
            .map(|&v| {
                (self.forecaster).scores(&self.training, &spread.with(candidate, v), FIT_MEMBERS)
            })
            .collect();
        let mean = |s: &[f64]| s.iter().sum::<f64>() / s.len().max(1) as f64;
        let best = (0..grid.len())
            .min_by(|&a, &b| mean(&scores[a]).total_cmp(&mean(&scores[b])))
            .unwrap_or(0);
        let t = t_975(self.training.len().saturating_sub(1));
        let within: Vec<f64> = (0..grid.len())
            .filter(|&j| Paired::of(&scores[j], &scores[best]).t() < t)
            .map(|j| grid[j])
            .collect();
        let lo = within.iter().copied().fold(grid[best], f64::min);
        let hi = within.iter().copied().fold(grid[best], f64::max);
        Fitted {
            value: grid[best],
            interval: (lo, hi),
        }
    }
}

impl Judge for ChanceJudge<'_> {
    type Error = std::convert::Infallible;

    fn trials(&mut self, _round: usize) -> Result<Option<Trials>, Self::Error> {
        let open: Vec<Candidate> = (self.candidates.iter())
            .filter(|c| !self.spread.holds(c))
            .cloned()
            .collect();
        if open.is_empty() || self.named.len() >= MAX_CHANCES {
            return Ok(None);
        }
        let reference = (self.forecaster).scores(&self.held_out, &self.spread, JUDGE_MEMBERS);
        self.open = open
            .into_iter()
            .map(|c| {
                let fitted = self.fit(&c, &self.spread);
                let spread = self.spread.with(&c, fitted.value);
                let held = (self.forecaster).scores(&self.held_out, &spread, JUDGE_MEMBERS);
                (c, fitted, held)
            })
            .collect();
        let mean = reference.iter().sum::<f64>() / reference.len().max(1) as f64;
        self.reference = mean;
        Ok(Some(Trials {
            floor: FLOOR_SHARE * mean,
            scores: self.open.iter().map(|(_, _, h)| Some(h.clone())).collect(),
            reference,
        }))
    }

    fn both(&self, best: usize, rival: usize) -> Option<Vec<f64>> {
        let (b, fitted, _) = &self.open[best];
        let with_best = self.spread.with(b, fitted.value);
        let r = &self.open[rival].0;
        let refit = self.fit(r, &with_best);
        let spread = with_best.with(r, refit.value);
        Some(
            self.forecaster
                .scores(&self.held_out, &spread, JUDGE_MEMBERS),
        )
    }

    fn one_model(&self, tied: &[usize]) -> Option<(usize, Vec<&'static str>)> {
        // The names are owned here: they are returned through `record`'s outcome by
        // index, so the tied ones' names are read from `open` there.
        let best = *tied.first()?;
        Some((best, Vec::new()))
    }

    fn record(&mut self, decision: &Decision, outcome: &Outcome) {
        let trials = (self.open.iter().zip(&decision.gains).zip(&decision.helps))
            .map(|(((c, f, _), gain), &helps)| ChanceTrial {
                effect: c.name(),
                value: f.value,
                interval: f.interval,
                gain: *gain,
                helps,
            })
            .collect();
        let verdict = match outcome {
            Outcome::Named(i, _) => {
                let (c, f, _) = &self.open[*i];
                let same_as = match &decision.verdict {
                    super::verdict::Verdict::Ambiguous(tied) => (tied.iter())
                        .filter(|&&j| j != *i)
                        .map(|&j| self.open[j].0.name())
                        .collect(),
                    _ => Vec::new(),
                };
                self.named.push(NamedChance {
                    effect: c.name(),
                    law_parameter: match c {
                        Candidate::Scatter(p) => Some(p.clone()),
                        Candidate::SensorNoise => None,
                    },
                    parameter: c.parameter(),
                    value: f.value,
                    interval: f.interval,
                    gain: decision.gains[*i],
                    same_as,
                });
                self.spread = self.spread.with(c, f.value);
                c.name()
            }
            Outcome::Ambiguous(tied) => {
                let names: Vec<String> = tied.iter().map(|&j| self.open[j].0.name()).collect();
                format!("ambiguous: {}", names.join(", "))
            }
            Outcome::Nothing => "none".to_owned(),
        };
        self.rounds.push(ChanceRound {
            reference: self.reference,
            trials,
            verdict,
        });
    }
}

/// The chance phase on the training and held-out samples of a force diagnosis: the
/// law and sensor the deterministic phase left (`law`, `sensor`), the sensor's noise σ
/// (N), the free parameters of the base law (`parameters`), and the held-out runs'
/// indices in the data (their streams).
pub(super) fn force_chance(
    (training, held_out): (&ContactSamples, &ContactSamples),
    (law, sensor): (&ExtendedLaw<f64>, Sensor),
    sigma: f64,
    parameters: &[String],
    (training_runs, held_out_runs): (&[usize], &[usize]),
) -> ForceChance {
    let training = cases(training, training_runs);
    let held_out = cases(held_out, held_out_runs);
    let scales = [0, 1, 2].map(|k| {
        let s = (training.iter()).map(|c| c.measured[k].abs()).sum::<f64>() / training.len() as f64;
        if s > 0.0 && s.is_finite() {
            s
        } else {
            1.0
        }
    });
    let candidates = (parameters.iter())
        .filter(|p| law.base.get(p).is_ok_and(|v| v != 0.0))
        .map(|p| Candidate::Scatter(p.clone()))
        .chain(std::iter::once(Candidate::SensorNoise))
        .collect();
    let mut judge = ChanceJudge {
        training,
        held_out,
        forecaster: Forecaster {
            law,
            sensor,
            sigma,
            scales,
        },
        candidates,
        spread: Spread::none(),
        open: Vec::new(),
        reference: f64::NAN,
        rounds: Vec::new(),
        named: Vec::new(),
    };
    let Ok(()) = search(&mut judge, MARGINS, MAX_CHANCES);
    let f = &judge.forecaster;
    let before = f.scores(&judge.held_out, &Spread::none(), JUDGE_MEMBERS);
    let after = f.scores(&judge.held_out, &judge.spread, JUDGE_MEMBERS);
    let mean = |s: &[f64]| s.iter().sum::<f64>() / s.len().max(1) as f64;
    ForceChance {
        members: JUDGE_MEMBERS,
        held_out: judge.held_out.len(),
        scores: (mean(&before), mean(&after)),
        gain: Paired::of(&before, &after),
        coverage: coverage(f, &judge.held_out, &judge.spread),
        coverage_reference: coverage(f, &judge.held_out, &Spread::none()),
        named: judge.named,
        rounds: judge.rounds,
    }
}

/// The shares of `cases`' indicators inside the 50 % and 90 % bands of `spread`'s
/// ensembles.
fn coverage(f: &Forecaster<'_>, cases: &[RunCase], spread: &Spread) -> [f64; 2] {
    let inside: Vec<[usize; 2]> = cases
        .par_iter()
        .map(|case| {
            let members = f.members(case, spread, JUDGE_MEMBERS);
            let mut inside = [0; 2];
            for (values, measured) in members.iter().zip(case.measured) {
                for (slot, level) in [0.5, 0.9].into_iter().enumerate() {
                    let (lo, hi) = central_band(values, level);
                    inside[slot] += usize::from(lo <= measured && measured <= hi);
                }
            }
            inside
        })
        .collect();
    let total = (3 * cases.len()).max(1) as f64;
    [0, 1].map(|slot| inside.iter().map(|i| i[slot]).sum::<usize>() as f64 / total)
}
