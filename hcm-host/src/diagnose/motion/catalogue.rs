//! What a motion-only diagnosis may find wrong with a tossed or sliding body's contact:
//! the friction law (its coefficient, its shape, a viscous part), resistance to
//! rotation (torsional, rolling), the impact's restitution (falling with the impact
//! speed), the body (its inertia, a box's rounded edges) and the measurement (the
//! table's height or tilt, the tracker's length scale). Each candidate is a small change of the user's model (or
//! of how the data are read) with its own parameters, every one of which has a neutral
//! value that changes nothing.

use super::super::Family;
use crate::dataset::Dataset;
use crate::numerics::optimize::Bound;
use crate::replay::{shift_surface, tilt_surface};
use crate::scenario::{Model, Shape};
use hcm_core::effect::{ContactEffect, HysteresisDamping};
use hcm_core::friction::{RollingResistance, TorsionalResistance, ViscousFriction};

/// Rotation rate (rad/s) below which the resistance couples fade: slow against a
/// tumbling cube (rad/s to tens of rad/s), fast against a body at rest.
const RESISTANCE_RATE: f64 = 0.1;

/// The stiffness k and exponent n of `model`'s `contact` law, if it has both.
fn stiffness_exponent(model: &Model, contact: usize) -> Option<(f64, f64)> {
    let law = model.contacts[contact].law();
    Some((law.get("stiffness").ok()?, law.get("exponent").ok()?))
}

/// The moving box of `model`'s `contact` that may be rounded: a box (not fixed)
/// against a plane or a sphere, the pairs a rounded box is modelled in.
fn rounded_box(model: &Model, contact: usize) -> Option<usize> {
    let c = &model.contacts[contact];
    let [one, two] = [c.body_1, c.body_2].map(|b| &model.bodies[b]);
    let partner_ok =
        |b: &crate::scenario::Body| matches!(b.shape, Shape::Plane { .. } | Shape::Sphere { .. });
    if matches!(one.shape, Shape::Box { .. }) && !one.fixed && partner_ok(two) {
        Some(c.body_1)
    } else if matches!(two.shape, Shape::Box { .. }) && !two.fixed && partner_ok(one) {
        Some(c.body_2)
    } else {
        None
    }
}

/// A body's rounding (m): a box's, 0 for any other shape.
fn box_rounding(body: &crate::scenario::Body) -> f64 {
    match body.shape {
        Shape::Box { rounding, .. } => rounding,
        _ => 0.0,
    }
}

/// One candidate change.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MotionEffect {
    /// Both friction coefficients scaled by k (–).
    FrictionCoefficient,
    /// Coulomb's law instead of STEP's two coefficients: μ_s = μ_d = μ (–).
    CoulombFriction,
    /// Viscous friction −c_v·v_t per contact point (N·s/m).
    ViscousFriction,
    /// Torsional resistance a_t (m).
    TorsionalResistance,
    /// Rolling resistance a_r (m).
    RollingResistance,
    /// A restitution that falls with the impact speed: Hunt–Crossley's damping
    /// χ·k·δ^n·δ̇ added to the law (k, n the law's stiffness and exponent; χ in s/m),
    /// e ≈ 1 − 2·χ·v/3 at impact speed v where the law alone keeps e about constant.
    SpeedDependentRestitution,
    /// The table's surface moved along its normal by Δz (m).
    TableOffset,
    /// The table tilted by small angles about the world x and y axes (rad).
    TableTilt,
    /// The tracker's lengths are s times the true ones (–).
    LengthScale,
    /// The body's inertia tensor scaled by k (–): its mass further out (or in) than the
    /// model has it.
    InertiaScale,
    /// A box's edges and corners rounded to a radius r (m): the point it pivots on as
    /// it rolls over an edge moves round it (`shape.box.rounding`).
    EdgeRounding,
}

impl MotionEffect {
    /// The catalogue, in the order a report lists it.
    pub const ALL: [MotionEffect; 11] = [
        MotionEffect::FrictionCoefficient,
        MotionEffect::CoulombFriction,
        MotionEffect::ViscousFriction,
        MotionEffect::TorsionalResistance,
        MotionEffect::RollingResistance,
        MotionEffect::SpeedDependentRestitution,
        MotionEffect::TableOffset,
        MotionEffect::TableTilt,
        MotionEffect::LengthScale,
        MotionEffect::InertiaScale,
        MotionEffect::EdgeRounding,
    ];

