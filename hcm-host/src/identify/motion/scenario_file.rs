//! The fitted model as a scenario file: the scenario as read (its `--set` overrides
//! applied) with the fitted law parameters, friction coefficients and table offset
//! written in, so that `hcm predict --scenario FILE` replays the fit with nothing else
//! to give; the physics file carries the same as its law, friction and `sets` (the
//! original's comments are not kept).

use super::MotionParameters;
use crate::replay::shift_surface;
use crate::scenario::{Assignment, Model, Scenario, ScenarioError, Shape};

/// The assignments that turn `model`'s scenario into the fitted one, from the
/// fit's `MotionParameters::named` values: the law's two parameters, `mu_static`,
/// `mu_dynamic` (on every contact fitted as one), `table_offset` (m), `inertia_scale`
/// (–) and a box's `rounding` (m) (on every body they change), and the joints' law
/// terms (their genes are named by their keys).
pub fn fitted_assignments(
    model: &Model,
    parameters: &MotionParameters,
    named: &[(String, f64)],
) -> Vec<Assignment> {
    let mut out = Vec::new();
    for (name, value) in named {
        match name.as_str() {
            _ if beside_the_contact(name) => {
                out.extend(body_assignments(model, parameters, name, *value))
            }
            "mu_static" | "mu_dynamic" => out.extend(
                (parameters.contacts.iter())
                    .map(|&c| Assignment::contact(c, &["friction", name], *value)),
            ),
            _ => out.extend(
                (parameters.contacts.iter())
                    .map(|&c| Assignment::contact(c, &["parameters", name], *value)),
            ),
        }
    }
    out
}

/// The assignments (`--set`s) a physics file — which holds the law and the friction, not the bodies —
/// needs beside it to replay the fit: the table's surface at the fitted offset (m),
/// the tossed body's inertia at the fitted scale of `model`'s (the scenario's) tensor
/// and a box's fitted rounding (m).
pub fn beside_physics(
    model: &Model,
    parameters: &MotionParameters,
    named: &[(String, f64)],
) -> Vec<Assignment> {
    (named.iter())
        .filter(|(name, _)| beside_the_contact(name))
        .flat_map(|(name, value)| body_assignments(model, parameters, name, *value))
        .collect()
}

/// Whether gene `name` is not a contact's: a body's, the table's or a joint's (what a
/// physics file carries as its `sets`).
fn beside_the_contact(name: &str) -> bool {
    matches!(name, "table_offset" | "inertia_scale" | "rounding") || name.starts_with("joint.")
}

/// [`body_assignment`] on every body the gene changes (the inertia and the rounding:
/// each of `parameters.bodies`); a joint's gene at its own key.
fn body_assignments(
    model: &Model,
    parameters: &MotionParameters,
    name: &str,
    value: f64,
) -> Vec<Assignment> {
    match name {
        "inertia_scale" | "rounding" => (parameters.bodies.iter())
            .map(|&b| body_assignment(model, parameters, b, name, value))
            .collect(),
        _ if name.starts_with("joint.") => vec![Assignment::new(name.split('.'), value)],
        _ => vec![body_assignment(
            model,
            parameters,
            parameters.body,
            name,
            value,
        )],
    }
}

/// The assignment of one body gene: `table_offset` moves the partner's surface by
/// `value` (m) from `model`'s (a plane's offset, another shape's position along the up
/// direction); `inertia_scale` sets the tossed body's inertia to `value` times `model`'s,
/// as principal moments when the tensor is diagonal (kg·m²).
fn body_assignment(
    model: &Model,
    parameters: &MotionParameters,
    body: usize,
    name: &str,
    value: f64,
) -> Assignment {
    if name == "table_offset" {
        // The fit's own move ([`shift_surface`]), written as the keys it changed.
        let mut moved = model.clone();
        shift_surface(&mut moved, parameters.partner, value);
        let partner = &moved.bodies[parameters.partner];
        return match partner.shape {
            Shape::Plane { offset, .. } => {
                Assignment::body(&partner.name, &["shape", "plane", "offset"], offset)
            }
            _ => {
                let row = (partner.position.iter()).map(|&x| x.into()).collect();
                Assignment::body(&partner.name, &["position"], toml::Value::Array(row))
            }
        };
    }
    let body = &model.bodies[body];
    if name == "rounding" {
        return Assignment::body(&body.name, &["shape", "box", "rounding"], value);
    }
    let inertia = body.inertia * value;
    let diagonal = (0..3).all(|i| (0..3).all(|j| i == j || inertia[(i, j)] == 0.0));
    let row = |values: [f64; 3]| toml::Value::Array(values.map(toml::Value::from).to_vec());
    let tensor = if diagonal {
        row([inertia[(0, 0)], inertia[(1, 1)], inertia[(2, 2)]])
    } else {
        let rows = (0..3).map(|i| row([inertia[(i, 0)], inertia[(i, 1)], inertia[(i, 2)]]));
        toml::Value::Array(rows.collect())
    };
    Assignment::body(&body.name, &["inertia"], tensor)
}

