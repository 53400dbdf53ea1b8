//! Parameter identification (PM2): fit a normal law to measured data, by separable
//! least squares ([`separable`]) or by the paper's genetic algorithm ([`evolve`]).

mod bounds;
mod contact_samples;
mod evolve;
mod motion;
mod objective;
mod physics;
mod replay;
mod rigid;
mod samples;
mod separable;
pub use bounds::{Bounds, BoundsOverrides};
pub use contact_samples::{contact_samples, contact_samples_of, ContactSamples};
pub use evolve::Fitness;
pub use motion::{
    beside_physics, fitted_physics, identify_motion, motion_fitness, set_options, split_tosses,
    MotionFit, MotionParameters, MotionTarget,
};
pub use motion::{
    fitted_assignments, fitted_scenario_text, identify_motion_and_force, part_of, ForceData, Part,
    Search as MotionSearch,
};
pub use objective::Objective;
pub use physics::PhysicsBody;
pub use physics::PhysicsError;
pub(crate) use replay::pre_contact_state;
pub(crate) use replay::simulate_target_as;
pub(crate) use replay::simulate_target_with;
pub use replay::{curve, targets, with_physics, Target};
pub use rigid::identify_from_samples;
pub(crate) use rigid::mover_name;
pub use rigid::{
    event_errors, event_fitness, identify_rigid, rigid_warnings, SampleIdentification,
};
pub use rigid::{
    fit_samples, identify_events, least_squares, replay_events, with_law, ContactScales,
    EventTarget, RecordedContact, RecordedSample, RigidIdentification, RigidIdentifyError,
    RigidParameters, SampleFit, WrenchTarget,
};
pub use samples::force_samples;

pub use physics::{variation_sets, FitRecord, Physics};

use crate::dataset::{Dataset, ForceSample};
use crate::indicators::IndicatorError;
use crate::progress::{in_stage, Progress, Stage};
use crate::scenario::{Assignment, Model, Scenario, ScenarioError};
use hcm_core::law::AnyNormalLaw;
use hcm_core::model::ContactModel;
use std::time::Instant;

