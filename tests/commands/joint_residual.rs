//! A joint's residual through the commands a user runs on a mechanism's poses: `hcm
//! train` learns the hinge's torque from simulated elbow tosses whose hinge hides
//! viscous friction (the rest of the physics the fitted elbow's), `hcm export` writes
//! the blob a controller embeds, and `hcm evaluate --residual` replays held-out tosses
//! by PM2 and by the HCM (the blob on the hinge), per toss paired.

use hcm_host::identify::{split_tosses, Physics};
use hcm_host::scenario::Scenario;
use hcm_tests::cli::Hcm;
use serde_json::Value;
use std::path::{Path, PathBuf};

/// Tosses simulated: half train, half are held out.
const TOSSES: usize = 24;

fn physics_file() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/results/elbow-toss/physics.toml")
}

#[test]
fn hcm_train_export_and_evaluate_carry_a_hinge_s_learned_torque() {
    let hcm = Hcm::new();
    let scenario = Scenario::load(&hcm_tests::scenario("elbow_toss.toml"), &[]).unwrap();
    let mut truth = Physics::read(&physics_file())
        .unwrap()
        .apply(&scenario, &physics_file())
        .unwrap()
        .model()
        .unwrap();
    truth.joints[0].law.viscous = Some(hcm_core::joint::JointViscous { damping: 0.01 });
    // Filmed as the real tosses are: poses only, the tracker's noise (0.5 mm, 0.3°).
    let thrown = hcm_tests::mechanism::thrown_mechanisms(&truth, TOSSES, 7);
    let filmed = hcm_tests::filmed_poses(thrown, (5e-4, 0.3_f64.to_radians()), 7);
    let (training, held_out) = split_tosses(&filmed);
    training.write(&hcm.path("training.csv")).unwrap();
    held_out.write(&hcm.path("held_out.csv")).unwrap();
    let printed = hcm
        .run("train")
        .opt("--scenario", hcm_tests::scenario("elbow_toss.toml"))
        .opt("--physics", physics_file())
        .opt("--data", "training.csv")
        .opt("--epochs", "150")
        .opt("--int8-epochs", "2")
        .opt("--out", "joint.json")
        .ok();
    assert!(
        printed.contains("joint `hinge`") && printed.contains("R²"),
        "{printed}"
    );
    hcm.run("export")
        .opt("--residual", "joint.json")
        .opt("--out", "joint.bin")
        .ok();
    let json = hcm
        .run("evaluate")
        .opt("--scenario", hcm_tests::scenario("elbow_toss.toml"))
        .opt("--physics", physics_file())
        .opt("--data", "held_out.csv")
        .opt("--residual", "joint.bin")
        .arg("--json")
        .ok();
    let evaluation: Value = serde_json::from_str(&json).unwrap();
    let columns = evaluation["columns"].as_array().unwrap();
    let mean = |c: &Value| {
        let scores = c["scores"].as_array().unwrap();
        scores.iter().map(|s| s.as_f64().unwrap()).sum::<f64>() / scores.len() as f64
    };
    let (pm2, hybrid) = (mean(&columns[0]), mean(&columns[1]));
    let paired = &columns[1]["paired"];
    let (difference, se) = (paired[0].as_f64().unwrap(), paired[1].as_f64().unwrap());
    println!(
        "held out (% + °): PM2 {pm2:.3}, HCM {hybrid:.3}; HCM − PM2 {difference:.3} ± {se:.3}"
    );
    assert_eq!(columns[1]["label"], "HCM");
    // Better toss by toss, beyond twice the paired difference's standard error.
    assert!(difference + 2.0 * se < 0.0, "HCM − PM2 {difference} ± {se}");
}
