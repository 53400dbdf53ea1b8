//! What the fit from motion frees, and the box it searches: the contact law's
//! stiffness and its damping (how hard and how bouncy the landing is), the STEP
//! friction's μ_s and μ_d (how far the body slides), the table's height (the
//! tracker puts the resting cube 1 mm lower than its half width) and the tossed body's
//! inertia, as a scale k on the scenario's tensor (how far its mass sits from the
//! centre: how long a tumble lasts for the spin it starts with — the ContactNets
//! cube's own inertia was itself identified by its authors). The law's exponent,
//! its full-damping depth and the friction's transition speeds stay the scenario's:
//! poses at 148 Hz cannot tell them apart from the rest.
//!
//! Friction is searched as μ_s and μ_d/μ_s ∈ [0.3, 1], so every candidate is a valid law.

use crate::numerics::optimize::{Bound, Parameters};
use crate::scenario::{Model, Shape};
use crate::toss::{TossError, TossSetup};

/// The law parameters freed per law: (name, lower, upper, log scale), SI units.
fn law_genes(law: &str) -> Option<[(&'static str, f64, f64, bool); 2]> {
    match law {
        "impact" => Some([
            ("stiffness", 1e6, 1e8, true),
            ("max_damping", 30.0, 3e3, true),
        ]),
        "hunt_crossley" => Some([("stiffness", 1e6, 1e8, true), ("damping", 0.1, 50.0, true)]),
        "lankarani_nikravesh" | "flores" => Some([
            ("stiffness", 1e6, 1e8, true),
            ("restitution", 0.05, 1.0, false),
        ]),
        _ => None,
    }
}

/// The friction, table and body genes: name, lower, upper (–, –, m, –), log scale.
/// The inertia scale's box spans a body with its mass at the centre to one with it
/// at its surface: a uniform cube's 6.8e-4 kg·m² is 0.84 of the ContactNets data
/// set's value, a hollow shell's 1.13e-3 is 1.4 of it.
const OTHER_GENES: [(&str, f64, f64, bool); 4] = [
    ("mu_static", 0.05, 0.6, false),
    ("mu_ratio", 0.3, 1.0, false),
    ("table_offset", -3e-3, 1e-3, false),
    ("inertia_scale", 0.5, 2.0, true),
];

/// The free parameters of the tossed body's contact with its plane.
#[derive(Clone, Debug, PartialEq)]
pub struct MotionParameters {
    /// Index of the contact.
    pub contact: usize,
    /// Index of the plane's body.
    pub(crate) plane: usize,
    /// Index of the tossed body.
    pub(crate) body: usize,
    /// The law's two genes.
    law: [(&'static str, f64, f64, bool); 2],
}

impl MotionParameters {
    /// The parameters of `model`'s contact between its tossed body and the plane; the
    /// contact needs STEP friction and a law with a stiffness and a damping to fit.
    pub fn new(model: &Model, setup: &TossSetup) -> Result<MotionParameters, TossError> {
        let fail = |problem: String| TossError::Setup {
            scenario: model.scenario.name.clone(),
            problem,
        };
        let (contact, plane) = (model.contacts.iter().enumerate())
            .filter(|(_, c)| c.body_1 == setup.body || c.body_2 == setup.body)
            .map(|(i, c)| (i, c.body_1 + c.body_2 - setup.body))
            .find(|&(_, other)| matches!(model.bodies[other].shape, Shape::Plane { .. }))
            .ok_or_else(|| fail(format!("body `{}` has no contact with a plane", setup.name)))?;
        let found = &model.contacts[contact];
        if found.model.friction.is_none() {
            return Err(fail(format!(
                "contact {contact} has no friction to fit; give it \
                 `friction = {{ mu_static, mu_dynamic, v_static, v_dynamic }}`"
            )));
        }
        let name = found.law().name();
        let law = law_genes(name).ok_or_else(|| {
            fail(format!(
                "contact {contact}: the fit from motion frees a stiffness and a damping of \
                 `impact`, `hunt_crossley`, `lankarani_nikravesh` or `flores`, not of `{name}`"
            ))
        })?;
        Ok(MotionParameters {
            contact,
            plane,
            body: setup.body,
            law,
        })
    }
}

/// The genes, in order: the law's two, `mu_static`, `mu_ratio` (μ_d/μ_s),
/// `table_offset` (m, the plane's surface along its normal), `inertia_scale` (–, on
/// the scenario's inertia tensor of the tossed body).
impl Parameters for MotionParameters {
    type Target = Model;

    fn bounds(&self) -> Vec<Bound> {
        (self.law.iter().chain(&OTHER_GENES))
            .map(Bound::of_row)
            .collect()
    }

    /// The genes of `model` as it is (the scenario's values), clamped into the box.
    fn values(&self, model: &Model) -> Vec<f64> {
        let contact = &model.contacts[self.contact];
        let law = contact.law();
        let (mu_static, mu_ratio) = match contact.model.friction {
            Some(f) if f.static_coefficient > 0.0 => (
                f.static_coefficient,
                f.dynamic_coefficient / f.static_coefficient,
            ),
            _ => (0.0, 1.0),
        };
        let offset = match model.bodies[self.plane].shape {
            Shape::Plane { offset, .. } => offset,
            _ => 0.0,
        };
        let mut genes: Vec<f64> = self
            .law
            .iter()
            .map(|g| law.get(g.0).unwrap_or(g.1))
            .collect();
        // The scenario's own inertia: scale 1.
        genes.extend([mu_static, mu_ratio, offset, 1.0]);
        genes
            .iter()
            .zip(self.bounds())
            .map(|(g, b)| g.clamp(b.lower, b.upper))
            .collect()
    }

    /// `model` with the parameters `genes` stand for (the inertia scale on `model`'s
    /// own tensor: give it the scenario's model, not a fitted one).
    fn apply(&self, model: &Model, genes: &[f64]) -> Model {
        let mut out = model.clone();
        let contact = &mut out.contacts[self.contact];
        for (gene, value) in self.law.iter().zip(genes) {
            // The names come from the law's own table above: set cannot fail.
            let _ = contact.model.normal.base.set(gene.0, *value);
        }
        if let (Some(friction), [_, _, mu_static, mu_ratio, offset, inertia_scale]) =
            (contact.model.friction.as_mut(), genes)
        {
            friction.static_coefficient = *mu_static;
            friction.dynamic_coefficient = mu_static * mu_ratio;
            if let Shape::Plane { offset: slot, .. } = &mut out.bodies[self.plane].shape {
                *slot = *offset;
            }
            out.bodies[self.body].inertia *= *inertia_scale;
        }
        out
    }

    /// The named values (SI units) `genes` stand for: the law's two, `mu_static`,
    /// `mu_dynamic`, `table_offset` (m), `inertia_scale` (–).
    fn named(&self, genes: &[f64]) -> Vec<(String, f64)> {
        let mut out: Vec<(String, f64)> = (self.law.iter())
            .zip(genes)
            .map(|(g, v)| (g.0.to_owned(), *v))
            .collect();
        if let [_, _, mu_static, mu_ratio, offset, inertia_scale] = genes {
            out.extend([
                ("mu_static".to_owned(), *mu_static),
                ("mu_dynamic".to_owned(), mu_static * mu_ratio),
                ("table_offset".to_owned(), *offset),
                ("inertia_scale".to_owned(), *inertia_scale),
            ]);
        }
        out
    }
}
