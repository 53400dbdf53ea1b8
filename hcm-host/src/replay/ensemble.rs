//! What decides the final face: the initial state's uncertainty propagated as an
//! ensemble. A replay starts from the state its free-flight fit gives
//! ([`super::initial_state`]); that fit has a covariance, σ_k²·(AᵀA)⁻¹ per axis for
//! the position and velocity, and the same for the rotation vector and the angular
//! velocity, σ_k² its own residual variance (`crate::dataset::FlightFit`): the
//! tracker's noise left in the state. A tumbling cube amplifies such a difference
//! until it ends on another face, so one replay says which face, where an ensemble
//! of replays from states drawn with that covariance says how likely each face is.
//!
//! Each member draws, for every moving body with a fitted state, its position and
//! velocity offsets per axis jointly from that axis's covariance, and its rotation
//! vector and angular-velocity offsets likewise (the rotation applied on the left:
//! R' = exp(δaₓ)·R). Draws come from ChaCha8 seeded with the seed, one stream per
//! toss: the same seed gives the same forecast on any number of threads.
//!
//! A member also draws every contact's parameter scatter (its `noise`, Eq 18, drawn
//! as `scenario::Draw::Member` does; `Spread::scatter` puts one relative σ on the
//! stiffness, damping and friction coefficient): a real table and cube are not the same at
//! every spot and every landing, and with the fitted ContactNets physics the start
//! state's own covariance, even ×30, moved no toss to another face
//! ([`calibrate_scatter`] chooses the scatter on training tosses).
//!
//! Scores (held out, toss by toss): whether the most probable face is the recorded
//! one; the Brier score Σ_f (p_f − y_f)² (0 perfect, 2 all on a wrong face; a single
//! replay's is 0 or 2); and the log-likelihood ln p of the recorded face, with the
//! add-½ estimate p_f = (n_f + ½)/(N + 3) so a face no member reached keeps a finite
//! score (one replay, N = 1: ln 0.375 right, ln 0.125 wrong).

use super::face::{Face, FACES};
use super::initial_state::{orientation, InitialState};
use super::predict::{prepare, simulate_toss, PreparedToss, TossPrediction};
use super::{Summary, TossError, TossSetup};
use crate::dataset::{Dataset, FlightFit, Sample};
use crate::scenario::{drawn_run, Draw, FRICTION_COEFFICIENT};
use crate::scenario::{Contact, Model, Shape};
use crate::simulate::SimulationError;
use nalgebra::{UnitQuaternion, Vector3};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use rayon::prelude::*;

/// How an ensemble is drawn: the model's own variation (its contacts' `noise`, its
/// `[variation]`), each part of it replaced where given.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spread {
    /// Members per toss (–).
    pub members: usize,
    /// Factor on the fits' standard deviations (–): 1 draws from their covariance as
    /// it is. None: the model's `variation.start_state`.
    pub inflation: Option<f64>,
    /// Relative standard deviation (–) of every contact's stiffness, damping and
    /// friction coefficient ([`scatter_all`]), drawn once per member, in place of the
    /// contacts' own `noise` (0: none). None: the contacts' own.
    pub scatter: Option<f64>,
    /// Seed of the draws.
    pub seed: u64,
}

impl Spread {
    /// `members` members drawn with `seed` from the model's own variation.
    pub fn of_model(members: usize, seed: u64) -> Spread {
        Spread {
            members,
            inflation: None,
            scatter: None,
            seed,
        }
    }

    /// One member without start draw or contact scatter: the single replay, of a model
    /// without the rest of a variation (`Model::without_variation`).
    pub fn replay() -> Spread {
        Spread {
            members: 1,
            inflation: Some(0.0),
            scatter: Some(0.0),
            seed: 0,
        }
    }

    /// The model the members draw from (its contacts' noise replaced by the scatter,
    /// where given) and the start-state factor.
    pub fn applied(&self, model: &Model) -> (Model, f64) {
        let mut model = model.clone();
        if let Some(scatter) = self.scatter {
            scatter_all(&mut model, scatter);
        }
        let inflation = (self.inflation).unwrap_or(model.scenario.variation.start_state);
        (model, inflation)
    }
}

