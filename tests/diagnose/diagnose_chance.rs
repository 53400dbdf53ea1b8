//! Chance as a cause (`hcm_host::diagnose::diagnose_motion`'s chance phase): simulated
//! tosses of the cube whose contact scatters from toss to toss (stiffness, damping and
//! friction each × (1 + 0.2·ζ), Eq 18) and tosses whose contact does not, both filmed
//! as a tracker films (poses only, 0.5 mm and 0.3° of noise per frame). The user's
//! model is the scenario's contact without scatter. On the scattered tosses the
//! diagnosis must name `contact_scatter` with an interval holding 0.2, and the extended
//! model's ensemble must hold the held-out recorded coordinates in its 50 % and 90 %
//! bands 45–55 % and 85–95 % of the time; on the others it must name no chance.
//!
//! Run with `--nocapture` to see every candidate.

use hcm_host::diagnose::{diagnose_motion_with, Catalogue, MotionBase, MotionDiagnosis};
use hcm_host::identify::split_tosses;
use hcm_host::replay::{band_shares, forecast_paths, summarize_paths, Spread};
use hcm_host::scenario::{Model, Scenario};

/// Tosses per scattered data set: half train, half held out.
const TOSSES: usize = 60;
/// Tosses of the data set without scatter: fewer suffice to find nothing (and a
/// smaller set is more easily fooled, not less).
const NULL_TOSSES: usize = 30;
/// The tracker's noise: centre (m) and orientation (rad) per axis.
const TRACKER: (f64, f64) = (5e-4, 0.3 * std::f64::consts::PI / 180.0);
/// The scatter the scattered tosses hide (–).
const SCATTER: f64 = 0.2;

fn cube_toss(sets: &[String]) -> Model {
    Scenario::load(&hcm_tests::scenario("cube_toss.toml"), sets)
        .unwrap()
        .model()
        .unwrap()
}

/// `count` filmed tosses of the cube whose contact scatters by `scatter`.
fn filmed(scatter: f64, count: usize, seed: u64) -> hcm_host::dataset::Dataset {
    let noise = if scatter > 0.0 {
        format!(
            "contact.0.noise={{ stiffness = {scatter}, max_damping = {scatter}, mu = {scatter} }}"
        )
    } else {
        "contact.0.noise={}".to_owned()
    };
    let truth = cube_toss(&[noise]);
    let tosses = hcm_tests::scattered_tosses(&truth, count, seed);
    hcm_tests::filmed_poses(tosses, TRACKER, seed)
}

fn diagnosed(what: &str, data: &hcm_host::dataset::Dataset) -> MotionDiagnosis {
    let begun = std::time::Instant::now();
    // The chance phase alone: the deterministic effects are tried first by every
    // diagnosis (tests/diagnose/diagnose_motion.rs), and find nothing here.
    let chance = Catalogue::default()
        .with_chance()
        .retain(|e| e.stochastic());
    let base = (MotionBase::Given, &chance);
    let silent = &hcm_host::progress::Silent;
    let d = diagnose_motion_with(&cube_toss(&[]), data, base, silent).unwrap();
    println!("== {what} ({:.1} s)", begun.elapsed().as_secs_f64());
    hcm_tests::print_motion_diagnosis(&d);
    d
}

const CHANCE: [&str; 4] = [
    "contact_scatter",
    "start_uncertainty",
    "fixed_height",
    "fixed_tilt",
];

#[test]
#[ignore = "study, over 12 s on 2 cores: cargo test -- --include-ignored"]
fn a_scattered_contact_is_named_with_its_scatter_and_forecast_calibrated() {
    let data = filmed(SCATTER, TOSSES, 11);
    let d = diagnosed("scattered by 0.2", &data);
    let named: Vec<&str> = d.named.iter().map(|(n, _)| n.as_str()).collect();
    assert!(named.contains(&"contact_scatter"), "{}", d.answer);
    let scatter = (d.rounds.iter())
        .flat_map(|r| &r.candidates)
        .find(|c| c.name == "contact_scatter" && c.helps)
        .unwrap();
    let [low, high] = scatter.interval.unwrap();
    assert!(
        low <= SCATTER && SCATTER <= high,
        "σ {:?}, interval {low}…{high}",
        scatter.parameters
    );
    // The extended model's bands on tosses it never saw: the held-out ones and twice
    // as many, filmed afresh (frames within a toss move together, so coverage needs many
    // tosses to be measured to a few points).
    let (_, mut held_out) = split_tosses(&data);
    held_out
        .runs
        .extend(filmed(SCATTER, TOSSES, 13).runs.into_iter().map(|mut run| {
            run.id = format!("fresh_{}", run.id);
            run
        }));
    let forecasts = forecast_paths(&d.extended, &held_out, Spread::of_model(40, 3), || {}).unwrap();
    let shares = band_shares(&summarize_paths(&forecasts).coverage);
    println!(
        "coverage of the 50 % and 90 % bands (40 members) on {} unseen tosses: {shares:?}",
        held_out.runs.len()
    );
    assert!((0.45..=0.55).contains(&shares[0]), "{shares:?}");
    assert!((0.85..=0.95).contains(&shares[1]), "{shares:?}");
}

#[test]
fn a_contact_without_scatter_names_no_chance() {
    let d = diagnosed("no scatter", &filmed(0.0, NULL_TOSSES, 12));
    let named: Vec<&str> = d.named.iter().map(|(n, _)| n.as_str()).collect();
    assert!(!named.iter().any(|n| CHANCE.contains(n)), "{}", d.answer);
}

/// A misfit is not chance: tosses of a cube whose inertia is 1.3 times the model's,
/// without scatter, filmed as above. A spread would cover some of the misfit; the whole
/// diagnosis (the deterministic effects, then chance on what is left) must name the
/// inertia and no chance.
#[test]
#[ignore = "study, over 12 s on 2 cores: cargo test -- --include-ignored"]
fn a_misfit_is_named_as_itself_not_as_chance() {
    let inertia = 1.3 * 8.1e-4;
    let truth = cube_toss(&[
        "contact.0.noise={}".to_owned(),
        format!("body.cube.inertia=[{inertia}, {inertia}, {inertia}]"),
    ]);
    let data =
        hcm_tests::filmed_poses(hcm_tests::scattered_tosses(&truth, TOSSES, 14), TRACKER, 14);
    let begun = std::time::Instant::now();
    let catalogue = Catalogue::default().with_chance();
    let base = (MotionBase::Given, &catalogue);
    let silent = &hcm_host::progress::Silent;
    let d = diagnose_motion_with(&cube_toss(&[]), &data, base, silent).unwrap();
    println!("== inertia × 1.3 ({:.1} s)", begun.elapsed().as_secs_f64());
    hcm_tests::print_motion_diagnosis(&d);
    let named: Vec<&str> = d.named.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(named, ["inertia_scale"], "{}", d.answer);
}
