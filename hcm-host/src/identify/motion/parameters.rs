//! What the fit from motion frees, and the box it searches: the contact law's
//! stiffness and its damping (how hard and how bouncy the landing is), the STEP
//! friction's μ_s and μ_d (how far the body slides), the fixed partner's height (the
//! tracker puts the resting ContactNets cube 1 mm lower than its half width) and the
//! replayed body's inertia, as a scale k on the scenario's tensor (how far its mass
//! sits from the centre: how long a tumble lasts for the spin it starts with — the
//! ContactNets cube's own inertia was itself identified by its authors). The law's
//! exponent, its full-damping depth and the friction's transition speeds stay the
//! scenario's: poses at a camera's rate cannot tell them apart from the rest.
//!
//! The law's box is the scenario's `[identify.bounds.<law>]` where it gives one, else
//! scaled from the scenario itself (no fixed numbers that fit one example):
//! a stiffness or a damping from the scenario's own value ÷/× [`SPAN`]; a damping the
//! scenario sets to zero from the body's critical damping on its static indentation;
//! a restitution over 0.05…1.
//!
//! Friction is searched as μ_s and μ_d/μ_s ∈ [0.3, 1], so every candidate is a valid law.
//!
//! A mechanism: the contacts the scenario declares alike with the fitted one (its
//! links on the same table with the same law and friction, [`Model::alike_contacts`])
//! take the same law and friction genes, its links that are copies of the replayed
//! body the same inertia scale and rounding; each joint's law terms the scenario
//! declares (`[[joint]] law = { viscous = …, coulomb = …, spring = … }`) are freed too,
//! each over 0 … [`JointTerm::upper`] of the joint's scales. A free hinge stays free:
//! what it lacks is the diagnosis' question.

use crate::numerics::optimize::{Bound, Parameters};
use crate::replay::shift_surface;
use crate::replay::{TossError, TossSetup};
use crate::scenario::{JointTerm, Model, Shape};

/// Factor on each side of the scenario's stiffness or damping its box spans (–).
pub const SPAN: f64 = 30.0;

/// Law parameters the fit from motion frees, where the law has them: what sets how
/// hard (a stiffness, a modulus) and how bouncy (a damping, a restitution) a landing is.
const FREED: [&str; 5] = [
    "stiffness",
    "effective_modulus",
    "max_damping",
    "damping",
    "restitution",
];

/// The friction, partner and body genes: name, lower, upper (–, –, m, –), log scale.
/// μ_s reaches past 0.6 when the scenario's own is higher (see [`other_genes`]). The
/// partner's shift is a tracker's calibration error, −3 … +1 mm whatever the body
/// (the ContactNets table sits 1 mm lower than the cube's half width). The inertia
/// scale's box spans a body with its mass at the centre to one with it at its
/// surface: a uniform cube's 6.8e-4 kg·m² is 0.84 of the ContactNets data set's
/// value, a hollow shell's 1.13e-3 is 1.4 of it.
const OTHER_GENES: [(&str, f64, f64, bool); 4] = [
    ("mu_static", 0.05, 0.6, false),
    ("mu_ratio", 0.3, 1.0, false),
    ("table_offset", -3e-3, 1e-3, false),
    ("inertia_scale", 0.5, 2.0, true),
];

/// The free parameters of the replayed body's contact with a fixed partner (and of
/// the contacts the scenario declares alike with it, [`Model::alike_contacts`]: a
/// mechanism's links on one table), and of its joints' declared law terms.
#[derive(Clone, Debug, PartialEq)]
pub struct MotionParameters {
    /// Index of the contact.
    pub contact: usize,
    /// The contacts fitted as one: `contact` and those alike with it.
    pub(crate) contacts: Vec<usize>,
    /// Index of the partner's body (a table, a ramp…).
    pub(crate) partner: usize,
    /// Index of the replayed body.
    pub(crate) body: usize,
    /// The bodies the inertia scale and the rounding change: the replayed body and the
    /// other movers of the alike contacts with its mass, shape and inertia (copies of
    /// it, as the elbow's two links).
    pub(crate) bodies: Vec<usize>,
    /// The law's genes (one or two), then the other four, the rounding, the joints'.
    genes: Vec<Bound>,
}

impl MotionParameters {
    /// The parameters of `model`'s first contact between its replayed body and a fixed
    /// body; the contact needs STEP friction and a law with a stiffness to fit.
    pub fn new(model: &Model, setup: &TossSetup) -> Result<MotionParameters, TossError> {
        Self::for_contact(model, setup, None)
    }

