//! The residual learned from motion alone (`hcm_host::train::train_motion_residual`):
//! no force, only the poses a tracker records. Simulated cube tosses hide a friction
//! 1.5 times the shipped scenario's; the contact-frame residual trained on what the
//! scenario's physics misses two frames after each recorded state must replay
//! held-out tosses better than the physics alone.
//!
//! What it does not do yet, measured on the real tosses (the session note of stop 40):
//! with the tracker's noise the residual made the held-out replays worse; a synthetic
//! check with 0.5 mm and 0.6° of pose noise gave the position's gain but lost the
//! rotation's.

use hcm_host::dataset::Dataset;
use hcm_host::identify::split_tosses;
use hcm_host::replay::{evaluate_tosses, summarize};
use hcm_host::residual::ContactResidual;
use hcm_host::scenario::{Model, Scenario};
use rand::SeedableRng;

/// `count` tosses of `truth` from seeded random throws, recorded at the scenario's
/// 148 Hz with poses and velocities; run ids `toss_000`….
fn tosses(truth: &Model, count: usize, seed: u64) -> Dataset {
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    let mut data = Dataset::default();
    for k in 0..count {
        let mut model = truth.clone();
        hcm_tests::throw_cube(&mut model.bodies[0], &mut rng);
        let mut run = hcm_host::simulate::simulate(&model).unwrap().run;
        run.id = format!("toss_{k:03}");
        data.runs.push(run);
    }
    data
}

/// Mean position error (%) + mean rotation error (°) of `model` over `data`'s tosses.
fn score(model: &Model, data: &Dataset) -> f64 {
    let summary = summarize(&evaluate_tosses(model, data, || {}).unwrap());
    summary.position.mean + summary.rotation.mean
}

#[test]
#[ignore = "study, over 12 s on 2 cores: cargo test -- --include-ignored"]
fn a_hidden_friction_is_learned_from_poses_alone() {
    let physics = Scenario::load(&hcm_tests::scenario("cube_toss.toml"), &[])
        .unwrap()
        .model()
        .unwrap();
    let mut truth = physics.clone();
    let friction = truth.contacts[0].model.friction.as_mut().unwrap();
    friction.static_coefficient *= 1.5;
    friction.dynamic_coefficient *= 1.5;
    let (training, held_out) = split_tosses(&tosses(&truth, 40, 3));
    let settings = hcm_host::train::ResidualSettings {
        epochs: 200,
        int8_epochs: 5,
        seed: 1,
    };
    let trained = hcm_host::train::train_motion_residual(
        &physics,
        &training,
        0,
        hcm_host::train::HORIZON,
        &settings,
        &hcm_host::progress::Silent,
    )
    .unwrap();
    let blob =
        hcm_host::export::blob(&trained.residual, hcm_core::residual::Quantisation::F32).unwrap();
    let mut hcm = physics.clone();
    hcm.contacts[0].model.residual = Some(ContactResidual::decode(&blob.bytes).unwrap());
    let (alone, hybrid) = (score(&physics, &held_out), score(&hcm, &held_out));
    println!(
        "{} rows, R² {:?}; held out (% + °): physics {alone:.3}, HCM {hybrid:.3}",
        trained.rows, trained.explained
    );
    assert!(hybrid < 0.75 * alone, "HCM {hybrid} vs physics {alone}");
}

/// A contact the scenario lacks is refused, naming it, before any replay.
#[test]
fn a_contact_the_scenario_lacks_is_refused() {
    let physics = Scenario::load(&hcm_tests::scenario("cube_toss.toml"), &[])
        .unwrap()
        .model()
        .unwrap();
    let error = hcm_host::train::motion_rows(&physics, &Dataset::default(), 3, 2)
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("contact 3") && error.contains("1 contact"),
        "{error}"
    );
}
