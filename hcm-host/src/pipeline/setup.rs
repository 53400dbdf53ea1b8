//! The experiment in words, for the report: what hits what, from where and how fast,
//! read from the scenario's bodies (not written per example), and how the noisy runs
//! were made and split.

use super::quantity::{number, parameter, Scale};
use super::CONTACT;
use crate::experiment::Split;
use crate::scenario::{Body, Model, Scenario, Shape};
use hcm_core::law::{AnyNormalLaw, LawKind};
use nalgebra::Vector3;

/// What the report says about the experiment; rendered text, not serialised.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Setup {
    /// One sentence on the validation condition: what hits what, from where, how fast.
    pub(crate) sentence: String,
    /// PM1's law and parameters, e.g. "the variable-stiffness law (Eq 6–7): c = 2, …".
    pub(crate) pm1: String,
    /// PM1's run-to-run parameter scatter (Eq 18), e.g. "c ± 2 %, λ ± 2 %"; empty: none.
    pub(crate) parameter_noise: String,
    /// σ of the noise on every force sample (N), Eq 19.
    pub(crate) force_noise: f64,
    /// The experimental conditions' names; empty: a single condition.
    pub(crate) conditions: Vec<String>,
    /// Runs in S1.
    pub(crate) training_runs: usize,
    /// Runs in S2.
    pub(crate) validation_runs: usize,
    /// How S2 was chosen, e.g. "a random 10 % of the runs".
    pub(crate) holdout: String,
}

impl Setup {
    /// The setup of `scenario` (as read, PM1 in place), split into `sets`, whose S2
    /// table is that of `condition` ("" without conditions).
    pub(crate) fn describe(scenario: &Scenario, sets: &Split, condition: &str) -> Self {
        let experiment = &scenario.experiment;
        let model = condition_model(scenario, condition);
        let contact = model.as_ref().and_then(|m| m.contacts.get(CONTACT));
        let holdout = if experiment.holdout_conditions.is_empty() {
            format!(
                "a random {:.0} % of the runs",
                100.0 * experiment.holdout_fraction
            )
        } else {
            format!("the runs of {}", experiment.holdout_conditions.join(", "))
        };
        Setup {
            sentence: model.as_ref().map(sentence).unwrap_or_default(),
            pm1: contact
                .map(|c| law_phrase(c.law().name(), c.law().named()))
                .unwrap_or_default(),
            parameter_noise: contact
                .map(|c| scatter(c.law(), &c.noise))
                .unwrap_or_default(),
            force_noise: experiment.force_noise,
            conditions: (experiment.conditions.iter())
                .map(|c| c.name.clone())
                .collect(),
            training_runs: sets.training.runs.len(),
            validation_runs: sets.validation.runs.len(),
            holdout,
        }
    }
}

/// The model of `condition`: the scenario with the condition's overrides applied.
fn condition_model(scenario: &Scenario, condition: &str) -> Option<Model> {
    let spec = scenario
        .experiment
        .conditions
        .iter()
        .find(|c| c.name == condition);
    match spec {
        Some(spec) => scenario.with(&spec.set).ok()?.model().ok(),
        None => scenario.model().ok(),
    }
}

/// "the Lankarani–Nikravesh law of the paper's Eq 4–5, with k = …, n = …, ce = …" for the law called
/// `name` with `parameters` (name, SI value) in any order.
pub(crate) fn law_phrase<'a>(
    name: &str,
    parameters: impl IntoIterator<Item = (&'a str, f64)>,
) -> String {
    let kind = LawKind::from_name(name);
    let info =
        |parameter: &str| kind.and_then(|k| k.parameters().iter().find(|p| p.name == parameter));
    let values: Vec<String> = (parameters.into_iter())
        .map(|(name, value)| {
            let (symbol, unit) = info(name).map_or((name.to_owned(), ""), |p| {
                // "k, contact stiffness" → "contact stiffness k"; a parenthesis after
                // the meaning (its range, its source) is left to the law's docs.
                let symbol = match p.meaning.split_once(", ") {
                    Some((symbol, meaning)) => {
                        let meaning = meaning.split(" (").next().unwrap_or(meaning);
                        format!("{meaning} {symbol}")
                    }
                    None => p.name.to_owned(),
                };
                (symbol, p.unit)
            });
            format!("{symbol} = {}", parameter(value, unit, 5))
        })
        .collect();
    let source = kind.map_or(String::new(), |k| format!(" of the paper's {}", k.source()));
    format!(
        "the {} law{source}, with {}",
        law_title(name),
        values.join(", ")
    )
}

