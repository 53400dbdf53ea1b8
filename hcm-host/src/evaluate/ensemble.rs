//! `hcm evaluate --members N`: each condition's contact forecast by an ensemble of the
//! model's runs — member m the model with its contacts' parameters drawn from their
//! `noise` (the run-to-run scatter of Eq 18, as a forecast draws it:
//! [`crate::experiment::member_model`]), replayed from the condition's mean pre-contact
//! state as the paper's table replays the model — and scored run by run against the
//! measured indicators by a proper score, the fair CRPS, beside the model's single
//! replay scored the same way (one member: the absolute error). Where the runs differ
//! from one another, a model that spreads as they do scores better than one that is
//! sure; the bands' coverage says whether the spread is the runs' own.

use crate::dataset::Dataset;
use crate::experiment::member_model;
use crate::identify::{simulate_target_with, targets, IdentifyError, Target};
use crate::indicators::Indicators;
use crate::numerics::scores::{calibrated_coverage, central_band, fair_crps};
use crate::scenario::Model;
use rayon::prelude::*;
use serde::Serialize;

/// The central bands whose coverage is reported (–): 50 % and 90 %.
pub const LEVELS: [f64; 2] = [0.5, 0.9];

/// One condition's indicators forecast by an ensemble, scored against its runs.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct IndicatorForecast {
    /// Condition name ("" without conditions).
    pub condition: String,
    /// Runs scored: those with a contact (–).
    pub runs: usize,
    /// Members drawn (–).
    pub members: usize,
    /// Members left out: their simulation failed or made no contact (–).
    pub failed: usize,
    /// Each indicator's fair CRPS per run, averaged over the runs, in % of the measured
    /// mean ([`Indicators::NAMES`] order); NaN (JSON `null`) where no member made contact.
    pub crps: [f64; 4],
    /// The same of the model's single replay (its contacts as given, no scatter): its
    /// mean absolute error per run (%).
    pub replay_crps: [f64; 4],
    /// Share of the runs' indicators, all four, inside the members' central 50 % and
    /// 90 % bands (–).
    pub inside: [f64; 2],
    /// What such bands of the members that made contact hold of outcomes drawn like
    /// them (–): the levels, or less for so few members that a band is their range.
    pub calibrated: [f64; 2],
}

/// Every condition of `data` (contact `c`) forecast by `members` runs of `model` drawn
/// from its contacts' `noise` with `seed` (member m from stream m: the same members on
/// any number of threads, member m the same whatever the member count).
pub fn evaluate_members(
    model: &Model,
    data: &Dataset,
    c: usize,
    members: usize,
    seed: u64,
) -> Result<Vec<IndicatorForecast>, IdentifyError> {
    let targets = targets(model, data, c)?;
    Ok((targets.iter())
        .map(|target| condition_forecast(target, c, members, seed))
        .collect())
}

/// The forecast of one condition's `target`.
fn condition_forecast(target: &Target, c: usize, members: usize, seed: u64) -> IndicatorForecast {
    let drawn: Vec<Option<Indicators>> = (0..members)
        .into_par_iter()
        .map(|m| {
            let member = member_model(&target.model, seed, m).ok()?;
            simulate_target_with(target, c, &member.contacts[c]).map(|(_, i)| i)
        })
        .collect();
    let ensemble: Vec<[f64; 4]> = drawn.iter().flatten().map(Indicators::values).collect();
    let replay: Vec<[f64; 4]> = simulate_target_with(target, c, &target.model.contacts[c])
        .map(|(_, i)| vec![i.values()])
        .unwrap_or_default();
    let measured = target.indicators.values();
    let (inside, outcomes) = band_counts(&ensemble, &target.run_indicators);
    IndicatorForecast {
        condition: target.condition.clone(),
        runs: target.run_indicators.len(),
        members,
        failed: members - ensemble.len(),
        crps: mean_crps(&ensemble, &target.run_indicators, &measured),
        replay_crps: mean_crps(&replay, &target.run_indicators, &measured),
        inside: inside.map(|k| k as f64 / outcomes.max(1) as f64),
        calibrated: LEVELS.map(|level| calibrated_coverage(ensemble.len(), level)),
    }
}

/// Each indicator's fair CRPS of `members` per run of `runs`, averaged, in % of the
/// measured mean `measured` (NaN without members or runs).
fn mean_crps(members: &[[f64; 4]], runs: &[Indicators], measured: &[f64; 4]) -> [f64; 4] {
    std::array::from_fn(|i| {
        if members.is_empty() || runs.is_empty() {
            return f64::NAN;
        }
        let values: Vec<f64> = members.iter().map(|m| m[i]).collect();
        let total: f64 = (runs.iter())
            .map(|r| fair_crps(&values, r.values()[i]))
            .sum();
        100.0 * total / runs.len() as f64 / measured[i].abs()
    })
}

/// How many of the runs' indicators (all four of each run) lie inside the members'
/// central bands of [`LEVELS`], and of how many.
fn band_counts(members: &[[f64; 4]], runs: &[Indicators]) -> ([usize; 2], usize) {
    let mut inside = [0; 2];
    if members.is_empty() {
        return (inside, 0);
    }
    for i in 0..4 {
        let values: Vec<f64> = members.iter().map(|m| m[i]).collect();
        for (count, level) in inside.iter_mut().zip(LEVELS) {
            let (lo, hi) = central_band(&values, level);
            *count += (runs.iter())
                .filter(|r| (lo..=hi).contains(&r.values()[i]))
                .count();
        }
    }
    (inside, 4 * runs.len())
}

/// The forecasts as a markdown table: per condition, the single replay's and the
/// ensemble's CRPS of each indicator and the bands' coverage.
pub fn members_markdown(forecasts: &[IndicatorForecast]) -> String {
    use std::fmt::Write;
    let mut out = String::from(
        "| condition | runs | forecast | CRPS: max force (%) | impulse (%) | energy loss (%) \
         | duration (%) | inside 50 % band | inside 90 % band |\n|---|---|---|---|---|---|---|---|---|\n",
    );
    let cell = |x: f64| match x.is_finite() {
        true => format!("{x:.2}"),
        false => "n/a".to_owned(),
    };
    for f in forecasts {
        let name = if f.condition.is_empty() {
            "all"
        } else {
            &f.condition
        };
        let crps = |v: &[f64; 4]| v.map(cell).join(" | ");
        let _ = writeln!(
            out,
            "| {name} | {} | single replay | {} | — | — |",
            f.runs,
            crps(&f.replay_crps)
        );
        let _ = writeln!(
            out,
            "| {name} | {} | ensemble of {} | {} | {:.3} | {:.3} |",
            f.runs,
            f.members - f.failed,
            crps(&f.crps),
            f.inside[0],
            f.inside[1]
        );
    }
    if let Some(f) = forecasts.first() {
        let _ = writeln!(
            out,
            "\nCRPS per run, in % of the measured mean (lower is better; a single replay's is \
             its absolute error). Bands of {} members drawn like the runs hold {:.3} and {:.3} \
             of them.",
            f.members - f.failed,
            f.calibrated[0],
            f.calibrated[1]
        );
    }
    out
}
