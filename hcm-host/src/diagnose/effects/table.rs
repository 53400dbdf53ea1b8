//! The fixed surface a body lands on, off from where the model has it: moved along its
//! normal by Δz (m), or tilted by small angles about the world x and y axes (rad).

use super::{first, Effect, Family, Scales, Site};
use crate::dataset::Evidence;
use crate::numerics::optimize::Bound;
use crate::replay::{shift_surface, tilt_surface};
use crate::scenario::Model;

/// The table's offset Δz ∈ ±L/20 (m) or tilt ∈ ±0.05 rad about x and y.
#[derive(Debug)]
pub struct Table {
    /// Tilted rather than moved.
    tilt: bool,
}

/// The table moved along its normal.
pub static OFFSET: Table = Table { tilt: false };
/// The table tilted.
pub static TILT: Table = Table { tilt: true };

impl Effect for Table {
    fn name(&self) -> &'static str {
        if self.tilt {
            "table_tilt"
        } else {
            "table_offset"
        }
    }
    fn family(&self) -> Family {
        Family::Measurement
    }
    fn evidence(&self, evidence: Evidence) -> bool {
        evidence == Evidence::Poses
    }
    /// A fixed body in the contact (a moving one starts where its own frames put it).
    fn applies(&self, model: &Model, site: Site) -> bool {
        let c = &model.contacts[site.contact];
        model.bodies[c.body_1].fixed || model.bodies[c.body_2].fixed
    }
    /// The fit from motion frees the partner's shift, not its tilt.
    fn within_base_fit(&self, _model: &Model, _site: Site) -> bool {
        !self.tilt
    }
    fn bounds(&self, _evidence: Evidence, s: &Scales) -> Vec<Bound> {
        if self.tilt {
            vec![
                Bound::linear("about_x", -0.05, 0.05),
                Bound::linear("about_y", -0.05, 0.05),
            ]
        } else {
            vec![Bound::linear("offset", -0.05 * s.arm, 0.05 * s.arm)]
        }
    }
    fn neutral(&self, _model: &Model, _site: Site) -> Vec<f64> {
        vec![0.0; 1 + usize::from(self.tilt)]
    }
    fn per_contact(&self) -> bool {
        false
    }
    fn apply(&self, model: &mut Model, site: Site, values: &[f64]) {
        if self.tilt {
            let second = values.get(1).copied().unwrap_or(0.0);
            tilt_surface(model, site.partner, first(values), second);
        } else {
            shift_surface(model, site.partner, first(values));
        }
    }
}
