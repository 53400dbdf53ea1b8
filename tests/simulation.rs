//! The simulator against the reconstruction's independent solver, its own
//! convergence, closed forms, energy bookkeeping, and the CSV round trip.

use hcm_host::dataset::Dataset;
use hcm_host::indicators::{from_run, Indicators};
use hcm_host::scenario::{Model, Scenario};
use hcm_host::simulate::{simulate, Simulation};
use std::path::{Path, PathBuf};

fn scenario_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenarios")
        .join(name)
}

fn model(name: &str, overrides: &[&str]) -> Model {
    let path = scenario_path(name);
    let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    Scenario::load(&path, &overrides)
        .unwrap()
        .resolve(&path)
        .unwrap()
}

fn first_event(simulation: &Simulation) -> Indicators {
    assert_eq!(
        simulation.events.len(),
        1,
        "expected exactly one contact event"
    );
    simulation.events[0].indicators().expect("the contact ends")
}

fn assert_close(name: &str, value: f64, expected: f64, tolerance: f64) {
    let error = ((value - expected) / expected).abs();
    assert!(
        error < tolerance,
        "{name}: {value:e} vs {expected:e} ({:.4} %)",
        100.0 * error
    );
}

#[test]
fn bouncing_ball_reproduces_the_reconstruction() {
    let i = first_event(&simulate(&model("bouncing_ball.toml", &[])).unwrap());
    assert_close("max force", i.max_force, 2923.6, 1e-3);
    assert_close("impulse", i.impulse, 0.18115, 1e-3);
    assert_close("energy loss", i.energy_loss, 0.0086711, 1e-3);
    assert_close("duration", i.duration, 1.1440e-4, 1e-3);
}

#[test]
fn flat_shot_reproduces_the_reconstruction_at_095() {
    let i = first_event(&simulate(&model("flat_shot.toml", &[])).unwrap());
    assert_close("max force", i.max_force, 1685.4, 1e-3);
    assert_close("impulse", i.impulse, 0.10582, 1e-3);
    assert_close("energy loss", i.energy_loss, 0.0024078, 1e-3);
    assert_close("duration", i.duration, 1.1569e-4, 1e-3);
}

#[test]
fn halving_the_tolerance_moves_no_indicator_by_more_than_a_ten_thousandth() {
    for name in ["bouncing_ball.toml", "flat_shot.toml"] {
        let base = first_event(&simulate(&model(name, &[])).unwrap());
        let tighter = model(
            name,
            &[
                "simulation.relative_tolerance=5e-11",
                "simulation.absolute_tolerance=5e-15",
            ],
        );
        let fine = first_event(&simulate(&tighter).unwrap());
        for ((label, _), (a, b)) in Indicators::NAMES
            .iter()
            .zip(base.values().into_iter().zip(fine.values()))
        {
            assert_close(&format!("{name} {label}"), a, b, 1e-4);
        }
    }
}

#[test]
fn hertz_ball_matches_the_closed_forms() {
    let speed = 1.4007_f64;
    let m = model(
        "bouncing_ball.toml",
        &[
            "contact.0.law=hertz",
            "contact.0.parameters={}",
            "contact.0.noise={}",
            "gravity=[0.0, 0.0, 0.0]",
            "body.ball.position=[0.0, 0.0, 0.0128]",
            &format!("body.ball.velocity=[0.0, 0.0, {}]", -speed),
        ],
    );
    let hcm_core::law::AnyNormalLaw::Hertz(law) = m.contacts[0].law else {
        panic!("not hertz")
    };
    let (k, mass) = (law.stiffness, m.bodies[0].mass);
    let max_depth = (5.0 * mass * speed * speed / (4.0 * k)).powf(0.4);
    let simulation = simulate(&m).unwrap();
    let i = first_event(&simulation);
    assert_close("max force", i.max_force, k * max_depth.powf(1.5), 5e-4);
    assert_close("duration", i.duration, 2.9433 * max_depth / speed, 5e-4);
    let ball = simulation.run.body("ball").unwrap();
    let deepest = ball
        .samples
        .iter()
        .map(|s| 0.0127 - s.position[2])
        .fold(f64::MIN, f64::max);
    assert_close("max depth", deepest, max_depth, 5e-4);
}