/// The text of the fitted scenario file: `scenario` with `assignments` applied, checked
/// by reading it back, under a header saying where it came from.
pub fn fitted_scenario_text(
    scenario: &Scenario,
    assignments: &[Assignment],
    header: &str,
) -> Result<String, ScenarioError> {
    let fitted = scenario.with_assignments(assignments)?;
    fitted.model()?;
    let body = toml::to_string(&fitted.source.document).map_err(|e| ScenarioError::Syntax {
        path: fitted.source.path.clone(),
        message: format!("cannot write the fitted scenario as TOML: {e}"),
    })?;
    let comment: String = header.lines().map(|l| format!("# {l}\n")).collect();
    Ok(comment + &body)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numerics::optimize::Parameters;
    use crate::replay::TossSetup;
    use nalgebra::Matrix3;
    use std::path::Path;

    const SCENARIO: &str = include_str!("../../../scenarios/cube_toss.toml");

    fn scenario(overrides: &[String]) -> Scenario {
        Scenario::parse(Path::new("cube_toss.toml"), SCENARIO, overrides).unwrap()
    }

    /// The `--set`s beside a physics file give the model the genes stand for: the
    /// table at the offset, the inertia at the scale — a diagonal tensor as principal
    /// moments, a full one row by row.
    #[test]
    fn the_sets_beside_the_physics_file_give_the_fitted_body_and_table() {
        let full = "body.cube.inertia=[[8e-4, 1e-5, 0.0], [1e-5, 9e-4, 2e-5], [0.0, 2e-5, 7e-4]]";
        for overrides in [vec![], vec![full.to_owned()]] {
            let base = scenario(&overrides);
            let model = base.model().unwrap();
            let setup = TossSetup::new(&model).unwrap();
            let parameters = MotionParameters::new(&model, &setup).unwrap();
            let mut genes = parameters.values(&model);
            let last = genes.len() - 1;
            genes[last - 1] = -1.5e-3;
            genes[last] = 1.25;
            let named = parameters.named(&genes);
            let sets = beside_physics(&model, &parameters, &named);
            assert_eq!(sets.len(), 2, "{sets:?}");
            let replayed = base.with_assignments(&sets).unwrap().model().unwrap();
            let fitted = parameters.apply(&model, &genes);
            let inertia: Matrix3<f64> = replayed.bodies[parameters.body].inertia;
            let expected = fitted.bodies[parameters.body].inertia;
            assert!(
                (inertia - expected).abs().max() <= 1e-15,
                "{inertia} vs {expected}"
            );
            assert!(
                (expected - model.bodies[parameters.body].inertia * 1.25)
                    .abs()
                    .max()
                    < 1e-18
            );
            match replayed.bodies[parameters.partner].shape {
                crate::scenario::Shape::Plane { offset, .. } => assert_eq!(offset, -1.5e-3),
                _ => panic!("the table is a plane"),
            }
        }
    }

    /// On a mechanism the fit's genes change every contact alike with the fitted one,
    /// every copy of the replayed link and the joint's declared terms — and the
    /// assignments written for the fitted scenario give the very model the genes stand
    /// for.
    #[test]
    fn a_mechanism_s_fit_is_written_whole() {
        const ELBOW: &str = include_str!("../../../scenarios/elbow_toss.toml");
        let sets = ["joint.hinge.law.viscous.damping=0.002".to_owned()];
        let base = Scenario::parse(Path::new("elbow_toss.toml"), ELBOW, &sets).unwrap();
        let model = base.model().unwrap();
        let setup = TossSetup::new(&model).unwrap();
        let parameters = MotionParameters::new(&model, &setup).unwrap();
        assert_eq!(parameters.contacts(), vec![0, 1]);
        let bounds = parameters.bounds();
        let names: Vec<&str> = bounds.iter().map(|b| b.name.as_str()).collect();
        assert_eq!(
            names.last(),
            Some(&"joint.0.law.viscous.damping"),
            "{names:?}"
        );
        // Every gene moved to 30 % of its box.
        let genes: Vec<f64> = bounds.iter().map(|b| b.value_at(0.3)).collect();
        let fitted = parameters.apply(&model, &genes);
        let law = |m: &Model, c: usize| m.contacts[c].model.normal.clone();
        assert_eq!(law(&fitted, 0), law(&fitted, 1));
        assert_ne!(law(&fitted, 0), law(&model, 0));
        assert_eq!(
            fitted.contacts[0].model.friction,
            fitted.contacts[1].model.friction
        );
        assert_eq!(fitted.bodies[0].inertia, fitted.bodies[1].inertia);
        assert_ne!(fitted.bodies[0].inertia, model.bodies[0].inertia);
        let damping = fitted.joints[0].law.viscous.unwrap().damping;
        assert_eq!(damping, genes[genes.len() - 1]);
        let named = parameters.named(&genes);
        let written = base
            .with_assignments(&fitted_assignments(&model, &parameters, &named))
            .unwrap()
            .model()
            .unwrap();
        for c in 0..2 {
            assert_eq!(law(&written, c), law(&fitted, c));
            assert_eq!(
                written.contacts[c].model.friction,
                fitted.contacts[c].model.friction
            );
        }
        for b in 0..3 {
            let gap = (written.bodies[b].inertia - fitted.bodies[b].inertia)
                .abs()
                .max();
            assert!(gap <= 1e-18, "body {b}: {gap}");
        }
        assert_eq!(written.joints[0].law, fitted.joints[0].law);
        match (&written.bodies[2].shape, &fitted.bodies[2].shape) {
            (Shape::Plane { offset: a, .. }, Shape::Plane { offset: b, .. }) => assert_eq!(a, b),
            _ => panic!("the table is a plane"),
        }
    }
}
