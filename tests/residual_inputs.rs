//! Which residual inputs carry a correction to conditions the training never saw
//! (issue 28): the body-state residual of Eq 12 (13 inputs: the moving body's position,
//! quaternion, velocity, angular velocity) against the contact-frame residual (5
//! inputs per touching point: δ, δ̇, slip speed, spin and rolling rates), each scene
//! generated, PM2 of another law fitted by least squares, both residuals trained on
//! the same S1 and judged on the same held-out runs. Run with `--nocapture` for the
//! tables.
//!
//! Measured (`cargo test --release -p hcm-tests --test residual_inputs -- --nocapture`;
//! seed 3, f32 blobs): HCM − PM2 mean event error (points per run), and the whole
//! path's position error (mm RMS) PM2 → HCM:
//!
//! | scene, held out | state | contact | path, contact HCM |
//! |---|---|---|---|
//! | block on block, dropped 10 cm away | = PM2 | −6.94 ± 0.08 | 20.2 → 0.84 |
//! | peg in hole, 30 % faster sideways | = PM2 | −3.11 ± 0.08 | 0.054 → 0.127 |
//! | ball on plate, thrown 50 % faster | = PM2 | −0.32 ± 0.21 | 91.2 → 91.2 |
//! | cube_drop, a random 10 % of the runs | −6.27 ± 0.72 | −6.70 ± 0.74 | 17.6 → 3.5 |
//!
//! The body-state network is switched off wherever the body is not where and as it
//! was in training; the contact-frame one acts wherever the contact feels as it did.

use hcm_host::evaluate::RigidEvaluation;
use hcm_host::scenario::Scenario;
use hcm_tests::rigid_pipeline::{pipeline, with_conditions, Inputs};

const BOTH: [Inputs; 2] = [Inputs::State, Inputs::Contact];

/// Model `m`'s (1 = the state HCM, 2 = the contact HCM) paired difference to PM2.
fn paired(e: &RigidEvaluation, m: usize) -> (f64, f64) {
    e.paired[m]
}

/// Model `m` beats PM2 run by run by more than 2 standard errors.
fn beats_pm2(e: &RigidEvaluation, m: usize) {
    let (difference, se) = paired(e, m);
    assert!(
        difference + 2.0 * se < 0.0,
        "model {m} − PM2 {difference:+.4} ± {se:.4} over {} runs",
        e.runs
    );
}

/// Model `m`'s mean position error of the whole path (m).
fn path(e: &RigidEvaluation, m: usize) -> f64 {
    e.trajectory[m].position.0
}

#[test]
fn a_block_dropped_where_no_training_run_fell_is_corrected_by_contact_frame_inputs_only() {
    let scenario = with_conditions(
        "block_on_block.toml",
        &[
            ("here", "\"body.block.position=[0.0, 0.0, 0.08]\""),
            ("there", "\"body.block.position=[0.08, -0.06, 0.08]\""),
        ],
    );
    let e = pipeline(&scenario, "hertz", 40, &BOTH);
    assert_eq!(paired(&e, 1), (0.0, 0.0), "the state HCM is PM2 there");
    beats_pm2(&e, 2);
    assert!(path(&e, 2) < 0.25 * path(&e, 0), "{:?}", e.trajectory);
}

#[test]
fn a_peg_thrown_faster_than_any_trained_is_corrected_by_contact_frame_inputs_only() {
    let text = std::fs::read_to_string(hcm_tests::scenario("peg_in_hole.toml")).unwrap();
    let text = text.replace("[experiment]", "[experiment]\nholdout_conditions = [\"wide\"]")
        + "\n[[experiment.condition]]\nname = \"narrow\"\nset = [\"body.peg.velocity=[0.1, 0.0, -0.5]\"]\n\
           \n[[experiment.condition]]\nname = \"wide\"\nset = [\"body.peg.velocity=[0.13, 0.0, -0.5]\"]\n";
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("peg_conditions.toml");
    std::fs::write(&file, text).unwrap();
    let scenario = Scenario::load(&file, &[]).unwrap();
    let e = pipeline(&scenario, "hunt_crossley", 40, &BOTH);
    assert_eq!(paired(&e, 1), (0.0, 0.0), "the state HCM is PM2 there");
    beats_pm2(&e, 2);
}

/// 50 % faster: the contact's δ̇ and δ leave the trained range over most of each
/// impact, so the contact-frame network too is mostly off — and where it acts it must
/// not make PM2 worse.
#[test]
fn a_ball_thrown_faster_than_any_trained_is_beyond_both_and_neither_harms() {
    let scenario = with_conditions(
        "ball_on_plate.toml",
        &[
            ("slow", "\"body.ball.velocity=[0.6, 0.1, -1.0]\""),
            ("fast", "\"body.ball.velocity=[0.6, 0.1, -1.5]\""),
        ],
    );
    let e = pipeline(&scenario, "hertz", 40, &BOTH);
    assert_eq!(paired(&e, 1), (0.0, 0.0));
    let (difference, se) = paired(&e, 2);
    assert!(difference - 2.0 * se < 0.0, "{difference:+.4} ± {se:.4}");
}

/// Within the trained conditions both serve; the contact-frame HCM also keeps the
/// tumbling cube's whole path (its later bounces on other corners and faces).
#[test]
fn on_cube_drop_both_beat_pm2_and_the_contact_frame_hcm_keeps_the_path() {
    let scenario = Scenario::load(&hcm_tests::scenario("cube_drop.toml"), &[]).unwrap();
    let e = pipeline(&scenario, "hunt_crossley", 100, &BOTH);
    beats_pm2(&e, 1);
    beats_pm2(&e, 2);
    assert!(path(&e, 2) < 0.5 * path(&e, 0), "{:?}", e.trajectory);
}
