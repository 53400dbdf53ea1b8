//! What a diagnosis gains, measured on data the fit never saw: the base model, the
//! extended model and the HCM replayed on held-out runs (and, with several
//! conditions, on a held-out condition outside the fitted range), each scored by its
//! force RMSE against the measured force and by the Eq 20 errors of its indicators.
//!
//! Force RMSE. Each held-out run is replayed from its own pre-contact state and the
//! simulated force is compared with the run's recorded normal force at the recorded
//! samples inside the contact (δ > 0), the simulated curve being linearly
//! interpolated at the same time after touch-down. The comparison is made at the
//! recorded samples, not on the resampled curve of [`targets`], because resampling
//! interpolates between two noisy samples and shrinks the noise (to about √(2/3)·σ
//! on average): against that curve a perfect model would score below σ and the
//! excess over noise would hide errors up to about 0.6·σ. At the recorded samples a
//! perfect model scores σ, the sensor noise of Eq 19, and
//! excess = √max(RMSE² − σ², 0) estimates the model's own error.

use super::noise::white_noise;
use super::sensor::Sensor;
use crate::dataset::Dataset;
use crate::evaluate::{IndicatorErrors, ModelRow};
use crate::experiment::condition_of;
use crate::identify::IdentifyError;
use crate::identify::{pre_contact_state, simulate_target_as, targets, with_physics, Target};
use crate::indicators::{contact_history, event_spans, ContactHistory, EventSpan, Indicators};
use crate::scenario::Model;
use crate::simulate::simulate;
use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

/// Which runs fit the models and which judge them (indices into the data set).
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Holdout {
    /// Runs the models may be fitted to, ascending.
    pub(crate) training: Vec<usize>,
    /// Runs kept for judging, ascending: the held-out condition's and a random share
    /// of the others.
    pub(crate) held_out: Vec<usize>,
    /// The condition held out entirely, if the data have at least three.
    pub(crate) condition: Option<String>,
}

/// The held-out runs of `data`: with ≥ 3 conditions, every run of the scenario's
/// first `experiment.holdout_conditions` entry (if present in the data, else of the
/// last condition to appear); in every case a random `fraction` (–) of the remaining
/// runs, at least one when two or more remain and never all of them. Deterministic
/// for a given `seed`.
pub fn holdout(model: &Model, data: &Dataset, seed: u64, fraction: f64) -> Holdout {
    let condition = held_out_condition(model, data);
    let in_condition = |i: usize| condition.as_deref() == Some(condition_of(&data.runs[i].id));
    let mut rest: Vec<usize> = (0..data.runs.len()).filter(|&i| !in_condition(i)).collect();
    let (min, max) = (usize::from(rest.len() >= 2), rest.len().saturating_sub(1));
    // NaN and negative fractions cast to 0, then the clamp keeps one held-out run.
    let count = ((rest.len() as f64 * fraction).round() as usize).clamp(min, max);
    // A stream of its own, so it does not repeat the S1/S2 split's draw.
    rest.shuffle(&mut ChaCha8Rng::seed_from_u64(seed ^ 0x6A17_D1A6));
    let mut held_out: Vec<usize> = (0..data.runs.len()).filter(|&i| in_condition(i)).collect();
    held_out.extend_from_slice(&rest[..count]);
    held_out.sort_unstable();
    let mut training = rest[count..].to_vec();
    training.sort_unstable();
    Holdout {
        training,
        held_out,
        condition,
    }
}

/// Conditions of `data` in order of first appearance.
fn conditions(data: &Dataset) -> Vec<&str> {
    let mut names: Vec<&str> = Vec::new();
    for run in &data.runs {
        if !names.contains(&condition_of(&run.id)) {
            names.push(condition_of(&run.id));
        }
    }
    names
}

/// The condition [`holdout`] holds out entirely, if any.
fn held_out_condition(model: &Model, data: &Dataset) -> Option<String> {
    let names = conditions(data);
    if names.len() < 3 {
        return None;
    }
    let named = model.scenario.experiment.holdout_conditions.first();
    match named.filter(|n| names.contains(&n.as_str())) {
        Some(name) => Some(name.clone()),
        None => names.last().map(|n| n.to_string()),
    }
}

/// A model the gain judges.
#[derive(Clone, Copy, Debug)]
pub struct Judged<'a> {
    /// Row label (`base`, `extended`, `HCM`).
    pub(crate) label: &'a str,
    /// Its physics: every contact (law, effects, residual) and every body's air drag
    /// are replayed from it (see [`with_physics`]); the start states come from the data.
    pub(crate) physics: &'a Model,
    /// The sensor correction taken off the held-out data before this model is judged
    /// on them (ideal: the data as recorded).
    pub(crate) sensor: Sensor,
}

