//! The peg-in-hole's generated runs as later stages use them: each run
//! replays from its recorded pre-contact state, and the S2 statistics of the wrench
//! indicators (mean and standard error per contact event) equal a direct computation,
//! with a run whose event count differs reported, not averaged.
//!
//! Run with `--nocapture` to see the replayed events and the table.

use hcm_host::dataset::Run;
use hcm_host::experiment::{generate, pre_contact_states, replay_model, Generation};
use hcm_host::indicators::{pair_events_from_run, wrench_statistics, WrenchIndicators};
use hcm_host::simulate::simulate;
use hcm_tests::cli::Hcm;

use hcm_tests::{mean_std, peg_in_hole as peg};

/// Two runs' event indicators agree within `rel` (relative), event by event.
fn assert_events_agree(label: &str, a: &[WrenchIndicators], b: &[WrenchIndicators], rel: f64) {
    assert_eq!(a.len(), b.len(), "{label}: event counts");
    for (k, (a, b)) in a.iter().zip(b).enumerate() {
        for ((name, _), (x, y)) in WrenchIndicators::NAMES
            .iter()
            .zip(a.values().iter().zip(b.values()))
        {
            let d = (x - y).abs() / x.abs();
            assert!(
                d < rel,
                "{label} event {} {name}: {x} vs {y} ({d:.1e})",
                k + 1
            );
        }
    }
}

#[test]
fn each_run_replays_from_its_recorded_pre_contact_state() {
    let scenario = peg();
    let generation = Generation::new(&scenario, 2, 8).unwrap();
    let runs: Vec<Run> = (0..2).map(|i| generation.run(i).unwrap()).collect();
    let model = scenario.model().unwrap();
    let pre = pre_contact_states(&model, &runs).unwrap();
    let margin = scenario.record.contact_margin;
    let mut regular = 0;
    for (i, pre) in pre.iter().enumerate() {
        assert_eq!(pre.run, runs[i].id);
        assert_eq!(pre.states.len(), 1, "one moving body");
        let tick = scenario.record.contact_sample_period;
        assert!(pre.time <= pre.touch_down && pre.touch_down - pre.time < tick * 1.001);
        assert!(pre.touch_down > margin);
        // The replay: the run's own parameters, from the recorded state, against the run
        // simulated from t = 0.
        let noisy = generation.noisy_model(i).unwrap();
        let whole = simulate(&noisy).unwrap();
        let replay = simulate(&replay_model(&noisy, pre)).unwrap();
        let indicators = |s: &hcm_host::simulate::Simulation| -> Vec<WrenchIndicators> {
            s.events.iter().filter_map(|e| e.indicators()).collect()
        };
        let (a, b) = (indicators(&whole), indicators(&replay));
        if a.len() == 3 {
            assert_events_agree(&format!("run {i}"), &a, &b, 1e-5);
            regular += 1;
        } else {
            // A second contact that grazes: its separation crosses zero for a few µs,
            // at the solver's tolerance (run 1 of this seed: 4 events from t = 0, 3 in
            // the replay). The first contact still replays exactly.
            assert_events_agree(&format!("run {i}"), &a[..1], &b[..1], 1e-5);
        }
        let shift = whole.events[0].touch_down - replay.events[0].touch_down;
        assert!(
            (shift - pre.time).abs() < 1e-9,
            "touch-down moved by {shift} − {}",
            pre.time
        );
        assert!((replay.end_time + pre.time - whole.end_time).abs() < 1e-12);
        println!(
            "run {i}: pre-contact t = {:.6} s, touch-down {:.9} s, {} events from t = 0, {} replayed",
            pre.time,
            pre.touch_down,
            a.len(),
            b.len()
        );
    }
    assert!(regular >= 1, "no run with the regular three contacts");
}

#[test]
fn s2_statistics_equal_a_direct_computation_and_a_shorter_run_is_reported() {
    let scenario = peg();
    let model = scenario.model().unwrap();
    let mut data = generate(&scenario, 8, 2, &hcm_host::progress::Silent).unwrap();
    // Cut run 5 after its second contact: 2 events where the others have 3.
    let events_5 = pair_events_from_run(&model, &data.runs[5]).unwrap();
    let cut = events_5[1].event.lift_off.unwrap() + 1e-4;
    data.runs[5].bodies[0].samples.retain(|s| s.time < cut);
    let ids: Vec<String> = data.runs.iter().map(|r| r.id.clone()).collect();
    let mut events = Vec::new();
    let mut per_run = Vec::new();
    for run in &data.runs {
        let found = pair_events_from_run(&model, run).unwrap();
        per_run.push(found.iter().map(|e| e.wrench()).collect::<Vec<_>>());
        events.extend(found);
    }
    let stats = wrench_statistics(&ids, &events);
    assert_eq!(stats.len(), 1);
    let s = &stats[0];
    assert_eq!((s.runs, s.expected_events, s.matched_runs), (8, 3, 7));
    assert_eq!(s.mismatched_runs.len(), 1);
    assert_eq!(
        (
            s.mismatched_runs[0].run.as_str(),
            s.mismatched_runs[0].events
        ),
        ("5", 2)
    );
    // Direct: the 7 complete runs, event by event.
    let complete: Vec<&Vec<WrenchIndicators>> = per_run.iter().filter(|e| e.len() == 3).collect();
    assert_eq!(complete.len(), 7);
    for (k, event) in s.events.iter().enumerate() {
        assert_eq!((event.event, event.runs), (k + 1, 7));
        for (i, estimate) in event.estimates().iter().enumerate() {
            let values: Vec<f64> = complete.iter().map(|run| run[k].values()[i]).collect();
            let (mean, std) = mean_std(&values);
            let se = std / 7f64.sqrt();
            assert!((estimate.mean - mean).abs() <= 1e-12 * mean.abs());
            assert!(
                (estimate.standard_error - se).abs() <= 1e-9 * se,
                "{} vs {se}",
                estimate.standard_error
            );
            assert!(
                se > 0.0 && se < 0.2 * mean,
                "event {} indicator {i}: {se} of {mean}",
                k + 1
            );
        }
    }

    // `hcm indicators --json` on the written file gives the same summary and names the run.
    let hcm = Hcm::new();
    let file = hcm.path("s2.csv");
    data.write(&file).unwrap();
    let json = hcm
        .run("indicators")
        .opt("--scenario", hcm_tests::scenario("peg_in_hole.toml"))
        .opt("--data", &file)
        .arg("--json")
        .ok();
    let parsed: serde_json::Value = serde_json::from_str(&json).unwrap();
    let summary = &parsed["summary"][0];
    assert_eq!(summary["expected_events"], 3);
    assert_eq!(summary["mismatched_runs"][0]["run"], "5");
    for (k, event) in s.events.iter().enumerate() {
        // serde_json's reader may round the last bit of what its writer printed.
        let printed = &summary["events"][k]["linear_impulse"];
        let close = |key: &str, value: f64| {
            let read = printed[key].as_f64().unwrap();
            assert!(
                (read - value).abs() <= 4.0 * f64::EPSILON * value,
                "{key}: {read} vs {value}"
            );
        };
        close("mean", event.linear_impulse.mean);
        close("standard_error", event.linear_impulse.standard_error);
    }
    let table = hcm
        .run("indicators")
        .opt("--scenario", hcm_tests::scenario("peg_in_hole.toml"))
        .opt("--data", &file)
        .ok();
    println!("{table}");
    assert!(table.contains("7 of 8 runs have 3 events"), "{table}");
    assert!(table.contains("`5` (2 events)"), "{table}");
}
