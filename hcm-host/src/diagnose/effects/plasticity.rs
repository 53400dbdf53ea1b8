//! Plasticity: unloading on a curve shifted by ρ·δ_max (–).

use super::{first, has_room, Candidate, Effect, Family, Scales, Site};
use crate::dataset::Evidence;
use crate::numerics::optimize::Bound;
use crate::scenario::Model;
use hcm_core::effect::{ContactEffect, Plasticity as Term};

/// ρ ∈ [0, 0.9] (–).
#[derive(Debug)]
pub struct Plasticity;

impl Effect for Plasticity {
    fn name(&self) -> &'static str {
        "plasticity"
    }
    fn family(&self) -> Family {
        Family::Normal
    }
    fn evidence(&self, evidence: Evidence) -> bool {
        evidence != Evidence::Poses
    }
    fn applies(&self, model: &Model, site: Site) -> bool {
        has_room(model, site)
    }
    fn bounds(&self, _evidence: Evidence, _scales: &Scales) -> Vec<Bound> {
        vec![Bound::linear("permanent_ratio", 0.0, 0.9)]
    }
    fn apply(&self, model: &mut Model, site: Site, values: &[f64]) {
        let term = ContactEffect::Plasticity(Term {
            permanent_ratio: first(values),
        });
        let _ = model.contacts[site.contact].model.normal.effects.push(term);
    }
    fn column(&self) -> Option<Candidate> {
        Some(Candidate::Plasticity)
    }
}