/// One model scored on one group of held-out runs. NaN (indicators and errors: None)
/// where its simulation failed.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct GainRow {
    /// The model (`base`, `extended`, `HCM`), its indicators (N, N·s, N·m, s) replayed
    /// from each condition's mean pre-contact state and their Eq 20 errors against the
    /// measured means, each a run-weighted mean over the group's conditions (so errors
    /// of opposite sign do not cancel): the row `evaluate` writes too, its keys inline
    /// in the JSON row.
    #[serde(flatten)]
    pub judged: ModelRow,
    /// |model − measured mean| of each indicator (N, N·s, N·m, s), run-weighted over
    /// the group's conditions like the errors and against the same means (a model
    /// with a sensor correction: the corrected runs'); None where a replay failed. The
    /// report gives it where the measured mean is not told from zero.
    pub absolute_errors: Option<[f64; 4]>,
    /// RMSE of the simulated against the recorded normal force over the contact
    /// samples of every run of the group (N), the recording corrected by the model's
    /// sensor (see [`Sensor::retime`]).
    pub(crate) force_rmse: f64,
    /// The part of the RMSE the noise does not explain, √max(RMSE² − σ², 0) (N).
    pub excess_rmse: f64,
    /// RMSE of the simulated against the recorded indentation rate δ̇ over the flight
    /// before the first touch-down (m/s) — the recorded one and the replay's own — each
    /// run replayed from its first recorded sample; NaN when the runs record no flight
    /// before their contact.
    pub(crate) flight_rmse: f64,
    /// √max(flight RMSE² − σ_v², 0) (m/s), σ_v the white noise of the recorded δ̇.
    pub flight_excess: f64,
}

/// The models scored on one group of held-out runs.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct GainTable {
    /// `held-out runs` (inside the fitted range) or `condition NAME`.
    pub(crate) group: String,
    /// Runs in the group.
    pub(crate) runs: usize,
    /// White noise σ_v of the recorded indentation rate in flight (m/s), from its
    /// second differences; NaN without flight samples.
    pub flight_noise: f64,
    /// One row per model, in the order given.
    pub rows: Vec<GainRow>,
    /// Per indicator, whether the measured mean is indistinguishable from zero in
    /// some condition (within [`ZERO_SE`] standard errors of it, e.g. an elastic
    /// contact's energy loss): no error relative to it means anything, so the report
    /// gives |model − measured| in the indicator's unit there instead of a percentage.
    pub near_zero: [bool; 4],
}

/// Standard errors of a measured mean within which it counts as zero (–): a mean
/// closer to 0 than twice its standard error is not told from 0 at 95 %.
pub const ZERO_SE: f64 = 2.0;

/// Per indicator, whether any of `means` is within [`ZERO_SE`] standard errors of 0
/// (never where the standard error is unknown, a single run).
fn near_zero(means: &[Target]) -> [bool; 4] {
    std::array::from_fn(|k| {
        means.iter().any(|t| {
            t.standard_error
                .is_some_and(|se| t.indicators.values()[k].abs() <= ZERO_SE * se.values()[k])
        })
    })
}

/// Scores the `judged` models on the held-out `runs` of `data` (contact `c` of
/// `model`, which gives the geometry and the recording's reading): one table for the
/// runs inside the fitted range, one for the condition [`holdout`] holds out entirely
/// (if any of its runs are given). `sigma` is the force noise σ (N). Errors only for
/// data that cannot be replayed (a run without contact, a bad run index); a failing
/// model gets NaN.
pub fn gain(
    model: &Model,
    data: &Dataset,
    runs: &[usize],
    c: usize,
    sigma: f64,
    judged: &[Judged],
) -> Result<Vec<GainTable>, IdentifyError> {
    check_runs(data, runs)?;
    let condition = held_out_condition(model, data);
    let (outside, inside): (Vec<usize>, Vec<usize>) = runs
        .iter()
        .partition(|&&r| condition.as_deref() == Some(condition_of(&data.runs[r].id)));
    let mut tables = Vec::new();
    if !inside.is_empty() {
        let group = "held-out runs".to_owned();
        tables.push(group_table(group, model, data, &inside, c, sigma, judged)?);
    }
    if let (Some(name), false) = (condition, outside.is_empty()) {
        let group = format!("condition {name}");
        tables.push(group_table(group, model, data, &outside, c, sigma, judged)?);
    }
    Ok(tables)
}

