//! The elastic exponent n → n + Δ about a reference depth δ_ref, judged on a line of
//! force only (from a wrench or poses a fitted base frees the exponent itself).

use super::{first, has_room, Candidate, Effect, Family, Scales, Site};
use crate::dataset::Evidence;
use crate::numerics::optimize::Bound;
use crate::scenario::Model;
use hcm_core::effect::{ContactEffect, StiffnessExponent as Term};

/// Δ ∈ [−0.5, 0.5] (–) about δ_ref ∈ [δ̂/10, δ̂] (m).
#[derive(Debug)]
pub struct StiffnessExponent;

impl Effect for StiffnessExponent {
    fn name(&self) -> &'static str {
        "stiffness_exponent"
    }
    fn family(&self) -> Family {
        Family::Normal
    }
    fn evidence(&self, evidence: Evidence) -> bool {
        evidence == Evidence::LineForce
    }
    fn applies(&self, model: &Model, site: Site) -> bool {
        has_room(model, site)
    }
    fn bounds(&self, _evidence: Evidence, s: &Scales) -> Vec<Bound> {
        let depth = s.contact.peak_depth.max(f64::MIN_POSITIVE);
        vec![
            Bound::linear("exponent_change", -0.5, 0.5),
            Bound::linear("reference_depth", 0.1 * depth, depth),
        ]
    }
    /// Δ = 0 changes nothing whatever δ_ref (1 mm).
    fn neutral(&self, _model: &Model, _site: Site) -> Vec<f64> {
        vec![0.0, 1e-3]
    }
    fn apply(&self, model: &mut Model, site: Site, values: &[f64]) {
        let term = ContactEffect::StiffnessExponent(Term {
            exponent_change: first(values),
            reference_depth: values.get(1).copied().unwrap_or(1e-3),
        });
        let _ = model.contacts[site.contact].model.normal.effects.push(term);
    }
    fn column(&self) -> Option<Candidate> {
        Some(Candidate::StiffnessExponent)
    }
}
