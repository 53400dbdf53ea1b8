//! Checks that a scenario describes something physically possible: what parses and
//! resolves can still be impossible (a Poisson's ratio of 0.6, a ball starting half
//! a metre inside the ground), and would then simulate without a word.

use super::geometry::{pair_contacts, pair_kinematics, Pose};
use super::{Model, Scenario, ScenarioError, Shape};
use hcm_core::geometry::{sphere_sphere, Material};
use hcm_core::LawError;
use std::path::Path;

/// Deepest indentation a contact may start with, as a share of its effective radius
/// R (dimensionless).
///
/// A start at δ = 0, touching, is legitimate (the flat shot starts so), and so is a
/// small preload; but every law here extends Hertz's small-strain theory, which needs
/// δ ≪ R (contact radius √(R·δ) ≪ R). At δ = 10⁻³·R the contact radius is already
/// 3 % of R — the paper's impacts peak near 10⁻³·R — so a deeper start is an overlap
/// of the bodies, not a contact state: usually a sign error or a position in the
/// wrong unit. 10⁻³·R is 12.7 µm for the 12.7 mm ball, ten orders of magnitude
/// above the rounding of positions written in metres.
pub(crate) const MAX_INITIAL_INDENTATION: f64 = 1e-3;

/// Every material of `scenario` physically possible ([`Material::validate`]); the
/// field named is `material.<name>.<property>`.
pub(super) fn materials(scenario: &Scenario, path: &Path) -> Result<(), ScenarioError> {
    for (name, material) in &scenario.materials {
        material
            .validate()
            .map_err(|error| material_error(path, name, material, error))?;
    }
    Ok(())
}

/// [`ScenarioError::Invalid`] for `error` of material `name`, with the value found
/// and what the property means.
fn material_error(
    path: &Path,
    name: &str,
    material: &Material<f64>,
    error: LawError,
) -> ScenarioError {
    let (property, value, hint) = match error {
        LawError::NotPositive { parameter } => (
            parameter,
            material.youngs_modulus,
            "Young's modulus E in Pa, e.g. 2.06e11 for steel",
        ),
        LawError::OutOfRange { parameter, .. } => (
            parameter,
            material.poisson_ratio,
            "outside it an isotropic elastic material would be unstable; \
             steel is about 0.3, rubber approaches 0.5",
        ),
        _ => ("", f64::NAN, ""),
    };
    ScenarioError::Invalid {
        path: path.to_owned(),
        field: format!("material.{name}.{property}"),
        message: format!("{error}, found {} ({hint})", round(value)),
    }
}

/// `model`, if no contact pair starts deeper than [`MAX_INITIAL_INDENTATION`] of its
/// effective radius; else an error naming the position to change and how.
pub(super) fn starts_apart(model: Model, path: &Path) -> Result<Model, ScenarioError> {
    for (index, contact) in model.contacts.iter().enumerate() {
        let (body_1, body_2) = (&model.bodies[contact.body_1], &model.bodies[contact.body_2]);
        // Body 1 is a sphere (resolve checks it); R as in Eq 3.
        let radius = match (&body_1.shape, &body_2.shape) {
            (&Shape::Sphere { radius: r1 }, &Shape::Sphere { radius: r2 }) => {
                sphere_sphere::effective_radius(r1, r2)
            }
            (&Shape::Sphere { radius }, Shape::Plane { .. }) => radius,
            // Pairs with a box: their manifold's deepest point.
            _ => {
                box_starts_apart(&model, index, path)?;
                continue;
            }
        };
        let at_start = |b: &super::Body| (b.position, b.velocity);
        let start = pair_kinematics(&model, contact, at_start(body_1), at_start(body_2));
        let allowed = MAX_INITIAL_INDENTATION * radius;
        if start.depth <= allowed {
            continue;
        }
        // Move the body that moves (body 1 along the normal, body 2 against it).
        let (moved, other, direction) = if body_1.fixed {
            (body_2, body_1, -start.normal)
        } else {
            (body_1, body_2, start.normal)
        };
        let touching = moved.position + direction * start.depth;
        return Err(ScenarioError::Invalid {
            path: path.to_owned(),
            field: format!("body.{}.position", moved.name),
            message: format!(
                "`{}` starts {depth} m inside `{}` (contact #{index} begins with indentation \
                 δ = {depth} m); a contact may start at most {} m deep ({MAX_INITIAL_INDENTATION} × \
                 its effective radius {} m, where small-strain contact laws end). Move `{}` \
                 {depth} m along [{}]: position = [{}] starts it touching",
                moved.name,
                other.name,
                round(allowed),
                round(radius),
                moved.name,
                list(direction.iter().copied()),
                list(touching.iter().copied()),
                depth = round(start.depth),
            ),
        });
    }
    Ok(model)
}

