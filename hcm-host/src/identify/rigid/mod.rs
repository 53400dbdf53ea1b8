//! PM2 for a rigid body (the peg-in-hole's way): the contact law's parameters but
//! its exponent, and its STEP friction, found by the genetic algorithm so that a
//! replay from S1's mean pre-contact state makes S1's contact events — peak force and
//! torque, linear and angular impulse, timing — event by event.

mod events;
mod fitness;
mod parameters;
mod quality;
mod recorded;
mod sample_fit;
mod scaled;
mod start;
mod target;

pub use events::identify_events;
pub use fitness::{event_errors, event_fitness, replay_events};
pub use parameters::RigidParameters;
pub use quality::warnings as rigid_warnings;
pub use recorded::{RecordedContact, RecordedSample};
pub use sample_fit::{
    fit_samples, identify_from_samples, least_squares, SampleFit, SampleIdentification,
};
pub use scaled::ContactScales;
pub use start::with_law;
pub use target::{EventTarget, WrenchTarget};

use crate::indicators::IndicatorError;
use crate::numerics::optimize::genetic::{minimize, GeneticError, GeneticSettings};
use crate::numerics::optimize::Parameters;
use crate::progress::{in_stage, Progress, Stage};
use crate::scenario::Model;
use std::time::Instant;

/// Why a rigid identification failed.
#[derive(Debug, thiserror::Error)]
pub enum RigidIdentifyError {
    /// The model has no such contact.
    #[error("the scenario has no contact number {0}")]
    NoSuchContact(usize),
    /// Neither body moves.
    #[error("contact `{0}`: both bodies are fixed; a contact to identify has a moving body")]
    NotOneMover(String),
    /// The runs do not usually make the events asked for.
    #[error("{wanted} contact events asked for, but the runs usually make {usual}; ask for at most {usual} or check the data against the scenario")]
    TooFewEvents {
        /// Contact events asked for (`--events`; 1 when none were asked for).
        wanted: usize,
        /// The event count most runs make (0 when no run makes one).
        usual: usize,
    },
    /// The data do not match the scenario.
    #[error(transparent)]
    Data(#[from] IndicatorError),
    /// A run has no usable pre-contact state.
    #[error(transparent)]
    PreContact(#[from] crate::experiment::PreContactError),
    /// Bad bounds.
    #[error("{0}")]
    Setup(String),
    /// The genetic algorithm failed.
    #[error("genetic algorithm: {0}")]
    Genetic(#[from] GeneticError),
}

/// What the identification found.
#[derive(Clone, Debug)]
pub struct RigidIdentification {
    /// The scenario's model with the identified parameters (started as the scenario
    /// says, not from the replay state).
    pub model: Model,
    /// The identified values (SI units), law parameters first, then friction.
    pub parameters: Vec<(String, f64)>,
    /// Best fitness (mean squared relative error).
    pub fitness: f64,
    /// Generations run.
    pub(crate) generations: usize,
    /// Replays simulated.
    pub evaluations: usize,
    /// Wall-clock time (s).
    pub seconds: f64,
    /// What the fit did not do, each with what to try ([`quality::warnings`]): a
    /// parameter at its search bound, events the best replay does not make, an
    /// indicator missed by more than the runs scatter. Empty for a fit that fitted.
    pub warnings: Vec<String>,
}

/// Finds contact `target.contact`'s parameters of `model` (law without exponent, and
/// friction) by the genetic algorithm, reporting [`Stage::Identify`] to `progress`: its
/// generations, with the best fitness so far as its status.
pub fn identify_rigid(
    model: &Model,
    target: &WrenchTarget,
    parameters: &RigidParameters,
    settings: &GeneticSettings,
    progress: &dyn Progress,
) -> Result<RigidIdentification, RigidIdentifyError> {
    let started = Instant::now();
    let generations = settings.generations as u64;
    let result = in_stage(progress, Stage::Identify, generations, || {
        minimize(
            &parameters.bounds(),
            settings,
            |genes| event_fitness(target, &parameters.apply(&target.model, genes)),
            |done: usize, best: f64| {
                progress.advance(done as u64, generations);
                progress.status(&format!("best {best:.4e}"));
            },
        )
    })?;
    let bounds = parameters.bounds();
    let best = parameters.apply(&target.model, &result.best);
    let warnings = quality::warnings(&bounds, &result.best, target, &best);
    Ok(RigidIdentification {
        warnings,
        model: parameters.apply(model, &result.best),
        parameters: parameters.named(&result.best),
        fitness: result.fitness,
        generations: result.generations,
        evaluations: result.evaluations,
        seconds: started.elapsed().as_secs_f64(),
    })
}

/// The name of contact `c`'s moving body: the one against a fixed body, or body 1 of
/// two moving bodies (the one whose path a replay is scored on).
pub(crate) fn mover_name(model: &Model, c: usize) -> Result<String, RigidIdentifyError> {
    let contact = model
        .contacts
        .get(c)
        .ok_or(RigidIdentifyError::NoSuchContact(c))?;
    let (b1, b2) = (&model.bodies[contact.body_1], &model.bodies[contact.body_2]);
    match (b1.fixed, b2.fixed) {
        (false, _) => Ok(b1.name.clone()),
        (true, false) => Ok(b2.name.clone()),
        _ => Err(RigidIdentifyError::NotOneMover(format!(
            "{}–{}",
            b1.name, b2.name
        ))),
    }
}