/// One held-out run as recorded: its replay target, its contact history and the span
/// of its first contact event.
struct Recorded {
    target: Target,
    history: ContactHistory,
    span: EventSpan,
}

fn recorded(model: &Model, data: &Dataset, r: usize, c: usize) -> Result<Recorded, IdentifyError> {
    let run = &data.runs[r];
    let one = Dataset {
        runs: vec![run.clone()],
    };
    let target = targets(model, &one, c)?
        .into_iter()
        .next()
        .ok_or(IdentifyError::NoData)?;
    let history = contact_history(model, run, c)?;
    let span =
        event_spans(&history)
            .into_iter()
            .next()
            .ok_or_else(|| IdentifyError::NoContact {
                run: run.id.clone(),
                from: history.time.first().copied().unwrap_or(f64::NAN),
                to: history.time.last().copied().unwrap_or(f64::NAN),
            })?;
    Ok(Recorded {
        target,
        history,
        span,
    })
}

impl Recorded {
    /// The recorded (time after touch-down (s), normal force (N)) samples inside the
    /// contact, corrected by `sensor`.
    fn force_samples(&self, sensor: &Sensor) -> impl Iterator<Item = (f64, f64)> + '_ {
        let t_in = self.span.touch_down.0;
        let sensor = *sensor;
        self.span.inside.clone().map(move |i| {
            let (t, f) = sensor.retime(&self.history, i);
            (t - t_in, f)
        })
    }

    /// Indices of the flight samples before the first touch-down.
    fn flight(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.span.inside.start).filter(|&i| self.history.depth[i] <= 0.0)
    }
}

/// The curve sampled at τ = j·period, linearly interpolated at `tau` (s); 0 beyond it.
fn at(curve: &[f64], period: f64, tau: f64) -> f64 {
    let x = (tau / period).max(0.0);
    let j = x.floor() as usize;
    match (curve.get(j), curve.get(j + 1)) {
        (Some(a), Some(b)) => a + (x - j as f64) * (b - a),
        (Some(a), None) => *a,
        _ => 0.0,
    }
}

/// An error naming the first of `runs` that is no run of `data`.
fn check_runs(data: &Dataset, runs: &[usize]) -> Result<(), IdentifyError> {
    match runs.iter().find(|&&r| r >= data.runs.len()) {
        Some(r) => Err(IdentifyError::Setup(format!(
            "run index {r} is out of range (the data hold {} runs)",
            data.runs.len()
        ))),
        None => Ok(()),
    }
}

/// Scores the `judged` models on `runs` of `data` as one group named `group`, whatever
/// their conditions (see [`gain`] for the rest).
pub fn group_table(
    group: String,
    model: &Model,
    data: &Dataset,
    runs: &[usize],
    c: usize,
    sigma: f64,
    judged: &[Judged],
) -> Result<GainTable, IdentifyError> {
    check_runs(data, runs)?;
    let records = runs
        .iter()
        .map(|&r| recorded(model, data, r, c))
        .collect::<Result<Vec<_>, _>>()?;
    let flight_noise = flight_noise(&records);
    // The measured means as recorded, shared by every model judged with an ideal sensor;
    // a model with a sensor correction gets the means of the corrected runs.
    let means_of = |sensor: &Sensor| -> Result<Vec<Target>, IdentifyError> {
        let runs = runs
            .iter()
            .map(|&r| sensor.correct(model, &data.runs[r], c))
            .collect::<Result<_, _>>()?;
        targets(model, &Dataset { runs }, c)
    };
    let recorded_means = means_of(&Sensor::default())?;
    let mut rows = Vec::with_capacity(judged.len());
    for j in judged {
        let corrected_means;
        let means = if j.sensor.is_ideal() {
            &recorded_means
        } else {
            corrected_means = means_of(&j.sensor)?;
            &corrected_means
        };
        let force_rmse = force_rmse(&records, c, j);
        let scored = indicator_errors(means, c, j.physics);
        let flight_rmse = flight_rmse(model, data, runs, &records, c, j.physics);
        // NaN (a failed replay) stays NaN: `f64::max` would turn it into 0, a perfect score.
        let excess = |rmse: f64, noise: f64| {
            let d = rmse.powi(2) - noise.powi(2);
            if d.is_nan() {
                f64::NAN
            } else {
                d.max(0.0).sqrt()
            }
        };
        rows.push(GainRow {
            judged: ModelRow {
                model: j.label.to_owned(),
                indicators: scored.map(|s| s.0),
                errors: scored.map(|s| s.1),
            },
            absolute_errors: scored.map(|s| s.2),
            force_rmse,
            excess_rmse: excess(force_rmse, sigma),
            flight_rmse,
            flight_excess: excess(flight_rmse, flight_noise.max(0.0)),
        });
    }
    Ok(GainTable {
        group,
        runs: runs.len(),
        flight_noise,
        rows,
        near_zero: near_zero(&recorded_means),
    })
}

