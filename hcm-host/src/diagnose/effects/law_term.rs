//! A term added to the normal law (`hcm_core::effect`), judged from the line force or
//! the wrench: viscous damping c·δ̇ (N·s/m), hysteresis damping c·δⁿ·δ̇ with n the law's
//! exponent (Hunt–Crossley's damping; Lankarani–Nikravesh's at one approach speed,
//! N·s/m^(1+n)), adhesion −a in contact (N), plasticity ρ·δ_max on unloading (–).

use super::{first, has_room, Candidate, Effect, Family, Scales, Site};
use crate::dataset::Evidence;
use crate::numerics::optimize::Bound;
use crate::scenario::Model;
use hcm_core::effect::{Adhesion, HysteresisDamping, Plasticity, ViscousDamping};

/// One of the normal law's added terms, with its one parameter.
#[derive(Debug)]
pub struct LawTerm {
    /// Its linear column on a line of force, which names it.
    column: Candidate,
}

/// c·δ̇, c ∈ [0, 10·F̂/δ̇̂] (N·s/m).
pub static VISCOUS_DAMPING: LawTerm = LawTerm {
    column: Candidate::ViscousDamping,
};
/// c·δⁿ·δ̇, c ∈ [0, 10·F̂/(δ̂ⁿ·δ̇̂)] (N·s/m^(1+n)).
pub static HYSTERESIS_DAMPING: LawTerm = LawTerm {
    column: Candidate::HysteresisDamping,
};
/// −a in contact, a ∈ [0, F̂/2] (N).
pub static ADHESION: LawTerm = LawTerm {
    column: Candidate::Adhesion,
};
/// Unloading on a curve shifted by ρ·δ_max, ρ ∈ [0, 0.9] (–).
pub static PLASTICITY: LawTerm = LawTerm {
    column: Candidate::Plasticity,
};

impl Effect for LawTerm {
    fn name(&self) -> &'static str {
        self.column.name()
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
        let per_rate = force / s.contact.peak_rate.max(1e-6);
        let (name, upper) = match self.column {
            Candidate::ViscousDamping => ("coefficient", 10.0 * per_rate),
            Candidate::HysteresisDamping => {
                let depth = s.contact.peak_depth.max(f64::MIN_POSITIVE).powf(s.exponent);
                ("coefficient", 10.0 * per_rate / depth)
            }
            Candidate::Adhesion => ("pull_off_force", 0.5 * force),
            _ => ("permanent_ratio", 0.9),
        };
        vec![Bound::linear(name, 0.0, upper)]
    }
    fn apply(&self, model: &mut Model, site: Site, values: &[f64]) {
        let normal = &mut model.contacts[site.contact].model.normal;
        let value = first(values);
        let term = match self.column {
            Candidate::ViscousDamping => ViscousDamping { coefficient: value }.into(),
            Candidate::HysteresisDamping => HysteresisDamping {
                coefficient: value,
                exponent: normal.base.get("exponent").unwrap_or(1.5),
            }
            .into(),
            Candidate::Adhesion => Adhesion {
                pull_off_force: value,
            }
            .into(),
            _ => Plasticity {
                permanent_ratio: value,
            }
            .into(),
        };
        let _ = normal.effects.push(term);
    }
    fn column(&self) -> Option<Candidate> {
        Some(self.column)
    }
}