#[test]
fn dissipated_work_equals_the_kinetic_energy_lost() {
    for name in ["bouncing_ball.toml", "flat_shot.toml"] {
        let simulation = simulate(&model(name, &[])).unwrap();
        let e = &simulation.events[0];
        let lost = e.kinetic_energy_in - e.kinetic_energy_out;
        assert_close(&format!("{name} work"), e.work, lost, 1e-6);
        assert_close(
            &format!("{name} relative-motion energy"),
            e.indicators().unwrap().energy_loss,
            lost,
            1e-6,
        );
    }
}

#[test]
fn indicators_from_the_written_csv_agree_with_the_simulation() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["bouncing_ball.toml", "flat_shot.toml"] {
        let m = model(name, &[]);
        let simulation = simulate(&m).unwrap();
        let path = dir.path().join("trajectory.csv");
        Dataset {
            runs: vec![simulation.run.clone()],
        }
        .write(&path)
        .unwrap();
        let data = Dataset::read(&path).unwrap();
        let events = from_run(&m, &data.runs[0]).unwrap();
        assert_eq!(events.len(), 1);
        let (from_csv, exact) = (events[0].indicators, first_event(&simulation));
        let samples_in_contact =
            (exact.duration / m.scenario.record.contact_sample_period) as usize;
        assert!(
            samples_in_contact >= 100,
            "{name}: {samples_in_contact} samples per contact"
        );
        // Bounds from the sampling (h = 1 µs, README "Indicators from data").
        assert!(
            (from_csv.duration - exact.duration).abs() < 1e-10,
            "{name} duration {:e}",
            from_csv.duration - exact.duration
        );
        assert_close(
            &format!("{name} max force"),
            from_csv.max_force,
            exact.max_force,
            1e-6,
        );
        assert_close(
            &format!("{name} impulse"),
            from_csv.impulse,
            exact.impulse,
            1e-4,
        );
        assert_close(
            &format!("{name} energy loss"),
            from_csv.energy_loss,
            exact.energy_loss,
            1e-4,
        );
    }
}

#[test]
fn the_peak_of_noisy_data_is_not_biased_upwards() {
    use rand::{RngExt, SeedableRng};
    // σ = 15 N on every force sample (the experiments' output noise): the mean of the
    // raw per-run maxima sits ≈ +0.5 % above the true peak; the smoothed peak of the
    // indicators must not (parameters.md: "compute indicators from a smoothed signal").
    let m = model("bouncing_ball.toml", &[]);
    let simulation = simulate(&m).unwrap();
    let exact = first_event(&simulation).max_force;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
    let (trials, sigma) = (200, 15.0);
    let (mut smoothed, mut raw) = (0.0, 0.0);
    for _ in 0..trials {
        let mut run = simulation.run.clone();
        for sample in &mut run.bodies[0].samples {
            let u1: f64 = 1.0 - rng.random::<f64>();
            let u2: f64 = rng.random();
            sample.force[2] += sigma * (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos();
        }
        raw += run.bodies[0]
            .samples
            .iter()
            .map(|s| s.force[2])
            .fold(f64::MIN, f64::max);
        smoothed += from_run(&m, &run).unwrap()[0].indicators.max_force;
    }
    let (raw, smoothed) = (raw / trials as f64, smoothed / trials as f64);
    let bias = |v: f64| (v - exact) / exact;
    assert!(bias(raw) > 3e-3, "the raw maximum's bias {:.2e}", bias(raw));
    // The estimator's σ per run is ≈ 15·√(3.5/23) ≈ 6 N (0.2 %), so the mean of 200
    // runs has a standard error of 0.015 %; allow 0.05 %.
    assert!(
        bias(smoothed).abs() < 5e-4,
        "smoothed peak bias {:.2e}",
        bias(smoothed)
    );
}