    /// The parameters of contact `chosen` of `model` (one of a moving body's), or when
    /// `None` of the primary body's first contact with a fixed body (else any moving
    /// body's first with a fixed body, else the primary's first). The contact needs STEP
    /// friction and a law with a stiffness to fit.
    pub fn for_contact(
        model: &Model,
        setup: &TossSetup,
        chosen: Option<usize>,
    ) -> Result<MotionParameters, TossError> {
        let fail = |problem: String| TossError::Setup {
            scenario: model.scenario.name.clone(),
            problem,
        };
        let contact = match chosen {
            Some(c) => Some(c).filter(|&c| {
                let found = model.contacts.get(c);
                found.is_some_and(|f| {
                    !(model.bodies[f.body_1].fixed && model.bodies[f.body_2].fixed)
                })
            }),
            None => default_contact(model, setup),
        }
        .ok_or_else(|| match chosen {
            Some(c) => fail(format!("contact {c} is not one of a moving body's")),
            None => fail(format!("body `{}` has no contact to fit", setup.name)),
        })?;
        let found = &model.contacts[contact];
        let Some(friction) = found.model.friction else {
            return Err(fail(format!(
                "contact {contact} has no friction to fit; give it \
                 `friction = {{ mu_static, mu_dynamic, v_static, v_dynamic }}`"
            )));
        };
        // The replayed body of the contact: the primary where it is one of them, else
        // its moving body (the first where both move); the partner is the other.
        let (a, b) = (found.body_1, found.body_2);
        let body = if b == setup.body || model.bodies[a].fixed {
            b
        } else {
            a
        };
        let partner = a + b - body;
        let mut genes = law_genes(model, contact, body).map_err(fail)?;
        genes.extend(other_genes(
            friction.static_coefficient,
            model.bodies[partner].fixed,
        ));
        genes.extend(rounding_gene(&model.bodies[body].shape));
        genes.extend(joint_genes(model));
        let contacts = model.alike_contacts(contact);
        let same = |b: usize| {
            let (one, other) = (&model.bodies[b], &model.bodies[body]);
            one.mass == other.mass && one.shape == other.shape && one.inertia == other.inertia
        };
        let bodies = (contacts.iter())
            .map(|&c| model.mover_of(c, partner))
            .filter(|&b| b == body || same(b))
            .collect();
        Ok(MotionParameters {
            contact,
            contacts,
            partner,
            body,
            bodies,
            genes,
        })
    }

    /// The contacts fitted as one: the fitted contact first, then those alike with it
    /// ([`Model::alike_contacts`]).
    pub fn contacts(&self) -> Vec<usize> {
        let others = self.contacts.iter().filter(|&&c| c != self.contact);
        std::iter::once(self.contact)
            .chain(others.copied())
            .collect()
    }

    /// Genes of the law (one or two): those before `mu_static`.
    fn law_len(&self) -> usize {
        (self.genes.iter())
            .position(|g| g.name == "mu_static")
            .unwrap_or(self.genes.len())
    }
}

/// The primary's first contact with a fixed body, else any moving body's first with a
/// fixed body, else the primary's first contact.
fn default_contact(model: &Model, setup: &TossSetup) -> Option<usize> {
    let of = |c: &crate::scenario::Contact, body: usize| c.body_1 == body || c.body_2 == body;
    let fixed =
        |c: &crate::scenario::Contact| model.bodies[c.body_1].fixed || model.bodies[c.body_2].fixed;
    let contacts = &model.contacts;
    (contacts.iter().position(|c| of(c, setup.body) && fixed(c)))
        .or_else(|| {
            contacts
                .iter()
                .position(|c| fixed(c) && setup.movers.iter().any(|m| of(c, m.body)))
        })
        .or_else(|| contacts.iter().position(|c| of(c, setup.body)))
}

/// The friction, partner and body bounds, μ_s's upper bound raised to twice the
/// scenario's μ_s (–) where that is higher; the partner's shift only when it is fixed
/// (a moving partner starts where its own frames put it).
fn other_genes(mu_static: f64, fixed_partner: bool) -> impl Iterator<Item = Bound> {
    let rows = OTHER_GENES
        .iter()
        .filter(move |row| fixed_partner || row.0 != "table_offset");
    rows.map(move |row| {
        let mut bound = Bound::of_row(row);
        if row.0 == "mu_static" && mu_static.is_finite() {
            bound.upper = bound.upper.max(2.0 * mu_static);
        }
        bound
    })
}

