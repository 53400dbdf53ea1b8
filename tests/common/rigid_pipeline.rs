//! A rigid scene through the commands' stages as a user runs them: generate → identify
//! (least squares, a law other than the data's) → train (either residual) → export →
//! evaluate on the held-out runs (S2: a random share, or the held-out conditions).

use hcm_host::evaluate::{evaluate_rigid, rigid_markdown, RigidEvaluation};
use hcm_host::experiment::generate_split;
use hcm_host::export::export_blobs;
use hcm_host::identify::{identify_from_samples, with_law};
use hcm_host::progress::Silent;
use hcm_host::scenario::Scenario;
use hcm_host::train::{train_point_residual, train_wrench_residual, ResidualSettings};

/// What the residual reads (`hcm train --inputs`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Inputs {
    /// The moving body's 13 state components (Eq 12).
    State,
    /// Each touching point's contact-frame features.
    Contact,
}

/// PM2: `law` (its exponent free) in place of `scenario`'s contact 0, fitted by least
/// squares on `data` (`hcm identify`'s default).
pub fn pm2_of(
    scenario: &Scenario,
    law: &str,
    data: &hcm_host::dataset::Dataset,
) -> hcm_host::scenario::Model {
    let model = scenario.model().unwrap();
    let start = with_law(&model, 0, law, None).unwrap();
    let bounds = &scenario.identify.bounds;
    identify_from_samples(&start, data, 0, bounds, true, &Silent)
        .unwrap()
        .fit
        .model
}

/// PM2 (`law` fitted by least squares on S1), then for each of `inputs` the HCM (PM2
/// plus that residual trained on S1, its f32 blob), all evaluated on S2 of `runs`
/// generated runs (seed 3): one evaluation with PM2 first, then the HCMs in order
/// ("HCM" alone, or "HCM (state)" and "HCM (contact)").
pub fn pipeline(scenario: &Scenario, law: &str, runs: usize, inputs: &[Inputs]) -> RigidEvaluation {
    let sets = generate_split(scenario, runs, 3, &Silent).unwrap();
    let pm2 = pm2_of(scenario, law, &sets.training);
    let settings = ResidualSettings {
        epochs: 200,
        int8_epochs: 10,
        seed: 3,
    };
    let hcms: Vec<(String, hcm_host::scenario::Model)> = (inputs.iter())
        .map(|kind| {
            let train = match kind {
                Inputs::State => train_wrench_residual,
                Inputs::Contact => train_point_residual,
            };
            let trained = train(&pm2, &sets.training, 0, usize::MAX, &settings, &Silent).unwrap();
            let blobs = export_blobs(&trained.residual).unwrap();
            let label = match (inputs.len(), kind) {
                (1, _) => "HCM".to_owned(),
                (_, Inputs::State) => "HCM (state)".to_owned(),
                (_, Inputs::Contact) => "HCM (contact)".to_owned(),
            };
            (label, blobs.hybrid_models(&pm2, 0).0)
        })
        .collect();
    let mut models = vec![("PM2", &pm2)];
    models.extend(hcms.iter().map(|(label, m)| (label.as_str(), m)));
    let evaluation = evaluate_rigid(&models, &sets.validation, 0).unwrap();
    println!(
        "{}: PM2 = {law}\n{}",
        scenario.name,
        rigid_markdown(&evaluation)
    );
    evaluation
}

/// `scene` (a file of `tests/common/scenes/`) with `conditions` added — (name, the
/// `--set` overrides) each — and the last one held out.
pub fn with_conditions(scene: &str, conditions: &[(&str, &str)]) -> Scenario {
    let dir = tempfile::tempdir().unwrap();
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/common/scenes")
        .join(scene);
    let held_out = conditions.last().map_or("", |c| c.0);
    let mut text = std::fs::read_to_string(path).unwrap().replace(
        "[experiment]",
        &format!("[experiment]\nholdout_conditions = [\"{held_out}\"]"),
    );
    for (name, set) in conditions {
        text += &format!("\n[[experiment.condition]]\nname = \"{name}\"\nset = [{set}]\n");
    }
    let file = dir.path().join(scene);
    std::fs::write(&file, text).unwrap();
    Scenario::load(&file, &[]).unwrap()
}
