//! Run-to-run scatter is the data's own variability, not structure:
//! with `hcm generate`'s own parameter scatter (2 % on the ball's surface loading
//! and damping, Eq 18) and a quiet sensor, nothing hidden must name nothing, and a
//! hidden effect must still be named.

use hcm_host::diagnose::BaseFreedom;
use hcm_host::diagnose::{contact_samples, noise_floor};
use hcm_tests::hidden::{decided, measured, model};

/// The names a diagnosis gives on `runs` runs of the ball with the scenario's own 2 %
/// scatter, force noise `sigma` (N) and `effect` hidden, against the scenario's law.
/// Also whether the answer is "unexplained".
fn named_with_scatter(
    effect: &str,
    sigma: f64,
    runs: usize,
    seed: u64,
) -> (Vec<&'static str>, bool) {
    let mut overrides = vec![format!("experiment.force_noise={sigma}")];
    if !effect.is_empty() {
        overrides.push(format!("contact.0.effects=[{effect}]"));
    }
    let data = measured(&model("bouncing_ball.toml", &overrides), runs, seed);
    let base = model("bouncing_ball.toml", &[]);
    let samples = contact_samples(&base, &data, 0).unwrap();
    let sigma = noise_floor(&samples).sigma;
    let naming = decided(&base, &samples, BaseFreedom::Given, sigma);
    let names: Vec<&'static str> = naming.chosen.iter().map(|(c, _)| c.name()).collect();
    println!(
        "{effect:?}, σ {sigma:.2} N, {runs} runs, seed {seed}: {names:?}, unexplained {}",
        naming.unexplained
    );
    (names, naming.unexplained)
}

/// Measured before the runs' spread entered the structure test: nothing hidden named
/// nothing, but a 40 N adhesion (σ = 1.2 N) was refused (seed 1; the run stopped there) — the scatter
/// left every residual "structured", so no cause could leave noise behind.
#[test]
#[ignore = "study, over 12 s on 2 cores: cargo test -- --include-ignored"]
fn scatter_alone_names_nothing_and_an_effect_is_still_named() {
    for seed in [1, 2] {
        let (names, unexplained) = named_with_scatter("", 1.0, 20, seed);
        assert!(names.is_empty() && !unexplained, "seed {seed}: {names:?}");
        let adhesion = "{ adhesion = { pull_off_force = 40.0 } }";
        let (names, _) = named_with_scatter(adhesion, 1.0, 20, seed);
        assert_eq!(names, ["adhesion"], "seed {seed}");
    }
}

/// The report states the rule the decision applied: every cause's
/// held-out gain always; with scattered runs, the held-out rival test and its
/// thresholds too; without scatter, not.
#[test]
#[ignore = "study, over 12 s on 2 cores: cargo test -- --include-ignored"]
fn the_report_states_the_held_out_rule_where_the_runs_scatter() {
    use hcm_host::diagnose::{diagnose, diagnosis_markdown, DiagnoseSettings};
    let settings = DiagnoseSettings {
        hcm_epochs: 2,
        ..DiagnoseSettings::default()
    };
    let adhesion = "contact.0.effects=[{ adhesion = { pull_off_force = 40.0 } }]".to_owned();
    let base = model("bouncing_ball.toml", &[]);
    for (scatter, says) in [(true, true), (false, false)] {
        let mut overrides = vec![adhesion.clone()];
        if !scatter {
            overrides.push("contact.0.noise={}".into());
        }
        let data = measured(&model("bouncing_ball.toml", &overrides), 16, 3);
        let d = diagnose(&base, &data, &settings).unwrap();
        assert_eq!(d.before.scattered, scatter);
        let text = diagnosis_markdown(&d, &[]);
        assert!(text.contains("it must predict runs it was not fitted on"));
        assert_eq!(
            text.contains(
                "its lead over the best effect of another family must also hold on held-out runs"
            ),
            says,
            "scatter {scatter}"
        );
        assert!(text.contains("scores worse by at least 10"));
    }
}
