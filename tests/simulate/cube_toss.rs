//! Predicting tosses (`hcm_host::replay`): the window and the initial state on
//! a toss made by the simulator (known truth), the scores on hand-computable cases, a
//! simulated toss predicted back to near-zero error, bit-identical results on 1 and 2
//! threads, and the errors of bad inputs. Run with `--nocapture` to see the figures.

use hcm_host::dataset::{Dataset, Run, Sample};
use hcm_host::replay::{
    estimate_initial_state, evaluate_tosses, find_window, frozen_pose, predict_toss,
    rotation_angle, score_toss, StateSource, Summary, TossError, TossSetup, LEAD_FRAMES,
};
use hcm_host::scenario::{Model, Scenario};
use hcm_tests::cli::Hcm;
use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use std::path::{Path, PathBuf};

/// The shipped cube-toss scenario with `sets` applied, resolved.
fn cube_toss(sets: &[&str]) -> Model {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    Scenario::load(&hcm_tests::scenario("cube_toss.toml"), &sets)
        .expect("scenarios/cube_toss.toml reads")
        .model()
        .expect("and resolves")
}

/// A toss made by the simulator: the cube thrown from 0.3 m, turning, recorded at the
/// scenario's 148 Hz for `end` seconds; run id `id`.
fn simulated_toss(id: &str, end: f64) -> Run {
    let end = format!("simulation.end_time={end}");
    let model = cube_toss(&[
        "body.cube.position=[0.0, 0.0, 0.3]",
        "body.cube.velocity=[0.4, -0.2, 0.5]",
        "body.cube.angular_velocity=[3.0, -5.0, 2.0]",
        &end,
    ]);
    let mut run = hcm_host::simulate::simulate(&model).unwrap().run;
    run.id = id.to_owned();
    run
}

/// The data set's path in the repository.
fn tosses_csv() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("data/contactnets-cube/tosses.csv")
}

fn orientation(sample: &Sample) -> UnitQuaternion<f64> {
    let [w, x, y, z] = sample.orientation;
    UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z))
}

#[test]
fn the_window_and_initial_state_of_a_simulated_toss_are_its_truth() {
    let model = cube_toss(&[]);
    let setup = TossSetup::new(&model).unwrap();
    assert!((setup.radius - 0.0524 * 3f64.sqrt()).abs() < 1e-15);
    assert!((setup.width - 0.1048).abs() < 1e-15);
    let run = simulated_toss("sim", 0.6);
    let track = run.body("cube").unwrap();
    let window = find_window(&setup, &run.id, track).unwrap();
    let height = |i: usize| track.samples[i].position[2];
    // The near frame is within the circumscribed radius, or the cube bounced off a
    // corner between it and the next one (both frames beyond the radius).
    let bounced = height(window.near - 1) >= height(window.near)
        && height(window.near + 1) > height(window.near);
    assert!(height(window.near) < setup.radius || bounced, "{window:?}");
    assert!(
        (0..window.near).all(|i| height(i) >= setup.radius),
        "{window:?}"
    );
    assert_eq!(window.start + LEAD_FRAMES, window.near);
    assert_eq!(window.frames, track.samples.len());
    // A fitted table height moves the contact surface, not the window.
    let lowered = cube_toss(&["body.table.shape.plane.offset=-2e-3"]);
    let lowered = TossSetup::new(&lowered).unwrap();
    assert_eq!(find_window(&lowered, &run.id, track).unwrap(), window);

    let initial = estimate_initial_state(&setup, &run.id, track, &window).unwrap();
    assert_eq!(initial.source, StateSource::FreeFlightFit { frames: 8 });
    let truth = &track.samples[window.start];
    let position = (initial.position - Vector3::from(truth.position)).norm();
    let velocity = (initial.velocity - Vector3::from(truth.velocity)).norm();
    let angle = rotation_angle(&initial.orientation, &orientation(truth));
    let spin = (initial.angular_velocity - Vector3::from(truth.angular_velocity)).norm();
    println!(
        "window {window:?}; initial state off by {position:.2e} m, {velocity:.2e} m/s, \
         {angle:.2e} rad, {spin:.2e} rad/s"
    );
    assert!(
        position < 1e-6 && velocity < 1e-5,
        "{position} m, {velocity} m/s"
    );
    assert!(angle < 1e-6 && spin < 1e-5, "{angle} rad, {spin} rad/s");
}

#[test]
fn a_toss_with_too_few_frames_before_its_window_starts_from_the_recorded_state() {
    let setup = TossSetup::new(&cube_toss(&[])).unwrap();
    let mut run = simulated_toss("late", 0.6);
    let track = &mut run.bodies[0];
    let near = find_window(&setup, "late", track).unwrap().near;
    // Keep 2 frames before the window start: too few to fit.
    track.samples.drain(..near - LEAD_FRAMES - 2);
    let window = find_window(&setup, "late", track).unwrap();
    assert_eq!(window.start, 2);
    let initial = estimate_initial_state(&setup, "late", track, &window).unwrap();
    assert_eq!(initial.source, StateSource::Recorded);
    assert_eq!(initial.velocity, Vector3::from(track.samples[2].velocity));
    // Without recorded velocities there, the error names the run and what is missing.
    track.samples[2].velocity = [f64::NAN; 3];
    let error = estimate_initial_state(&setup, "late", track, &window).unwrap_err();
    let message = error.to_string();
    assert!(
        message.contains("run `late`") && message.contains("vx, vy, vz"),
        "{message}"
    );
}

