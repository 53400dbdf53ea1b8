//! The hybrid contact model end to end on a small noisy ball experiment: PM2 by least
//! squares, the residual trained on S1, exported, decoded in the core and simulated
//! inside the integrator's force.

use hcm_core::residual::Quantisation;
use hcm_host::evaluate::evaluate;
use hcm_host::experiment::{generate, split};
use hcm_host::export::encode;
use hcm_host::identify::force_samples;
use hcm_host::identify::{identify, Method, Physics};
use hcm_host::residual::{ContactResidual, HIDDEN, WIDTH};
use hcm_host::scenario::Scenario;
use hcm_host::train::{residual_pairs, train, TrainSettings};
use std::path::Path;

#[test]
fn the_hcm_beats_pm2_on_energy_loss_and_its_blob_reproduces_the_host_network() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/bouncing_ball.toml");
    let scenario = Scenario::load(&path, &[]).unwrap();
    let model = scenario.model().unwrap();
    let sets = split(
        &scenario,
        generate(&scenario, 30, 5, &hcm_host::progress::Silent).unwrap(),
        5,
    );
    let found = identify(
        &scenario,
        &model,
        &sets.training,
        0,
        "lankarani_nikravesh",
        Method::Lsq,
        &hcm_host::progress::Silent,
    )
    .unwrap();
    let pm2 = Physics::for_contact(&model, 0, &found.law, found.fit)
        .apply(&scenario, &path)
        .unwrap()
        .model()
        .unwrap();
    let (samples, _) = force_samples(&pm2, &sets.training, 0).unwrap();
    let (inputs, targets) = residual_pairs(&samples, &pm2.contacts[0].model);
    let settings = TrainSettings {
        hidden_layers: HIDDEN,
        width: WIDTH,
        seed: 2,
        ..TrainSettings::default()
    };
    let (network, _) = train(&inputs, &targets, &settings, |_, _, _| {}).unwrap();

    // Round trip: host network → blob → core model, same outputs.
    let blob = encode(&network, Quantisation::F32).unwrap();
    let residual = ContactResidual::decode(&blob).unwrap();
    let scale = network.output_scale[0];
    for x in inputs.iter().step_by(7) {
        let (host, core) = (
            network.evaluate(x)[0],
            residual
                .correction(x[0], x[1], x[2])
                .expect("training inputs lie in the envelope"),
        );
        assert!(
            (host - core).abs() <= 1e-6 * host.abs().max(scale),
            "host {host} core {core} at {x:?}"
        );
    }

    // The HCM, simulated with the residual inside the force, on S2.
    let mut hcm = pm2.clone();
    hcm.contacts[0].model.residual = Some(residual);
    let table = &evaluate(&[("PM2", &pm2), ("HCM", &hcm)], &sets.validation, 0).unwrap()[0];
    let (pm2_errors, hcm_errors) = (
        table.models[0].errors.unwrap().values(),
        table.models[1].errors.unwrap().values(),
    );
    assert!(
        hcm_errors[2] < 0.5 * pm2_errors[2],
        "energy loss: PM2 {pm2_errors:?} HCM {hcm_errors:?}"
    );
    assert!(
        hcm_errors[1] < pm2_errors[1],
        "impulse: PM2 {pm2_errors:?} HCM {hcm_errors:?}"
    );
}
