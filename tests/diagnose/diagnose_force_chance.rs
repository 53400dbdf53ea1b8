//! Chance in a force diagnosis: the ball's PM1 runs, their contact parameters scattered
//! from run to run as `hcm generate` draws them (Eq 18), diagnosed against the law they
//! were generated with — the scatter named, with σ's interval holding the truth — and
//! the same runs without scatter, where no chance is named.

use hcm_host::diagnose::{diagnose, diagnosis_markdown, DiagnoseSettings, Diagnosis};
use hcm_tests::hidden::{measured, model};

/// The diagnosis with chance of `runs` ball runs generated with `overrides` (seed
/// `seed`), against the scenario's law without its scatter.
fn diagnosed(overrides: &[String], runs: usize, seed: u64) -> Diagnosis {
    let data = measured(&model("bouncing_ball.toml", overrides), runs, seed);
    let base = model("bouncing_ball.toml", &["contact.0.noise={}".to_owned()]);
    let settings = DiagnoseSettings {
        hcm_epochs: 2,
        chance: true,
        ..DiagnoseSettings::default()
    };
    let d = diagnose(&base, &data, &settings).unwrap();
    let causes: Vec<_> = d.causes.iter().map(|c| c.effect).collect();
    println!("{overrides:?}, {runs} runs, seed {seed}: causes {causes:?}");
    // The report's section 5: every round, what was named, the held-out forecast.
    let report = diagnosis_markdown(&d, &[]);
    match report.find("## 5. Chance") {
        Some(start) => println!("{}", &report[start..]),
        None => println!("no chance phase"),
    }
    d
}

/// Runs per data set: 60 held out (the diagnosis' 25 %). At 160 (40 held out) the
/// scenario's 2 % scatter of the surface loading was named on 3 of 4 seeds (the fourth
/// t = 2.3), at 240 on 4 of 4.
const RUNS: usize = 240;

/// The chances named, with their σ and interval.
fn named(d: &Diagnosis) -> Vec<(String, f64, (f64, f64))> {
    let chance = d.chance.as_ref().expect("a chance phase");
    (chance.named.iter())
        .map(|n| (n.effect.clone(), n.value, n.interval))
        .collect()
}

/// The shipped PM1 (2 % on the surface loading c and the damping λ, Eq 18, 15 N of
/// sensor noise): c's scatter is named, its interval holding 2 %; λ's 2 % moves the
/// force too little to tell on 60 runs, and whatever else is named must be a
/// parameter that scatters, never the sensor's noise. The extended model's bands hold
/// the held-out indicators nearer their nominal shares than the deterministic model's.
#[test]
#[ignore = "study, about 6 to 10 s of both cores: kept out of CI's 15 minutes (docs/tests.md); cargo test -- --include-ignored"]
fn the_balls_pm1_scatter_is_named_with_its_sigma() {
    let d = diagnosed(&[], RUNS, 1);
    assert!(
        d.causes.is_empty(),
        "no deterministic cause: {:?}",
        d.causes
    );
    let named = named(&d);
    assert_eq!(named[0].0, "surface_loading_scatter", "{named:?}");
    for (effect, _, (lo, hi)) in &named {
        assert!(
            ["surface_loading_scatter", "damping_scatter"].contains(&effect.as_str()),
            "{named:?}"
        );
        assert!(*lo <= 0.02 && 0.02 <= *hi, "{named:?}");
    }
    let chance = d.chance.as_ref().unwrap();
    assert!(chance.gain.t() > 3.0, "{:?}", chance.gain);
    // Measured: 0.411 and 0.839 against the deterministic model's 0.133 and 0.289 (the
    // damping's scatter, not named, is missing from the spread).
    for (level, (with, without)) in [0.5, 0.9]
        .iter()
        .zip(chance.coverage.iter().zip(&chance.coverage_reference))
    {
        assert!((with - level).abs() < (without - level).abs());
    }
}

/// A 10 % scatter of the damping alone is named as the damping's.
#[test]
fn a_scattered_damping_is_named_as_the_dampings() {
    let d = diagnosed(&["contact.0.noise={damping=0.1}".to_owned()], RUNS, 1);
    let named = named(&d);
    assert_eq!(named.len(), 1, "{named:?}");
    let (effect, _, (lo, hi)) = &named[0];
    assert_eq!(effect, "damping_scatter");
    assert!(*lo <= 0.1 && 0.1 <= *hi, "{named:?}");
}

/// The same runs without scatter: the sensor's noise alone, and no chance named.
#[test]
fn runs_without_scatter_name_no_chance() {
    let d = diagnosed(&["contact.0.noise={}".to_owned()], RUNS, 1);
    assert!(named(&d).is_empty(), "{:?}", named(&d));
}