/// A track of `frames` poses at rest at `position`, turned by `turn`.
fn still(position: [f64; 3], turn: UnitQuaternion<f64>, frames: usize) -> Vec<Sample> {
    let q = turn.quaternion();
    (0..frames)
        .map(|k| Sample {
            position,
            orientation: [q.w, q.i, q.j, q.k],
            ..Sample::at_rest(k as f64 / 148.0)
        })
        .collect()
}

#[test]
fn the_scores_of_a_pure_translation_and_a_known_rotation() {
    let setup = TossSetup::new(&cube_toss(&[])).unwrap();
    let identity = UnitQuaternion::identity();
    let measured = still([0.1, 0.2, 0.06], identity, 10);
    // Shifted by 3 cm and 4 cm: 5 cm off in every frame, 5/10.48 of the width.
    let shifted = still([0.13, 0.24, 0.06], identity, 10);
    let score = score_toss(&setup, "shift", &measured, &shifted).unwrap();
    assert!((score.position_error - 100.0 * 0.05 / 0.1048).abs() < 1e-9);
    assert_eq!(score.rotation_error, 0.0);
    assert_eq!(score.frames, 10);
    // Turned by 30° about an oblique axis, the quaternion's sign flipped: 30°.
    let axis = nalgebra::Unit::new_normalize(Vector3::new(1.0, -2.0, 0.5));
    let turn = UnitQuaternion::from_axis_angle(&axis, 30f64.to_radians());
    let mut turned = still([0.1, 0.2, 0.06], turn, 10);
    for s in &mut turned {
        s.orientation = s.orientation.map(|c| -c);
    }
    let score = score_toss(&setup, "turn", &measured, &turned).unwrap();
    assert_eq!(score.position_error, 0.0);
    assert!((score.rotation_error - 30.0).abs() < 1e-9, "{score:?}");
    // Half the frames 60° off and half exact: a mean of 30°.
    let half = UnitQuaternion::from_axis_angle(&axis, 60f64.to_radians());
    let mut mixed = still([0.1, 0.2, 0.06], identity, 10);
    mixed.extend(still([0.1, 0.2, 0.06], half, 10));
    let reference = still([0.1, 0.2, 0.06], identity, 20);
    let score = score_toss(&setup, "mixed", &reference, &mixed).unwrap();
    assert!((score.rotation_error - 30.0).abs() < 1e-9, "{score:?}");
    // A tiny angle keeps its digits.
    let tiny = UnitQuaternion::from_axis_angle(&axis, 1e-9);
    assert!((rotation_angle(&identity, &tiny) - 1e-9).abs() < 1e-20);

    let summary = Summary::of(&[4.0, 1.0, 3.0, 2.0]);
    assert_eq!((summary.count, summary.mean, summary.median), (4, 2.5, 2.5));
    assert!((summary.std - (5.0f64 / 3.0).sqrt()).abs() < 1e-15);
    assert_eq!(Summary::of(&[3.0, 1.0, 2.0]).median, 2.0);
}

#[test]
fn predicting_a_simulated_toss_recovers_it() {
    let model = cube_toss(&[]);
    let setup = TossSetup::new(&model).unwrap();
    let run = simulated_toss("sim", 0.6);
    let prediction = predict_toss(&model, &setup, &run).unwrap();
    let track = run.body("cube").unwrap();
    let measured = &track.samples[prediction.window.start..];
    assert_eq!(prediction.samples.len(), measured.len());
    for (p, m) in prediction.samples.iter().zip(measured) {
        assert_eq!(p.time, m.time);
    }
    let score = score_toss(&setup, "sim", measured, &prediction.samples).unwrap();
    let frozen = frozen_pose(track, &prediction.window);
    let baseline = score_toss(&setup, "sim", measured, &frozen).unwrap();
    println!("simulated toss predicted: {score:?}; frozen pose: {baseline:?}");
    assert!(score.position_error < 0.05, "{score:?}");
    assert!(score.rotation_error < 0.05, "{score:?}");
    assert!(
        baseline.position_error > 20.0 && baseline.rotation_error > 20.0,
        "{baseline:?}"
    );
}

