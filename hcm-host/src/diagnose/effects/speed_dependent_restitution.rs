//! A restitution that falls with the impact speed: Hunt–Crossley's damping χ·k·δⁿ·δ̇
//! added to the law (k, n the law's stiffness and exponent; χ in s/m), e ≈ 1 − 2·χ·v/3
//! at impact speed v where the law alone keeps e about constant. The same term as
//! [`super::hysteresis_damping`], scaled by the law's stiffness so that its box needs
//! no force scale: the form judged from poses.

use super::{first, has_room, Effect, Family, Scales, Site};
use crate::dataset::Evidence;
use crate::numerics::optimize::Bound;
use crate::scenario::Model;
use hcm_core::effect::{ContactEffect, HysteresisDamping};

/// χ ∈ [0, 3] (s/m).
#[derive(Debug)]
pub struct SpeedDependentRestitution;

/// The stiffness k and exponent n of `model`'s contact law, if it has both.
fn stiffness_exponent(model: &Model, site: Site) -> Option<(f64, f64)> {
    let law = model.contacts[site.contact].law();
    Some((law.get("stiffness").ok()?, law.get("exponent").ok()?))
}

impl Effect for SpeedDependentRestitution {
    fn name(&self) -> &'static str {
        "speed_dependent_restitution"
    }
    fn family(&self) -> Family {
        Family::Normal
    }
    fn evidence(&self, evidence: Evidence) -> bool {
        evidence == Evidence::Poses
    }
    fn applies(&self, model: &Model, site: Site) -> bool {
        stiffness_exponent(model, site).is_some() && has_room(model, site)
    }
    /// On a Hunt–Crossley law the fit from motion frees its damping χ already.
    fn within_base_fit(&self, model: &Model, site: Site) -> bool {
        model.contacts[site.contact].law().name() == "hunt_crossley"
    }
    fn bounds(&self, _evidence: Evidence, _scales: &Scales) -> Vec<Bound> {
        vec![Bound::linear("chi", 0.0, 3.0)]
    }
    fn apply(&self, model: &mut Model, site: Site, values: &[f64]) {
        if let Some((k, n)) = stiffness_exponent(model, site) {
            let damping = HysteresisDamping {
                coefficient: first(values) * k,
                exponent: n,
            };
            let effects = &mut model.contacts[site.contact].model.normal.effects;
            let _ = effects.push(ContactEffect::HysteresisDamping(damping));
        }
    }
}