    /// The catalogue name a diagnosis prints.
    pub fn name(self) -> &'static str {
        match self {
            MotionEffect::FrictionCoefficient => "friction_coefficient",
            MotionEffect::CoulombFriction => "coulomb_friction",
            // The core's names of the tangential effects the candidates add.
            MotionEffect::ViscousFriction => ViscousFriction::<f64>::NAME,
            MotionEffect::TorsionalResistance => TorsionalResistance::<f64>::NAME,
            MotionEffect::RollingResistance => RollingResistance::<f64>::NAME,
            MotionEffect::SpeedDependentRestitution => "speed_dependent_restitution",
            MotionEffect::TableOffset => "table_offset",
            MotionEffect::TableTilt => "table_tilt",
            MotionEffect::LengthScale => "length_scale",
            MotionEffect::InertiaScale => "inertia_scale",
            MotionEffect::EdgeRounding => "edge_rounding",
        }
    }

    /// Its family.
    pub fn family(self) -> Family {
        match self {
            MotionEffect::FrictionCoefficient
            | MotionEffect::CoulombFriction
            | MotionEffect::ViscousFriction => Family::Friction,
            MotionEffect::TorsionalResistance | MotionEffect::RollingResistance => {
                Family::Resistance
            }
            MotionEffect::SpeedDependentRestitution => Family::Normal,
            MotionEffect::TableOffset | MotionEffect::TableTilt | MotionEffect::LengthScale => {
                Family::Measurement
            }
            MotionEffect::InertiaScale | MotionEffect::EdgeRounding => Family::Body,
        }
    }

    /// The box its parameters are searched in, scaled by the body's `mass` (kg) and
    /// `size` (m, its largest half extent); names with units.
    pub fn bounds(self, mass: f64, size: f64) -> Vec<Bound> {
        let bound = |name: &str, lower: f64, upper: f64, log_scale: bool| Bound {
            name: name.to_owned(),
            lower,
            upper,
            log_scale,
        };
        match self {
            MotionEffect::FrictionCoefficient => vec![bound("scale", 0.2, 5.0, true)],
            MotionEffect::CoulombFriction => vec![bound("mu", 0.01, 1.5, true)],
            // Up to a decay rate 4·c/m of 20 /s for a body on four corners.
            MotionEffect::ViscousFriction => vec![bound("coefficient", 0.0, 5.0 * mass, false)],
            MotionEffect::TorsionalResistance => vec![bound("arm", 0.0, 0.5 * size, false)],
            MotionEffect::RollingResistance => vec![bound("arm", 0.0, 0.5 * size, false)],
            // Up to e ≈ 0 at 0.5 m/s.
            MotionEffect::SpeedDependentRestitution => vec![bound("chi", 0.0, 3.0, false)],
            MotionEffect::TableOffset => vec![bound("offset", -0.05 * size, 0.05 * size, false)],
            MotionEffect::TableTilt => vec![
                bound("about_x", -0.05, 0.05, false),
                bound("about_y", -0.05, 0.05, false),
            ],
            MotionEffect::LengthScale => vec![bound("scale", 0.9, 1.1, false)],
            MotionEffect::InertiaScale => vec![bound("scale", 0.5, 2.0, true)],
            // Up to a fifth of the half extent: 10 mm on the 105 mm ContactNets cube.
            MotionEffect::EdgeRounding => vec![bound("radius", 0.0, 0.2 * size, false)],
        }
    }

    /// Whether it can change `model`'s `contact` at all: a coefficient or a shape needs
    /// a friction law, and Coulomb's law is no change of shape for a law whose μ_s = μ_d
    /// already (it would only repeat the coefficient's candidate); the restitution's
    /// damping needs a law with a stiffness and an exponent, and room for an effect; a
    /// surface's shift or tilt needs a fixed body in the contact (a moving one starts
    /// where its own frames put it).
    pub fn changes(self, model: &Model, contact: usize) -> bool {
        let friction = model.contacts[contact].model.friction;
        let c = &model.contacts[contact];
        match self {
            MotionEffect::TableOffset | MotionEffect::TableTilt => {
                model.bodies[c.body_1].fixed || model.bodies[c.body_2].fixed
            }
            MotionEffect::FrictionCoefficient => friction.is_some(),
            MotionEffect::CoulombFriction => {
                friction.is_some_and(|f| f.static_coefficient != f.dynamic_coefficient)
            }
            MotionEffect::SpeedDependentRestitution => {
                let normal = &model.contacts[contact].model.normal;
                stiffness_exponent(model, contact).is_some() && !normal.effects.is_full()
            }
            MotionEffect::EdgeRounding => rounded_box(model, contact).is_some(),
            _ => true,
        }
    }

    /// Whether the fit from motion ([`crate::identify::motion`]) already frees this
    /// change: the friction's coefficients (so also Coulomb's law, μ_s = μ_d), the
    /// partner's shift, the inertia's scale, and on a Hunt–Crossley law its damping χ,
    /// which a restitution falling with the impact speed (c·δⁿ·δ̇) only adds to. On a
    /// base that fit made, such a candidate is a better optimum of the base's own
    /// parameters, not a cause.
    pub fn within_motion_fit(self, model: &Model, contact: usize) -> bool {
        match self {
            MotionEffect::FrictionCoefficient
            | MotionEffect::CoulombFriction
            | MotionEffect::TableOffset
            | MotionEffect::InertiaScale => true,
            MotionEffect::SpeedDependentRestitution => {
                model.contacts[contact].law().name() == "hunt_crossley"
            }
            // identify-motion frees a rounding the scenario gives above 0.
            MotionEffect::EdgeRounding => {
                rounded_box(model, contact).is_some_and(|b| box_rounding(&model.bodies[b]) > 0.0)
            }
            _ => false,
        }
    }

    /// The parameters that change nothing (for Coulomb's law, which has none, the
    /// model's μ_d: the nearest Coulomb law).
    pub fn neutral(self, model: &Model, contact: usize) -> Vec<f64> {
        match self {
            MotionEffect::FrictionCoefficient
            | MotionEffect::LengthScale
            | MotionEffect::InertiaScale => vec![1.0],
            MotionEffect::CoulombFriction => {
                let friction = model.contacts[contact].model.friction;
                vec![friction.map_or(0.1, |f| f.dynamic_coefficient)]
            }
            MotionEffect::TableTilt => vec![0.0, 0.0],
            MotionEffect::EdgeRounding => {
                vec![rounded_box(model, contact).map_or(0.0, |b| box_rounding(&model.bodies[b]))]
            }
            _ => vec![0.0],
        }
    }

    /// `model` with the change `values` stand for at `contact` against fixed body `partner` (data
    /// transforms leave the model as it is).
    pub fn apply(self, model: &Model, contact: usize, partner: usize, values: &[f64]) -> Model {
        let mut out = model.clone();
        let first = values.first().copied().unwrap_or(0.0);
        let physics = &mut out.contacts[contact].model;
        match self {
            MotionEffect::FrictionCoefficient => {
                if let Some(f) = physics.friction.as_mut() {
                    f.static_coefficient *= first;
                    f.dynamic_coefficient *= first;
                }
            }
            MotionEffect::CoulombFriction => {
                if let Some(f) = physics.friction.as_mut() {
                    f.static_coefficient = first;
                    f.dynamic_coefficient = first;
                }
            }
            MotionEffect::ViscousFriction => {
                physics.tangential.viscous_friction = Some(ViscousFriction { coefficient: first });
            }
            MotionEffect::TorsionalResistance => {
                physics.tangential.torsional_resistance = Some(TorsionalResistance {
                    arm: first,
                    spin_rate: RESISTANCE_RATE,
                });
            }
            MotionEffect::RollingResistance => {
                physics.tangential.rolling_resistance = Some(RollingResistance {
                    arm: first,
                    roll_rate: RESISTANCE_RATE,
                });
            }
            MotionEffect::SpeedDependentRestitution => {
                if let Some((k, n)) = stiffness_exponent(model, contact) {
                    let damping = HysteresisDamping {
                        coefficient: first * k,
                        exponent: n,
                    };
                    // `changes` checked the room: a full list leaves the model as it is.
                    let _ = physics
                        .normal
                        .effects
                        .push(ContactEffect::HysteresisDamping(damping));
                }
            }
            MotionEffect::TableOffset => shift_surface(&mut out, partner, first),
            MotionEffect::TableTilt => {
                let second = values.get(1).copied().unwrap_or(0.0);
                tilt_surface(&mut out, partner, first, second);
            }
            MotionEffect::InertiaScale => {
                let c = &out.contacts[contact];
                let body = c.body_1 + c.body_2 - partner;
                out.bodies[body].inertia *= first;
            }
            MotionEffect::EdgeRounding => {
                if let Some(b) = rounded_box(model, contact) {
                    if let Shape::Box {
                        rounding,
                        half_extents,
                    } = &mut out.bodies[b].shape
                    {
                        // Below the smallest half extent, as the scenario key must be.
                        *rounding = first.clamp(0.0, 0.99 * half_extents.min());
                    }
                }
            }
            MotionEffect::LengthScale => {}
        }
        out
    }

    /// The data as the candidate reads them: for a length scale s, every position and
    /// velocity divided by s (about the world origin); otherwise `None` (as recorded).
    pub fn transform(self, data: &Dataset, values: &[f64]) -> Option<Dataset> {
        if self != MotionEffect::LengthScale {
            return None;
        }
        let scale = values.first().copied().unwrap_or(1.0);
        let mut out = data.clone();
        for run in &mut out.runs {
            for body in &mut run.bodies {
                for sample in &mut body.samples {
                    sample.position = sample.position.map(|x| x / scale);
                    sample.velocity = sample.velocity.map(|x| x / scale);
                }
            }
        }
        Some(out)
    }
}