/// A pair with a box may start at most [`MAX_INITIAL_INDENTATION`] of its smallest
/// box half extent deep (a box's faces are flat, so its size, not a radius, says what
/// an overlap is): else an error naming the moving body and where to move it.
fn box_starts_apart(model: &Model, index: usize, path: &Path) -> Result<(), ScenarioError> {
    let contact = &model.contacts[index];
    let (body_1, body_2) = (&model.bodies[contact.body_1], &model.bodies[contact.body_2]);
    let pose = |b: &super::Body| Pose {
        position: b.position,
        orientation: b.orientation,
        velocity: b.velocity,
        angular_velocity: b.angular_velocity,
    };
    let size = [&body_1.shape, &body_2.shape]
        .into_iter()
        .filter_map(|shape| match shape {
            Shape::Box { half_extents, .. } => Some(half_extents.min()),
            Shape::Sphere { radius } => Some(*radius),
            _ => None,
        })
        .fold(f64::INFINITY, f64::min);
    let allowed = MAX_INITIAL_INDENTATION * size;
    let Some(deepest) = pair_contacts(model, contact, &pose(body_1), &pose(body_2))
        .into_iter()
        .max_by(|a, b| a.depth.total_cmp(&b.depth))
        .filter(|g| g.depth > allowed)
    else {
        return Ok(());
    };
    let (moved, other, direction) = if body_1.fixed {
        (body_2, body_1, -deepest.normal)
    } else {
        (body_1, body_2, deepest.normal)
    };
    let touching = moved.position + direction * deepest.depth;
    Err(ScenarioError::Invalid {
        path: path.to_owned(),
        field: format!("body.{}.position", moved.name),
        message: format!(
            "`{}` starts {depth} m inside `{}` (contact #{index}'s deepest point is at \
             δ = {depth} m); a contact may start at most {} m deep ({MAX_INITIAL_INDENTATION} × \
             the smallest half extent or radius, {} m). Move `{}` {depth} m along [{}]: \
             position = [{}] starts it touching",
            moved.name,
            other.name,
            round(allowed),
            round(size),
            moved.name,
            list(direction.iter().copied()),
            list(touching.iter().copied()),
            depth = round(deepest.depth),
        ),
    })
}

/// `x` to 9 significant digits, printed briefly: 0.0127 rather than
/// 0.012700000000000003, 1.27e-5 rather than 0.0000127, 2.06e11.
pub(crate) fn round(x: f64) -> String {
    // + 0.0 turns −0 into 0: "-0" is not a useful thing to tell a user.
    let rounded = format!("{x:.8e}").parse().unwrap_or(x) + 0.0;
    if rounded == 0.0 || (1e-3..1e6).contains(&rounded.abs()) {
        format!("{rounded}")
    } else {
        format!("{rounded:e}")
    }
}

/// `a, b, c` with each number [`round`]ed.
fn list(values: impl Iterator<Item = f64>) -> String {
    values.map(round).collect::<Vec<_>>().join(", ")
}

#[cfg(test)]
mod tests {
    use super::round;

    #[test]
    fn numbers_are_told_briefly() {
        assert_eq!(round(-0.5 + 0.5127), "0.0127");
        assert_eq!(round(0.0127 * 1e-3), "1.27e-5");
        assert_eq!(round(-2.06e11), "-2.06e11");
        assert_eq!(round(-0.0), "0");
        assert_eq!(round(0.5127), "0.5127");
    }
}
