//! PM1 on a 3D scenario: `hcm generate` on the peg-in-hole. Each run
//! scatters IMPACT's and the friction's parameters (Eq 18) and adds noise to the
//! recorded force and torque (Eq 19); the files are bit-identical at 1 and 2 threads and
//! read back exactly; bad data are named by file, line and column, or by run. The
//! replay from each run's pre-contact state and the S2 statistics: tests/identify/peg_s2.rs.
//!
//! Run with `--nocapture` to see the measured spreads.

use hcm_host::dataset::Dataset;
use hcm_host::experiment::{
    generate, pre_contact_states, ExperimentWriter, Generation, PreContactError,
};
use hcm_host::scenario::{Model, Scenario};
use hcm_host::simulate::simulate;
use std::path::{Path, PathBuf};

use hcm_tests::{mean_std, peg_in_hole as peg};

/// Asserts that `values` look drawn from N(0, σ²): mean within 4 standard errors of 0,
/// sample standard deviation within 4 of its standard errors (σ/√(2n)) of σ.
fn assert_normal(label: &str, values: &[f64], sigma: f64) {
    let n = values.len() as f64;
    let (mean, std) = mean_std(values);
    println!(
        "{label}: n = {n}, mean {mean:.3e}, std {std:.4e} (σ = {sigma:e}, ratio {:.4})",
        std / sigma
    );
    assert!(mean.abs() < 4.0 * sigma / n.sqrt(), "{label}: mean {mean}");
    assert!(
        (std / sigma - 1.0).abs() < 4.0 / (2.0 * n).sqrt(),
        "{label}: std {std} for σ {sigma}"
    );
}

#[test]
fn parameter_noise_spreads_impact_and_friction_by_b() {
    let scenario = peg();
    let nominal = scenario.model().unwrap();
    let runs = 4000;
    let generation = Generation::new(&scenario, runs, 11).unwrap();
    let models: Vec<Model> = (0..runs)
        .map(|i| generation.noisy_model(i).unwrap())
        .collect();
    let law = |m: &Model, name: &str| m.contacts[0].law().get(name).unwrap();
    let friction = |m: &Model| m.contacts[0].model.friction.unwrap();
    let base = friction(&nominal);
    // (name, noisy value of run m, nominal, b from the scenario)
    type Reader<'a> = Box<dyn Fn(&Model) -> f64 + 'a>;
    let noisy: [(&str, Reader, f64); 4] = [
        ("stiffness", Box::new(|m| law(m, "stiffness")), 1e8),
        ("max_damping", Box::new(|m| law(m, "max_damping")), 100.0),
        (
            "mu_static",
            Box::new(|m| friction(m).static_coefficient),
            base.static_coefficient,
        ),
        (
            "mu_dynamic",
            Box::new(|m| friction(m).dynamic_coefficient),
            base.dynamic_coefficient,
        ),
    ];
    let noise = &nominal.contacts[0].noise;
    let mut ratios = Vec::new();
    for (name, read, a) in &noisy {
        let b = noise.iter().find(|(n, _)| n == name).unwrap().1;
        assert_eq!(b, 0.02, "{name}: the scenario's b");
        // η = a + a·b·ζ: (η/a − 1)/b ~ N(0, 1).
        let zeta: Vec<f64> = models.iter().map(|m| (read(m) / a - 1.0) / b).collect();
        assert_normal(&format!("ζ of {name}"), &zeta, 1.0);
        ratios.push(zeta);
    }
    // One draw per parameter: pairwise uncorrelated.
    let n = runs as f64;
    for i in 0..ratios.len() {
        for j in i + 1..ratios.len() {
            let r: f64 = ratios[i]
                .iter()
                .zip(&ratios[j])
                .map(|(x, y)| x * y)
                .sum::<f64>()
                / n;
            assert!(
                r.abs() < 4.0 / n.sqrt(),
                "{} and {}: {r}",
                noisy[i].0,
                noisy[j].0
            );
        }
    }
    // What is not named in `noise` stays as written.
    for m in &models {
        assert_eq!(law(m, "exponent"), 1.5);
        assert_eq!(law(m, "full_damping_depth"), 1e-4);
        assert_eq!(friction(m).stiction_speed, base.stiction_speed);
        assert_eq!(friction(m).dynamic_speed, base.dynamic_speed);
    }
}

#[test]
fn recorded_force_and_torque_carry_eq19_noise_and_nothing_else_does() {
    let scenario = peg();
    let (sigma_f, sigma_t) = (
        scenario.experiment.force_noise,
        scenario.experiment.torque_noise,
    );
    assert!(sigma_f > 0.0 && sigma_t > 0.0);
    let generation = Generation::new(&scenario, 3, 5).unwrap();
    let (mut force, mut torque) = (Vec::new(), Vec::new());
    for i in 0..3 {
        let noisy = generation.run(i).unwrap();
        // The same run without output noise: its own noisy parameters, simulated.
        let clean = simulate(&generation.noisy_model(i).unwrap()).unwrap().run;
        let (a, b) = (&noisy.bodies[0].samples, &clean.bodies[0].samples);
        assert_eq!(a.len(), b.len());
        for (a, b) in a.iter().zip(b) {
            assert_eq!(
                (a.time, a.position, a.orientation),
                (b.time, b.position, b.orientation)
            );
            assert_eq!(
                (a.velocity, a.angular_velocity),
                (b.velocity, b.angular_velocity)
            );
            force.extend((0..3).map(|k| a.force[k] - b.force[k]));
            torque.extend((0..3).map(|k| a.torque[k] - b.torque[k]));
        }
    }
    assert_normal("force noise (N)", &force, sigma_f);
    assert_normal("torque noise (N·m)", &torque, sigma_t);
}

