//! Diagnosis of a mechanism from its poses: tosses of the elbow (two links on a hinge,
//! `scenarios/elbow_toss.toml`) simulated with hidden joint friction — viscous, then
//! Coulomb — or none, or with a hidden contact effect beside the free hinge, filmed as
//! the real elbow tosses are (poses only, 0.5 mm and 0.3° of tracker noise per frame).
//! The user's model is the scenario as shipped: a free hinge. The diagnosis must name
//! the joint's friction with an interval holding the truth, nothing on the null, and
//! the contact's effect where that is what is hidden.
//!
//! Studies (each minutes: a mechanism replays 20× slower than the cube):
//! `cargo test --release -p hcm-tests --test diagnose diagnose_joint -- --include-ignored --nocapture`.

use hcm_host::dataset::Dataset;
use hcm_host::diagnose::{diagnose_motion, MotionDiagnosis};
use hcm_host::scenario::{Model, Scenario};

/// Tosses per data set: half train (even numbers), half are held out.
const TOSSES: usize = 24;
/// Tosses of the Coulomb study: with 24, Coulomb friction (gain 34.1, t 3.7) and a
/// stiffness about the aligned frames (31.2, t 3.1) could not be told apart on 12
/// held-out tosses — both hold the hinge back — and the answer was "ambiguous".
const COULOMB_TOSSES: usize = 48;
/// The tracker's noise: centre (m) and orientation (rad) per axis.
const TRACKER: (f64, f64) = (5e-4, 0.3 * std::f64::consts::PI / 180.0);

/// The shipped elbow scenario with `sets` applied.
fn elbow(sets: &[&str]) -> Model {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    Scenario::load(&hcm_tests::scenario("elbow_toss.toml"), &sets)
        .expect("scenarios/elbow_toss.toml reads")
        .model()
        .expect("and resolves")
}

/// `count` throws of `truth`, filmed.
fn filmed(truth: &Model, count: usize, seed: u64) -> Dataset {
    let thrown = hcm_tests::mechanism::thrown_mechanisms(truth, count, seed);
    hcm_tests::filmed_poses(thrown, TRACKER, seed)
}

fn diagnosed(what: &str, truth: &Model, seed: u64) -> MotionDiagnosis {
    diagnosed_from(what, truth, (TOSSES, seed))
}

fn diagnosed_from(what: &str, truth: &Model, (count, seed): (usize, u64)) -> MotionDiagnosis {
    let data = filmed(truth, count, seed);
    let begun = std::time::Instant::now();
    let d = diagnose_motion(&elbow(&[]), &data, &hcm_host::progress::Silent)
        .expect("the diagnosis runs");
    println!("== {what} ({:.1} s)", begun.elapsed().as_secs_f64());
    hcm_tests::print_motion_diagnosis(&d);
    d
}

fn names(d: &MotionDiagnosis) -> Vec<&str> {
    d.named.iter().map(|(n, _)| n.as_str()).collect()
}

/// The named cause's interval (its candidate's in the round that named it).
fn interval(d: &MotionDiagnosis, name: &str) -> [f64; 2] {
    let candidate = (d.rounds.iter())
        .flat_map(|r| &r.candidates)
        .find(|c| c.name == name && c.helps)
        .expect("the named candidate is in its round");
    candidate
        .interval
        .expect("a named cause of one parameter has its interval")
}

#[test]
#[ignore = "study, minutes: cargo test --release -- --include-ignored"]
fn hidden_viscous_joint_friction_is_named_with_its_interval() {
    let truth = 0.01;
    let model = elbow(&[&format!("joint.hinge.law.viscous.damping={truth}")]);
    let d = diagnosed("viscous hinge friction 0.01 N·m·s/rad", &model, 21);
    assert_eq!(names(&d), ["joint_viscous_friction"], "{}", d.answer);
    let [lo, hi] = interval(&d, "joint_viscous_friction");
    assert!(lo <= truth && truth <= hi, "{lo} … {hi} misses {truth}");
}

#[test]
#[ignore = "study, minutes: cargo test --release -- --include-ignored"]
fn hidden_coulomb_joint_friction_is_named_with_its_interval() {
    let truth = 0.04;
    let model = elbow(&[&format!(
        "joint.hinge.law.coulomb={{ torque = {truth}, smoothing_rate = 0.5 }}"
    )]);
    let d = diagnosed_from(
        "Coulomb hinge friction 0.04 N·m",
        &model,
        (COULOMB_TOSSES, 22),
    );
    assert_eq!(names(&d), ["joint_coulomb_friction"], "{}", d.answer);
    let [lo, hi] = interval(&d, "joint_coulomb_friction");
    assert!(lo <= truth && truth <= hi, "{lo} … {hi} misses {truth}");
}

#[test]
#[ignore = "study, minutes: cargo test --release -- --include-ignored"]
fn a_free_hinge_names_nothing() {
    let d = diagnosed("nothing hidden", &elbow(&[]), 23);
    assert!(d.named.is_empty() && d.ambiguous.is_empty(), "{}", d.answer);
}

#[test]
#[ignore = "study, minutes: cargo test --release -- --include-ignored"]
fn a_contact_effect_beside_the_hinge_is_named_as_the_contact_s() {
    let model = elbow(&[
        "contact.0.friction.mu_static=0.6",
        "contact.0.friction.mu_dynamic=0.6",
        "contact.1.friction.mu_static=0.6",
        "contact.1.friction.mu_dynamic=0.6",
    ]);
    let d = diagnosed("both links' friction twice the model's", &model, 24);
    assert_eq!(names(&d)[..1], ["friction_coefficient"], "{}", d.answer);
    let (_, values) = &d.named[0];
    let scale = values[0].1;
    assert!((scale - 2.0).abs() < 0.3, "scale {scale}");
}
