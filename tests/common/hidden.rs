//! Noisy runs of the bouncing ball with one hidden effect, and what `hcm diagnose`'s
//! stepwise selection and joint re-fit name from them, shared by the diagnose tests.

use hcm_host::dataset::Dataset;
use hcm_host::diagnose::sensor_gain;
use hcm_host::diagnose::ContactSamples;
use hcm_host::diagnose::{contact_samples, noise_floor};
use hcm_host::diagnose::{name_causes_beside_momentum, Naming};
use hcm_host::diagnose::{select, BaseFreedom, Refit, Selection};
use hcm_host::experiment::generate;
use hcm_host::scenario::{Model, Scenario};

/// The catalogue's force effects by name, in report order (the power tests' rows).
pub const EFFECTS: [&str; 8] = [
    "viscous_damping",
    "hysteresis_damping",
    "stiffness_exponent",
    "adhesion",
    "plasticity",
    "force_offset",
    "sensor_delay",
    "sensor_filter",
];

/// The scenario `name` with `overrides`, resolved to a model.
pub fn model(name: &str, overrides: &[String]) -> Model {
    let path = crate::scenario(name);
    Scenario::load(&path, overrides)
        .unwrap()
        .resolve(&path)
        .unwrap()
}

/// `runs` noisy runs of the ball with `effect` hidden (σ = 15 N, no parameter noise),
/// written to CSV and read back, and the base model (the scenario's own law).
///
/// `effect` is either an `experiment.`/`body.` override or a contact effect table
/// (`{ viscous_damping = { coefficient = 40.0 } }`); empty hides nothing.
pub fn hidden(effect: &str, runs: usize, seed: u64) -> (Model, Dataset) {
    let mut overrides = vec!["contact.0.noise={}".to_owned()];
    if effect.starts_with("experiment.") || effect.starts_with("body.") {
        overrides.push(effect.to_owned());
    } else if !effect.is_empty() {
        overrides.push(format!("contact.0.effects=[{effect}]"));
    }
    let truth = model("bouncing_ball.toml", &overrides);
    (
        model("bouncing_ball.toml", &["contact.0.noise={}".to_owned()]),
        measured(&truth, runs, seed),
    )
}

/// `runs` runs of `truth` as `hcm generate` makes them (seed `seed`), written to CSV and
/// read back, as a user's measured data would be.
pub fn measured(truth: &Model, runs: usize, seed: u64) -> Dataset {
    let data = generate(&truth.scenario, runs, seed, &hcm_host::progress::Silent).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("measured.csv");
    data.write(&path).unwrap();
    Dataset::read(&path).unwrap()
}

/// What `hcm diagnose` makes of `runs` runs with `effect` hidden (see [`hidden`]): the
/// linear stepwise selection (its first-order ranking) and the re-fit of the causes the
/// decision names (the naming rule, `hcm-host/src/diagnose/naming.rs`: nonlinear steps, named only if the residual
/// left is noise).
pub fn selected(effect: &str, runs: usize, seed: u64) -> (Selection, Refit) {
    let (base, data) = hidden(effect, runs, seed);
    let samples = contact_samples(&base, &data, 0).unwrap();
    let sigma = noise_floor(&samples).sigma;
    let law = base.contacts[0].model.normal.clone();
    let selection = select(&samples, &law, BaseFreedom::Given, sigma);
    (
        selection,
        decided(&base, &samples, BaseFreedom::Given, sigma).fit,
    )
}

/// The decision `hcm diagnose` takes on contact 0 of `base` along `samples` (noise σ in
/// N), the base's freedom `freedom`: the causes named beside the momentum balance.
pub fn decided(base: &Model, samples: &ContactSamples, freedom: BaseFreedom, sigma: f64) -> Naming {
    let contact = &base.contacts[0];
    let gain = sensor_gain(samples, contact.effective_mass);
    name_causes_beside_momentum(samples, &contact.model.normal, freedom, sigma, gain)
}

/// The named causes of a re-fit, each as (effect name, parameter values, share).
pub fn causes(fit: &Refit) -> Vec<(&'static str, Vec<f64>, f64)> {
    fit.causes
        .iter()
        .map(|c| {
            (
                c.effect,
                c.parameters.iter().map(|p| p.value).collect(),
                c.share,
            )
        })
        .collect()
}
