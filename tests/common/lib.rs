//! What the workspace's integration tests (`tests/<area>/`) and benchmarks (`benches/*.rs`)
//! share: the reference setup of the paper's examples, the hidden-effect data sets of the
//! diagnosis tests, and a fixture that runs the `hcm` binary (`cli`).
//!
//! This is the library of the root package `hcm-tests`, so that Cargo finds every area of
//! `tests/` and every file of `benches/` by itself; `tests/common/` holds no tests of its own.

#![warn(missing_docs)]

pub mod cli;
pub mod hidden;
pub mod mechanism;
pub mod reference;
pub mod rig;
pub mod rigid_pipeline;
pub mod rigid_reference;
pub mod sources;

use std::path::{Path, PathBuf};

/// The environment variable that runs the long studies (power tables over seeds) at
/// their full size: `HCM_FULL_STUDIES=1 cargo test --release -p hcm-tests --test diagnose`.
/// Without it they run smaller in `cargo test`, asserting the same properties over fewer
/// data sets (docs/tests.md, "Sizes").
pub const FULL_STUDIES: &str = "HCM_FULL_STUDIES";

/// `full` when [`FULL_STUDIES`] is set to anything but `0` or the empty string, else
/// `quick`: the size a long study runs at.
pub fn study_size<T>(quick: T, full: T) -> T {
    match std::env::var(FULL_STUDIES) {
        Ok(value) if !value.is_empty() && value != "0" => full,
        _ => quick,
    }
}

/// The shipped peg-in-hole scenario (`scenarios/peg_in_hole.toml`), as read.
pub fn peg_in_hole() -> hcm_host::scenario::Scenario {
    hcm_host::scenario::Scenario::load(&scenario("peg_in_hole.toml"), &[])
        .expect("scenarios/peg_in_hole.toml reads")
}

/// Mean and sample standard deviation (n − 1) of `values`.
pub fn mean_std(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, var.sqrt())
}

/// A scene of the tests' own (`tests/common/scenes/`), written with the README's keys
/// and shipped with no example of its own: the checks that hcm's commands work on
/// scenarios they were not shaped around.
pub fn scene(name: &str) -> hcm_host::scenario::Scenario {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/common/scenes")
        .join(name);
    hcm_host::scenario::Scenario::load(&path, &[]).expect("the test scene reads")
}

/// A test scene (`tests/common/scenes/`) filmed by a camera at 200 Hz for `seconds` (s):
/// every body sampled once per 5 ms, in contact or not; `sets` applied after.
pub fn filmed(name: &str, seconds: f64, sets: &[String]) -> hcm_host::scenario::Model {
    let camera = [
        "record.contact_sample_period=0.005".to_owned(),
        "record.flight_sample_period=0.005".to_owned(),
        "record.contact_margin=0.0".to_owned(),
        format!("simulation.end_time={seconds}"),
    ];
    let all: Vec<String> = camera.into_iter().chain(sets.iter().cloned()).collect();
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/common/scenes")
        .join(name);
    let scenario = hcm_host::scenario::Scenario::load(&path, &all).expect("the test scene reads");
    scenario.model().expect("the test scene resolves")
}

/// A seeded random throw of the cube onto the table: 0.15–0.25 m up, 0.8–1.6 m/s sideways
/// in any direction and 0.5 m/s down, spinning up to 6 rad/s about the horizontal axes
/// and 3 about the vertical, tilted up to 0.6 rad (the diagnosis's and the residual's
/// simulated tosses).
pub fn throw_cube(body: &mut hcm_host::scenario::Body, rng: &mut impl rand::RngExt) {
    let angle = rng.random_range(0.0..std::f64::consts::TAU);
    let speed = rng.random_range(0.8..1.6);
    body.position = [0.0, 0.0, rng.random_range(0.15..0.25)].into();
    body.velocity = [speed * angle.cos(), speed * angle.sin(), -0.5].into();
    body.angular_velocity = [
        rng.random_range(-6.0..6.0),
        rng.random_range(-6.0..6.0),
        rng.random_range(-3.0..3.0),
    ]
    .into();
    body.orientation = nalgebra::UnitQuaternion::from_euler_angles(
        rng.random_range(-0.6..0.6),
        rng.random_range(-0.6..0.6),
        rng.random_range(0.0..1.5),
    );
}

/// The shipped cube-toss scenario with `scatter` (–, relative) of run-to-run scatter on
/// its contact's stiffness, maximum damping and friction coefficients (Eq 18).
pub fn cube_toss_scattered(scatter: f64) -> hcm_host::scenario::Model {
    let sets = [format!(
        "contact.0.noise={{ stiffness = {scatter}, max_damping = {scatter}, \
         mu_static = {scatter}, mu_dynamic = {scatter} }}"
    )];
    hcm_host::scenario::Scenario::load(&scenario("cube_toss.toml"), &sets)
        .unwrap()
        .model()
        .unwrap()
}

/// `count` seeded random tosses ([`throw_cube`]) of `model`, each with its contact drawn
/// from the model's scatter (Eq 18), recorded as the scenario records (148 Hz for the
/// cube); run ids `toss_000`….
pub fn scattered_tosses(
    model: &hcm_host::scenario::Model,
    count: usize,
    seed: u64,
) -> hcm_host::dataset::Dataset {
    use rand::SeedableRng;
    let mut throw = rand::rngs::StdRng::seed_from_u64(seed);
    let mut scatter = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut data = hcm_host::dataset::Dataset::default();
    for k in 0..count {
        let mut toss = hcm_host::experiment::noisy_model(model, &mut scatter).unwrap();
        throw_cube(&mut toss.bodies[0], &mut throw);
        let mut run = hcm_host::simulate::simulate(&toss).unwrap().run;
        run.id = format!("toss_{k:03}");
        data.runs.push(run);
    }
    data
}

