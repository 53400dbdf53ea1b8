//! The paper's route to PM2: a genetic algorithm whose fitness compares simulations of
//! a candidate law with the measured data, replayed per condition ([`super::replay`]).

use super::bounds::Bounds;
use super::genetic::{minimize, GeneticSettings};
use super::replay::{simulate_target, Target};
use super::IdentifyError;
use crate::law_catalogue;
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

/// The fitness of `law` against `targets` (+∞ when a simulation fails).
pub fn fitness(law: &AnyNormalLaw<f64>, targets: &[Target], c: usize, kind: Fitness) -> f64 {
    let mut total = 0.0;
    let mut count = 0.0;
    for target in targets {
        let Some((curve, indicators)) = simulate_target(target, c, law) else {
            return f64::INFINITY;
        };
        match kind {
            Fitness::Curve => {
                total += curve
                    .iter()
                    .zip(&target.curve)
                    .map(|(a, b)| (a - b).powi(2))
                    .sum::<f64>();
                count += curve.len() as f64;
            }
            Fitness::Indicators => {
                total += indicators
                    .relative_error(&target.indicators)
                    .iter()
                    .map(|e| e * e)
                    .sum::<f64>();
                count = 1.0;
            }
        }
    }
    match kind {
        Fitness::Curve => (total / count.max(1.0)).sqrt(),
        Fitness::Indicators => total,
    }
}

/// Runs the genetic algorithm over the free parameters of `template` in `bounds`.
pub fn fit(
    template: &AnyNormalLaw<f64>,
    bounds: &Bounds,
    targets: &[Target],
    c: usize,
    kind: Fitness,
    settings: &GeneticSettings,
    mut progress: impl FnMut(usize, usize, f64),
) -> Result<AnyNormalLaw<f64>, IdentifyError> {
    let free = bounds.free();
    let with = |p: &[f64]| {
        law_catalogue::map_parameters(template, |name, v| {
            free.iter().position(|f| *f == name).map_or(v, |i| p[i])
        })
    };
    let generations = settings.generations;
    let result = minimize(
        &bounds.genetic(),
        settings,
        |p| fitness(&with(p), targets, c, kind),
        |generation, best| progress(generation, generations, best),
    )?;
    Ok(with(&result.best))
}
