//! Replaying measured impacts in simulation: for each experimental condition, the
//! mean state of the bodies just before touch-down becomes a simulation's initial
//! state, and the mean measured force curve and indicators its targets. The genetic
//! fitness and `evaluate` compare a physics model with data this way, so they need
//! no knowledge of how the data were made.

use super::IdentifyError;
use crate::dataset::{Dataset, Run};
use crate::experiment::condition_of;
use crate::indicators::{contact_history, event_spans, Indicators};
use crate::scenario::{Contact, Model};
use crate::simulate::simulate;
use hcm_core::law::AnyNormalLaw;
use nalgebra::Vector3;

/// One experimental condition to reproduce.
#[derive(Clone, Debug)]
pub struct Target {
    /// Condition name (run-id prefix; "" for none).
    pub(crate) condition: String,
    /// Runs averaged.
    pub(crate) runs: usize,
    /// The model started from the mean pre-contact state.
    pub(crate) model: Model,
    /// Mean measured normal force at τ = j·period after touch-down (N).
    pub(crate) curve: Vec<f64>,
    /// Mean measured indicators.
    pub(crate) indicators: Indicators,
    /// Each run's measured indicators (the runs with a contact), in data order.
    pub(crate) run_indicators: Vec<Indicators>,
    /// Standard error of each mean indicator, s/√n over the runs (same units): the
    /// noise floor below which a model's error against the mean cannot be told apart.
    /// None for a single run, whose spread is unknown (not zero).
    pub(crate) standard_error: Option<Indicators>,
    /// Time step of the curve (s).
    pub(crate) period: f64,
}

/// The normal-force curve of the first event of contact `c` in `run`, sampled at
/// τ = j·period after touch-down for j < len (0 after lift-off), and its indicators.
pub fn curve(
    model: &Model,
    run: &Run,
    c: usize,
    period: f64,
    len: usize,
) -> Result<Option<(Vec<f64>, Indicators)>, IdentifyError> {
    let history = contact_history(model, run, c)?;
    let Some(span) = event_spans(&history).into_iter().next() else {
        return Ok(None);
    };
    let indicators = (span.event(&history, c, model.contacts[c].effective_mass)).line_indicators();
    let (t_in, t_out) = (span.touch_down.0, span.lift_off.0);
    let mut i = span.inside.start;
    let values = (0..len)
        .map(|j| {
            let t = t_in + j as f64 * period;
            if t >= t_out || i >= history.time.len() {
                return 0.0;
            }
            while i + 1 < history.time.len() && history.time[i] < t {
                i += 1;
            }
            let (a, b) = (i.saturating_sub(1), i);
            let (ta, tb) = (history.time[a], history.time[b]);
            if tb <= ta {
                history.force[b]
            } else {
                history.force[a] + (t - ta) / (tb - ta) * (history.force[b] - history.force[a])
            }
        })
        .collect();
    Ok(Some((values, indicators)))
}

/// The targets of contact `c` in `data`, one per condition, in order of appearance.
pub fn targets(model: &Model, data: &Dataset, c: usize) -> Result<Vec<Target>, IdentifyError> {
    let mut names: Vec<&str> = Vec::new();
    for run in &data.runs {
        if !names.contains(&condition_of(&run.id)) {
            names.push(condition_of(&run.id));
        }
    }
    let mut targets = Vec::new();
    for name in names {
        let runs: Vec<&Run> = data
            .runs
            .iter()
            .filter(|r| condition_of(&r.id) == name)
            .collect();
        targets.push(condition_target(model, name, &runs, c)?);
    }
    Ok(targets)
}

/// The target of one condition's `runs`: their mean state before touch-down, mean
/// force curve and mean indicators.
fn condition_target(
    model: &Model,
    name: &str,
    runs: &[&Run],
    c: usize,
) -> Result<Target, IdentifyError> {
    let period = model.scenario.record.contact_sample_period;
    let (start, len) = mean_start(model, runs, c, period)?;
    let mut curves = Vec::new();
    let mut indicators = Vec::new();
    for run in runs {
        if let Some((values, i)) = curve(model, run, c, period, len)? {
            curves.push(values);
            indicators.push(i);
        }
    }
    let n = curves.len() as f64;
    let mean_curve = (0..len)
        .map(|j| curves.iter().map(|v| v[j]).sum::<f64>() / n)
        .collect();
    let (mean, standard_error) = indicator_statistics(&indicators);
    Ok(Target {
        condition: name.to_owned(),
        runs: runs.len(),
        model: start,
        curve: mean_curve,
        indicators: mean,
        run_indicators: indicators,
        standard_error,
        period,
    })
}

