//! Adhesion: a pull-off force −a while in contact (N).

use super::{first, has_room, Candidate, Effect, Family, Scales, Site};
use crate::dataset::Evidence;
use crate::numerics::optimize::Bound;
use crate::scenario::Model;
use hcm_core::effect::{Adhesion as Term, ContactEffect};

/// a ∈ [0, F̂/2] (N).
#[derive(Debug)]
pub struct Adhesion;

impl Effect for Adhesion {
    fn name(&self) -> &'static str {
        "adhesion"
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
        vec![Bound::linear("pull_off_force", 0.0, 0.5 * force)]
    }
    fn apply(&self, model: &mut Model, site: Site, values: &[f64]) {
        let term = ContactEffect::Adhesion(Term {
            pull_off_force: first(values),
        });
        let _ = model.contacts[site.contact].model.normal.effects.push(term);
    }
    fn column(&self) -> Option<Candidate> {
        Some(Candidate::Adhesion)
    }
}
