//! The parameters PM2 frees on a rigid contact: the normal law's (but the exponent,
//! which PM2 fixes) and its STEP friction's (Eq 10–11), with their search box.
//!
//! Friction is searched as μ_s, μ_d/μ_s, v_s and v_d/v_s, so that every point of the
//! box is a valid law (μ_d ≤ μ_s, v_s < v_d) and none of the algorithm's budget is
//! spent on impossible candidates.

use super::RigidIdentifyError;
use crate::identify::bounds::{Bounds, BoundsOverrides};
use crate::numerics::optimize::{Bound, Parameters};
use crate::scenario::Model;
use hcm_core::friction::VelocityStepFriction;

/// The friction genes: name, lower, upper, log scale.
const FRICTION: [(&str, f64, f64, bool); 4] = [
    ("mu_static", 0.05, 1.0, false),
    ("mu_ratio", 0.1, 1.0, false),
    ("v_static", 1e-5, 1e-2, true),
    ("v_ratio", 2.0, 1e3, true),
];

/// The free parameters of one contact and their box.
#[derive(Clone, Debug)]
pub struct RigidParameters {
    /// Index of the contact they are parameters of.
    contact: usize,
    /// The law's free parameters (the exponent excluded).
    law: Bounds,
    /// Whether the contact has friction to fit.
    friction: bool,
    /// The law's parameters whose box the scenario sets (`[identify.bounds.<law>]`):
    /// [`RigidParameters::scale`] leaves them alone.
    given: Vec<String>,
}

impl RigidParameters {
    /// The law's box (defaults, or the scenario's `[identify.bounds.<law>]`) without
    /// `exponent`, plus friction when contact `c` has it.
    pub fn new(
        model: &Model,
        c: usize,
        overrides: &BoundsOverrides,
    ) -> Result<RigidParameters, RigidIdentifyError> {
        let contact = model
            .contacts
            .get(c)
            .ok_or(RigidIdentifyError::NoSuchContact(c))?;
        let name = contact.law().name();
        let mut law =
            Bounds::for_law(name, overrides.get(name)).map_err(RigidIdentifyError::Setup)?;
        law.parameters.retain(|p| p.name != "exponent");
        let given = overrides
            .get(name)
            .map_or_else(Vec::new, |o| o.keys().cloned().collect());
        Ok(RigidParameters {
            contact: c,
            law,
            friction: contact.model.friction.is_some(),
            given,
        })
    }

    /// The same parameters with the law's exponent free too, in its box (the default
    /// or the scenario's): the least-squares fit from force samples can find it where
    /// the replayed events of PM2 (Table 15) fix it.
    pub fn with_exponent(
        mut self,
        model: &Model,
        overrides: &BoundsOverrides,
    ) -> Result<RigidParameters, RigidIdentifyError> {
        let name = model.contacts[self.contact].law().name();
        let all = Bounds::for_law(name, overrides.get(name)).map_err(RigidIdentifyError::Setup)?;
        let at = all.parameters.iter().position(|p| p.name == "exponent");
        if let (Some(at), false) = (at, self.fits_exponent()) {
            let exponent = all.parameters[at].clone();
            self.law
                .parameters
                .insert(at.min(self.law.parameters.len()), exponent);
        }
        Ok(self)
    }

    /// Whether the exponent is among the free parameters.
    pub fn fits_exponent(&self) -> bool {
        self.law.parameters.iter().any(|p| p.name == "exponent")
    }

    /// Sets the box of the law's parameter `name` to [lower, upper] (its units) unless
    /// the scenario gives that box or the law has no such free parameter; whether it
    /// did. A box scaled from the data ([`super::scaled`]) replaces the defaults, which
    /// fit the paper's examples and not every rig.
    pub fn scale(&mut self, name: &str, lower: f64, upper: f64) -> bool {
        if self.given.iter().any(|g| g == name) || !(lower < upper && lower.is_finite()) {
            return false;
        }
        match self.law.parameters.iter_mut().find(|p| p.name == name) {
            Some(bound) if !bound.log_scale || lower > 0.0 => {
                (bound.lower, bound.upper) = (lower, upper);
                true
            }
            _ => false,
        }
    }
}

/// The genes, in order: the law's, then μ_s, μ_d/μ_s, v_s, v_d/v_s.
impl Parameters for RigidParameters {
    type Target = Model;

    fn bounds(&self) -> Vec<Bound> {
        let mut bounds = self.law.bounds();
        if self.friction {
            bounds.extend(FRICTION.iter().map(Bound::of_row));
        }
        bounds
    }

    /// The contact's law parameters as they are, then its friction's genes (μ_s,
    /// μ_d/μ_s, v_s, v_d/v_s; NaN without friction).
    fn values(&self, model: &Model) -> Vec<f64> {
        let contact = &model.contacts[self.contact];
        let mut values = self.law.values(&contact.model.normal.base);
        if self.friction {
            let f = contact.model.friction;
            values.extend(f.map_or([f64::NAN; 4], |f| {
                [
                    f.static_coefficient,
                    f.dynamic_coefficient / f.static_coefficient,
                    f.stiction_speed,
                    f.dynamic_speed / f.stiction_speed,
                ]
            }));
        }
        values
    }

    /// `model` with the contact's free parameters set to `genes`.
    fn apply(&self, model: &Model, genes: &[f64]) -> Model {
        let mut out = model.clone();
        let contact = &mut out.contacts[self.contact];
        let count = self.law.free().len();
        let (law, friction) = genes.split_at(count.min(genes.len()));
        contact.model.normal.base = self.law.with(&contact.model.normal.base, law);
        if let (true, [mu_static, mu_ratio, v_static, v_ratio]) = (self.friction, friction) {
            contact.model.friction = Some(VelocityStepFriction {
                static_coefficient: *mu_static,
                dynamic_coefficient: mu_static * mu_ratio,
                stiction_speed: *v_static,
                dynamic_speed: v_static * v_ratio,
            });
        }
        out
    }

    /// The named values (SI units) of the parameters `genes` stand for: the law's, then
    /// `mu_static`, `mu_dynamic`, `v_static`, `v_dynamic`.
    fn named(&self, genes: &[f64]) -> Vec<(String, f64)> {
        let count = self.law.free().len();
        let mut out: Vec<(String, f64)> = self
            .law
            .free()
            .iter()
            .zip(genes)
            .map(|(n, v)| (n.to_string(), *v))
            .collect();
        if let (true, Some([mu_static, mu_ratio, v_static, v_ratio])) = (
            self.friction,
            genes
                .get(count..)
                .and_then(|f| <&[f64; 4]>::try_from(f).ok()),
        ) {
            out.extend([
                ("mu_static".to_owned(), *mu_static),
                ("mu_dynamic".to_owned(), mu_static * mu_ratio),
                ("v_static".to_owned(), *v_static),
                ("v_dynamic".to_owned(), v_static * v_ratio),
            ]);
        }
        out
    }
}
