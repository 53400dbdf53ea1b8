//! Couples against the bodies' relative rotation: torsional resistance a_t and rolling
//! resistance a_r (m), fading below [`super::RESISTANCE_RATE`].

use super::{first, Effect, Family, Scales, Site, RESISTANCE_RATE};
use crate::dataset::Evidence;
use crate::numerics::optimize::Bound;
use crate::scenario::Model;
use hcm_core::friction::{RollingResistance, TorsionalResistance};

/// A resistance couple with lever arm a ∈ [0, L/2] (m).
#[derive(Debug)]
pub struct Resistance {
    /// Rolling (about the tangent axes) rather than torsional (about the normal).
    rolling: bool,
}

/// Torsional resistance (about the contact normal).
pub static TORSIONAL: Resistance = Resistance { rolling: false };
/// Rolling resistance (about the tangent axes).
pub static ROLLING: Resistance = Resistance { rolling: true };

impl Effect for Resistance {
    fn name(&self) -> &'static str {
        if self.rolling {
            RollingResistance::<f64>::NAME
        } else {
            TorsionalResistance::<f64>::NAME
        }
    }
    fn family(&self) -> Family {
        Family::Resistance
    }
    fn evidence(&self, evidence: Evidence) -> bool {
        evidence != Evidence::LineForce
    }
    fn bounds(&self, evidence: Evidence, s: &Scales) -> Vec<Bound> {
        let arm = match evidence {
            Evidence::Poses => s.arm,
            _ => s.arm.max(1e-6),
        };
        vec![Bound::linear("arm", 0.0, 0.5 * arm)]
    }
    fn apply(&self, model: &mut Model, site: Site, values: &[f64]) {
        let tangential = &mut model.contacts[site.contact].model.tangential;
        let arm = first(values);
        if self.rolling {
            tangential.rolling_resistance = Some(RollingResistance {
                arm,
                roll_rate: RESISTANCE_RATE,
            });
        } else {
            tangential.torsional_resistance = Some(TorsionalResistance {
                arm,
                spin_rate: RESISTANCE_RATE,
            });
        }
    }
}