/// One toss's final faces: recorded, replayed, and the ensemble's.
#[derive(Clone, Debug, PartialEq)]
pub struct FaceForecast {
    /// Run id.
    pub run: String,
    /// The face the body lies on in the window's last recorded frame.
    pub measured: Face,
    /// The face of the replay from the fitted initial state, at that frame.
    pub replay: Face,
    /// How many members ended on each face.
    pub counts: [usize; FACES],
    /// Members whose replay failed (left out of the counts).
    pub failed: usize,
}

impl FaceForecast {
    /// Members that ended on a face (–).
    pub fn members(&self) -> usize {
        self.counts.iter().sum()
    }

    /// The ensemble's probability of each face, n_f / N (–); all 0 without members.
    pub fn probabilities(&self) -> [f64; FACES] {
        let n = self.members().max(1) as f64;
        self.counts.map(|c| c as f64 / n)
    }

    /// The most probable face (the first of a tie); the replay's without members.
    pub fn most_probable(&self) -> Face {
        match (0..FACES).max_by_key(|&f| (self.counts[f], FACES - f)) {
            Some(f) if self.members() > 0 => Face(f),
            _ => self.replay,
        }
    }

    /// The ensemble's Brier score Σ_f (p_f − y_f)² (–, 0…2).
    pub fn brier(&self) -> f64 {
        brier(&self.probabilities(), self.measured)
    }

    /// The single replay's Brier score: 0 on the recorded face, 2 off it (–).
    pub fn replay_brier(&self) -> f64 {
        let mut one_hot = [0.0; FACES];
        one_hot[self.replay.0] = 1.0;
        brier(&one_hot, self.measured)
    }

    /// ln p of the recorded face under the ensemble, add-½ estimate (–, ≤ 0).
    pub fn log_likelihood(&self) -> f64 {
        add_half(self.counts[self.measured.0], self.members())
    }

    /// ln p of the recorded face under the single replay as a one-member ensemble,
    /// add-½ estimate (–): ln 0.375 or ln 0.125.
    pub fn replay_log_likelihood(&self) -> f64 {
        add_half(usize::from(self.replay == self.measured), 1)
    }
}

/// Σ_f (p_f − y_f)² for the recorded face `measured` (–).
fn brier(p: &[f64; FACES], measured: Face) -> f64 {
    crate::numerics::scores::brier(p, measured.0)
}

/// ln((n + ½)/(N + 3)): the add-½ estimate of a face reached `n` times of `members`.
fn add_half(n: usize, members: usize) -> f64 {
    ((n as f64 + 0.5) / (members as f64 + 0.5 * FACES as f64)).ln()
}

/// The face scores over tosses.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct FaceSummary {
    /// Tosses (–).
    pub tosses: usize,
    /// Members per toss (–).
    pub members: usize,
    /// Tosses whose replay ends on the recorded face (–).
    pub replay_right: usize,
    /// Tosses whose ensemble's most probable face is the recorded one (–).
    pub ensemble_right: usize,
    /// Mean Brier score of the single replays and of the ensembles (–).
    pub brier: (f64, f64),
    /// Mean log-likelihood of the recorded faces, single replays and ensembles (–).
    pub log_likelihood: (f64, f64),
    /// The ensembles' gain in Brier score over the single replays, toss by toss
    /// (replay − ensemble): mean and the half-width of its 95 % interval,
    /// 1.96·sd/√n (–; 0 for fewer than two tosses).
    pub brier_gain: [f64; 2],
    /// Members whose replay failed, over all tosses (–).
    pub failed: usize,
}

/// The face scores of `forecasts` of `members` members each.
pub fn summarize_faces(forecasts: &[FaceForecast], members: usize) -> FaceSummary {
    let n = forecasts.len().max(1) as f64;
    let mean = |f: fn(&FaceForecast) -> f64| forecasts.iter().map(f).sum::<f64>() / n;
    let right = |f: fn(&FaceForecast) -> Face| {
        (forecasts.iter())
            .filter(|forecast| f(forecast) == forecast.measured)
            .count()
    };
    FaceSummary {
        tosses: forecasts.len(),
        members,
        replay_right: right(|f| f.replay),
        ensemble_right: right(FaceForecast::most_probable),
        brier: (mean(FaceForecast::replay_brier), mean(FaceForecast::brier)),
        log_likelihood: (
            mean(FaceForecast::replay_log_likelihood),
            mean(FaceForecast::log_likelihood),
        ),
        brier_gain: paired_gain(forecasts),
        failed: forecasts.iter().map(|f| f.failed).sum(),
    }
}