/// The law's name in words.
fn law_title(name: &str) -> &str {
    match name {
        "hertz" => "Hertz",
        "lankarani_nikravesh" => "Lankarani–Nikravesh",
        "variable_stiffness" => "variable-stiffness",
        "impact" => "MSC ADAMS IMPACT",
        "hunt_crossley" => "Hunt–Crossley",
        "flores" => "Flores",
        other => other,
    }
}

/// "c ± 2 %, λ ± 2 %": each noisy parameter's symbol and relative standard deviation,
/// in the law's parameter order.
fn scatter(law: &AnyNormalLaw<f64>, noise: &[(String, f64)]) -> String {
    (law.kind().parameters().iter())
        .filter_map(|p| {
            let (_, b) = noise.iter().find(|(name, _)| name == p.name)?;
            let symbol = p.meaning.split_once(", ").map_or(p.name, |(s, _)| s);
            (*b != 0.0).then(|| format!("{symbol} ± {} %", number(100.0 * b, 3)))
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// A body as seen from outside: "a steel sphere, radius 12.7 mm, mass 66.93 g".
fn body_phrase(body: &Body, material: Option<&str>) -> String {
    let material = material.map_or(String::new(), |m| format!("{m} "));
    let fixed = if body.fixed { "fixed " } else { "" };
    let mass = if body.fixed {
        String::new()
    } else {
        format!(", mass {}", Scale::mass(body.mass).brief(body.mass, 4))
    };
    match &body.shape {
        Shape::Sphere { radius } => format!(
            "a {fixed}{material}sphere, radius {}{mass}",
            Scale::prefixed(*radius, "m").brief(*radius, 4)
        ),
        Shape::Plane { .. } if body.fixed => format!("a fixed {material}plane"),
        Shape::Plane { .. } => format!("a flat-faced {material}body{mass}"),
        Shape::Box {
            half_extents: h,
            rounding,
        } => {
            let side = |x: f64| Scale::prefixed(2.0 * x, "m").brief(2.0 * x, 4);
            let sides = format!("{} × {} × {}", side(h.x), side(h.y), side(h.z));
            let rounded = if *rounding > 0.0 {
                let r = Scale::prefixed(*rounding, "m").brief(*rounding, 3);
                format!(", edges rounded to {r}")
            } else {
                String::new()
            };
            format!("a {fixed}{material}box {sides}{rounded}{mass}")
        }
        Shape::Compound { parts } => {
            format!("a {fixed}{material}body of {} boxes", parts.len())
        }
    }
}

/// The kinematics of the model's contact: (gap along the normal (m), approach speed
/// (m/s, > 0 closing), approach acceleration from gravity (m/s², > 0 closing)).
fn approach(model: &Model, one: &Body, two: &Body) -> Option<(f64, f64, f64)> {
    let (normal, gap) = match (&one.shape, &two.shape) {
        (&Shape::Sphere { radius }, &Shape::Plane { normal, offset }) => (
            normal,
            normal.dot(&(one.position - two.position)) - offset - radius,
        ),
        (&Shape::Sphere { radius: r1 }, &Shape::Sphere { radius: r2 }) => {
            let between = one.position - two.position;
            (between.try_normalize(0.0)?, between.norm() - r1 - r2)
        }
        _ => return None,
    };
    let gravity = |b: &Body| {
        if b.fixed {
            Vector3::zeros()
        } else {
            model.gravity
        }
    };
    let speed = -normal.dot(&(one.velocity - two.velocity));
    let pull = -normal.dot(&(gravity(one) - gravity(two)));
    Some((gap, speed, pull))
}

/// One sentence: the mover, its start, the other body, and the impact speed.
fn sentence(model: &Model) -> String {
    let Some(contact) = model.contacts.get(CONTACT) else {
        return String::new();
    };
    let (one, two) = (&model.bodies[contact.body_1], &model.bodies[contact.body_2]);
    let Some((gap, speed, pull)) = approach(model, one, two) else {
        return String::new();
    };
    let materials = &model.scenario.bodies;
    let named = |i: usize| {
        let body = &model.bodies[i];
        let material = materials.get(i).and_then(|b| b.material.as_deref());
        format!("`{}` ({})", body.name, body_phrase(body, material))
    };
    // The subject is the body that moves (or falls); the other is met.
    let moves = |b: &Body| !b.fixed && (b.velocity.norm() > 0.0 || pull > 0.0);
    let one_moves = moves(one) && (one.velocity.norm() >= two.velocity.norm() || !moves(two));
    let (mover, other) = if one_moves {
        (contact.body_1, contact.body_2)
    } else {
        (contact.body_2, contact.body_1)
    };
    let metres_per_second = Scale::plain("m/s");
    let velocity = |i: usize| model.bodies[i].velocity.norm();
    let other_state = match (&model.bodies[other], velocity(other)) {
        (b, _) if b.fixed => String::new(),
        (_, 0.0) => ", which is at rest,".to_owned(),
        (_, v) => format!(", which moves at {},", metres_per_second.brief(v, 4)),
    };
    let impact = (speed * speed + 2.0 * pull * gap.max(0.0)).sqrt();
    let hits = if speed > 0.0 || (gap > 0.0 && pull > 0.0) {
        format!("hits it at {}", metres_per_second.brief(impact, 4))
    } else {
        "never reaches it".to_owned()
    };
    let start = if velocity(mover) == 0.0 {
        "starts at rest".to_owned()
    } else {
        format!("starts at {}", metres_per_second.brief(velocity(mover), 4))
    };
    if gap > 1e-12 {
        let (place, fall) = if pull > 0.0 {
            let g = Scale::plain("m/s²").brief(model.gravity.norm(), 4);
            ("above", format!(", falls under gravity ({g})"))
        } else {
            ("from", String::new())
        };
        let gap = Scale::prefixed(gap, "m").brief(gap, 4);
        format!(
            "{} {start} {gap} {place} {}{other_state}{fall} and {hits}.",
            named(mover),
            named(other)
        )
    } else {
        format!(
            "{} {start}, just touching {}{other_state} and {hits}.",
            named(mover),
            named(other)
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::Example;

    fn shipped(example: Example) -> Scenario {
        crate::pipeline::preset::shipped_scenario(example.shipped())
    }

    #[test]
    fn the_ball_is_dropped_on_the_ground() {
        let model = condition_model(&shipped(Example::BouncingBall), "").unwrap();
        assert_eq!(
            sentence(&model),
            "`ball` (a steel sphere, radius 12.7 mm, mass 66.93 g) starts at rest 100 mm above \
             `ground` (a fixed concrete plane), falls under gravity (9.81 m/s²) and hits it at \
             1.401 m/s."
        );
    }

    #[test]
    fn the_plate_of_a_condition_hits_the_resting_ball_at_its_speed() {
        let model = condition_model(&shipped(Example::FlatShot), "v0.5").unwrap();
        assert_eq!(
            sentence(&model),
            "`plate` (a flat-faced plate body, mass 387.2 g) starts at 0.5 m/s, just touching \
             `ball` (a steel sphere, radius 12.7 mm, mass 66.93 g), which is at rest, and hits \
             it at 0.5 m/s."
        );
    }

    #[test]
    fn the_law_is_named_with_its_parameters_meanings_and_units() {
        let phrase = law_phrase(
            "lankarani_nikravesh",
            [
                ("stiffness", 6.902464e9),
                ("exponent", 1.489387),
                ("restitution", 0.9288223),
            ],
        );
        assert_eq!(
            phrase,
            "the Lankarani–Nikravesh law of the paper's Eq 4–5, with contact stiffness k = \
             6.9025 × 10⁹ N/m^n, force exponent n = 1.4894, coefficient of restitution ce = 0.92882"
        );
    }
}
