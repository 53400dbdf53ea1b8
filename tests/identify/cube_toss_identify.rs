//! Identification from motion alone (`hcm_host::identify::identify_motion`) on tosses
//! made by the simulator with hidden parameters — friction μ = 0.4, a softer landing,
//! the table 1 mm low — that the shipped scenario does not have: the fit, started from
//! the scenario, must cut the training fitness, predict the held-out tosses better than
//! the scenario does and far better than the frozen pose, and give the same bits on 1
//! and 2 threads. Small (6 tosses, a short GA) for CI; the real tosses' figures are the
//! README's.

use hcm_host::dataset::{Dataset, Run};
use hcm_host::identify::{split_tosses, MotionFit};
use hcm_host::replay::{evaluate_tosses, summarize};
use hcm_host::scenario::{Model, Scenario};

/// The shipped cube-toss scenario with `sets` applied.
fn cube_toss(sets: &[String]) -> Model {
    Scenario::load(&hcm_tests::scenario("cube_toss.toml"), sets)
        .unwrap()
        .model()
        .unwrap()
}

/// Six tosses of the hidden physics, each thrown differently; ids `toss_000`…`toss_005`.
fn hidden_tosses() -> Dataset {
    let throws = [
        ([0.8, 0.1, 0.3], [4.0, -3.0, 1.0]),
        ([-0.6, 0.5, 0.0], [-2.0, 5.0, 0.5]),
        ([0.3, -0.9, 0.4], [6.0, 1.0, -2.0]),
        ([-1.0, -0.2, 0.2], [1.0, -6.0, 3.0]),
        ([0.5, 0.7, -0.3], [-5.0, -2.0, 2.0]),
        ([-0.2, -0.8, 0.1], [3.0, 3.0, -4.0]),
    ];
    let runs: Vec<Run> = (throws.iter().enumerate())
        .map(|(k, (velocity, spin))| {
            let sets = [
                "contact.0.friction.mu_static=0.4".to_owned(),
                "contact.0.friction.mu_dynamic=0.4".to_owned(),
                "contact.0.parameters.max_damping=120.0".to_owned(),
                "body.table.shape.plane.offset=-1e-3".to_owned(),
                "body.cube.position=[0.0, 0.0, 0.25]".to_owned(),
                format!("body.cube.velocity={velocity:?}"),
                format!("body.cube.angular_velocity={spin:?}"),
                "simulation.end_time=0.55".to_owned(),
            ];
            let mut run = hcm_host::simulate::simulate(&cube_toss(&sets)).unwrap().run;
            run.id = format!("toss_{k:03}");
            run
        })
        .collect();
    Dataset { runs }
}

/// The fit of the shipped scenario to the training tosses, on `threads` threads.
fn fit(model: &Model, training: &Dataset, threads: usize) -> MotionFit {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| hcm_tests::motion_fit(model, training, 3))
}

#[test]
fn the_fit_from_motion_beats_the_scenario_on_held_out_tosses() {
    let model = cube_toss(&[]);
    let data = hidden_tosses();
    let (training, held_out) = split_tosses(&data);
    assert_eq!((training.runs.len(), held_out.runs.len()), (3, 3));
    let found = fit(&model, &training, 2);
    println!("{:?}", found.parameters);
    println!(
        "training fitness {:.3} → GA {:.3} → polish {:.3} ({} replays)",
        found.start_fitness, found.genetic_fitness, found.fitness, found.evaluations
    );
    assert!(found.fitness < 0.5 * found.start_fitness, "{found:?}");
    let before = summarize(&evaluate_tosses(&model, &held_out, || {}).unwrap());
    let after = summarize(&evaluate_tosses(&found.model, &held_out, || {}).unwrap());
    let total = |p: f64, r: f64| p + r;
    let (scenario, fitted, frozen) = (
        total(before.position.mean, before.rotation.mean),
        total(after.position.mean, after.rotation.mean),
        total(after.baseline_position.mean, after.baseline_rotation.mean),
    );
    println!(
        "held out: scenario {scenario:.3}, fitted {fitted:.3}, frozen pose {frozen:.3} (% + °)"
    );
    assert!(fitted < scenario, "{fitted} vs {scenario}");
    assert!(fitted < 0.1 * frozen, "{fitted} vs {frozen}");

    let again = fit(&model, &training, 1);
    let bits = |f: &MotionFit| -> Vec<u64> { f.parameters.iter().map(|p| p.1.to_bits()).collect() };
    assert_eq!(bits(&found), bits(&again));
    assert_eq!(found.fitness.to_bits(), again.fitness.to_bits());
}

#[test]
fn identify_motion_writes_a_scenario_that_predict_replays_as_it_scored() {
    let hcm = hcm_tests::cli::Hcm::new();
    hidden_tosses().write(&hcm.path("tosses.csv")).unwrap();
    let scenario = hcm_tests::scenario("cube_toss.toml");
    let out = hcm
        .run("identify-motion")
        .opt("--scenario", &scenario)
        .opt("--data", "tosses.csv")
        .opt("--population", "4")
        .opt("--generations", "2")
        .opt("--polish", "4")
        .opt("--out", "fitted.toml")
        .opt("--held-out", "held_out.csv")
        .opt("--scenario-out", "fitted_scenario.toml")
        .ok();
    println!("{out}");
    // The fitted held-out row, e.g. `| held out (3) | fitted | 1.23 ± …`.
    // The cells after the label's (the label spans `cells` cells).
    let row = |text: &str, label: &str, cells: usize| -> String {
        let line = text.lines().find(|l| l.contains(label)).unwrap_or_default();
        line.split('|')
            .skip(1 + cells)
            .collect::<Vec<_>>()
            .join("|")
    };
    let fitted = row(&out, "| held out (3) | fitted |", 2);
    assert!(!fitted.is_empty(), "{out}");
    let physics = std::fs::read_to_string(hcm.path("fitted.toml")).unwrap();
    assert!(physics.contains("mu_dynamic") && physics.contains("max_damping"));
    let predicted = hcm
        .run("predict")
        .opt("--scenario", "fitted_scenario.toml")
        .opt("--data", "held_out.csv")
        .opt("--out", "predicted.csv")
        .ok();
    assert_eq!(row(&predicted, "| simulation |", 1), fitted, "{predicted}");
    // The physics file alone (its `sets` put the table offset and the inertia) gives
    // the same.
    assert!(physics.contains("sets = ["), "{physics}");
    let again = hcm
        .run("predict")
        .opt("--scenario", &scenario)
        .opt("--physics", "fitted.toml")
        .opt("--data", "held_out.csv")
        .opt("--out", "again.csv")
        .ok();
    assert_eq!(row(&again, "| simulation |", 1), fitted, "{again}");
}