/// Mean and 95 % half-width (1.96·sd/√n) of the per-toss Brier gain replay − ensemble
/// (–), from the tosses' [`Summary`].
fn paired_gain(forecasts: &[FaceForecast]) -> [f64; 2] {
    let gains: Vec<f64> = (forecasts.iter())
        .map(|f| f.replay_brier() - f.brier())
        .collect();
    if gains.len() < 2 {
        return [gains.first().copied().unwrap_or(0.0), 0.0];
    }
    let s = Summary::of(&gains);
    [s.mean, 1.96 * s.std / (s.count as f64).sqrt()]
}

/// The final-face forecast of every toss of `data` under `model`, `members` replays
/// each from initial states drawn with `seed` (see the module documentation), in the
/// data's order; tosses run in parallel, `done` called as each finishes. The scenario's
/// primary moving body must be a box.
pub fn forecast_faces(
    model: &Model,
    data: &Dataset,
    spread: Spread,
    done: impl Fn() + Sync,
) -> Result<Vec<FaceForecast>, TossError> {
    let setup = TossSetup::new(model)?;
    has_faces(model, &setup)?;
    let forecast = |toss: &PreparedToss<'_>, stream| {
        let members = member_replays(model, &setup, toss, &spread, stream);
        forecast_face(model, &setup, toss, &members)
    };
    each_toss(&setup, data, forecast, done)
}

/// Refuses a primary body that is not a box: only a box has faces to land on.
pub(super) fn has_faces(model: &Model, setup: &TossSetup) -> Result<(), TossError> {
    if let Some(link) = setup.joints.first() {
        return Err(TossError::Setup {
            scenario: model.scenario.name.clone(),
            problem: format!(
                "joint `{}`: a mechanism has no one face to land on; the faces are forecast for \
                 a lone box",
                link.joint.name
            ),
        });
    }
    if matches!(model.bodies[setup.body].shape, Shape::Box { .. }) {
        return Ok(());
    }
    Err(TossError::Setup {
        scenario: model.scenario.name.clone(),
        problem: format!(
            "body `{}` is not a box: only a box has faces to land on",
            setup.name
        ),
    })
}

