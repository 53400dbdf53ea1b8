//! Viscous friction −c_v·v_t per contact point (N·s/m).

use super::{first, Effect, Family, Scales, Site};
use crate::dataset::Evidence;
use crate::numerics::optimize::Bound;
use crate::scenario::Model;
use hcm_core::friction::ViscousFriction as Term;

/// c_v ∈ [0, F̂/v̂] from the wrench, [0, 5·m] from poses (N·s/m).
#[derive(Debug)]
pub struct ViscousFriction;

impl Effect for ViscousFriction {
    fn name(&self) -> &'static str {
        Term::<f64>::NAME
    }
    fn family(&self) -> Family {
        Family::Friction
    }
    fn evidence(&self, evidence: Evidence) -> bool {
        evidence != Evidence::LineForce
    }
    fn bounds(&self, evidence: Evidence, s: &Scales) -> Vec<Bound> {
        let upper = match evidence {
            Evidence::Poses => 5.0 * s.mass,
            _ => s.contact.peak_force.max(f64::MIN_POSITIVE) / s.slip.max(1e-6),
        };
        vec![Bound::linear("coefficient", 0.0, upper)]
    }
    fn apply(&self, model: &mut Model, site: Site, values: &[f64]) {
        let tangential = &mut model.contacts[site.contact].model.tangential;
        tangential.viscous_friction = Some(Term {
            coefficient: first(values),
        });
    }
}