/// `model` started from the runs' mean pre-contact state of contact `c` and stopped
/// after one contact, and the samples (at `period`, s) a curve needs to hold the
/// longest of the runs' contacts.
fn mean_start(
    model: &Model,
    runs: &[&Run],
    c: usize,
    period: f64,
) -> Result<(Model, usize), IdentifyError> {
    let mut len = 0;
    let mut starts: Vec<Vec<(Vector3<f64>, Vector3<f64>)>> = Vec::new();
    for run in runs {
        let history = contact_history(model, run, c)?;
        let Some(span) = event_spans(&history).into_iter().next() else {
            return Err(IdentifyError::NoContact {
                run: run.id.clone(),
                from: history.time.first().copied().unwrap_or(f64::NAN),
                to: history.time.last().copied().unwrap_or(f64::NAN),
            });
        };
        len = len.max(((span.lift_off.0 - span.touch_down.0) / period).ceil() as usize + 2);
        starts.push(pre_contact_state(
            model,
            run,
            span.inside.start.saturating_sub(1),
        ));
    }
    let mut start = model.clone();
    for (b, body) in start.bodies.iter_mut().enumerate() {
        if !body.fixed && starts.iter().all(|s| s.len() == model.bodies.len()) {
            body.position =
                starts.iter().map(|s| s[b].0).sum::<Vector3<f64>>() / starts.len() as f64;
            body.velocity =
                starts.iter().map(|s| s[b].1).sum::<Vector3<f64>>() / starts.len() as f64;
        }
    }
    start.scenario.simulation.stop_after_contacts = 1;
    Ok((start, len))
}

/// The mean of each indicator over the runs and, from two runs on, its standard
/// error s/√n.
fn indicator_statistics(indicators: &[Indicators]) -> (Indicators, Option<Indicators>) {
    let n = indicators.len() as f64;
    let mean = |f: fn(&Indicators) -> f64| indicators.iter().map(f).sum::<f64>() / n;
    // The sample standard deviation s needs two runs: with one, n − 1 = 0.
    let standard_error = |f: fn(&Indicators) -> f64| {
        let m = mean(f);
        let squares = indicators.iter().map(|i| (f(i) - m).powi(2)).sum::<f64>();
        (squares / (n - 1.0)).sqrt() / n.sqrt()
    };
    let means = Indicators {
        max_force: mean(|i| i.max_force),
        impulse: mean(|i| i.impulse),
        energy_loss: mean(|i| i.energy_loss),
        duration: mean(|i| i.duration),
    };
    let errors = (indicators.len() >= 2).then(|| Indicators {
        max_force: standard_error(|i| i.max_force),
        impulse: standard_error(|i| i.impulse),
        energy_loss: standard_error(|i| i.energy_loss),
        duration: standard_error(|i| i.duration),
    });
    (means, errors)
}

/// Every body's recorded (position, velocity) at sample `i` of `run` (bodies not
/// in the data keep the scenario's state).
pub(crate) fn pre_contact_state(
    model: &Model,
    run: &Run,
    i: usize,
) -> Vec<(Vector3<f64>, Vector3<f64>)> {
    model
        .bodies
        .iter()
        .map(
            |body| match run.body(&body.name).and_then(|t| t.samples.get(i)) {
                Some(s) => (Vector3::from(s.position), Vector3::from(s.velocity)),
                None => (body.position, body.velocity),
            },
        )
        .collect()
}

/// Simulates `target` with contact `c` under `law`: its force curve and indicators,
/// or None when the simulation fails or makes no complete contact.
pub(crate) fn simulate_target(
    target: &Target,
    c: usize,
    law: &AnyNormalLaw<f64>,
) -> Option<(Vec<f64>, Indicators)> {
    let mut contact = target.model.contacts[c].clone();
    contact.model.normal.base = *law;
    simulate_target_with(target, c, &contact)
}

/// `model` (its bodies, their state and the settings) under the physics of `physics`:
/// every contact (law, effects, residual) and every body's air drag taken from it.
/// The two must come from one scenario (same bodies and contacts, in order).
pub fn with_physics(model: &Model, physics: &Model) -> Model {
    let mut out = model.clone();
    out.contacts.clone_from(&physics.contacts);
    for (body, source) in out.bodies.iter_mut().zip(&physics.bodies) {
        body.air_drag = source.air_drag;
    }
    out
}

/// Step attempts a judged replay of one contact event may take at most (–): the
/// paper's ball and flat shot take about 140 (`simulate`'s `steps`); a model whose
/// contact chatters (a residual network pulling at δ → 0) would otherwise spend the
/// scenario's whole budget, 10⁶ by default and seconds per replay, before it is
/// called failed.
const REPLAY_MAX_STEPS: u64 = 100_000;

/// Simulates `target` under the physics of `physics` (see [`with_physics`]), within
/// [`REPLAY_MAX_STEPS`]: its force curve on contact `c` and indicators, or None as
/// [`simulate_target`].
pub(crate) fn simulate_target_as(
    target: &Target,
    c: usize,
    physics: &Model,
) -> Option<(Vec<f64>, Indicators)> {
    let mut model = with_physics(&target.model, physics);
    let budget = &mut model.scenario.simulation.max_steps;
    *budget = (*budget).min(REPLAY_MAX_STEPS);
    let run = simulate(&model).ok()?.run;
    curve(&model, &run, c, target.period, target.curve.len())
        .ok()
        .flatten()
}

/// Simulates `target` with contact `c` replaced by `contact` (law and residual).
pub(crate) fn simulate_target_with(
    target: &Target,
    c: usize,
    contact: &Contact,
) -> Option<(Vec<f64>, Indicators)> {
    let mut model = target.model.clone();
    model.contacts[c] = contact.clone();
    let run = simulate(&model).ok()?.run;
    curve(&model, &run, c, target.period, target.curve.len())
        .ok()
        .flatten()
}
