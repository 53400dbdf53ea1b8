//! A run drawn from a model's variation: each contact's parameter scatter (its
//! `noise`, Eq 18) and the `[variation]` of the fixed bodies — written once, for the
//! noise-added experiment's runs (`crate::experiment`) and a forecast's members
//! (`crate::replay`). And the moves of a fixed body both draw (and a diagnosis fits).

use super::{Contact, FrictionSpec, Model, Shape};
use hcm_core::effect::ExtendedLaw;
use hcm_core::LawError;
use nalgebra::{UnitQuaternion, Vector3};
use rand_chacha::ChaCha8Rng;
use rand_distr::{ChiSquared, Distribution, StandardNormal};

/// How Eq 18's ζ becomes a parameter's new value a′ from its value a and relative σ b.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Draw {
    /// The paper's: a′ = a + a·b·ζ, ζ ~ N(0, 1) as drawn (a generated experiment).
    Exact,
    /// A forecast member's: ζ truncated to ±2.5 (offsets too) and the factor 1 + b·ζ held ≥ 0.05, so
    /// a positive parameter stays positive; a value the law still refuses (a
    /// restitution above 1) has its offset from a halved until the law takes it. A
    /// member is a plausible run, never a run the model cannot simulate.
    Member,
}

impl Draw {
    /// a′ for ζ (the new value before any halving).
    pub fn value(self, a: f64, b: f64, zeta: f64) -> f64 {
        match self {
            Draw::Exact => a + a * b * zeta,
            Draw::Member => a * (1.0 + b * zeta.clamp(-2.5, 2.5)).max(0.05),
        }
    }

    /// An offset of standard deviation σ for ζ: σ·ζ, ζ truncated as the draw truncates.
    fn offset(self, sigma: f64, zeta: f64) -> f64 {
        match self {
            Draw::Exact => sigma * zeta,
            Draw::Member => sigma * zeta.clamp(-2.5, 2.5),
        }
    }
}

/// The name in a contact's `noise` table that scatters μ_s and μ_d by one ζ (both ×
/// the same factor, so μ_d ≤ μ_s holds): the friction coefficient of a surface that is
/// not the same at every spot.
pub const FRICTION_COEFFICIENT: &str = "mu";

/// One run of `model`: every contact's `noise` drawn by `draw` (Eq 18), in contact
/// order, then every fixed body's height and tilt (`[variation]`), in body order — a
/// generated run's model (`Draw::Exact`) or a forecast member's (`Draw::Member`); with
/// `variation.tails`, one scale for all of the run's draws is drawn first. An
/// error names the contact whose parameter left its law's domain.
pub fn drawn_run(
    model: &Model,
    rng: &mut ChaCha8Rng,
    draw: Draw,
) -> Result<Model, (usize, LawError)> {
    let mut model = model.clone();
    let scale = run_scale(rng, model.scenario.variation.tails);
    for (index, contact) in model.contacts.iter_mut().enumerate() {
        scatter_parameters(contact, rng, draw, scale).map_err(|source| (index, source))?;
    }
    let variation = &model.scenario.variation;
    let (height, tilt) = (variation.fixed_height, variation.fixed_tilt);
    if height > 0.0 || tilt > 0.0 {
        let fixed: Vec<usize> = (0..model.bodies.len())
            .filter(|&b| model.bodies[b].fixed)
            .collect();
        for body in fixed {
            if height > 0.0 {
                let shift = draw.offset(height, scale * normal(rng));
                shift_surface(&mut model, body, shift);
            }
            if tilt > 0.0 {
                let [x, y] = [0; 2].map(|_| draw.offset(tilt, scale * normal(rng)));
                tilt_surface(&mut model, body, x, y);
            }
        }
    }
    Ok(model)
}