/// The genes of every joint's declared law terms, named by their scenario keys
/// (`joint.0.law.viscous.damping`): 0 … [`JointTerm::upper`] of the joint's scales.
fn joint_genes(model: &Model) -> Vec<Bound> {
    let mut genes = Vec::new();
    for (j, joint) in model.joints.iter().enumerate() {
        let scales = joint.scales(model);
        for term in joint.declared_terms() {
            let [name, coefficient] = term.key();
            genes.push(Bound::linear(
                format!("joint.{j}.law.{name}.{coefficient}"),
                0.0,
                term.upper(&scales),
            ));
        }
    }
    genes
}

/// The joint and the term a joint gene (`joint.<j>.law.<term>.<coefficient>`) sets.
fn joint_gene(name: &str) -> Option<(usize, JointTerm)> {
    let mut parts = name.split('.');
    let (Some("joint"), Some(j), Some("law"), Some(term)) =
        (parts.next(), parts.next(), parts.next(), parts.next())
    else {
        return None;
    };
    let term = JointTerm::ALL.into_iter().find(|t| t.key()[0] == term)?;
    Some((j.parse().ok()?, term))
}

/// Upper bound of a box's rounding gene, as a multiple of the rounding the scenario
/// gives (–): from a sharp box to three times the guess.
const ROUNDING_SPAN: f64 = 3.0;

/// Most a rounding may reach, as a fraction of the box's smallest half extent (–).
const ROUNDING_MAX: f64 = 0.9;

/// The `rounding` gene (m) of a replayed box whose scenario gives its edges a radius
/// above 0 (a user's guess: a sharp box keeps its edges sharp, and the fits of the
/// scenarios that give none are unchanged): 0 … [`ROUNDING_SPAN`] × the guess, below
/// [`ROUNDING_MAX`] of the smallest half extent.
fn rounding_gene(shape: &Shape) -> Option<Bound> {
    match shape {
        Shape::Box {
            half_extents,
            rounding,
        } if *rounding > 0.0 => Some(Bound {
            name: "rounding".to_owned(),
            lower: 0.0,
            upper: (ROUNDING_SPAN * rounding).min(ROUNDING_MAX * half_extents.min()),
            log_scale: false,
        }),
        _ => None,
    }
}

/// The law's freed parameters of `contact` and their box (see the module
/// documentation), or why the law has none to fit.
fn law_genes(model: &Model, contact: usize, body: usize) -> Result<Vec<Bound>, String> {
    let law = model.contacts[contact].law();
    let name = law.name();
    let given = model.scenario.identify.bounds.get(name);
    let genes: Vec<Bound> = (law.kind().parameters().iter())
        .filter(|p| FREED.contains(&p.name))
        .map(|p| {
            let value = law.get(p.name).unwrap_or(f64::NAN);
            let (lower, upper, log) = match given.and_then(|g| g.get(p.name)) {
                Some(&[lower, upper]) => (lower, upper, lower > 0.0),
                None if p.name == "restitution" => (0.05, 1.0, false),
                None if value > 0.0 && value.is_finite() => (value / SPAN, value * SPAN, true),
                None => {
                    let scale = zero_damping_scale(model, contact, body, p.name);
                    (scale / 1e3, scale * 10.0, true)
                }
            };
            Bound {
                name: p.name.to_owned(),
                lower,
                upper,
                log_scale: log,
            }
        })
        .collect();
    if genes
        .iter()
        .any(|g| g.name == "stiffness" || g.name == "effective_modulus")
    {
        Ok(genes)
    } else {
        Err(format!(
            "contact {contact}: the fit from motion frees a law's stiffness and damping \
             ({}), and `{name}` has none of them",
            FREED.join(", ")
        ))
    }
}

/// The rounding of a box (m); 0 for any other shape.
fn box_rounding(shape: &Shape) -> f64 {
    match shape {
        Shape::Box { rounding, .. } => *rounding,
        _ => 0.0,
    }
}

/// The scale of a damping the scenario sets to zero: for IMPACT's `max_damping` the
/// critical damping 2·√(k_lin·m) (N·s/m) of the body's mass on the linearised law at
/// its static indentation, δ_s = (m·g/k)^(1/e), k_lin = e·k·δ_s^(e−1); for any other
/// damping 1 in its own unit (Hunt–Crossley's χ: 1 s/m, the restitution of a 1 m/s
/// landing near 0.3).
fn zero_damping_scale(model: &Model, contact: usize, body: usize, name: &str) -> f64 {
    let law = model.contacts[contact].law();
    let (Ok(k), Ok(e)) = (law.get("stiffness"), law.get("exponent")) else {
        return 1.0;
    };
    if name != "max_damping" || !(k > 0.0 && e > 0.0) {
        return 1.0;
    }
    let m = model.bodies[body].mass;
    let weight = m * model.gravity.norm();
    let depth = (weight / k).powf(1.0 / e);
    let linear = e * k * depth.powf(e - 1.0);
    let critical = 2.0 * (linear * m).sqrt();
    if critical.is_finite() && critical > 0.0 {
        critical
    } else {
        1.0
    }
}