/// Every toss of `data` prepared for `setup` (a data error before any simulation), then
/// `forecast` of each with its index, the stream of the seed its members draw from;
/// tosses in parallel, the results in the data's order, `done` called as each finishes.
pub(super) fn each_toss<T: Send>(
    setup: &TossSetup,
    data: &Dataset,
    forecast: impl Fn(&PreparedToss<'_>, u64) -> Result<T, TossError> + Sync,
    done: impl Fn() + Sync,
) -> Result<Vec<T>, TossError> {
    let tosses = (data.runs.iter())
        .map(|run| prepare(setup, run))
        .collect::<Result<Vec<_>, _>>()?;
    (tosses.par_iter().enumerate())
        .map(|(index, toss)| {
            let forecast = forecast(toss, index as u64);
            done();
            forecast
        })
        .collect()
}

/// The contact-parameter scatters (–) [`calibrate_scatter`] tries by default.
pub const SCATTERS: [f64; 5] = [0.0, 0.1, 0.2, 0.3, 0.5];

/// The scatter of `scatters` whose ensembles (`spread`'s members, inflation and seed)
/// give `training`'s tosses the lowest mean Brier score (the first of a tie), with
/// each scatter's score: the per-toss variability of the contact, chosen on tosses the
/// judged ones are not. `done` is called as each toss of each scatter finishes.
pub fn calibrate_scatter(
    model: &Model,
    training: &Dataset,
    spread: Spread,
    scatters: &[f64],
    done: impl Fn() + Sync,
) -> Result<(f64, Vec<(f64, f64)>), TossError> {
    let mut scores = Vec::with_capacity(scatters.len());
    for &scatter in scatters {
        let forecasts = forecast_faces(
            model,
            training,
            Spread {
                scatter: Some(scatter),
                ..spread
            },
            &done,
        )?;
        scores.push((scatter, summarize_faces(&forecasts, spread.members).brier.1));
    }
    let best = (scores.iter())
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map_or(0.0, |b| b.0);
    Ok((best, scores))
}

/// One toss's final-face forecast by `members` (failed ones counted), beside the
/// single replay's.
pub(super) fn forecast_face(
    model: &Model,
    setup: &TossSetup,
    toss: &PreparedToss<'_>,
    members: &[Result<TossPrediction, TossError>],
) -> Result<FaceForecast, TossError> {
    let down = setup.gravity;
    let last = toss.primary().measured().last();
    let measured = last
        .map(|frame| orientation(&setup.name, toss.run, frame))
        .transpose()?
        .and_then(|q| Face::facing(&q, &down));
    let final_face = |prediction: &TossPrediction| {
        prediction.samples.last().and_then(|s| {
            let [w, x, y, z] = s.orientation;
            let q = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z));
            Face::facing(&q, &down)
        })
    };
    let undefined = || TossError::Frame {
        run: toss.run.to_owned(),
        time: last.map_or(f64::NAN, |s| s.time),
        problem: "no face points down in the window's last frame (no gravity?)".into(),
    };
    let measured = measured.ok_or_else(undefined)?;
    let replay = final_face(&simulate_toss(model, setup, toss)?).ok_or_else(undefined)?;
    let (mut counts, mut failed) = ([0; FACES], 0);
    for member in members {
        let face = member.as_ref().ok().and_then(final_face);
        match face {
            Some(face) => counts[face.0] += 1,
            None => failed += 1,
        }
    }
    Ok(FaceForecast {
        run: toss.run.to_owned(),
        measured,
        replay,
        counts,
        failed,
    })
}

/// The members' replays of one toss, in draw order: each member's start states drawn
/// ([`drawn`]), then its contacts' parameters and fixed bodies ([`drawn_run`]), from stream `stream` of the
/// spread's seed.
pub(super) fn member_replays(
    model: &Model,
    setup: &TossSetup,
    toss: &PreparedToss<'_>,
    spread: &Spread,
    stream: u64,
) -> Vec<Result<TossPrediction, TossError>> {
    let mut rng = ChaCha8Rng::seed_from_u64(spread.seed);
    rng.set_stream(stream);
    let (model, inflation) = spread.applied(model);
    let tracker = model.scenario.variation.tracker;
    (0..spread.members)
        .map(|_| {
            let mut member = toss.clone();
            for body in &mut member.bodies {
                body.initial = drawn(&body.initial, inflation, &mut rng);
            }
            // Drawn link by link, the start is assembled onto the joints again.
            super::predict::assemble_bodies(setup, &mut member.bodies);
            let drawn =
                drawn_run(&model, &mut rng, Draw::Member).map_err(|(contact, source)| {
                    TossError::Simulation {
                        run: toss.run.to_owned(),
                        error: SimulationError::Noise { contact, source },
                    }
                })?;
            let mut prediction = simulate_toss(&drawn, setup, &member)?;
            if tracker > 0.0 {
                let companions = prediction.companions.iter_mut().map(|c| &mut c.samples);
                let tracks = std::iter::once(&mut prediction.samples).chain(companions);
                for (samples, body) in tracks.zip(&toss.bodies) {
                    filmed(samples, &body.initial, tracker, &mut rng);
                }
            }
            Ok(prediction)
        })
        .collect()
}

