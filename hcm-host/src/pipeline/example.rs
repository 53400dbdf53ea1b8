//! The paper's two examples and how to reproduce them.

use super::results::PaperErrors;
use crate::evaluate::IndicatorErrors;
use crate::identify::evolve::Fitness;
use crate::identify::genetic::GeneticSettings;
use crate::identify::Method;
use serde::Serialize;
use std::path::PathBuf;

/// The paper's examples.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Example {
    /// Section 5.1, Table 5: a ball dropped on a plate.
    BouncingBall,
    /// Section 5.2, Table 10: a plate shot flat at ten speeds.
    FlatShot,
}

impl Example {
    /// Its scenario file in the repository's `scenarios/`.
    pub fn file(self) -> &'static str {
        match self {
            Example::BouncingBall => "bouncing_ball.toml",
            Example::FlatShot => "flat_shot.toml",
        }
    }

    /// Runs per condition as in the paper (1000 ball runs; 10 speeds × 100).
    pub fn runs(self) -> usize {
        match self {
            Example::BouncingBall => 1000,
            Example::FlatShot => 100,
        }
    }

    /// The paper's PM2 and HCM errors (Tables 5 and 10), as fractions (–).
    pub fn paper(self) -> PaperErrors {
        let (pm2, hcm) = match self {
            Example::BouncingBall => ([1.58, 0.31, 8.05, 0.88], [0.12, 0.01, 0.01, 0.01]),
            Example::FlatShot => ([0.46, 1.02, 37.50, 0.86], [0.16, 0.02, 4.17, 0.01]),
        };
        // The tables print per cent.
        let fraction = |percent: [f64; 4]| IndicatorErrors::from_values(percent.map(|p| p / 100.0));
        PaperErrors {
            pm2: fraction(pm2),
            hcm: fraction(hcm),
        }
    }
}

/// How PM2 is identified.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Pm2Method {
    /// The paper's genetic algorithm on the replayed force curves, polished by
    /// Levenberg–Marquardt.
    Ga,
    /// Separable least squares on the force samples.
    Lsq,
}

impl Pm2Method {
    /// The identification method, seeded with `seed`.
    pub fn method(self, seed: u64) -> Method {
        match self {
            Pm2Method::Lsq => Method::Lsq,
            Pm2Method::Ga => Method::Ga(
                Fitness::Curve,
                GeneticSettings {
                    population: 60,
                    generations: 150,
                    seed,
                    ..GeneticSettings::default()
                },
            ),
        }
    }
}

/// What [`super::reproduce`] runs.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ReproduceSettings {
    /// Which example (its paper figures).
    pub example: Example,
    /// Its scenario file.
    pub scenario: PathBuf,
    /// Overrides of the scenario's values (`key=value`, as
    /// [`crate::scenario::Scenario::load`] takes them).
    pub overrides: Vec<String>,
    /// Seed of the experiment, the split, the GA and the training.
    pub seed: u64,
    /// Runs per condition.
    pub runs: usize,
    /// PM2's identification.
    pub method: Pm2Method,
}

impl ReproduceSettings {
    /// The paper's run count and method for `example` (its scenario read from
    /// `scenario`), seed 1.
    pub fn paper(example: Example, scenario: PathBuf) -> Self {
        Self {
            example,
            scenario,
            overrides: Vec::new(),
            seed: 1,
            runs: example.runs(),
            method: Pm2Method::Ga,
        }
    }
}
