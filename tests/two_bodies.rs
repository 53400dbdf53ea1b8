//! Contacts between two moving bodies (issue 28: "several moving bodies"): a ball
//! dropped and rolling into a block that rests on a fixed table
//! (`tests/common/scenes/ball_hits_block.toml`). The ball's sensor feels both its
//! contacts, the block's and the table's; the ball–block contact is fitted on what is
//! left once the table's (the scenario's physics) is taken off, at the two bodies'
//! recorded poses. Identify recovers the data's Hunt–Crossley law; a Hertz PM2 and the
//! contact-frame HCM over it are judged on held-out runs.

use hcm_host::experiment::generate_split;
use hcm_host::identify::rigid::{identify_from_samples, with_law};
use hcm_host::progress::Silent;
use hcm_tests::rigid_pipeline::{pipeline, Inputs};

#[test]
fn the_ball_block_contact_is_fitted_at_both_bodies_recorded_poses() {
    let scenario = hcm_tests::scene("ball_hits_block.toml");
    let model = scenario.model().unwrap();
    let sets = generate_split(&scenario, 40, 5, &Silent).unwrap();
    // Away from the truth: stiffness × 1.6, damping × 1.5, friction × 1.4.
    let mut start = with_law(&model, 0, "hunt_crossley", None).unwrap();
    let base = &mut start.contacts[0].model.normal.base;
    base.set("stiffness", 1.6e9).unwrap();
    base.set("damping", 0.45).unwrap();
    base.set("exponent", 1.3).unwrap();
    let friction = start.contacts[0].model.friction.as_mut().unwrap();
    friction.static_coefficient *= 1.4;
    friction.dynamic_coefficient *= 1.4;
    let bounds = &scenario.identify.bounds;
    let found = identify_from_samples(&start, &sets.training, 0, bounds, true, &Silent).unwrap();
    let fit = &found.fit;
    println!("{} rows; {:?}", fit.rows, fit.parameters);
    hcm_tests::assert_recovered(
        fit,
        &[
            ("stiffness", 1e9, 0.15),
            ("exponent", 1.5, 0.01),
            ("damping", 0.3, 0.03),
            ("mu_dynamic", 0.15, 0.03),
        ],
    );
}

#[test]
fn a_hertz_pm2_between_two_moving_bodies_is_corrected_by_the_contact_frame_hcm() {
    let scenario = hcm_tests::scene("ball_hits_block.toml");
    let e = pipeline(&scenario, "hertz", 60, &[Inputs::Contact]);
    let (d, se) = e.paired[1];
    assert!(d + 2.0 * se < 0.0, "HCM − PM2 {d} ± {se}");
}

/// Poses alone of two moving bodies: the replay from motion follows one body, and says
/// so, pointing to the force data that fit such a contact.
#[test]
fn poses_alone_of_two_moving_bodies_are_refused_with_what_to_do() {
    let model = hcm_tests::scene("ball_hits_block.toml").model().unwrap();
    let error = hcm_host::toss::TossSetup::new(&model)
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("one moving body") && error.contains("has 2") && error.contains("force"),
        "{error}"
    );
}