/// Why identification failed.
#[derive(Debug, thiserror::Error)]
pub enum IdentifyError {
    /// The data hold no runs.
    #[error("the data file holds no runs")]
    NoData,
    /// A run never makes (and ends) contact: it cannot be fitted and is not dropped silently.
    #[error("run `{run}` (t = {from} … {to} s) has no completed contact; remove it from the data or check the scenario's geometry")]
    NoContact {
        /// The run's id.
        run: String,
        /// Time of the run's first sample (s).
        from: f64,
        /// Time of the run's last sample (s).
        to: f64,
    },
    /// The data do not match the scenario.
    #[error(transparent)]
    Data(#[from] IndicatorError),
    /// The motion could not be reconstructed at the force samples.
    #[error(transparent)]
    Reconstruct(#[from] crate::dataset::ReconstructError),
    /// The law cannot be built in this scenario.
    #[error(transparent)]
    Scenario(#[from] ScenarioError),
    /// Bad bounds or law name.
    #[error("{0}")]
    Setup(String),
    /// The law has no least-squares structure here.
    #[error("law `{0}` cannot be identified")]
    UnsupportedLaw(String),
    /// The least-squares solver failed.
    #[error("least squares: {0}")]
    LeastSquares(#[from] crate::numerics::optimize::LeastSquaresError),
    /// The genetic algorithm failed.
    #[error("genetic algorithm: {0}")]
    Genetic(#[from] crate::numerics::optimize::genetic::GeneticError),
}

/// How to identify.
#[derive(Clone, Debug, PartialEq)]
pub enum Method {
    /// Separable least squares + Levenberg–Marquardt on the force samples.
    Lsq,
    /// Genetic algorithm on simulated vs measured data.
    Ga(
        evolve::Fitness,
        crate::numerics::optimize::genetic::GeneticSettings,
    ),
}

/// An identified law.
#[derive(Clone, Debug)]
pub struct Identification {
    /// The law with every parameter.
    pub law: AnyNormalLaw<f64>,
    /// Index of the contact it was fitted for.
    pub contact: usize,
    /// How it went.
    pub fit: FitRecord,
    /// One-sigma standard errors of the free parameters (least squares only).
    pub standard_errors: Vec<(String, f64)>,
}

/// The law `law_name` for contact `c` of `scenario`, with its fixed parameters
/// (geometry, masses) derived from the scenario and its free ones at the middle of
/// their box, and that box.
pub(crate) fn template(
    scenario: &Scenario,
    c: usize,
    law_name: &str,
) -> Result<(AnyNormalLaw<f64>, Bounds), IdentifyError> {
    Bounds::check_scenario(&scenario.identify.bounds).map_err(IdentifyError::Setup)?;
    let bounds = Bounds::for_law(law_name, scenario.identify.bounds.get(law_name))
        .map_err(IdentifyError::Setup)?;
    if bounds.parameters.is_empty() {
        return Err(IdentifyError::UnsupportedLaw(law_name.to_owned()));
    }
    let middle = bounds.middle();
    let middle: Vec<(&str, f64)> = middle.iter().map(|(n, v)| (n.as_str(), *v)).collect();
    let assignments = [
        Assignment::contact(c, &["law"], law_name),
        Assignment::contact(c, &["parameters"], physics::float_table(&middle)),
        Assignment::contact(c, &["noise"], toml::Table::new()),
    ];
    let model = scenario.with_assignments(&assignments)?.model()?;
    Ok((*model.contacts[c].law(), bounds))
}

/// RMS of modelled − measured force over `samples` (N).
pub fn force_rms(law: &AnyNormalLaw<f64>, samples: &[ForceSample]) -> f64 {
    let physics = ContactModel::physics(*law);
    let sum: f64 = samples
        .iter()
        .map(|s| {
            let (state, memory) = s.state();
            (physics.physics_normal_force(&state, &memory) - s.force).powi(2)
        })
        .sum();
    (sum / samples.len().max(1) as f64).sqrt()
}

/// Identifies `law_name` for contact `c` of `scenario` from `data`, reporting the fit
/// as [`Stage::Identify`] to `progress`: one step for least squares, the generations
/// of the genetic algorithm (with the best fitness so far as its status).
pub fn identify(
    scenario: &Scenario,
    model: &Model,
    data: &Dataset,
    c: usize,
    law_name: &str,
    method: Method,
    progress: &dyn Progress,
) -> Result<Identification, IdentifyError> {
    let started = Instant::now();
    let (template, bounds) = template(scenario, c, law_name)?;
    // Camera frames and force rows on their own clocks: the motion at the force samples.
    let completed = crate::dataset::complete(model, data)?;
    let data = completed.data.as_ref();
    let (samples, events) = samples::force_samples(model, data, c)?;
    let targets = replay::targets(model, data, c)?;
    let steps = match &method {
        Method::Lsq => 1,
        Method::Ga(_, settings) => settings.generations as u64,
    };
    let fitted: Result<_, IdentifyError> = in_stage(progress, Stage::Identify, steps, || {
        match method {
            Method::Lsq => {
                let fit = separable::fit(&template, &samples, &bounds)?;
                Ok((fit.law, fit.notes, fit.standard_errors, "lsq".to_owned()))
            }
            Method::Ga(fitness, settings) => {
                let generations = settings.generations as u64;
                let observer = |done: usize, best: f64| {
                    progress.advance(done as u64, generations);
                    progress.status(&format!("best {best:.4e}"));
                };
                let outcome = evolve::fit(
                    &template, &bounds, &targets, c, fitness, &settings, observer,
                )?;
                let note = format!(
                    "GA: {} generations, {} fitness evaluations, best {} fitness {:.6e} before the Levenberg–Marquardt polish",
                    outcome.generations,
                    outcome.evaluations,
                    fitness.name(),
                    outcome.ga_fitness
                );
                let label = format!("ga ({})", fitness.name());
                Ok((outcome.law, vec![note], Vec::new(), label))
            }
        }
    });
    let (law, notes, standard_errors, label) = fitted?;
    let seconds = started.elapsed().as_secs_f64();
    let fit = FitRecord {
        method: label,
        data: String::new(),
        runs: data.runs.len(),
        events,
        samples: samples.len(),
        force_rms: force_rms(&law, &samples),
        curve_rms: evolve::fitness(&law, &targets, c, evolve::Fitness::Curve),
        seconds,
        notes,
    };
    Ok(Identification {
        law,
        contact: c,
        fit,
        standard_errors,
    })
}