/// Pooled force RMSE (N) of the judged model over the runs; NaN if any replay fails.
fn force_rmse(records: &[Recorded], c: usize, judged: &Judged) -> f64 {
    let (mut squares, mut count) = (0.0, 0usize);
    for record in records {
        let Some((curve, _)) = simulate_target_as(&record.target, c, judged.physics) else {
            return f64::NAN;
        };
        // In the reading's units (times g), so that a perfect model scores σ.
        let gain = judged.sensor.gain;
        for (tau, measured) in record.force_samples(&judged.sensor) {
            squares += (gain * (at(&curve, record.target.period, tau) - measured)).powi(2);
            count += 1;
        }
    }
    if count == 0 {
        return f64::NAN;
    }
    (squares / count as f64).sqrt()
}

/// White noise of the recorded δ̇ over the flight samples before the first touch-down
/// (m/s); NaN without three flight samples on one clock.
fn flight_noise(records: &[Recorded]) -> f64 {
    let (mut run, mut time, mut rate) = (Vec::new(), Vec::new(), Vec::new());
    for (k, record) in records.iter().enumerate() {
        for i in record.flight() {
            run.push(k);
            time.push(record.history.time[i]);
            rate.push(record.history.rate[i]);
        }
    }
    white_noise(&run, &time, &rate).sigma
}

/// Pooled RMSE (m/s) of δ̇ in flight before the first touch-down, each run replayed
/// under `physics` from its first recorded sample; NaN without flight samples or if a
/// replay fails.
fn flight_rmse(
    model: &Model,
    data: &Dataset,
    runs: &[usize],
    records: &[Recorded],
    c: usize,
    physics: &Model,
) -> f64 {
    let (mut squares, mut count) = (0.0, 0usize);
    for (&r, record) in runs.iter().zip(records) {
        let flight: Vec<usize> = record.flight().collect();
        if flight.is_empty() {
            continue;
        }
        let mut start = with_physics(model, physics);
        for ((body, spec), state) in start
            .bodies
            .iter_mut()
            .zip(&model.bodies)
            .zip(pre_contact_state(model, &data.runs[r], 0))
        {
            if !spec.fixed {
                (body.position, body.velocity) = state;
            }
        }
        // Simulated up to the last flight sample, however early this model's own
        // contact comes.
        let t0 = record.history.time[0];
        let last = flight.last().map_or(t0, |&i| record.history.time[i]);
        start.scenario.simulation.stop_after_contacts = 0;
        start.scenario.simulation.end_time = last - t0 + start.scenario.record.flight_sample_period;
        let Some(simulated) = simulate(&start)
            .ok()
            .and_then(|s| contact_history(&start, &s.run, c).ok())
        else {
            return f64::NAN;
        };
        // Only while the replay is in flight too: past its own touch-down a model's δ̇
        // turns with the bounce, an error of the contact timing, not of the flight.
        let touch = simulated
            .depth
            .iter()
            .position(|&d| d > 0.0)
            .map_or(f64::INFINITY, |k| simulated.time[k]);
        for i in flight
            .into_iter()
            .filter(|&i| record.history.time[i] - t0 < touch)
        {
            let rate = interpolate(
                &simulated.time,
                &simulated.rate,
                record.history.time[i] - t0,
            );
            squares += (rate - record.history.rate[i]).powi(2);
            count += 1;
        }
    }
    if count == 0 {
        return f64::NAN;
    }
    (squares / count as f64).sqrt()
}

/// `values` sampled at ascending `times`, linearly interpolated at `t`; NaN outside.
fn interpolate(times: &[f64], values: &[f64], t: f64) -> f64 {
    let j = times.partition_point(|&x| x < t);
    match times.get(j) {
        Some(&x) if x == t => values[j],
        Some(&x) if j > 0 => {
            let a = j - 1;
            values[a] + (t - times[a]) / (x - times[a]) * (values[j] - values[a])
        }
        _ => f64::NAN,
    }
}

