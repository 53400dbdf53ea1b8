//! Identification from motion alone: a tossed body's contact law, friction
//! and table height fitted to filmed tosses — poses, no force — by replaying each
//! training toss from its window start ([`crate::replay`]) and minimising the mean score
//! `hcm predict` prints ([`fitness`](mod@fitness)). The genetic algorithm
//! ([`crate::numerics::optimize::genetic`], seeded, its generation evaluated in parallel) searches
//! the box of [`parameters`]; Nelder–Mead ([`crate::numerics::optimize::nelder_mead`]) refines its best. The tosses are
//! split by [`split`]: the fit never sees the held-out part.

mod combined;
mod fitness;
mod identifiability;
mod parameters;
mod physics_file;
mod scenario_file;
mod split;

pub use combined::ForceData;
pub use fitness::{motion_fitness, MotionTarget};
pub use identifiability::Sensitivity;
pub use parameters::MotionParameters;
pub use physics_file::{fitted_physics, set_options};
pub use scenario_file::{beside_physics, fitted_assignments, fitted_scenario_text};
pub use split::{part_of, split_tosses, Part};

use crate::numerics::optimize::genetic::{minimize, GeneticError, GeneticSettings};
use crate::numerics::optimize::{nelder_mead, Parameters};
use crate::progress::{in_stage, Fold, Progress, Stage};
use crate::scenario::Model;
use std::time::Instant;

/// What the fit found.
#[derive(Clone, Debug)]
pub struct MotionFit {
    /// The scenario's model with the fitted parameters.
    pub model: Model,
    /// The fitted values, in [`MotionParameters::named`] form (SI units).
    pub parameters: Vec<(String, f64)>,
    /// The fitness of the scenario's own parameters (% + °).
    pub start_fitness: f64,
    /// The genetic algorithm's best fitness.
    pub genetic_fitness: f64,
    /// The fitness after the polish.
    pub fitness: f64,
    /// Replays of the training set simulated (the search and the polish; the probes
    /// add two per parameter).
    pub evaluations: usize,
    /// Which parameters the training tosses fix ([`identifiability`]), in
    /// `parameters`' gene order (μ_d/μ_s for `mu_dynamic`).
    pub sensitivity: Vec<Sensitivity>,
    /// Wall-clock time (s).
    pub seconds: f64,
}

/// Fits `parameters` of `model` to `target`'s tosses: the genetic algorithm with
/// `settings`, then a polish of about `polish_budget` evaluations from the better of its
/// best and the scenario's own parameters (so the fit never ends worse than the
/// scenario on the training tosses). Reports to `progress` the stages
/// [`Stage::MotionGenetic`] (its generations) and then [`Stage::MotionPolish`] (its
/// fitness evaluations) of `fold`, each with the best fitness so far as its status.
pub fn identify_motion(
    model: &Model,
    target: &MotionTarget<'_>,
    parameters: &MotionParameters,
    settings: &GeneticSettings,
    polish_budget: usize,
    fold: Fold,
    progress: &dyn Progress,
) -> Result<MotionFit, GeneticError> {
    let score = |candidate: &Model| motion_fitness(target, candidate);
    let search = Search {
        settings,
        polish_budget,
        fold,
    };
    search.run(model, parameters, score, progress)
}

/// The force measured at the recorded poses as a second term of the motion fit's
/// objective: the score of a candidate is
/// its trajectory fitness over the scenario's own plus its force cost
/// (`combined::force_cost`) over the scenario's own — each 1 at the start, so that
/// neither dominates by its unit. `MotionFit`'s fitnesses are in those units.
pub fn identify_motion_and_force(
    model: &Model,
    (target, force): (&MotionTarget<'_>, &combined::ForceData<'_>),
    parameters: &MotionParameters,
    search: &Search<'_>,
    progress: &dyn Progress,
) -> Result<MotionFit, GeneticError> {
    let (motion_start, force_start) = (motion_fitness(target, model), force.cost(model));
    let score = |candidate: &Model| {
        motion_fitness(target, candidate) / motion_start + force.cost(candidate) / force_start
    };
    search.run(model, parameters, score, progress)
}

/// The GA and the polish of a fit from motion: the GA's settings, the polish's budget
/// (replays of the training tosses) and the fold its progress is reported under.
pub struct Search<'a> {
    /// The genetic algorithm's settings (population, generations, seed, …).
    pub settings: &'a GeneticSettings,
    /// Replays of the training tosses the Nelder–Mead polish of the GA's best may take.
    pub polish_budget: usize,
    /// The fold of the two-fold split the fit's progress is reported under.
    pub fold: Fold,
}

impl Search<'_> {
    /// Fits `parameters` of `model` minimising `objective` of the candidate model.
    fn run(
        &self,
        model: &Model,
        parameters: &MotionParameters,
        objective: impl Fn(&Model) -> f64 + Sync,
        progress: &dyn Progress,
    ) -> Result<MotionFit, GeneticError> {
        let (settings, polish_budget, fold) = (self.settings, self.polish_budget, self.fold);
        let started = Instant::now();
        let bounds = parameters.bounds();
        let score = |genes: &[f64]| objective(&parameters.apply(model, genes));
        let start = parameters.values(model);
        let start_fitness = score(&start);
        let observer = |steps: usize| {
            move |done: usize, best: f64| {
                progress.advance(done as u64, steps as u64);
                progress.status(&format!("best {best:.3}"));
            }
        };
        let generations = settings.generations;
        let genetic = in_stage(
            progress,
            Stage::MotionGenetic(fold),
            generations as u64,
            || minimize(&bounds, settings, score, observer(generations)),
        )?;
        // A short search may end above the scenario's own parameters: polish the better.
        let (from, from_fitness) = if start_fitness < genetic.fitness {
            (&start, start_fitness)
        } else {
            (&genetic.best, genetic.fitness)
        };
        let polished = in_stage(
            progress,
            Stage::MotionPolish(fold),
            polish_budget as u64,
            || {
                let observer = observer(polish_budget);
                nelder_mead::polish(&bounds, from, from_fitness, polish_budget, score, observer)
            },
        );
        let names: Vec<String> = (bounds.iter())
            .map(|b| match b.name.as_str() {
                "mu_ratio" => "mu_dynamic".to_owned(),
                name => name.to_owned(),
            })
            .collect();
        let sensitivity =
            identifiability::probe(&bounds, &names, &polished.best, polished.fitness, score);
        Ok(MotionFit {
            model: parameters.apply(model, &polished.best),
            sensitivity,
            parameters: parameters.named(&polished.best),
            start_fitness,
            genetic_fitness: genetic.fitness,
            fitness: polished.fitness,
            evaluations: 1 + genetic.evaluations + polished.evaluations,
            seconds: started.elapsed().as_secs_f64(),
        })
    }
}