/// The genes, in order: the law's (one or two), `mu_static`, `mu_ratio` (μ_d/μ_s),
/// `table_offset` (m, the partner's surface moved from the scenario's: a plane along
/// its normal, another shape along the up direction), `inertia_scale` (–, on the
/// scenario's inertia tensor of the replayed body), and for a box given rounded edges
/// `rounding` (m, their radius).
impl Parameters for MotionParameters {
    type Target = Model;

    fn bounds(&self) -> Vec<Bound> {
        self.genes.clone()
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
        let mut genes: Vec<f64> = (self.genes[..self.law_len()].iter())
            .map(|g| law.get(&g.name).unwrap_or(g.lower))
            .collect();
        // The scenario's own partner and inertia: shift 0, scale 1.
        genes.extend(
            self.genes[self.law_len()..]
                .iter()
                .map(|g| match g.name.as_str() {
                    "mu_static" => mu_static,
                    "mu_ratio" => mu_ratio,
                    "table_offset" => 0.0,
                    "rounding" => box_rounding(&model.bodies[self.body].shape),
                    name => match joint_gene(name) {
                        Some((j, term)) => term.get(&model.joints[j].law).unwrap_or(0.0),
                        None => 1.0,
                    },
                }),
        );
        (genes.iter().zip(&self.genes))
            .map(|(g, b)| g.clamp(b.lower, b.upper))
            .collect()
    }

    /// `model` with the parameters `genes` stand for (the shift and the inertia scale
    /// on `model`'s own partner and tensor: give it the scenario's model, not a fitted
    /// one).
    fn apply(&self, model: &Model, genes: &[f64]) -> Model {
        let mut out = model.clone();
        let (law, other) = genes.split_at(self.law_len().min(genes.len()));
        let named = |name: &str| {
            let at = self.genes[self.law_len()..]
                .iter()
                .position(|g| g.name == name);
            at.and_then(|i| other.get(i).copied())
        };
        for &c in &self.contacts {
            let contact = &mut out.contacts[c];
            for (gene, value) in self.genes.iter().zip(law) {
                // The names come from the law's own parameter list: set cannot fail.
                let _ = contact.model.normal.base.set(&gene.name, *value);
            }
            if let (Some(friction), Some(mu_static), Some(mu_ratio)) = (
                contact.model.friction.as_mut(),
                named("mu_static"),
                named("mu_ratio"),
            ) {
                friction.static_coefficient = mu_static;
                friction.dynamic_coefficient = mu_static * mu_ratio;
            }
        }
        if let Some(shift) = named("table_offset") {
            shift_surface(&mut out, self.partner, shift);
        }
        for &b in &self.bodies {
            let body = &mut out.bodies[b];
            if let Some(scale) = named("inertia_scale") {
                body.inertia *= scale;
            }
            if let (Some(r), Shape::Box { rounding, .. }) = (named("rounding"), &mut body.shape) {
                *rounding = r;
            }
        }
        let joints =
            (self.genes.iter().zip(genes)).filter_map(|(g, v)| Some((joint_gene(&g.name)?, *v)));
        for ((j, term), value) in joints {
            let scales = out.joints[j].scales(&out);
            term.set(&mut out.joints[j].law, value, &scales);
        }
        out
    }

    /// The named values (SI units) `genes` stand for: the law's, `mu_static`,
    /// `mu_dynamic`, `table_offset` (m), `inertia_scale` (–), `rounding` (m).
    fn named(&self, genes: &[f64]) -> Vec<(String, f64)> {
        let (law, other) = genes.split_at(self.law_len().min(genes.len()));
        let mut out: Vec<(String, f64)> = (self.genes.iter())
            .zip(law)
            .map(|(g, v)| (g.name.clone(), *v))
            .collect();
        let mu_static = (self.genes.iter().zip(genes)).find(|(g, _)| g.name == "mu_static");
        for (gene, &value) in self.genes[self.law_len()..].iter().zip(other) {
            match (gene.name.as_str(), mu_static) {
                ("mu_ratio", Some((_, &mu))) => out.push(("mu_dynamic".to_owned(), mu * value)),
                (name, _) => out.push((name.to_owned(), value)),
            }
        }
        out
    }
}