/// The run-weighted mean indicators of `physics` replayed on each condition's mean
/// target, and the run-weighted means of their Eq 20 errors and of their absolute
/// errors |simulated − measured| (units of each indicator); None without conditions
/// or if any replay fails.
fn indicator_errors(
    means: &[Target],
    c: usize,
    physics: &Model,
) -> Option<(Indicators, IndicatorErrors, [f64; 4])> {
    if means.is_empty() {
        return None;
    }
    let total = means.iter().map(|t| t.runs).sum::<usize>() as f64;
    let (mut values, mut errors, mut absolute) = ([0.0; 4], [0.0; 4], [0.0; 4]);
    for target in means {
        let (_, simulated) = simulate_target_as(target, c, physics)?;
        let weight = target.runs as f64 / total;
        let error = simulated.relative_error(&target.indicators);
        let (got, wanted) = (simulated.values(), target.indicators.values());
        for k in 0..4 {
            values[k] += weight * got[k];
            errors[k] += weight * error[k];
            absolute[k] += weight * (got[k] - wanted[k]).abs();
        }
    }
    let [max_force, impulse, energy_loss, duration] = values;
    let indicators = Indicators {
        max_force,
        impulse,
        energy_loss,
        duration,
    };
    Some((indicators, IndicatorErrors::from_values(errors), absolute))
}

/// Indicator `k`'s error cell of `row` in `table`: the Eq 20 error in per cent, or
/// where the measured mean is not told from zero, |model − measured| in its unit.
fn error_cell(table: &GainTable, row: &GainRow, k: usize, relative: f64) -> String {
    match row.absolute_errors {
        Some(absolute) if table.near_zero[k] => {
            format!("Δ {:.3e} {}", absolute[k], Indicators::NAMES[k].1)
        }
        _ => format!("{:.3}", 100.0 * relative),
    }
}

/// `value`·`unit` with `decimals` decimals, or `failed` where a replay gave NaN.
fn cell(value: f64, unit: f64, decimals: usize) -> String {
    if value.is_nan() {
        "failed".to_owned()
    } else {
        format!("{:.*}", decimals, unit * value)
    }
}

/// What a table's cells need said under it: the models whose replay `failed`, and the
/// indicators given as absolute errors.
fn notes(table: &GainTable, failed: &[&str]) -> String {
    use std::fmt::Write;
    let mut out = String::new();
    if !failed.is_empty() {
        let _ = writeln!(
            out,
            "\n`failed`: the replay of {} stopped on some held-out run (a contact that \
             chatters or never ends under that model), so it has no score there.",
            failed.join(" and ")
        );
    }
    if table.near_zero.iter().any(|z| *z) {
        let names: Vec<&str> = (0..4)
            .filter(|&k| table.near_zero[k])
            .map(|k| Indicators::NAMES[k].0)
            .collect();
        let _ = writeln!(
            out,
            "\nThe measured {} is within {ZERO_SE} standard errors of zero: an error \
             relative to it means nothing, so its cells give Δ = |model − measured| in its \
             unit.",
            names.join(" and ")
        );
    }
    out
}

