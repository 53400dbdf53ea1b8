//! `hcm simulate --scenario scenarios/cube_drop.toml` against the independent reference
//! solver (`hcm_tests::rigid_reference`: rotation matrix and world angular momentum,
//! fixed-step RK4 — nothing shared with hcm's quaternion Dormand–Prince, manifold or
//! laws): within 1 mm in position and 1° in orientation over the whole 0.4 s, and
//! converged: halving the solver's tolerances moves the final pose by < 0.1 mm.
//!
//! Run with `--nocapture` to see the measured differences.

use hcm_host::dataset::{Dataset, Sample};
use hcm_tests::cli::Hcm;
use hcm_tests::rigid_reference::{compare, cube_drop, simulate};
use nalgebra::{Quaternion, UnitQuaternion, Vector3};

/// The reference's fixed step (s); its own tests show it converged to 6e-5°.
const REFERENCE_STEP: f64 = 2.5e-6;

/// The cube's samples of `hcm simulate` on the shipped scenario with `sets` applied.
fn hcm_cube(hcm: &Hcm, name: &str, sets: &[&str]) -> Vec<Sample> {
    let out = hcm.path(name);
    let mut call = hcm
        .run("simulate")
        .opt("--scenario", hcm_tests::scenario("cube_drop.toml"))
        .opt("--out", &out);
    for set in sets {
        call = call.opt("--set", set);
    }
    println!("{}", call.ok());
    let data = Dataset::read(&out).unwrap();
    data.runs[0].body("cube").unwrap().samples.clone()
}

fn orientation(s: &Sample) -> UnitQuaternion<f64> {
    let [w, x, y, z] = s.orientation;
    UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z))
}

#[test]
fn the_cube_drop_agrees_with_an_independent_solver_and_is_converged() {
    let hcm = Hcm::new();
    let samples = hcm_cube(&hcm, "cube.csv", &[]);
    assert_eq!(samples.len(), 401, "every 1 ms over 0.4 s");
    assert!((samples.last().unwrap().time - 0.4).abs() < 1e-12);
    let reference = simulate(&cube_drop(), REFERENCE_STEP);
    let times: Vec<f64> = samples.iter().map(|s| s.time).collect();
    let positions: Vec<[f64; 3]> = samples.iter().map(|s| s.position).collect();
    let quaternions: Vec<[f64; 4]> = samples.iter().map(|s| s.orientation).collect();
    let (position_error, angle_error) =
        compare(&reference.samples, &times, &positions, &quaternions);
    println!(
        "against the reference over 0.4 s: max position error {:.3e} m, max orientation error {:.3e}°",
        position_error,
        angle_error.to_degrees()
    );
    assert!(position_error < 1e-3, "{position_error} m");
    assert!(
        angle_error.to_degrees() < 1.0,
        "{}°",
        angle_error.to_degrees()
    );

    let halved = hcm_cube(
        &hcm,
        "halved.csv",
        &[
            "simulation.relative_tolerance=5e-10",
            "simulation.absolute_tolerance=5e-11",
        ],
    );
    let (a, b) = (samples.last().unwrap(), halved.last().unwrap());
    let moved = (Vector3::from(a.position) - Vector3::from(b.position)).norm();
    let turned = orientation(a).angle_to(&orientation(b)).to_degrees();
    println!("halving the tolerances moves the final pose by {moved:.3e} m and {turned:.3e}°");
    assert!(moved < 1e-4, "{moved} m");
}
