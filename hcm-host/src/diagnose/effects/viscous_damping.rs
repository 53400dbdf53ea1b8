//! Viscous damping c·δ̇ added to the normal law (N·s/m).

use super::{first, has_room, Candidate, Effect, Family, Scales, Site};
use crate::dataset::Evidence;
use crate::numerics::optimize::Bound;
use crate::scenario::Model;
use hcm_core::effect::{ContactEffect, ViscousDamping as Term};

/// c ∈ [0, 10·F̂/δ̇̂] (N·s/m).
#[derive(Debug)]
pub struct ViscousDamping;

impl Effect for ViscousDamping {
    fn name(&self) -> &'static str {
        "viscous_damping"
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
    fn bounds(&self, _evidence: Evidence, s: &Scales) -> Vec<Bound> {
        let force = s.contact.peak_force.max(f64::MIN_POSITIVE);
        let upper = 10.0 * (force / s.contact.peak_rate.max(1e-6));
        vec![Bound::linear("coefficient", 0.0, upper)]
    }
    fn apply(&self, model: &mut Model, site: Site, values: &[f64]) {
        let term = ContactEffect::ViscousDamping(Term {
            coefficient: first(values),
        });
        let _ = model.contacts[site.contact].model.normal.effects.push(term);
    }
    fn column(&self) -> Option<Candidate> {
        Some(Candidate::ViscousDamping)
    }
}