/// The tables as markdown: one per group, a row per model; the flight columns only
/// where the runs record a flight before their contact.
pub fn markdown(tables: &[GainTable]) -> String {
    use std::fmt::Write;
    let mut out = String::new();
    for (t, table) in tables.iter().enumerate() {
        if t > 0 {
            out.push('\n');
        }
        let flight = table.rows.iter().any(|r| r.flight_rmse.is_finite());
        let _ = writeln!(out, "**{}** ({} runs)\n", table.group, table.runs);
        out.push_str(
            "| model | force RMSE (N) | excess over noise (N) | max force error (%) \
             | impulse error (%) | energy loss error (%) | duration error (%) |",
        );
        if flight {
            out.push_str(" flight δ̇ RMSE (mm/s) | excess over noise (mm/s) |");
        }
        out.push_str("\n|---|---|---|---|---|---|---|");
        if flight {
            out.push_str("---|---|");
        }
        out.push('\n');
        let mut failed = Vec::new();
        for row in &table.rows {
            if row.force_rmse.is_nan() || row.judged.errors.is_none() {
                failed.push(row.judged.model.as_str());
            }
            let _ = write!(
                out,
                "| {} | {} | {} |",
                row.judged.model,
                cell(row.force_rmse, 1.0, 3),
                cell(row.excess_rmse, 1.0, 3)
            );
            match row.judged.errors {
                Some(errors) => {
                    for (k, e) in errors.values().into_iter().enumerate() {
                        let _ = write!(out, " {} |", error_cell(table, row, k, e));
                    }
                }
                None => out.push_str(" failed | failed | failed | failed |"),
            }
            if flight {
                let _ = write!(
                    out,
                    " {} | {} |",
                    cell(row.flight_rmse, 1e3, 4),
                    cell(row.flight_excess, 1e3, 4)
                );
            }
            out.push('\n');
        }
        out.push_str(&notes(table, &failed));
        if flight {
            let _ = writeln!(
                out,
                "\nNoise of the recorded δ̇ in flight: {:.4} mm/s.",
                1e3 * table.flight_noise
            );
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dataset::Run;
    use crate::scenario::Scenario;
    use std::path::Path;
    use std::sync::OnceLock;

    /// A table of one base row against `measured`, with `near_zero` flags.
    fn table_of(measured: [f64; 4], model: [f64; 4], near_zero: [bool; 4]) -> GainTable {
        let of = |[max_force, impulse, energy_loss, duration]: [f64; 4]| Indicators {
            max_force,
            impulse,
            energy_loss,
            duration,
        };
        GainTable {
            group: "held-out runs".into(),
            runs: 4,
            flight_noise: f64::NAN,
            rows: vec![GainRow {
                judged: ModelRow::judged("base", Some(of(model)), &of(measured)),
                absolute_errors: Some(std::array::from_fn(|k| (model[k] - measured[k]).abs())),
                force_rmse: 1.0,
                excess_rmse: 0.5,
                flight_rmse: f64::NAN,
                flight_excess: f64::NAN,
            }],
            near_zero,
        }
    }

    #[test]
    fn an_indicator_not_told_from_zero_gets_an_absolute_error_not_a_percentage() {
        // An elastic contact: the energy lost is noise about 0 (1e-9 J measured).
        let (measured, model) = ([2900.0, 0.18, 1e-9, 1.1e-4], [2910.0, 0.18, 6.9e-3, 1.1e-4]);
        let plain = markdown(&[table_of(measured, model, [false; 4])]);
        assert!(plain.contains("689999900.000"), "{plain}");
        let judged = markdown(&[table_of(measured, model, [false, false, true, false])]);
        assert!(!judged.contains("689999900"), "{judged}");
        assert!(judged.contains("Δ 6.900e-3 N·m"), "{judged}");
        assert!(
            judged.contains("energy_loss is within 2 standard errors of zero"),
            "{judged}"
        );
        // The other cells stay relative: 10 N of 2900 N.
        assert!(judged.contains("| 0.345 |"), "{judged}");
    }

    #[test]
    fn a_failed_replay_is_marked_failed_not_scored() {
        let mut table = table_of([1.0; 4], [1.0; 4], [false; 4]);
        let row = &mut table.rows[0];
        (
            row.judged.indicators,
            row.judged.errors,
            row.absolute_errors,
        ) = (None, None, None);
        row.force_rmse = f64::NAN;
        row.excess_rmse = f64::NAN;
        let text = markdown(&[table]);
        assert!(
            text.contains("| base | failed | failed | failed | failed | failed | failed |"),
            "{text}"
        );
        assert!(text.contains("the replay of base stopped"), "{text}");
        assert!(!text.contains("NaN") && !text.contains("0.000"), "{text}");
    }

    const SIGMA: f64 = 15.0; // N, the scenario's force_noise

    fn ball() -> Model {
        let path = Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../scenarios/bouncing_ball.toml"
        ));
        Scenario::load(path, &[]).unwrap().resolve(path).unwrap()
    }

    /// Six generated runs of the bouncing ball, made once.
    fn generated() -> &'static (Model, Dataset) {
        static DATA: OnceLock<(Model, Dataset)> = OnceLock::new();
        DATA.get_or_init(|| {
            let model = ball();
            // Without the Eq 18 parameter noise, so a perfect model leaves only the
            // sensor noise σ (with it, the nominal law misses each run's own
            // parameters by ~2 % and scores ≈ 21 N).
            let exact = model.scenario.with(&["contact.0.noise={}".into()]).unwrap();
            let data = crate::experiment::generate(&exact, 6, 7, &crate::progress::Silent).unwrap();
            (model, data)
        })
    }

    fn judged<'a>(label: &'a str, physics: &'a Model) -> Judged<'a> {
        Judged {
            label,
            physics,
            sensor: Sensor::default(),
        }
    }

    /// The Eq 20 errors of `row`, in [`Indicators::NAMES`] order; panics if its replay
    /// failed.
    fn errors(row: &GainRow) -> [f64; 4] {
        row.judged.errors.expect("the replay succeeds").values()
    }

    fn ids(ids: &[String]) -> Dataset {
        let runs = ids
            .iter()
            .map(|id| Run {
                id: id.clone(),
                bodies: Vec::new(),
            })
            .collect();
        Dataset { runs }
    }

    fn conditioned(names: &[&str], per: usize) -> Dataset {
        let ids: Vec<String> = names
            .iter()
            .flat_map(|n| (0..per).map(move |k| format!("{n}/{k}")))
            .collect();
        super::tests::ids(&ids)
    }

    fn check_partition(h: &Holdout, n: usize) {
        let mut all: Vec<usize> = h.training.iter().chain(&h.held_out).copied().collect();
        all.sort_unstable();
        assert_eq!(all, (0..n).collect::<Vec<_>>(), "{h:?}");
    }

    #[test]
    fn holdout_is_deterministic_per_seed() {
        let model = ball();
        let data = ids(&(0..20).map(|k| format!("{k:02}")).collect::<Vec<_>>());
        let a = holdout(&model, &data, 1, 0.25);
        assert_eq!(a, holdout(&model, &data, 1, 0.25));
        assert_ne!(a.held_out, holdout(&model, &data, 2, 0.25).held_out);
        assert_eq!((a.held_out.len(), a.condition.clone()), (5, None));
        check_partition(&a, 20);
        // Even a zero share holds out one run, and a full share keeps one for training.
        assert_eq!(holdout(&model, &data, 1, 0.0).held_out.len(), 1);
        assert_eq!(holdout(&model, &data, 1, 1.0).training.len(), 1);
    }

    #[test]
    fn holdout_takes_a_whole_condition_and_some_others() {
        let mut model = ball();
        let data = conditioned(&["a", "b", "c", "d"], 5);
        let in_condition = |h: &Holdout, name: &str| {
            h.held_out
                .iter()
                .filter(|&&i| condition_of(&data.runs[i].id) == name)
                .count()
        };
        let last = holdout(&model, &data, 3, 0.2);
        assert_eq!(last.condition.as_deref(), Some("d"));
        assert_eq!(in_condition(&last, "d"), 5);
        assert_eq!(last.held_out.len(), 5 + 3, "{last:?}"); // 20 % of the other 15
        check_partition(&last, 20);
        model.scenario.experiment.holdout_conditions = vec!["b".into()];
        let named = holdout(&model, &data, 3, 0.2);
        assert_eq!(named.condition.as_deref(), Some("b"));
        assert_eq!(in_condition(&named, "b"), 5);
        assert!(named.held_out.len() > 5 && !named.training.is_empty());
        // A named condition absent from the data falls back to the last one.
        model.scenario.experiment.holdout_conditions = vec!["v9".into()];
        assert_eq!(
            holdout(&model, &data, 3, 0.2).condition.as_deref(),
            Some("d")
        );
        // Two conditions are no range to step out of.
        assert_eq!(
            holdout(&model, &conditioned(&["a", "b"], 5), 3, 0.2).condition,
            None
        );
    }

    #[test]
    fn the_true_model_gains_over_a_wrong_one() {
        let (model, data) = generated();
        let mut wrong = model.clone();
        let law = &mut wrong.contacts[0].model.normal.base;
        law.set("damping", 0.5 * law.get("damping").unwrap())
            .unwrap();
        let runs: Vec<usize> = (0..data.runs.len()).collect();
        let models = [judged("true", model), judged("damping ×0.5", &wrong)];
        let tables = gain(model, data, &runs, 0, SIGMA, &models).unwrap();
        eprintln!("{}", markdown(&tables));
        assert_eq!(tables.len(), 1);
        let (t, w) = (&tables[0].rows[0], &tables[0].rows[1]);
        assert_eq!(
            (tables[0].group.as_str(), tables[0].runs),
            ("held-out runs", 6)
        );
        assert!((t.force_rmse - SIGMA).abs() < 0.1 * SIGMA, "{t:?}");
        assert!(t.excess_rmse < 0.5 * w.excess_rmse, "{t:?}\n{w:?}");
        for k in 0..4 {
            assert!(errors(t)[k] < errors(w)[k], "indicator {k}: {t:?}\n{w:?}");
        }
    }

    /// Four runs of the ball generated with `overrides`, without parameter noise.
    fn generated_with(overrides: &[&str]) -> (Model, Dataset) {
        let mut all = vec!["contact.0.noise={}".to_owned()];
        all.extend(overrides.iter().map(|o| o.to_string()));
        let truth = ball().scenario.with(&all).unwrap();
        let data = crate::experiment::generate(&truth, 4, 11, &crate::progress::Silent).unwrap();
        let path = Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../scenarios/bouncing_ball.toml"
        ));
        (truth.resolve(path).unwrap(), data)
    }

    #[test]
    fn a_model_with_the_sensor_found_is_judged_on_corrected_data() {
        let (truth, data) = generated_with(&[
            "experiment.force_offset=[0.0, 0.0, 40.0]",
            "experiment.sensor_delay=1e-6",
            "experiment.force_gain=1.03",
        ]);
        // The generator adds its offset after the gain, the sensor model before it.
        let corrected = Judged {
            sensor: Sensor {
                offset: 40.0 / 1.03,
                delay: 1e-6,
                gain: 1.03,
                filter: 0.0,
            },
            ..judged("sensor corrected", &truth)
        };
        let models = [judged("as recorded", &truth), corrected];
        let tables = gain(&truth, &data, &[0, 1, 2, 3], 0, SIGMA, &models).unwrap();
        eprintln!("{}", markdown(&tables));
        let (raw, fixed) = (&tables[0].rows[0], &tables[0].rows[1]);
        // The same physics: only the correction of the data differs. Re-timed, the
        // corrected samples keep the noise σ, so the true model scores σ.
        assert!((fixed.force_rmse - SIGMA).abs() < 0.1 * SIGMA, "{fixed:?}");
        assert!(raw.excess_rmse > 30.0 && fixed.excess_rmse < 0.2 * raw.excess_rmse);
        assert!(
            errors(fixed)[0] < 0.3 * errors(raw)[0],
            "{raw:?}\n{fixed:?}"
        );
        assert!(
            errors(fixed)[1] < 0.3 * errors(raw)[1],
            "{raw:?}\n{fixed:?}"
        );
    }

    #[test]
    fn air_drag_is_judged_on_the_flight() {
        let (truth, data) = generated_with(&[
            "body.ball.air_drag={ coefficient = 0.02 }",
            "experiment.velocity_noise=1e-4",
        ]);
        let mut without = truth.clone();
        without.bodies[0].air_drag = None;
        let models = [judged("no drag", &without), judged("drag", &truth)];
        let tables = gain(&truth, &data, &[0, 1, 2, 3], 0, SIGMA, &models).unwrap();
        let table = &tables[0];
        eprintln!("σ_v = {:e} m/s\n{}", table.flight_noise, markdown(&tables));
        assert!((table.flight_noise - 1e-4).abs() < 0.2e-4, "{table:?}");
        let (none, drag) = (&table.rows[0], &table.rows[1]);
        // Over the 0.14 s fall the drag takes up to ≈ 12 mm/s off δ̇; the noise is 0.1 mm/s.
        assert!(none.flight_excess > 3e-3, "{none:?}");
        assert!(drag.flight_excess < 0.1 * none.flight_excess, "{drag:?}");
        // Replayed from the state just before contact, the contact force is the same.
        assert!((none.force_rmse - drag.force_rmse).abs() < 0.01 * SIGMA);
    }

    #[test]
    fn a_held_out_condition_gets_its_own_table() {
        let (model, data) = generated();
        // The same physics under three names: grouping only.
        let mut data = data.clone();
        for (k, run) in data.runs.iter_mut().enumerate() {
            run.id = format!("{}/{}", ["a", "b", "c"][k / 2], k % 2);
        }
        let mut broken = model.clone();
        broken.contacts[0].model.normal.base = model.contacts[0].law().map_named(|_, _| f64::NAN);
        let models = [judged("true", model), judged("broken", &broken)];
        let tables = gain(model, &data, &[1, 2, 4, 5], 0, SIGMA, &models).unwrap();
        let groups: Vec<_> = tables.iter().map(|t| (t.group.as_str(), t.runs)).collect();
        assert_eq!(groups, [("held-out runs", 2), ("condition c", 2)]);
        for table in &tables {
            assert!(table.rows[0].force_rmse.is_finite() && errors(&table.rows[0])[0] < 0.05);
            assert!(table.rows[1].force_rmse.is_nan() && table.rows[1].judged.errors.is_none());
        }
        let text = markdown(&tables);
        assert!(text.contains("**condition c** (2 runs)") && text.contains("| broken | failed |"));
        assert_eq!(text.matches("| model | force RMSE (N) |").count(), 2);
        assert!(gain(model, &data, &[6], 0, SIGMA, &models).is_err());
    }
}
