//! `hcm reproduce peg-in-hole` as a test: the shipped pipeline (400 runs)
//! makes an HCM that beats PM2 on the linear and angular impulse of both wall contacts
//! with blobs that round-trip through the core within 1e-6; and a smaller one (20
//! runs) is bit-identical on 1 and 2 threads.
//!
//! Smaller runs do not make the first claim: with 90 S1 runs instead of 360 the error
//! model's second wall contact drifts (measured on seed 3: HCM 3.2 % against PM2's
//! 5.0 % on its linear impulse, but 3.2 % against 0.5 % on its angular impulse), so the
//! claim is tested at the shipped size (about a minute).

use hcm_host::pipeline::ScenarioChoice;
use hcm_host::pipeline::Silent;
use hcm_host::pipeline::{reproduce_peg, PegReproduction, PegSettings};

fn settings(runs: usize) -> PegSettings {
    PegSettings {
        scenario: ScenarioChoice {
            file: Some(hcm_tests::scenario("peg_in_hole.toml")),
            ..PegSettings::shipped().scenario
        },
        runs,
        ..PegSettings::shipped()
    }
}

fn on_threads(threads: usize, settings: &PegSettings) -> PegReproduction {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| reproduce_peg(settings, &Silent).unwrap())
}

#[test]
#[ignore = "study, over 12 s on 2 cores: cargo test -- --include-ignored"]
fn the_shipped_pipeline_makes_an_hcm_that_beats_pm2_on_both_wall_contacts() {
    let r = reproduce_peg(&settings(400), &Silent).unwrap();
    println!("{}", r.markdown());
    // Table 15's two wall contacts × four indicators, every model making both.
    assert_eq!(r.evaluation.rows.len(), 8);
    for row in &r.evaluation.rows {
        assert!(row.values.iter().all(Option::is_some), "{row:?}");
        assert!(row.standard_error > 0.0 && row.mean > 0.0, "{row:?}");
        // Columns: PM2, HCM, HCM int8, PM1 nominal.
        if row.indicator.ends_with("impulse") {
            assert!(row.beats(1, 0), "HCM not better than PM2: {row:?}");
            assert!(row.beats(2, 0), "HCM int8 not better than PM2: {row:?}");
        }
        // The true physics of a mean run meets the bounds (the paper's HCM error or two
        // S2 standard errors) on every cell but contact 2's maximum force, whose S2 mean
        // (of each run's peak) lies above the peak of a mean run by more than two
        // standard errors (README).
        let floor = (row.contact, row.indicator) == (2, "max_force");
        assert_eq!(r.evaluation.models[3], "PM1 nominal");
        assert_eq!(row.verdict(3) == "neither", floor, "PM1 nominal: {row:?}");
    }
    // The same models as `hcm evaluate` judges them, every S2 run's events replayed
    // from the state before each: the HCM (f32 and int8) better than PM2 run by run.
    for m in [1, 2] {
        let (d, se) = r.events.paired[m];
        assert!(d + 2.0 * se < 0.0, "{}: {d} ± {se}", r.events.models[m]);
    }
    // Both blobs decode in the core and give the host's wrench: f32 within 1e-6, int8
    // within 1e-4 (its Q15 activations may land one unit, 3.1e-5, from the host's
    // where an f64 and an f32 pre-activation straddle a step; 1.7e-5 measured).
    assert!(
        r.blobs.f32.round_trip_error < 1e-6,
        "{}",
        r.blobs.f32.round_trip_error
    );
    assert!(
        r.blobs.int8.round_trip_error < 1e-4,
        "{}",
        r.blobs.int8.round_trip_error
    );
}

/// 20 runs (18 in S1, 2 in S2): every stage runs, in parallel where it does at the shipped
/// size (training's mini-batches of 64 rows are two chunks of 32 on two threads), and
/// whether the bits depend on the thread count does not depend on the size.
#[test]
#[ignore = "study, over 12 s on 2 cores: cargo test -- --include-ignored"]
fn the_pipeline_is_bit_identical_on_one_and_two_threads() {
    let small = PegSettings {
        seed: 3,
        ..settings(20)
    };
    let (one, two) = (on_threads(1, &small), on_threads(2, &small));
    assert_eq!(one.pm2.parameters, two.pm2.parameters);
    assert_eq!(one.pm2.fitness.to_bits(), two.pm2.fitness.to_bits());
    assert_eq!(one.sets, two.sets);
    assert_eq!(one.blobs.f32.bytes, two.blobs.f32.bytes);
    assert_eq!(one.blobs.int8.bytes, two.blobs.int8.bytes);
    assert_eq!(one.evaluation.rows, two.evaluation.rows);
}
