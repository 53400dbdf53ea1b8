//! Chance as a cause: the run-to-run variation the deterministic model cannot carry,
//! each a spread the extended model keeps and every forecast member draws
//! (`crate::experiment::member_model`, `crate::replay::Spread`).
//!
//! - `contact_scatter`: the contact's stiffness, damping and friction coefficient each
//!   × (1 + σ·ζ) per run (its `noise`, Eq 18; `crate::replay::scatter_all`'s family):
//!   a table and a body that are not the same at every spot and landing.
//! - `start_uncertainty`: the replay's start state drawn with its free-flight fit's
//!   covariance × k² (`variation.start_state = k`): the state a replay starts from less
//!   (or more) certain than the tracker's noise makes it. The chance phase of a
//!   diagnosis draws it with k = 1 already, its neutral value.
//! - `fixed_height`, `fixed_tilt`: the fixed bodies moved by σ·ζ (m) along the up
//!   direction, or tilted by σ·ζ₁, σ·ζ₂ (rad) about x and y, per run.
//!
//! The neutral value 0 is no variation.

use super::{first, Effect, Family, Scales, Site};
use crate::dataset::Evidence;
use crate::numerics::optimize::Bound;
use crate::replay::scatter_contact;
use crate::scenario::Model;

/// Which variation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    ContactScatter,
    StartState,
    FixedHeight,
    FixedTilt,
}

/// One kind of run-to-run variation, its size the one parameter.
#[derive(Debug)]
pub struct Chance {
    kind: Kind,
}

/// The contact's parameters scattered by a relative σ ∈ [0, 0.6].
pub static CONTACT_SCATTER: Chance = Chance {
    kind: Kind::ContactScatter,
};
/// The start state's σ × k, k ∈ [0, [`START_FACTOR_MAX`]].
pub static START_UNCERTAINTY: Chance = Chance {
    kind: Kind::StartState,
};
/// The fixed bodies' height σ ∈ [0, L/20] m (less where resting bodies show less).
pub static FIXED_HEIGHT: Chance = Chance {
    kind: Kind::FixedHeight,
};
/// The fixed bodies' tilt σ ∈ [0, 0.05] rad (less where resting bodies show less).
pub static FIXED_TILT: Chance = Chance {
    kind: Kind::FixedTilt,
};

/// The largest factor on the start state's σ the fit's own residuals allow (–): the
/// residual σ̂ of a fit of `FIT_FRAMES` = 8 frames with 2 parameters per axis has 6
/// degrees of freedom, and σ/σ̂ exceeds √(6/χ²₆(0.025)) = √(6/1.237) = 2.2 one time in
/// 40. A spread the start state would need a larger factor for is not the start
/// state's: the frames it was fitted to say so.
const START_FACTOR_MAX: f64 = 2.2;

/// The largest tilt σ (rad) of the fixed body per run: 0.05, or where the recordings
/// end at rest, the most the resting body's tilt leaves for it beyond the tracker's
/// noise ([`Scales::rest_tilt`]) — a box resting on a table tilted by σ·ζ per run shows
/// that tilt, so a tilt the resting poses do not show is not the table's.
fn tilt_max(s: &Scales) -> f64 {
    const MAX: f64 = 0.05;
    if s.rest_tilt.is_finite() {
        s.rest_tilt.min(MAX)
    } else {
        MAX
    }
}

/// The largest height σ (m) of the fixed body per run: L/20, or less where the
/// recordings end at rest and the resting centre's height varies less beyond the
/// tracker's noise ([`Scales::rest_height`]).
fn height_max(s: &Scales) -> f64 {
    let max = 0.05 * s.arm;
    if s.rest_height.is_finite() {
        s.rest_height.min(max)
    } else {
        max
    }
}

impl Effect for Chance {
    fn name(&self) -> &'static str {
        match self.kind {
            Kind::ContactScatter => "contact_scatter",
            Kind::StartState => "start_uncertainty",
            Kind::FixedHeight => "fixed_height",
            Kind::FixedTilt => "fixed_tilt",
        }
    }
    fn family(&self) -> Family {
        Family::Chance
    }
    fn evidence(&self, evidence: Evidence) -> bool {
        evidence == Evidence::Poses
    }
    fn stochastic(&self) -> bool {
        true
    }
    fn applies(&self, model: &Model, site: Site) -> bool {
        let variation = &model.scenario.variation;
        match self.kind {
            Kind::ContactScatter => model.contacts[site.contact].noise.is_empty(),
            Kind::StartState => true,
            Kind::FixedHeight => variation.fixed_height == 0.0 && model.bodies[site.partner].fixed,
            Kind::FixedTilt => variation.fixed_tilt == 0.0 && model.bodies[site.partner].fixed,
        }
    }
    fn bounds(&self, _evidence: Evidence, s: &Scales) -> Vec<Bound> {
        vec![match self.kind {
            Kind::ContactScatter => Bound::linear("sigma", 0.0, 0.6),
            Kind::StartState => Bound::linear("factor", 0.0, START_FACTOR_MAX),
            Kind::FixedHeight => Bound::linear("sigma", 0.0, height_max(s)),
            Kind::FixedTilt => Bound::linear("sigma", 0.0, tilt_max(s)),
        }]
    }
    /// No variation; for the start state, the factor the model has (the chance phase
    /// draws it as its fit says, 1).
    fn neutral(&self, model: &Model, _site: Site) -> Vec<f64> {
        match self.kind {
            Kind::StartState => vec![model.scenario.variation.start_state],
            _ => vec![0.0],
        }
    }
    /// The contact's scatter on each alike contact; the others once.
    fn per_contact(&self) -> bool {
        self.kind == Kind::ContactScatter
    }
    fn apply(&self, model: &mut Model, site: Site, values: &[f64]) {
        let size = first(values).max(0.0);
        let variation = &mut model.scenario.variation;
        match self.kind {
            Kind::ContactScatter => scatter_contact(&mut model.contacts[site.contact], size),
            Kind::StartState => variation.start_state = size,
            Kind::FixedHeight => variation.fixed_height = size,
            Kind::FixedTilt => variation.fixed_tilt = size,
        }
    }
}
