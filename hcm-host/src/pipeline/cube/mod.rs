//! `hcm reproduce cube-toss`: identification from motion end to end on filmed tosses — the tosses split
//! by toss number ([`split_tosses`]), the contact fitted from motion alone on the
//! training part (`identify_motion`), the held-out tosses predicted with the fitted
//! model and with the scenario's own parameters beside the frozen pose, the second fold
//! (the same fit on the held-out part, judged on the training part: every toss
//! predicted by a fit that never saw it), their error over
//! time and per phase ([`errors`], [`phases`]), the diagnosis of what the fitted model
//! still gets wrong (`diagnose_motion`), and the report's figures (`figures`).
//! Nothing here prints or writes a file: progress goes to a [`Progress`], and the
//! caller writes what comes back.

mod cross_validated;
mod errors;
mod faces;
mod figures;
mod forecast;
mod forecast_figures;
mod peers;
mod phases;
mod report;
mod results;
mod stages;

pub use figures::toss_figures;
pub use forecast::{chance_forecast, ForecastResults};
pub use peers::Peers;
pub use results::CubeResults;
pub use stages::{Predictions, SecondFold};

use crate::dataset::{DataError, Dataset};
use crate::diagnose::{diagnose_motion_split, MotionDiagnoseError, MotionDiagnosis};
use crate::identify::{split_tosses, MotionFit};
use crate::numerics::optimize::genetic::GeneticError;
use crate::replay::{TossError, TossSetup};
use crate::scenario::{Assignment, Model, Scenario, ScenarioError};
use std::path::{Path, PathBuf};

use super::{
    Artifact, Fold, NamedFigure, Progress, Reproduced, ScenarioChoice, Shipped, StageClock,
    StageTiming,
};
use crate::identify::fitted_physics;
use crate::replay::predicted_dataset;
use std::borrow::Cow;

/// What [`reproduce_cube`] runs.
#[derive(Clone, Debug, PartialEq)]
pub struct CubeSettings {
    /// The tosses (measured-data CSV).
    pub data: PathBuf,
    /// Use only the first N runs of the data (before the split).
    pub first: Option<usize>,
    /// Its scenario: the shipped `cube_toss.toml` unless a file is given.
    pub scenario: ScenarioChoice,
    /// Seed of the genetic algorithm.
    pub seed: u64,
    /// GA individuals per generation.
    pub population: usize,
    /// GA generations.
    pub generations: usize,
    /// Fitness evaluations of the Nelder–Mead polish.
    pub polish: usize,
    /// Whether to diagnose the fitted model (most of the run's time).
    pub diagnose: bool,
    /// Replays per toss of the final faces' ensembles (0: no faces stage).
    pub face_members: usize,
    /// The example's name in the report and the files' comments (`cube-toss`,
    /// `elbow-toss`).
    pub name: &'static str,
    /// The fits — the GA's, the polish's, the diagnosis' candidates' — see every
    /// `fit_stride`th toss of their part (1: all); every toss of the other part is
    /// predicted and judged. A mechanism replays 20 times slower than the cube
    /// (criterion, `benches/ball_simulation.rs`): its fits see a quarter of the tosses
    /// so that the whole run stays within 15 minutes.
    pub fit_stride: usize,
    /// Whether the diagnosis tries chance after the deterministic effects (issue 48).
    pub chance: bool,
}

impl CubeSettings {
    /// The defaults of `hcm reproduce cube-toss` on `data`: those of
    /// `hcm identify-motion` (population 20, 10 generations, 40 polish evaluations),
    /// which keep the whole run, diagnosis included, under 15 minutes on two cores.
    pub fn shipped(data: &Path) -> CubeSettings {
        CubeSettings {
            data: data.to_owned(),
            first: None,
            scenario: ScenarioChoice::shipped(Shipped::CubeToss),
            seed: 1,
            population: 20,
            generations: 10,
            polish: 40,
            diagnose: true,
            face_members: 16,
            name: "cube-toss",
            fit_stride: 1,
            chance: true,
        }
    }

    /// The defaults of `hcm reproduce elbow-toss` on `data`: the shipped elbow (a free
    /// hinge: what it lacks is the diagnosis' question), a GA of 12 × 8 and a polish of
    /// 30, fits on every fourth toss of their part (55 of the 217 even tosses), no faces
    /// (a mechanism's are not forecast), no chance — within 15 minutes on two cores
    /// (docs/real-data.md, "The elbow").
    pub fn elbow(data: &Path) -> CubeSettings {
        CubeSettings {
            scenario: ScenarioChoice::shipped(Shipped::ElbowToss),
            population: 12,
            generations: 8,
            polish: 30,
            face_members: 0,
            name: "elbow-toss",
            fit_stride: 4,
            chance: false,
            ..CubeSettings::shipped(data)
        }
    }
}

