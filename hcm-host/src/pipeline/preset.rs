//! `hcm reproduce <example>` as presets over the stages: each example's shipped
//! scenario (built into the program), its defaults and the table it is compared with,
//! one entry point ([`Preset::reproduce`]) and one writer
//! ([`super::write_reproduction`]).

use super::cube::{reproduce_cube, CubeSettings};
use super::peg::{reproduce_peg, PegSettings};
use super::{reproduce, PipelineError, Progress, ReproduceSettings, Reproduced};
use crate::scenario::{Scenario, ScenarioError};
#[cfg(test)]
use std::path::Path;
use std::path::PathBuf;

/// The scenarios shipped with hcm, one per example, built into the program so that
/// `hcm reproduce` runs from any directory, with or without the repository.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shipped {
    /// `scenarios/bouncing_ball.toml` (the paper's Section 5.1).
    BouncingBall,
    /// `scenarios/flat_shot.toml` (Section 5.2).
    FlatShot,
    /// `scenarios/peg_in_hole.toml` (Section 5.3).
    PegInHole,
    /// `scenarios/cube_toss.toml` (the ContactNets tosses).
    CubeToss,
    /// `scenarios/elbow_toss.toml` (the ContactNets elbow's tosses).
    ElbowToss,
}

impl Shipped {
    /// Its file name in the repository's `scenarios/`.
    pub fn file(self) -> &'static str {
        match self {
            Shipped::BouncingBall => "bouncing_ball.toml",
            Shipped::FlatShot => "flat_shot.toml",
            Shipped::PegInHole => "peg_in_hole.toml",
            Shipped::CubeToss => "cube_toss.toml",
            Shipped::ElbowToss => "elbow_toss.toml",
        }
    }

    /// The file's text as built into the program.
    pub(crate) fn text(self) -> &'static str {
        match self {
            Shipped::BouncingBall => include_str!("../../scenarios/bouncing_ball.toml"),
            Shipped::FlatShot => include_str!("../../scenarios/flat_shot.toml"),
            Shipped::PegInHole => include_str!("../../scenarios/peg_in_hole.toml"),
            Shipped::CubeToss => include_str!("../../scenarios/cube_toss.toml"),
            Shipped::ElbowToss => include_str!("../../scenarios/elbow_toss.toml"),
        }
    }
}

/// The scenario an example runs on: its shipped one or a user's file, with values
/// overridden.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ScenarioChoice {
    /// The example's shipped scenario, used when `file` is `None`.
    pub shipped: Shipped,
    /// A scenario file to run instead.
    pub file: Option<PathBuf>,
    /// Overrides of the scenario's values (`key=value`, as [`Scenario::load`] takes
    /// them).
    pub overrides: Vec<String>,
}

impl ScenarioChoice {
    /// The shipped scenario of an example, unchanged.
    pub fn shipped(shipped: Shipped) -> Self {
        ScenarioChoice {
            shipped,
            file: None,
            overrides: Vec::new(),
        }
    }

    /// How errors and reports name it: the file as given, or
    /// `scenarios/NAME.toml (built in)` for the shipped one.
    pub fn label(&self) -> PathBuf {
        match &self.file {
            Some(path) => path.clone(),
            None => PathBuf::from(format!("scenarios/{} (built in)", self.shipped.file())),
        }
    }

    /// The scenario, overrides applied.
    pub fn load(&self) -> Result<Scenario, ScenarioError> {
        match &self.file {
            Some(path) => Scenario::load(path, &self.overrides),
            None => Scenario::parse(&self.label(), self.shipped.text(), &self.overrides),
        }
    }
}

/// One example as `hcm reproduce` runs it: the stages it chains, on its settings.
#[derive(Clone, Debug, PartialEq)]
pub enum Preset {
    /// The paper's 1D examples (the ball, the flat shot): Tables 5 and 10.
    Paper(ReproduceSettings),
    /// The paper's peg-in-hole: Table 15.
    PegInHole(PegSettings),
    /// Real filmed tosses (the cube's against the published peers, the elbow's).
    CubeToss(CubeSettings),
}

impl Preset {
    /// Runs the example's stages; the caller writes what they made with
    /// [`super::write_reproduction`].
    pub fn reproduce(&self, progress: &dyn Progress) -> Result<Box<dyn Reproduced>, PipelineError> {
        Ok(match self {
            Preset::Paper(settings) => Box::new(reproduce(settings, progress)?),
            Preset::PegInHole(settings) => Box::new(reproduce_peg(settings, progress)?),
            Preset::CubeToss(settings) => Box::new(reproduce_cube(settings, progress)?),
        })
    }
}

/// The shipped scenario `shipped` parsed as it is (for tests).
#[cfg(test)]
pub(crate) fn shipped_scenario(shipped: Shipped) -> Scenario {
    Scenario::parse(Path::new(shipped.file()), shipped.text(), &[]).unwrap()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_shipped_scenario_parses_and_is_the_repository_file() {
        for shipped in [
            Shipped::BouncingBall,
            Shipped::FlatShot,
            Shipped::PegInHole,
            Shipped::CubeToss,
            Shipped::ElbowToss,
        ] {
            let on_disk = Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("../scenarios")
                .join(shipped.file());
            assert_eq!(
                std::fs::read_to_string(&on_disk).unwrap(),
                shipped.text(),
                "{}",
                shipped.file()
            );
            shipped_scenario(shipped).model().unwrap();
        }
        let choice = ScenarioChoice {
            overrides: vec!["simulation.end_time=0.5".into()],
            ..ScenarioChoice::shipped(Shipped::PegInHole)
        };
        assert_eq!(
            choice.label(),
            Path::new("scenarios/peg_in_hole.toml (built in)")
        );
        assert_eq!(choice.load().unwrap().simulation.end_time, 0.5);
    }
}
