//! A box's edges and corners rounded to a radius r (m): the point it pivots on as it
//! rolls over an edge moves round it (`shape.box.rounding`).

use super::{first, Effect, Family, Scales, Site};
use crate::dataset::Evidence;
use crate::numerics::optimize::Bound;
use crate::scenario::{Body, Model, Shape};

/// r ∈ [0, L/5] (m).
#[derive(Debug)]
pub struct EdgeRounding;

/// The moving box of `model`'s contact that may be rounded: a box (not fixed) against a
/// plane or a sphere, the pairs a rounded box is modelled in.
fn rounded_box(model: &Model, site: Site) -> Option<usize> {
    let c = &model.contacts[site.contact];
    let [one, two] = [c.body_1, c.body_2].map(|b| &model.bodies[b]);
    let partner_ok = |b: &Body| matches!(b.shape, Shape::Plane { .. } | Shape::Sphere { .. });
    if matches!(one.shape, Shape::Box { .. }) && !one.fixed && partner_ok(two) {
        Some(c.body_1)
    } else if matches!(two.shape, Shape::Box { .. }) && !two.fixed && partner_ok(one) {
        Some(c.body_2)
    } else {
        None
    }
}

/// A body's rounding (m): a box's, 0 for any other shape.
fn box_rounding(body: &Body) -> f64 {
    match body.shape {
        Shape::Box { rounding, .. } => rounding,
        _ => 0.0,
    }
}

impl Effect for EdgeRounding {
    fn name(&self) -> &'static str {
        "edge_rounding"
    }
    fn family(&self) -> Family {
        Family::Body
    }
    fn evidence(&self, evidence: Evidence) -> bool {
        evidence == Evidence::Poses
    }
    fn applies(&self, model: &Model, site: Site) -> bool {
        rounded_box(model, site).is_some()
    }
    /// The fit from motion frees a rounding the model has already.
    fn within_base_fit(&self, model: &Model, site: Site) -> bool {
        rounded_box(model, site).is_some_and(|b| box_rounding(&model.bodies[b]) > 0.0)
    }
    fn bounds(&self, _evidence: Evidence, s: &Scales) -> Vec<Bound> {
        vec![Bound::linear("radius", 0.0, 0.2 * s.arm)]
    }
    fn neutral(&self, model: &Model, site: Site) -> Vec<f64> {
        vec![rounded_box(model, site).map_or(0.0, |b| box_rounding(&model.bodies[b]))]
    }
    fn apply(&self, model: &mut Model, site: Site, values: &[f64]) {
        if let Some(b) = rounded_box(model, site) {
            if let Shape::Box {
                rounding,
                half_extents,
            } = &mut model.bodies[b].shape
            {
                *rounding = first(values).clamp(0.0, 0.99 * half_extents.min());
            }
        }
    }
}
