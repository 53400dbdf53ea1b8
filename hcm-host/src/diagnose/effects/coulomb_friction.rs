//! Coulomb's law instead of STEP's two coefficients: μ_s = μ_d = μ (–).

use super::{first, Effect, Family, Scales, Site};
use crate::dataset::Evidence;
use crate::numerics::optimize::Bound;
use crate::scenario::Model;

/// μ_s = μ_d = μ ∈ [0.01, 1.5], searched on a log scale from poses.
#[derive(Debug)]
pub struct CoulombFriction;

impl Effect for CoulombFriction {
    fn name(&self) -> &'static str {
        "coulomb_friction"
    }
    fn family(&self) -> Family {
        Family::Friction
    }
    fn evidence(&self, evidence: Evidence) -> bool {
        evidence != Evidence::LineForce
    }
    /// No change of shape for a law whose μ_s = μ_d already (it would only repeat the
    /// coefficient's candidate).
    fn applies(&self, model: &Model, site: Site) -> bool {
        let friction = model.contacts[site.contact].model.friction;
        friction.is_some_and(|f| f.static_coefficient != f.dynamic_coefficient)
    }
    fn within_base_fit(&self, _model: &Model, _site: Site) -> bool {
        true
    }
    fn bounds(&self, evidence: Evidence, _scales: &Scales) -> Vec<Bound> {
        vec![Bound {
            log_scale: evidence == Evidence::Poses,
            ..Bound::linear("mu", 0.01, 1.5)
        }]
    }
    /// The model's μ_d: the nearest Coulomb law.
    fn neutral(&self, model: &Model, site: Site) -> Vec<f64> {
        let friction = model.contacts[site.contact].model.friction;
        vec![friction.map_or(0.1, |f| f.dynamic_coefficient)]
    }
    fn apply(&self, model: &mut Model, site: Site, values: &[f64]) {
        if let Some(f) = model.contacts[site.contact].model.friction.as_mut() {
            (f.static_coefficient, f.dynamic_coefficient) = (first(values), first(values));
        }
    }
}
