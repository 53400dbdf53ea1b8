//! The paper's route to PM2: a genetic algorithm whose fitness compares simulations of
//! a candidate law with the measured data, replayed per condition ([`super::replay`]).

use super::bounds::Bounds;
use super::replay::{simulate_target, Target};
use super::IdentifyError;
use crate::numerics::optimize::genetic::{minimize, GeneticSettings};
use crate::numerics::optimize::levenberg_marquardt::{levenberg_marquardt, LmSettings};
use crate::numerics::optimize::{Observer, Parameters};
use hcm_core::law::AnyNormalLaw;

/// What the genetic algorithm minimises.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fitness {
    /// RMS difference (N) between simulated and mean measured force curves over the
    /// contact, all conditions together (the default: it uses the whole curve, so it
    /// constrains stiffness, exponent and damping at once).
    Curve,
    /// Sum over conditions and the four indicators of the squared relative error.
    Indicators,
}

impl Fitness {
    /// Name on the command line.
    pub fn name(&self) -> &'static str {
        match self {
            Fitness::Curve => "curve",
            Fitness::Indicators => "indicators",
        }
    }
}

/// Number of residuals [`residuals`] writes for `targets`.
pub(crate) fn residual_count(targets: &[Target], kind: Fitness) -> usize {
    match kind {
        Fitness::Curve => targets.iter().map(|t| t.curve.len()).sum(),
        Fitness::Indicators => 4 * targets.len(),
    }
}

/// The mismatch of `law` with `targets` as a vector: simulated − measured force at
/// every curve point (N), or the relative error of every indicator. NaN where a
/// simulation fails.
pub fn residuals(
    law: &AnyNormalLaw<f64>,
    targets: &[Target],
    c: usize,
    kind: Fitness,
    out: &mut [f64],
) {
    let mut at = 0;
    for target in targets {
        let simulated = simulate_target(target, c, law);
        let len = match kind {
            Fitness::Curve => target.curve.len(),
            Fitness::Indicators => 4,
        };
        let slot = &mut out[at..at + len];
        match (&simulated, kind) {
            (None, _) => slot.fill(f64::NAN),
            (Some((curve, _)), Fitness::Curve) => slot
                .iter_mut()
                .zip(curve.iter().zip(&target.curve))
                .for_each(|(r, (a, b))| *r = a - b),
            (Some((_, indicators)), Fitness::Indicators) => {
                let (sim, measured) = (indicators.values(), target.indicators.values());
                slot.iter_mut()
                    .enumerate()
                    .for_each(|(i, r)| *r = (sim[i] - measured[i]) / measured[i]);
            }
        }
        at += len;
    }
}

/// The fitness of `law`: RMS of the curve residuals (N), or the sum of squared
/// relative indicator errors; +∞ when a simulation fails.
pub fn fitness(law: &AnyNormalLaw<f64>, targets: &[Target], c: usize, kind: Fitness) -> f64 {
    let mut r = vec![0.0; residual_count(targets, kind)];
    residuals(law, targets, c, kind, &mut r);
    let sum: f64 = r.iter().map(|x| x * x).sum();
    let value = match kind {
        Fitness::Curve => (sum / r.len().max(1) as f64).sqrt(),
        Fitness::Indicators => sum,
    };
    if value.is_nan() {
        f64::INFINITY
    } else {
        value
    }
}

/// Runs the genetic algorithm over the free parameters of `template` in `bounds`,
/// telling `observer` of each generation.
pub fn fit(
    template: &AnyNormalLaw<f64>,
    bounds: &Bounds,
    targets: &[Target],
    c: usize,
    kind: Fitness,
    settings: &GeneticSettings,
    observer: impl Observer,
) -> Result<GaOutcome, IdentifyError> {
    bounds.check(template)?;
    let with = |p: &[f64]| bounds.with(template, p);
    let result = minimize(
        &bounds.bounds(),
        settings,
        |p| fitness(&with(p), targets, c, kind),
        observer,
    )?;
    // Polish: Levenberg–Marquardt on the same mismatch, started from the GA's best.
    // The GA finds the basin; in the narrow k–n valley of these laws it would need
    // thousands more simulations to reach the bottom that LM reaches in a few dozen.
    let scales: Vec<f64> = result.best.iter().map(|v| v.abs().max(1e-12)).collect();
    let box_bounds = bounds.bounds();
    let polished = levenberg_marquardt(
        |p: &[f64], out: &mut [f64]| residuals(&with(p), targets, c, kind, out),
        residual_count(targets, kind),
        &result.best,
        &scales,
        Some(&box_bounds),
        &LmSettings::default(),
    );
    let law = match polished {
        Ok(lm) if fitness(&with(&lm.parameters), targets, c, kind) <= result.fitness => {
            with(&lm.parameters)
        }
        _ => with(&result.best),
    };
    Ok(GaOutcome {
        law,
        ga_fitness: result.fitness,
        generations: result.generations,
        evaluations: result.evaluations,
    })
}

/// What the genetic route found.
#[derive(Clone, Debug)]
pub struct GaOutcome {
    /// The law after polishing.
    pub(crate) law: AnyNormalLaw<f64>,
    /// The GA's own best fitness, before polishing.
    pub(crate) ga_fitness: f64,
    /// Generations run.
    pub(crate) generations: usize,
    /// Fitness evaluations (simulations of every condition).
    pub(crate) evaluations: usize,
}