/// Writes `runs` runs of `scenario` with `seed` to OUT, S1, S2 in `dir`, on a pool of
/// `threads` threads; returns the three paths.
fn write_on(
    scenario: &Scenario,
    runs: usize,
    seed: u64,
    dir: &Path,
    threads: usize,
) -> [PathBuf; 3] {
    let paths =
        ["peg.csv", "peg.s1.csv", "peg.s2.csv"].map(|n| dir.join(format!("{threads}-{seed}-{n}")));
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let targets = paths.each_ref().map(|p| p.as_path());
        ExperimentWriter::new(scenario, runs, seed, targets)
            .unwrap()
            .write(&hcm_host::progress::Silent)
            .unwrap()
    });
    paths
}

#[test]
fn the_files_are_bit_identical_on_one_and_two_threads_and_read_back_exactly() {
    let scenario = peg();
    let dir = tempfile::tempdir().unwrap();
    let one = write_on(&scenario, 6, 3, dir.path(), 1);
    let two = write_on(&scenario, 6, 3, dir.path(), 2);
    for (a, b) in one.iter().zip(&two) {
        let (a, b) = (std::fs::read(a).unwrap(), std::fs::read(b).unwrap());
        assert!(!a.is_empty());
        assert!(a == b, "1 and 2 threads differ");
    }
    let other_seed = write_on(&scenario, 6, 4, dir.path(), 2);
    assert_ne!(
        std::fs::read(&one[0]).unwrap(),
        std::fs::read(&other_seed[0]).unwrap()
    );
    // Read back: exactly the runs made in memory (every number bit for bit), and
    // written again, the same bytes.
    let read = Dataset::read(&one[0]).unwrap();
    let made = generate(&scenario, 6, 3, &hcm_host::progress::Silent).unwrap();
    assert_eq!(read, made);
    let mut again = Vec::new();
    read.to_writer(&mut again).unwrap();
    assert!(again == std::fs::read(&one[0]).unwrap());
    // Every sample holds the peg's 13 state components and its wrench.
    let sample = &read.runs[0].bodies[0].samples[100];
    let q = sample.orientation;
    assert!((q.iter().map(|x| x * x).sum::<f64>() - 1.0).abs() < 1e-12);
    assert!(read
        .runs
        .iter()
        .all(|r| r.bodies.len() == 1 && r.bodies[0].body == "peg"));
}

#[test]
fn bad_data_is_named_by_file_line_column_or_run() {
    let scenario = peg();
    let model = scenario.model().unwrap();
    let data = generate(&scenario, 1, 1, &hcm_host::progress::Silent).unwrap();
    let mut text = Vec::new();
    data.to_writer(&mut text).unwrap();
    let text = String::from_utf8(text).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let read = |name: &str, body: String| {
        Dataset::from_reader(name, body.as_bytes())
            .unwrap_err()
            .to_string()
    };
    // NaN in the torque on line 5.
    let mut cells: Vec<String> = lines[4].split(',').map(String::from).collect();
    *cells.last_mut().unwrap() = "NaN".into();
    let mut bad = lines.clone();
    let joined = cells.join(",");
    bad[4] = &joined;
    let error = read("peg.csv", bad.join("\n"));
    assert!(
        error.starts_with("peg.csv, line 5, column `tz`") && error.contains("NaN"),
        "{error}"
    );
    // A missing quaternion column.
    let without_qw: Vec<String> = lines
        .iter()
        .map(|l| {
            let mut c: Vec<&str> = l.split(',').collect();
            c.remove(6);
            c.join(",")
        })
        .collect();
    let error = read("peg.csv", without_qw.join("\n"));
    assert!(error.contains("`qw`"), "{error}");

    // A quaternion that is not unit just before the contact: the replay refuses it.
    let mut run = data.runs[0].clone();
    let pre = pre_contact_states(&model, std::slice::from_ref(&run)).unwrap();
    let sample = (run.bodies[0].samples.iter_mut())
        .find(|s| s.time == pre[0].time)
        .unwrap();
    sample.orientation = sample.orientation.map(|x| 1.01 * x);
    let error = pre_contact_states(&model, &[run]).unwrap_err();
    assert!(matches!(error, PreContactError::NotUnit { .. }));
    let message = error.to_string();
    assert!(
        message.contains("run `0`") && message.contains("`peg`") && message.contains("`qw`"),
        "{message}"
    );
    // A run cut before it touches has no pre-contact state.
    let mut early = data.runs[0].clone();
    early.bodies[0].samples.retain(|s| s.time < 0.02);
    let error = pre_contact_states(&model, &[early])
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("run `0` has no completed contact"),
        "{error}"
    );
}

#[test]
fn friction_noise_needs_friction_and_a_known_name() {
    let error = |file: &str, set: &str| {
        let path = hcm_tests::scenario(file);
        Scenario::load(&path, &[set.to_owned()])
            .unwrap()
            .model()
            .unwrap_err()
            .to_string()
    };
    let message = error("bouncing_ball.toml", "contact.0.noise={ mu_static = 0.02 }");
    assert!(
        message.contains("`mu_static` is a friction parameter")
            && message.contains("no `friction`"),
        "{message}"
    );
    let message = error("peg_in_hole.toml", "contact.0.noise={ mu_statik = 0.02 }");
    assert!(
        message.contains("mu_statik")
            && message.contains("stiffness")
            && message.contains("mu_static, mu_dynamic, v_static, v_dynamic"),
        "{message}"
    );
    let message = error("peg_in_hole.toml", "contact.0.noise={ v_dynamic = -0.1 }");
    assert!(
        message.contains("relative standard deviation ≥ 0"),
        "{message}"
    );
}
