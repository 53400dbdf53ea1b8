//! A fit's objective as a function of the free parameters, for optimisers outside hcm
//! (DEAP, nevergrad, a cluster's map): the fitness the genetic algorithm minimises
//! (`hcm identify --method ga`), evaluated for many candidates at once.
//!
//! Each candidate is evaluated on its own (replays of every condition), so a batch is
//! embarrassingly parallel; its values come back in the batch's order, the same bits
//! on any thread count and in any split of the batch.

use super::evolve::{fitness, Fitness};
use super::{targets, template, Bounds, IdentifyError, Target};
use crate::dataset::Dataset;
use crate::scenario::{Model, Scenario};
use hcm_core::law::AnyNormalLaw;
use rayon::prelude::*;

/// The fitness of contact `c`'s law on the data, over the law's free parameters.
pub struct Objective {
    template: AnyNormalLaw<f64>,
    bounds: Bounds,
    targets: Vec<Target>,
    contact: usize,
    kind: Fitness,
}

impl Objective {
    /// The objective `hcm identify --law LAW --method ga --fitness KIND` minimises for
    /// contact `c` of `model` (the scenario resolved) on `data`: the law's fixed
    /// parameters derived from the scenario, the free ones in the scenario's bounds.
    pub fn new(
        scenario: &Scenario,
        model: &Model,
        data: &Dataset,
        c: usize,
        law: &str,
        kind: Fitness,
    ) -> Result<Objective, IdentifyError> {
        let (template, bounds) = template(scenario, c, law)?;
        bounds.check(&template)?;
        let completed = crate::dataset::complete(model, data)?;
        let targets = targets(model, completed.data.as_ref(), c)?;
        Ok(Objective {
            template,
            bounds,
            targets,
            contact: c,
            kind,
        })
    }

    /// The free parameters' names, in the order a candidate lists their values.
    pub fn parameters(&self) -> Vec<&str> {
        self.bounds.free()
    }

    /// Each free parameter's interval (SI units), in [`Self::parameters`] order.
    pub fn bounds(&self) -> Vec<(f64, f64)> {
        let free = self.bounds.free();
        free.iter().map(|name| self.bounds.range(name)).collect()
    }

    /// The law a candidate stands for.
    pub fn law(&self, candidate: &[f64]) -> AnyNormalLaw<f64> {
        self.bounds.with(&self.template, candidate)
    }

    /// The fitness of one candidate (curve: RMS N; indicators: sum of squared relative
    /// errors); +∞ where a replay fails.
    pub fn value(&self, candidate: &[f64]) -> f64 {
        fitness(&self.law(candidate), &self.targets, self.contact, self.kind)
    }

    /// The fitness of every candidate (`candidates[i]`: the free parameters' values), in
    /// parallel, in order.
    pub fn values(&self, candidates: &[Vec<f64>]) -> Vec<f64> {
        candidates.par_iter().map(|p| self.value(p)).collect()
    }
}