#[test]
fn tosses_predict_bit_identically_on_one_and_two_threads() {
    let mut data = Dataset::read(&tosses_csv()).unwrap();
    data.runs.truncate(3);
    let model = cube_toss(&[]);
    let on = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| evaluate_tosses(&model, &data, || {}).unwrap())
    };
    let (one, two) = (on(1), on(2));
    assert_eq!(one.len(), 3);
    for (a, b) in one.iter().zip(&two) {
        assert_eq!(a.score, b.score);
        assert_eq!(a.baseline, b.baseline);
        let bits = |s: &[Sample]| -> Vec<u64> {
            s.iter()
                .flat_map(|s| s.position.iter().chain(&s.orientation).chain(&s.velocity))
                .map(|v| v.to_bits())
                .collect()
        };
        assert_eq!(bits(&a.prediction.samples), bits(&b.prediction.samples));
        println!(
            "{}: {:.2} % {:.2}° (frozen {:.2} % {:.2}°)",
            a.score.run,
            a.score.position_error,
            a.score.rotation_error,
            a.baseline.position_error,
            a.baseline.rotation_error
        );
        // The real tosses: the simulation beats the frozen pose.
        assert!(a.score.position_error < a.baseline.position_error, "{a:?}");
    }
}

#[test]
fn a_toss_that_never_nears_the_table_is_an_error_naming_it() {
    let model = cube_toss(&[]);
    let setup = TossSetup::new(&model).unwrap();
    // 0.1 s of flight from 0.3 m: the centre stays above 0.0908 m.
    let run = simulated_toss("high", 0.1);
    let error = predict_toss(&model, &setup, &run).unwrap_err();
    assert!(matches!(error, TossError::NoContact { .. }), "{error:?}");
    let message = error.to_string();
    assert!(
        message.contains("run `high`") && message.contains("0.0907"),
        "{message}"
    );
}

#[test]
fn predict_writes_the_window_frames_and_scores_tosses() {
    let hcm = Hcm::new();
    let out = hcm
        .run("predict")
        .opt("--scenario", hcm_tests::scenario("cube_toss.toml"))
        .opt("--data", tosses_csv())
        .opt("--first", "2")
        .opt("--out", "predicted.csv")
        .opt("--scores", "scores.csv")
        .ok();
    println!("{out}");
    assert!(out.contains("| frozen pose |"), "{out}");
    let predicted = Dataset::read(&hcm.path("predicted.csv")).unwrap();
    let measured = Dataset::read(&tosses_csv()).unwrap();
    assert_eq!(predicted.runs.len(), 2);
    for (p, m) in predicted.runs.iter().zip(&measured.runs) {
        assert_eq!(p.id, m.id);
        let (p, m) = (&p.bodies[0].samples, &m.bodies[0].samples);
        // The window's frames: the toss's last ones, at the same times.
        let times = |s: &[Sample]| s.iter().map(|s| s.time).collect::<Vec<_>>();
        assert_eq!(times(p), times(&m[m.len() - p.len()..]));
        assert!(p.len() < m.len());
    }
    let scores = std::fs::read_to_string(hcm.path("scores.csv")).unwrap();
    assert_eq!(scores.lines().count(), 3, "{scores}");
    assert!(scores.starts_with("run,frames,window_start"), "{scores}");
    // The initial state's columns: the replay's first frame is the window start, where
    // it stands at the state written (p0x, p0y, p0z; q0w…q0z).
    let header: Vec<&str> = scores.lines().next().unwrap().split(',').collect();
    let row: Vec<&str> = scores.lines().nth(1).unwrap().split(',').collect();
    let cell = |name: &str| -> f64 {
        let at = header.iter().position(|h| *h == name).unwrap();
        row[at].parse().unwrap()
    };
    let first = &predicted.runs[0].bodies[0].samples[0];
    assert_eq!(header.len(), 21, "{scores}");
    for (k, axis) in ["p0x", "p0y", "p0z"].iter().enumerate() {
        assert!((cell(axis) - first.position[k]).abs() < 1e-12, "{axis}");
    }
    for (k, part) in ["q0w", "q0x", "q0y", "q0z"].iter().enumerate() {
        assert!((cell(part) - first.orientation[k]).abs() < 1e-9, "{part}");
    }
}

#[test]
fn predict_refuses_data_without_poses() {
    let hcm = Hcm::new();
    // Toss 0 without its orientation columns.
    let text = std::fs::read_to_string(tosses_csv()).unwrap();
    let cut: String = text
        .lines()
        .take(120)
        .map(|line| {
            let cells: Vec<&str> = line.split(',').collect();
            let kept: Vec<&str> = [&cells[..6], &cells[10..]].concat();
            kept.join(",") + "\n"
        })
        .collect();
    std::fs::write(hcm.path("no_pose.csv"), cut).unwrap();
    let error = hcm
        .run("predict")
        .opt("--scenario", hcm_tests::scenario("cube_toss.toml"))
        .opt("--data", "no_pose.csv")
        .opt("--out", "predicted.csv")
        .fails();
    assert!(
        error.contains("no_pose.csv")
            && error.contains("orientation")
            && error.contains("qw, qx, qy, qz"),
        "{error}"
    );
    assert!(!hcm.path("predicted.csv").exists());
    // A scenario of another body: the data's body and the scenario's named.
    let error = hcm
        .run("predict")
        .opt("--scenario", hcm_tests::scenario("bouncing_ball.toml"))
        .opt("--data", tosses_csv())
        .opt("--out", "predicted.csv")
        .fails();
    assert!(
        error.contains("bouncing_ball") && error.contains("`cube`") && error.contains("`ball`"),
        "{error}"
    );
}