/// Every `stride`th run of `data` (1: all of it), in order.
pub(crate) fn strided(data: &Dataset, stride: usize) -> Dataset {
    Dataset {
        runs: data.runs.iter().step_by(stride.max(1)).cloned().collect(),
    }
}

/// Why the cube pipeline stopped.
#[derive(Debug, thiserror::Error)]
pub enum CubeError {
    /// The scenario.
    #[error(transparent)]
    Scenario(#[from] ScenarioError),
    /// The data file.
    #[error(transparent)]
    Data(#[from] DataError),
    /// The tosses against the scenario.
    #[error(transparent)]
    Toss(#[from] TossError),
    /// The fit's settings.
    #[error("the fit from motion")]
    Genetic(#[from] GeneticError),
    /// The diagnosis.
    #[error("the diagnosis from motion")]
    Diagnose(#[from] MotionDiagnoseError),
    /// Too few tosses for the fits, which see every `stride`th toss of a part.
    #[error("{data}: the fits see every {stride}th toss of a part, {fitted} here; they need at least 3: give --first {least} or more")]
    Stride {
        /// The data file's path.
        data: String,
        /// Tosses the smaller part's fit would see.
        fitted: usize,
        /// Every how many tosses a fit sees one.
        stride: usize,
        /// Runs the data need (`--first`).
        least: usize,
    },
    /// Too few tosses for one part of the split.
    #[error("{data}: the split by toss number left {training} training and {held_out} held-out runs; both need at least 3 (even and odd toss numbers)")]
    Split {
        /// The data file's path.
        data: String,
        /// Training tosses (even toss numbers).
        training: usize,
        /// Held-out tosses (odd toss numbers).
        held_out: usize,
    },
}

/// Everything [`reproduce_cube`] made.
pub struct CubeReproduction {
    /// The scenario as read (its label in the results).
    pub(crate) scenario: Scenario,
    /// The training tosses (even toss numbers).
    pub(crate) training: Dataset,
    /// The held-out tosses (odd toss numbers).
    pub(crate) held_out: Dataset,
    /// The fit.
    pub(crate) fit: MotionFit,
    /// The fitted table offset and inertia as the `--set`s that apply them beside the
    /// physics file.
    pub(crate) sets: Vec<Assignment>,
    /// The fitted contacts (the fitted one first, then those alike with it).
    pub(crate) contacts: Vec<usize>,
    /// Both parts predicted with both models.
    pub(crate) predicted: Predictions,
    /// The second fold: the fit on the held-out part, the training part predicted.
    pub second_fold: SecondFold,
    /// The diagnosis of the fitted model, unless the settings skip it.
    pub diagnosis: Option<MotionDiagnosis>,
    /// Scores, errors over time and per phase, timings.
    pub results: CubeResults,
    /// The figures.
    pub(crate) figures: Vec<NamedFigure>,
    /// A section the caller adds to the report's end (the peers' table of
    /// `hcm reproduce cube-toss --peers`).
    pub appendix: Option<String>,
}

impl CubeReproduction {
    /// What `benches/peers/peers.py` reads beside the tosses, for every toss of both
    /// parts: the scenario's and the fitted model's scores with each toss's window and
    /// initial state (`scores_scenario.csv`, `scores_fitted.csv`, the fitted model of
    /// the first fold), and the scenario's predictions (`predicted_scenario.csv`).
    pub fn peer_inputs(&self) -> anyhow::Result<Vec<Artifact<'_>>> {
        let p = &self.predicted;
        let both = |a: &[crate::replay::TossEvaluation], b: &[crate::replay::TossEvaluation]| {
            [a, b].concat()
        };
        let scenario = both(&p.training_scenario, &p.held_out_scenario);
        let body = TossSetup::new(&self.fit.model)?.name;
        let predicted = predicted_dataset(&scenario, &body);
        Ok(vec![
            Artifact::Scores("scores_scenario.csv", scenario),
            Artifact::Scores(
                "scores_fitted.csv",
                both(&p.training_fitted, &p.held_out_fitted),
            ),
            Artifact::Data("predicted_scenario.csv", Cow::Owned(predicted)),
        ])
    }
}

/// The cube's files: the fit as a physics file, the two parts of the split, the
/// fitted model's held-out predictions and the figures.
impl Reproduced for CubeReproduction {
    fn artifacts(&self) -> anyhow::Result<Vec<Artifact<'_>>> {
        let method = format!(
            "ga + Nelder–Mead on toss replays (motion only), hcm reproduce {}",
            self.results.name
        );
        // The tosses the fit saw: every `fit_stride`th of the training part.
        let runs = (self.training.runs.len()).div_ceil(self.results.fit_stride.max(1));
        let physics = fitted_physics(
            &self.fit,
            &self.contacts,
            &self.sets,
            &method,
            &self.results.data,
            runs,
        );
        let comment = format!(
            "contact of scenario `{}` fitted to tosses by hcm reproduce {}",
            self.scenario.name, self.results.name
        );
        let body = TossSetup::new(&self.fit.model)?.name;
        let predicted = predicted_dataset(&self.predicted.held_out_fitted, &body);
        let extended = (self.diagnosis.as_ref())
            .filter(|d| d.extended.varies() && d.only_chance_named())
            .map(|d| {
                let comment = format!(
                    "{comment}, with the chance the diagnosis named (what forecast members \
                     draw)"
                );
                let physics = physics.clone().with_variation(&d.extended);
                Artifact::Physics("extended.toml", physics, comment)
            });
        Ok(vec![
            Artifact::Physics("physics.toml", physics, comment),
            Artifact::Data("training.csv", Cow::Borrowed(&self.training)),
            Artifact::Data("held_out.csv", Cow::Borrowed(&self.held_out)),
            Artifact::Data("predicted_held_out.csv", Cow::Owned(predicted)),
            Artifact::Figures(&self.figures),
        ]
        .into_iter()
        .chain(extended)
        .collect())
    }

    fn record(&mut self, timing: StageTiming) {
        self.results.timings.push(timing);
    }

    fn results_json(&self) -> anyhow::Result<String> {
        Ok(serde_json::to_string_pretty(&self.results)?)
    }

    fn report(&self) -> String {
        let mut report = self.results.markdown();
        if let Some(appendix) = &self.appendix {
            report.push('\n');
            report.push_str(appendix);
        }
        report
    }
}

/// Runs the cube toss's stages. Bit-identical results (but for the timings) for the
/// same settings, whatever the thread count.
pub fn reproduce_cube(
    settings: &CubeSettings,
    progress: &dyn Progress,
) -> Result<CubeReproduction, CubeError> {
    let mut clock = StageClock::default();
    let scenario = settings.scenario.load()?;
    let model = scenario.model()?;
    let setup = TossSetup::new(&model)?;
    let (training, held_out) =
        clock.time("read + split", || read_split(settings, &setup, &model))?;
    let (fit, parameters) = clock.time("fit (GA + polish)", || {
        stages::fit(settings, &model, &setup, &training, Fold::First, progress)
    })?;
    let sets = stages::sets(&model, &parameters, &fit);
    let predicted = clock.time("predict", || {
        stages::predict(&model, &fit.model, &training, &held_out, progress)
    })?;
    let second_fold = clock.time("second fold (fit on odd, predict even)", || {
        stages::second_fold(settings, &model, &setup, &held_out, &training, progress)
    })?;
    let timeline = clock.time("errors over time and per phase", || {
        stages::timeline(&setup, &held_out, &predicted)
    })?;
    let diagnosis = match settings.diagnose {
        true => Some(clock.time("diagnose", || {
            diagnose(settings, &fit.model, (&training, &held_out), progress)
        })?),
        false => None,
    };
    split_diagnosis_timing(&mut clock, diagnosis.as_ref());
    let parts = (&training, &held_out);
    let chance = chance_stages(
        &mut clock,
        diagnosis.as_ref(),
        &fit,
        &second_fold,
        parts,
        progress,
    )?;
    let (forecast, cross_validated) = chance;
    let faces = match settings.face_members {
        0 => None,
        members => Some(clock.time("final faces (ensembles)", || {
            faces::faces(&fit.model, &training, &held_out, members, progress)
        })?),
    };
    let figures = clock.time("figures", || {
        let mut figures = toss_figures(&setup, &held_out, &predicted, &timeline)?;
        figures.extend(forecast.iter().flat_map(forecast_figures::forecast_figures));
        Ok::<_, CubeError>(figures)
    })?;
    let folds = results::Folds {
        fit: &fit,
        sets: &sets,
        predicted: &predicted,
        second: &second_fold,
    };
    let results = CubeResults::gather(settings, folds, timeline, diagnosis.as_ref(), clock.0)
        .with_faces(faces)
        .with_forecast(forecast)
        .with_cross_validated(cross_validated);
    Ok(CubeReproduction {
        scenario,
        training,
        held_out,
        fit,
        sets,
        contacts: parameters.contacts(),
        predicted,
        second_fold,
        diagnosis,
        results,
        figures,
        appendix: None,
    })
}

/// The stages of a named chance: the held-out tosses forecast by it, and the chance
/// cross-validated on the second fold (both None where no chance was named).
fn chance_stages(
    clock: &mut StageClock,
    diagnosis: Option<&MotionDiagnosis>,
    fit: &MotionFit,
    second_fold: &SecondFold,
    (training, held_out): (&Dataset, &Dataset),
    progress: &dyn Progress,
) -> Result<
    (
        Option<ForecastResults>,
        Option<cross_validated::CrossValidated>,
    ),
    CubeError,
> {
    let Some(d) = diagnosis.filter(|d| d.extended.varies()) else {
        return Ok((None, None));
    };
    let (forecast, fold) = clock.time("forecast by the named chance", || {
        let variation = extended_physics_sets(&d.extended);
        forecast::forecast(&fit.model, &d.extended, variation, held_out, progress)
    })?;
    let cross_validated = clock.time("the named chance cross-validated", || {
        let parts = (held_out, training);
        cross_validated::cross_validate(&second_fold.fit.model, d, &fold, parts, progress)
    })?;
    Ok((Some(forecast), cross_validated))
}

/// What the extended physics file adds to the fitted one for `extended`'s variation:
/// its contacts' `noise` and its `[variation]`, as `--set`s.
fn extended_physics_sets(extended: &Model) -> Vec<String> {
    let noise = (extended.contacts.iter().enumerate())
        .filter(|(_, c)| !c.noise.is_empty())
        .map(|(i, c)| {
            let entries: Vec<String> = (c.noise.iter())
                .map(|(name, b)| format!("{name} = {b:?}"))
                .collect();
            format!("contact.{i}.noise={{ {} }}", entries.join(", "))
        });
    let variation = crate::identify::variation_sets(extended);
    noise
        .chain(variation.iter().map(ToString::to_string))
        .collect()
}

/// The diagnosis' row of `clock` (the last) split in two where its chance phase ran:
/// the deterministic effects and chance on rows of their own, what chance adds
/// (issue 48).
fn split_diagnosis_timing(clock: &mut StageClock, diagnosis: Option<&MotionDiagnosis>) {
    let Some(d) = diagnosis.filter(|d| d.chance_seconds > 0.0) else {
        return;
    };
    if let Some(whole) = clock.0.pop() {
        let phases = [
            (
                "diagnose: deterministic effects",
                whole.seconds - d.chance_seconds,
            ),
            ("diagnose: chance", d.chance_seconds),
        ];
        (clock.0).extend(phases.map(|(stage, seconds)| StageTiming {
            stage: stage.into(),
            seconds,
        }));
    }
}

/// The diagnosis of `fitted`: its candidates fitted on every `fit_stride`th training
/// toss, judged on every held-out one.
fn diagnose(
    settings: &CubeSettings,
    fitted: &Model,
    (training, held_out): (&Dataset, &Dataset),
    progress: &dyn Progress,
) -> Result<MotionDiagnosis, CubeError> {
    let (training, held_out) = (strided(training, settings.fit_stride), held_out.clone());
    // Chance where asked for: the cube's tosses vary from toss to toss (issue 48).
    let catalogue = match settings.chance {
        true => crate::diagnose::Catalogue::default().with_chance(),
        false => crate::diagnose::Catalogue::default(),
    };
    Ok(diagnose_motion_split(
        fitted, training, held_out, &catalogue, progress,
    )?)
}

/// The data read, cut to `first`, checked against the scenario, and split.
fn read_split(
    settings: &CubeSettings,
    setup: &TossSetup,
    model: &Model,
) -> Result<(Dataset, Dataset), CubeError> {
    let mut data = Dataset::read(&settings.data)?;
    if let Some(first) = settings.first {
        data.runs.truncate(first);
    }
    let name = settings.data.display().to_string();
    setup.check_data(&name, model, &data)?;
    let (training, held_out) = split_tosses(&data);
    let least = crate::diagnose::MIN_HELD_OUT;
    if training.runs.len() < least || held_out.runs.len() < least {
        return Err(CubeError::Split {
            data: name,
            training: training.runs.len(),
            held_out: held_out.runs.len(),
        });
    }
    let stride = settings.fit_stride.max(1);
    let fitted = training
        .runs
        .len()
        .min(held_out.runs.len())
        .div_ceil(stride);
    if fitted < least {
        return Err(CubeError::Stride {
            data: name,
            fitted,
            stride,
            least: 2 * least * stride,
        });
    }
    Ok((training, held_out))
}