/// `samples` as the tracker records them: each frame's centre moved by σ_k·ζ per axis
/// and its orientation turned by σ_k·ζ per rotation-vector component (on the left), σ_k
/// the residual σ of `initial`'s free-flight fits × `factor`, frame by frame, axis by
/// axis; unchanged without fits.
fn filmed(samples: &mut [Sample], initial: &InitialState, factor: f64, rng: &mut ChaCha8Rng) {
    let Some([flight, turning]) = &initial.fits else {
        return;
    };
    let sigma = |fit: &FlightFit| fit.noise.map(|v| factor * v.max(0.0).sqrt());
    let (position, rotation) = (sigma(flight), sigma(turning));
    let mut normal = || -> f64 { StandardNormal.sample(&mut *rng) };
    for sample in samples {
        for (p, s) in sample.position.iter_mut().zip(position) {
            *p += s * normal();
        }
        let turn = Vector3::from_fn(|k, _| rotation[k] * normal());
        let [w, x, y, z] = sample.orientation;
        let q = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z));
        let q = UnitQuaternion::from_scaled_axis(turn) * q;
        sample.orientation = [q.w, q.i, q.j, q.k];
    }
}

/// Law parameters [`scatter_all`] scatters, where the law has them.
const SCATTERED: [&str; 5] = [
    "stiffness",
    "effective_modulus",
    "max_damping",
    "damping",
    "restitution",
];

/// Sets every contact's `noise` (Eq 18, as forecast members draw it) to relative σ
/// `scatter` (–) on its law's parameters of [`SCATTERED`] and, with friction, on the
/// friction coefficient (μ_s and μ_d by one ζ); `scatter` 0 clears it.
pub fn scatter_all(model: &mut Model, scatter: f64) {
    for contact in &mut model.contacts {
        scatter_contact(contact, scatter);
    }
}

/// Sets `contact`'s `noise` as [`scatter_all`] sets every contact's.
pub fn scatter_contact(contact: &mut Contact, scatter: f64) {
    contact.noise.clear();
    if scatter <= 0.0 {
        return;
    }
    let law = &contact.model.normal.base;
    for name in SCATTERED.into_iter().filter(|name| law.get(name).is_ok()) {
        contact.noise.push((name.to_owned(), scatter));
    }
    if contact.model.friction.is_some() {
        (contact.noise).push((FRICTION_COEFFICIENT.to_owned(), scatter));
    }
    contact.noise.sort_by(|a, b| a.0.cmp(&b.0));
}

/// `initial` moved by one draw from its fits' covariance (unchanged without fits).
fn drawn(initial: &InitialState, inflation: f64, rng: &mut ChaCha8Rng) -> InitialState {
    let Some([flight, turning]) = &initial.fits else {
        return initial.clone();
    };
    let (dp, dv) = offsets(flight, inflation, rng);
    let (da, dw) = offsets(turning, inflation, rng);
    InitialState {
        position: initial.position + dp,
        velocity: initial.velocity + dv,
        orientation: UnitQuaternion::from_scaled_axis(da) * initial.orientation,
        angular_velocity: initial.angular_velocity + dw,
        ..initial.clone()
    }
}

/// Offsets of the fit's intercept and slope, per axis jointly from σ_k²·(AᵀA)⁻¹ by its
/// Cholesky factor (units of the fit: m and m/s, or rad and rad/s). A degenerate
/// covariance (rounding) gives zero offsets rather than NaN.
fn offsets(fit: &FlightFit, inflation: f64, rng: &mut ChaCha8Rng) -> (Vector3<f64>, Vector3<f64>) {
    let [[caa, cab], [_, cbb]] = fit.unscaled;
    let l00 = caa.max(0.0).sqrt();
    let l10 = if l00 > 0.0 { cab / l00 } else { 0.0 };
    let l11 = (cbb - l10 * l10).max(0.0).sqrt();
    let (mut intercept, mut slope) = (Vector3::zeros(), Vector3::zeros());
    for k in 0..3 {
        let sigma = inflation * fit.noise[k].max(0.0).sqrt();
        let (z1, z2): (f64, f64) = (StandardNormal.sample(rng), StandardNormal.sample(rng));
        intercept[k] = sigma * l00 * z1;
        slope[k] = sigma * (l10 * z1 + l11 * z2);
    }
    let finite = |v: Vector3<f64>| {
        if v.iter().all(|x| x.is_finite()) {
            v
        } else {
            Vector3::zeros()
        }
    };
    (finite(intercept), finite(slope))
}
