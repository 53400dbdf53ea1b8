//! Hysteresis damping c·δⁿ·δ̇ added to the normal law, n the law's exponent
//! (Hunt–Crossley's damping; Lankarani–Nikravesh's at one approach speed).

use super::{first, has_room, Candidate, Effect, Family, Scales, Site};
use crate::dataset::Evidence;
use crate::numerics::optimize::Bound;
use crate::scenario::Model;
use hcm_core::effect::{ContactEffect, HysteresisDamping as Term};

/// c ∈ [0, 10·F̂/(δ̂ⁿ·δ̇̂)] (N·s/m^(1+n)).
#[derive(Debug)]
pub struct HysteresisDamping;

impl Effect for HysteresisDamping {
    fn name(&self) -> &'static str {
        "hysteresis_damping"
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
        let depth = s.contact.peak_depth.max(f64::MIN_POSITIVE).powf(s.exponent);
        let upper = 10.0 * (force / s.contact.peak_rate.max(1e-6)) / depth;
        vec![Bound::linear("coefficient", 0.0, upper)]
    }
    fn apply(&self, model: &mut Model, site: Site, values: &[f64]) {
        let normal = &mut model.contacts[site.contact].model.normal;
        let exponent = normal.base.get("exponent").unwrap_or(1.5);
        let term = ContactEffect::HysteresisDamping(Term {
            coefficient: first(values),
            exponent,
        });
        let _ = normal.effects.push(term);
    }
    fn column(&self) -> Option<Candidate> {
        Some(Candidate::HysteresisDamping)
    }
}
