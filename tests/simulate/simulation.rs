//! The simulator against the reconstruction's independent solver, its own
//! convergence, closed forms, energy bookkeeping, and the CSV round trip.

use hcm_host::dataset::Dataset;
use hcm_host::indicators::{from_run, Indicators};
use hcm_host::scenario::{Model, Scenario};
use hcm_host::simulate::{simulate, Simulation};
use std::path::{Path, PathBuf};

fn scenario_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenarios")
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
    simulation.events[0]
        .normal_indicators()
        .expect("the contact ends")
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
    let hcm_core::law::AnyNormalLaw::Hertz(law) = *m.contacts[0].law() else {
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
            e.normal_indicators().unwrap().energy_loss,
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
        let (from_csv, exact) = (events[0].line(), first_event(&simulation));
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
            // The peak is read from a degree-4 fit over ±10 % of the contact (unbiased
            // under noise); its model error on a noise-free pulse is ~1e-6.
            5e-6,
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
    // indicators must not (docs/reconstruction.md: indicators come from a smoothed signal).
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
        smoothed += from_run(&m, &run).unwrap()[0].event.max_force;
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

#[test]
fn contact_effects_act_in_the_simulation_and_keep_the_energy_books() {
    let base = first_event(&simulate(&model("bouncing_ball.toml", &[])).unwrap());
    // Each dissipative effect raises the energy loss; the work books stay exact.
    for effect in [
        "{ viscous_damping = { coefficient = 40.0 } }",
        "{ hysteresis_damping = { coefficient = 4e5, exponent = 0.5 } }",
        "{ adhesion = { pull_off_force = 40.0 } }",
        "{ plasticity = { permanent_ratio = 0.05 } }",
    ] {
        let set = format!("contact.0.effects=[{effect}]");
        let simulation = simulate(&model("bouncing_ball.toml", &[&set])).unwrap();
        let e = &simulation.events[0];
        let lost = e.kinetic_energy_in - e.kinetic_energy_out;
        assert_close(&format!("{effect} work"), e.work, lost, 1e-6);
        let i = e.normal_indicators().unwrap();
        assert!(
            i.energy_loss > base.energy_loss * 1.01,
            "{effect}: energy loss {:e} vs {:e}",
            i.energy_loss,
            base.energy_loss
        );
    }
}

#[test]
fn plasticity_ends_the_force_before_the_indentation() {
    let ratio = 0.1;
    let set = format!("contact.0.effects=[{{ plasticity = {{ permanent_ratio = {ratio} }} }}]");
    let m = model("bouncing_ball.toml", &[&set]);
    let simulation = simulate(&m).unwrap();
    let ball = simulation.run.body("ball").unwrap();
    let depth = |s: &hcm_host::dataset::Sample| 0.0127 - s.position[2];
    let deepest = ball.samples.iter().map(depth).fold(f64::MIN, f64::max);
    // After the deepest point: every sample with 0 < δ < ρ·δ_max has zero force.
    let peak = ball
        .samples
        .iter()
        .position(|s| depth(s) == deepest)
        .unwrap();
    let late: Vec<_> = ball.samples[peak..]
        .iter()
        .filter(|s| depth(s) > 0.0 && depth(s) < 0.9 * ratio * deepest)
        .collect();
    assert!(
        late.len() >= 3,
        "{} samples below the permanent depth",
        late.len()
    );
    assert!(late.iter().all(|s| s.force[2] == 0.0));
    // Before it, the force is positive at the same depths.
    assert!(ball.samples[..peak]
        .iter()
        .filter(|s| depth(s) > 0.5 * ratio * deepest)
        .all(|s| s.force[2] > 0.0));
}

#[test]
fn air_drag_slows_the_fall_as_the_closed_form_says() {
    // Quadratic drag from rest over a drop h: v² = (m·g/c)·(1 − exp(−2·c·h/m)).
    let c = 0.05;
    let set = format!("body.ball.air_drag={{ coefficient = {c} }}");
    let m = model("bouncing_ball.toml", &[&set]);
    let simulation = simulate(&m).unwrap();
    let (mass, g, h) = (m.bodies[0].mass, 9.81, 0.1);
    let expected = (mass * g / c * (1.0 - (-2.0 * c * h / mass).exp())).sqrt();
    assert_close(
        "impact speed",
        simulation.events[0].approach_speed,
        expected,
        1e-6,
    );
    assert!(expected < 0.99 * (2.0 * g * h).sqrt());
}

#[test]
fn an_offset_and_a_lagging_force_sensor_are_simulated_as_stated() {
    use hcm_host::experiment::noisy_run;
    use rand::SeedableRng;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
    let clean = noisy_run(
        &model(
            "bouncing_ball.toml",
            &["experiment.force_noise=0.0", "contact.0.noise={}"],
        ),
        &mut rng,
    )
    .unwrap();
    let (tau, offset) = (3e-6, 25.0);
    let lagging = noisy_run(
        &model(
            "bouncing_ball.toml",
            &[
                "experiment.force_noise=0.0",
                "contact.0.noise={}",
                &format!("experiment.sensor_delay={tau}"),
                &format!("experiment.force_offset=[0.0, 0.0, {offset}]"),
            ],
        ),
        &mut rng,
    )
    .unwrap();
    let (a, b) = (&clean.bodies[0].samples, &lagging.bodies[0].samples);
    assert_eq!(a.len(), b.len());
    // In flight the sensor reads the offset; in contact the force of 3 samples (3 µs) ago.
    assert!((b[0].force[2] - offset).abs() < 1e-9);
    let peak = (0..a.len())
        .max_by(|&i, &j| a[i].force[2].total_cmp(&a[j].force[2]))
        .unwrap();
    let shifted = (0..b.len())
        .max_by(|&i, &j| b[i].force[2].total_cmp(&b[j].force[2]))
        .unwrap();
    assert!(
        (b[shifted].time - a[peak].time - tau).abs() < 1e-9,
        "peak moved by {:e}",
        b[shifted].time - a[peak].time
    );
    assert!((b[shifted].force[2] - offset - a[peak].force[2]).abs() < 1e-6);
}

#[test]
fn parameter_noise_on_a_parameter_the_law_does_not_have_is_an_error() {
    use hcm_host::experiment::noisy_run;
    use rand::SeedableRng;
    // In the scenario file: rejected where the contact is resolved, naming the key.
    let path = scenario_path("bouncing_ball.toml");
    let overrides = ["contact.0.noise={ stifness = 0.1 }".to_owned()];
    let error = Scenario::load(&path, &overrides)
        .unwrap()
        .resolve(&path)
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("noise") && error.contains("stifness") && error.contains("damping"),
        "{error}"
    );
    // In a model built by a program: the run fails instead of ignoring the name.
    let mut model = model("bouncing_ball.toml", &["contact.0.noise={}"]);
    model.contacts[0].noise = vec![("stifness".into(), 0.1)];
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
    let error = noisy_run(&model, &mut rng).unwrap_err().to_string();
    assert_eq!(
        error,
        "contact 0: parameter noise: `variable_stiffness` has no parameter `stifness`; its \
         parameters are: surface_loading, effective_modulus, radius, damping, effective_mass"
    );
}
