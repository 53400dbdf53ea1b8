//! The body's inertia tensor scaled by k (–): its mass further out (or in) than the
//! model has it.

use super::{first, Effect, Family, Scales, Site};
use crate::dataset::Evidence;
use crate::numerics::optimize::Bound;
use crate::scenario::Model;

/// k ∈ [0.5, 2] (–, searched on a log scale).
#[derive(Debug)]
pub struct InertiaScale;

impl Effect for InertiaScale {
    fn name(&self) -> &'static str {
        "inertia_scale"
    }
    fn family(&self) -> Family {
        Family::Body
    }
    fn evidence(&self, evidence: Evidence) -> bool {
        evidence == Evidence::Poses
    }
    fn within_base_fit(&self, _model: &Model, _site: Site) -> bool {
        true
    }
    fn bounds(&self, _evidence: Evidence, _scales: &Scales) -> Vec<Bound> {
        vec![Bound {
            log_scale: true,
            ..Bound::linear("scale", 0.5, 2.0)
        }]
    }
    fn neutral(&self, _model: &Model, _site: Site) -> Vec<f64> {
        vec![1.0]
    }
    /// The body of the contact that is not the partner.
    fn apply(&self, model: &mut Model, site: Site, values: &[f64]) {
        let c = &model.contacts[site.contact];
        let body = c.body_1 + c.body_2 - site.partner;
        model.bodies[body].inertia *= first(values);
    }
}
