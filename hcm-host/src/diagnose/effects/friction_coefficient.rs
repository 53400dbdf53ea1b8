//! Both friction coefficients scaled by s (–).

use super::{first, Effect, Family, Scales, Site};
use crate::dataset::Evidence;
use crate::numerics::optimize::Bound;
use crate::scenario::Model;

/// μ_s, μ_d × s, s ∈ [0.2, 5] (searched on a log scale).
#[derive(Debug)]
pub struct FrictionCoefficient;

impl Effect for FrictionCoefficient {
    fn name(&self) -> &'static str {
        "friction_coefficient"
    }
    fn family(&self) -> Family {
        Family::Friction
    }
    fn evidence(&self, evidence: Evidence) -> bool {
        evidence != Evidence::LineForce
    }
    fn applies(&self, model: &Model, site: Site) -> bool {
        model.contacts[site.contact].model.friction.is_some()
    }
    fn within_base_fit(&self, _model: &Model, _site: Site) -> bool {
        true
    }
    fn bounds(&self, _evidence: Evidence, _scales: &Scales) -> Vec<Bound> {
        vec![Bound {
            log_scale: true,
            ..Bound::linear("scale", 0.2, 5.0)
        }]
    }
    fn neutral(&self, _model: &Model, _site: Site) -> Vec<f64> {
        vec![1.0]
    }
    fn apply(&self, model: &mut Model, site: Site, values: &[f64]) {
        if let Some(f) = model.contacts[site.contact].model.friction.as_mut() {
            f.static_coefficient *= first(values);
            f.dynamic_coefficient *= first(values);
        }
    }
}