/// Eq 18 on one contact: each parameter of its `noise` table (sorted by name, one draw
/// each × the run's `scale`, so a scenario's runs draw alike whatever else changes)
/// drawn by `draw`. A friction name acts on the contact's friction when it has one ([`FRICTION_COEFFICIENT`]
/// on both coefficients); any other name on the normal law, which refuses names it does
/// not have. Friction scattered out of its domain (v_d below v_s, say) is refused
/// rather than simulated.
fn scatter_parameters(
    contact: &mut Contact,
    rng: &mut ChaCha8Rng,
    draw: Draw,
    scale: f64,
) -> Result<(), LawError> {
    for (name, b) in &contact.noise {
        let zeta = scale * normal(rng);
        let friction = contact.model.friction.as_mut();
        if let Some(f) = friction {
            if name == FRICTION_COEFFICIENT {
                let factor = draw.value(1.0, *b, zeta);
                f.static_coefficient *= factor;
                f.dynamic_coefficient *= factor;
                continue;
            }
            if let Some(a) = FrictionSpec::parameter(f, name) {
                *a = draw.value(*a, *b, zeta);
                continue;
            }
        }
        draw_parameter(&mut contact.model.normal, name, *b, zeta, draw)?;
    }
    match &contact.model.friction {
        Some(friction) => friction.validate(),
        None => Ok(()),
    }
}

/// Eq 18 on one parameter `name` of `law`'s base law: its value a drawn by `draw` for
/// relative σ `b` (–) and `zeta`. A member's value the law refuses (a restitution
/// above one) has its offset from a halved until the law takes it, at most 30 times,
/// then keeps a; an exact draw is taken as drawn. [`LawError::UnknownParameter`] if the
/// law has no `name`.
pub fn draw_parameter(
    law: &mut ExtendedLaw<f64>,
    name: &str,
    b: f64,
    zeta: f64,
    draw: Draw,
) -> Result<(), LawError> {
    let a = law.base.get(name)?;
    let mut value = draw.value(a, b, zeta);
    law.base.set(name, value)?;
    if draw == Draw::Member {
        for _ in 0..30 {
            if law.validate().is_ok() {
                return Ok(());
            }
            value = a + 0.5 * (value - a);
            law.base.set(name, value)?;
        }
        if law.validate().is_err() {
            law.base.set(name, a)?;
        }
    }
    Ok(())
}

/// The unit up direction of `model`: against gravity, or +z without gravity.
pub fn up(model: &Model) -> Vector3<f64> {
    let g = model.gravity;
    if g.norm() > 0.0 {
        -g / g.norm()
    } else {
        Vector3::z()
    }
}

/// Moves fixed body `body`'s contact surface by `shift` (m): a plane's along its own
/// normal (its `offset`), any other shape's reference point along the up direction.
pub fn shift_surface(model: &mut Model, body: usize, shift: f64) {
    let up = up(model);
    let fixed = &mut model.bodies[body];
    match &mut fixed.shape {
        Shape::Plane { offset, .. } => *offset += shift,
        _ => fixed.position += up * shift,
    }
}

/// Tilts fixed body `body` by the rotation vector `(x, y, 0)` (rad, world axes): a
/// plane's normal turns, any other shape turns about its reference point.
pub fn tilt_surface(model: &mut Model, body: usize, x: f64, y: f64) {
    let tilt = UnitQuaternion::from_scaled_axis(Vector3::new(x, y, 0.0));
    let fixed = &mut model.bodies[body];
    match &mut fixed.shape {
        Shape::Plane { normal, .. } => *normal = tilt * *normal,
        _ => fixed.orientation = tilt * fixed.orientation,
    }
}

/// The run's scale on its normal draws for Student-t tails with `nu` degrees of freedom
/// (`VariationSpec::tails`): √((ν − 2)/χ²_ν), of mean square 1, so that each scaled
/// draw has unit variance; 1, drawing nothing, for the normal law (`nu` = 0), so that a
/// model without tails draws the same numbers it always drew.
fn run_scale(rng: &mut ChaCha8Rng, nu: f64) -> f64 {
    match ChiSquared::new(nu) {
        Ok(chi) if nu > 2.0 => {
            let w: f64 = chi.sample(rng);
            ((nu - 2.0) / w.max(f64::MIN_POSITIVE)).sqrt()
        }
        _ => 1.0,
    }
}

/// ζ ~ N(0, 1).
fn normal(rng: &mut ChaCha8Rng) -> f64 {
    StandardNormal.sample(rng)
}
