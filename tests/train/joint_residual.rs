//! A joint's residual learned from a mechanism's poses alone
//! (`hcm_host::train::train_joint_residual`): simulated elbow tosses (two links on a
//! hinge, `scenarios/elbow_toss.toml`) hide viscous hinge friction that the user's
//! model — the scenario as shipped, a free hinge — lacks. The torque network learned
//! from the joint angle the physics misses two frames after each recorded state must
//! push against the hinge's turn as the hidden friction does, and replay held-out
//! tosses better than the physics alone, through the blob a controller would embed.

use hcm_host::dataset::Dataset;
use hcm_host::identify::split_tosses;
use hcm_host::replay::{evaluate_tosses, summarize};
use hcm_host::residual::ContactResidual;
use hcm_host::scenario::{Model, Scenario};

/// The hidden hinge friction (N·m·s/rad): the diagnosis study's.
const DAMPING: f64 = 0.01;

fn elbow(sets: &[String]) -> Model {
    Scenario::load(&hcm_tests::scenario("elbow_toss.toml"), sets)
        .expect("scenarios/elbow_toss.toml reads")
        .model()
        .expect("and resolves")
}

/// Mean position error (%) + mean rotation error (°) of `model` over `data`'s tosses
/// (each link's, averaged).
fn score(model: &Model, data: &Dataset) -> f64 {
    let summary = summarize(&evaluate_tosses(model, data, || {}).unwrap());
    summary.position.mean + summary.rotation.mean
}

/// The hinge's residual of `physics` trained on `data` for at most `epochs` (no int8
/// twin), and its f32 blob decoded as the simulator and a controller read it.
fn trained(
    physics: &Model,
    data: &Dataset,
    epochs: usize,
) -> (hcm_host::train::Trained, ContactResidual) {
    let settings = hcm_host::train::ResidualSettings {
        epochs,
        int8_epochs: 0,
        seed: 1,
    };
    let trained = hcm_host::train::train_joint_residual(
        physics,
        data,
        0,
        hcm_host::train::HORIZON,
        &settings,
        &hcm_host::progress::Silent,
    )
    .unwrap();
    let blob =
        hcm_host::export::blob(&trained.residual, hcm_core::residual::Quantisation::F32).unwrap();
    let residual = ContactResidual::decode(&blob.bytes).unwrap();
    (trained, residual)
}

#[test]
fn a_hidden_hinge_friction_is_learned_as_the_joint_s_torque_from_poses_alone() {
    let physics = elbow(&[]);
    let truth = elbow(&[format!("joint.hinge.law.viscous.damping={DAMPING}")]);
    let thrown = hcm_tests::mechanism::thrown_mechanisms(&truth, 16, 5);
    let (training, held_out) = split_tosses(&thrown);
    let (trained, residual) = trained(&physics, &training, 150);
    let ContactResidual::JointTorque(joint) = &residual else {
        panic!(
            "a 2-input network decodes as a joint's: {:?}",
            residual.shape()
        );
    };
    // The learned torque opposes the turn as −c·θ̇ does, at rates inside its envelope.
    let law = physics.joints[0].law;
    for rate in [-2.0, -1.0, 1.0, 2.0] {
        let learned = joint.torque(&law, 0.0, rate);
        let hidden = -DAMPING * rate;
        println!("θ̇ {rate:+.1} rad/s: learned {learned:+.5} N·m, hidden {hidden:+.5}");
        assert!(
            learned * hidden > 0.0,
            "{learned} against {hidden} at {rate}"
        );
        assert!(
            (learned - hidden).abs() < 0.5 * hidden.abs(),
            "{learned} vs {hidden}"
        );
    }
    let hcm = physics
        .with_residual(0, residual.clone(), "the trained blob")
        .unwrap();
    let (alone, hybrid) = (score(&physics, &held_out), score(&hcm, &held_out));
    println!(
        "{} rows, R² {:?}; held out (% + °): physics {alone:.3}, HCM {hybrid:.3}, truth {:.3}",
        trained.rows,
        trained.explained,
        score(&truth, &held_out)
    );
    assert!(hybrid < 0.75 * alone, "HCM {hybrid} vs physics {alone}");
}

/// A joint's network fits only a scenario with one joint: the cube's refuses it, naming
/// what it lacks.
#[test]
fn a_joint_s_network_on_a_scene_without_joints_is_refused() {
    let physics = elbow(&[]);
    let thrown = hcm_tests::mechanism::thrown_mechanisms(&physics, 2, 1);
    let (_, residual) = trained(&physics, &thrown, 2);
    let cube = Scenario::load(&hcm_tests::scenario("cube_toss.toml"), &[])
        .unwrap()
        .model()
        .unwrap();
    let error = cube.with_residual(0, residual, "joint.bin").unwrap_err();
    assert!(
        error.contains("joint.bin") && error.contains("no joint") && error.contains("θ̇"),
        "{error}"
    );
}
