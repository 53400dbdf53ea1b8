//! The paper's two examples and how to reproduce them.

use super::preset::{ScenarioChoice, Shipped};
use super::results::PaperErrors;
use crate::evaluate::IndicatorErrors;
use crate::identify::Fitness;
use crate::identify::Method;
use crate::numerics::optimize::genetic::GeneticSettings;
use serde::Serialize;

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
    /// Its name on the command line and in reports (`bouncing-ball`).
    pub fn name(self) -> &'static str {
        match self {
            Example::BouncingBall => "bouncing-ball",
            Example::FlatShot => "flat-shot",
        }
    }

    /// Where the paper has it: section and results table.
    pub fn section(self) -> &'static str {
        match self {
            Example::BouncingBall => "Section 5.1, Table 5",
            Example::FlatShot => "Section 5.2, Table 10",
        }
    }

    /// Its scenario shipped with hcm.
    pub fn shipped(self) -> Shipped {
        match self {
            Example::BouncingBall => Shipped::BouncingBall,
            Example::FlatShot => Shipped::FlatShot,
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
    /// Its scenario: the example's shipped one unless a file is given.
    pub scenario: ScenarioChoice,
    /// Seed of the experiment, the split, the GA and the training.
    pub seed: u64,
    /// Runs per condition.
    pub runs: usize,
    /// PM2's identification.
    pub method: Pm2Method,
}

impl ReproduceSettings {
    /// The paper's run count and method for `example` on its shipped scenario, seed 1.
    pub fn paper(example: Example) -> Self {
        Self {
            example,
            scenario: ScenarioChoice::shipped(example.shipped()),
            seed: 1,
            runs: example.runs(),
            method: Pm2Method::Ga,
        }
    }
}