/// `data` as a tracker films it: each frame's centre moved by `noise.0` (m) per axis
/// and its orientation turned by a rotation vector of `noise.1` (rad) per axis, drawn
/// from `seed`; poses only (velocities, forces and torques not sampled).
pub fn filmed_poses(
    mut data: hcm_host::dataset::Dataset,
    noise: (f64, f64),
    seed: u64,
) -> hcm_host::dataset::Dataset {
    use rand::SeedableRng;
    use rand_distr::{Distribution, StandardNormal};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut normal = || -> f64 { StandardNormal.sample(&mut rng) };
    for run in &mut data.runs {
        for body in &mut run.bodies {
            for s in &mut body.samples {
                s.position = s.position.map(|p| p + noise.0 * normal());
                let [w, x, y, z] = s.orientation;
                let q = nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
                    w, x, y, z,
                ));
                let turn = nalgebra::Vector3::new(normal(), normal(), normal()) * noise.1;
                let q = nalgebra::UnitQuaternion::from_scaled_axis(turn) * q;
                s.orientation = [q.w, q.i, q.j, q.k];
                s.velocity = [f64::NAN; 3];
                s.angular_velocity = [f64::NAN; 3];
                s.force = [f64::NAN; 3];
                s.torque = [f64::NAN; 3];
            }
        }
    }
    data
}

/// Prints a motion diagnosis round by round, every candidate's gain, fit and (for a
/// chance) interval, then its answer: what `--nocapture` shows of a diagnosis test.
pub fn print_motion_diagnosis(d: &hcm_host::diagnose::MotionDiagnosis) {
    for round in &d.rounds {
        println!(
            "  round: training {:.4}, held-out {:.4} (% + °)",
            round.training, round.held_out
        );
        for c in &round.candidates {
            let interval = c.interval.map_or(String::new(), |i| format!(" in {i:?}"));
            println!(
                "    {:<27} gain {:>9.4} ± {:.4} (t {:>7.1}) {}  {:?}{interval}",
                c.name,
                c.gain.mean,
                c.gain.standard_error,
                c.gain.t(),
                if c.helps { "helps" } else { "     " },
                c.parameters
            );
        }
    }
    println!("  answer: {}", d.answer);
}

/// The path of a scenario file in the workspace's `scenarios/`.
pub fn scenario(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenarios")
        .join(name)
}

/// The fit from motion the tests run: `model`'s first contact fitted to `training` by a
/// short GA (24 × 12, `seed`) and a 60-replay polish.
pub fn motion_fit(
    model: &hcm_host::scenario::Model,
    training: &hcm_host::dataset::Dataset,
    seed: u64,
) -> hcm_host::identify::MotionFit {
    use hcm_host::identify::{identify_motion, MotionParameters, MotionTarget};
    let setup = hcm_host::replay::TossSetup::new(model).unwrap();
    let target = MotionTarget::new(model, training).unwrap();
    let parameters = MotionParameters::new(model, &setup).unwrap();
    let settings = hcm_host::numerics::optimize::GeneticSettings {
        population: 24,
        generations: 12,
        seed,
        ..Default::default()
    };
    let progress = hcm_host::progress::Silent;
    let fold = hcm_host::progress::Fold::First;
    identify_motion(model, &target, &parameters, &settings, 60, fold, &progress).unwrap()
}

/// Prints a fit from motion: its parameters, its training fitness before and after,
/// the held-out scores `(scene, fitted, truth)` (% + °) and each parameter's probe.
pub fn print_motion_fit(
    label: &str,
    found: &hcm_host::identify::MotionFit,
    (scene, fitted, truth): (f64, f64, f64),
) {
    println!(
        "{label}: {:?}\n  training {:.3} → {:.3}; held out: scene {scene:.3}, fitted \
         {fitted:.3}, truth {truth:.3} (% + °)",
        found.parameters, found.start_fitness, found.fitness,
    );
    for s in &found.sensitivity {
        let loose = if s.loose { "loose" } else { "" };
        println!("  {:<14} rise {:.4} {loose}", s.name, s.rise);
    }
}

/// Asserts that each `(parameter, true value, relative tolerance)` of `expected` was
/// found by `fit` within the tolerance and within 4 of its standard errors, printing
/// each.
pub fn assert_recovered(fit: &hcm_host::identify::SampleFit, expected: &[(&str, f64, f64)]) {
    for &(name, truth, tolerance) in expected {
        let i = (fit.parameters.iter().position(|p| p.0 == name))
            .unwrap_or_else(|| panic!("no parameter {name}"));
        let (got, se) = (fit.parameters[i].1, fit.standard_errors[i]);
        println!("{name}: {got:.6e} ± {se:.2e} (truth {truth})");
        assert!(
            (got - truth).abs() <= tolerance * truth,
            "{name} {got} vs {truth}"
        );
        assert!(
            (got - truth).abs() <= 4.0 * se,
            "{name} {got} ± {se} vs {truth}"
        );
    }
}
