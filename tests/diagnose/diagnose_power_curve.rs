//! Power curves of `hcm diagnose`'s naming rule (`hcm_host::diagnose`): for each
//! catalogued effect hidden in the bouncing ball's data at strengths from 0.25 % to 5 %
//! of the peak force, 10 seeds each, the fraction of seeds in which it is named
//! exactly — that effect and nothing else — and the false-alarm rate with nothing
//! hidden. Run with `--nocapture` for the table the README shows.
//!
//! A strength "x % of the peak" is the effect's own scale at that size, from the
//! no-effect runs' peak force F, deepest indentation δ_max, impact speed v0 and contact
//! duration t_c: viscous c = x·F/v0, hysteresis (p = 0.5) c = x·F/(δ_max^0.5·v0),
//! adhesion and offset x·F, plasticity ρ = x, stiffness exponent Δ = x, delay τ =
//! x·t_c/π (a half-sine's steepest slope is π·F/t_c). Hysteresis at p = 0.5: near the
//! ball's own law's damping exponent (variable stiffness, δ^1.25·δ̇) re-tuning the base
//! absorbs most of it (README, "Known limit"), which would measure the base, not the rule.

use hcm_host::diagnose::BaseFreedom;
use hcm_host::diagnose::{contact_samples, noise_floor};
use hcm_tests::hidden::{decided, hidden, EFFECTS};
use rayon::prelude::*;

/// Runs per data set, as in tests/diagnose/diagnose.rs.
const RUNS: usize = 12;
/// Seeds per cell.
const SEEDS: u64 = 10;
/// Strengths, as fractions of the peak force.
const LEVELS: [f64; 5] = [0.0025, 0.005, 0.01, 0.02, 0.05];

/// The no-effect runs' scales: peak force F (N), δ_max (m), impact speed v0 (m/s),
/// contact duration t_c (s).
fn scales() -> (f64, f64, f64, f64) {
    let (base, data) = hidden("", RUNS, 100);
    let s = contact_samples(&base, &data, 0).unwrap();
    let contact: Vec<usize> = (0..s.len()).filter(|&i| s.in_contact[i]).collect();
    let peak = contact.iter().map(|&i| s.measured[i]).fold(0.0, f64::max);
    let depth = contact.iter().map(|&i| s.depth[i]).fold(0.0, f64::max);
    let speed = contact
        .iter()
        .map(|&i| s.approach_speed[i])
        .fold(0.0, f64::max);
    let first_run: Vec<usize> = contact.iter().copied().filter(|&i| s.run[i] == 0).collect();
    let duration = s.time[*first_run.last().unwrap()] - s.time[first_run[0]];
    (peak, depth, speed, duration)
}

/// The scenario override hiding `effect` at fraction `x` of the peak.
fn hide(effect: &str, x: f64, (f, depth, speed, duration): (f64, f64, f64, f64)) -> String {
    match effect {
        "viscous_damping" => format!(
            "{{ viscous_damping = {{ coefficient = {} }} }}",
            x * f / speed
        ),
        "hysteresis_damping" => format!(
            "{{ hysteresis_damping = {{ coefficient = {}, exponent = 0.5 }} }}",
            x * f / (depth.sqrt() * speed)
        ),
        "adhesion" => format!("{{ adhesion = {{ pull_off_force = {} }} }}", x * f),
        "plasticity" => format!("{{ plasticity = {{ permanent_ratio = {x} }} }}"),
        "stiffness_exponent" => format!(
            "{{ stiffness_exponent = {{ exponent_change = {x}, reference_depth = {} }} }}",
            depth / 2.0
        ),
        "force_offset" => format!("experiment.force_offset=[0.0, 0.0, {}]", x * f),
        "sensor_delay" => format!(
            "experiment.sensor_delay={}",
            x * duration / std::f64::consts::PI
        ),
        // A filter lags by T to first order: the delay's strength.
        "sensor_filter" => format!(
            "experiment.sensor_filter={}",
            x * duration / std::f64::consts::PI
        ),
        _ => String::new(),
    }
}

/// The names the decision gives on `RUNS` runs with `hidden_effect`, seed `seed`.
fn named(hidden_effect: &str, seed: u64) -> Vec<&'static str> {
    let (base, data) = hidden(hidden_effect, RUNS, seed);
    let samples = contact_samples(&base, &data, 0).unwrap();
    let sigma = noise_floor(&samples).sigma;
    let naming = decided(&base, &samples, BaseFreedom::Given, sigma);
    naming.chosen.iter().map(|(c, _)| c.name()).collect()
}

#[test]
#[ignore = "study, over 12 s on 2 cores: cargo test -- --include-ignored"]
fn every_effect_at_5_percent_is_named_in_8_of_10_seeds_never_wrongly_and_nothing_without_one() {
    let scale = scales();
    println!(
        "scales: peak {:.1} N, δ_max {:.3e} m, v0 {:.4} m/s, t_c {:.3e} s",
        scale.0, scale.1, scale.2, scale.3
    );
    let cells: Vec<(usize, usize, u64)> = (0..EFFECTS.len())
        .flat_map(|e| (0..LEVELS.len()).flat_map(move |l| (1..=SEEDS).map(move |s| (e, l, s))))
        .collect();
    let answers: Vec<Vec<&str>> = cells
        .par_iter()
        .map(|&(e, l, seed)| named(&hide(EFFECTS[e], LEVELS[l], scale), seed))
        .collect();
    let exact: Vec<bool> = (0..cells.len())
        .map(|k| answers[k] == [EFFECTS[cells[k].0]])
        .collect();
    // A wrong name: something named that is not the hidden effect.
    let wrong: Vec<usize> = (0..cells.len())
        .filter(|&k| answers[k].iter().any(|n| *n != EFFECTS[cells[k].0]))
        .collect();
    let alarms: Vec<Vec<&str>> = (1..=SEEDS).into_par_iter().map(|s| named("", s)).collect();
    let false_alarms = alarms.iter().filter(|n| !n.is_empty()).count();
    println!(
        "| effect | {} | weakest named in ≥ 8/10 |",
        LEVELS.map(|x| format!("{} %", 100.0 * x)).join(" | ")
    );
    println!("|---|{}---|", "---|".repeat(LEVELS.len()));
    let mut failures = Vec::new();
    for (e, effect) in EFFECTS.iter().enumerate() {
        let counts: Vec<usize> = (0..LEVELS.len())
            .map(|l| {
                (0..cells.len())
                    .filter(|&k| cells[k].0 == e && cells[k].1 == l && exact[k])
                    .count()
            })
            .collect();
        let weakest = (0..LEVELS.len())
            .find(|&l| counts[l..].iter().all(|&c| c >= 8))
            .map_or("—".to_owned(), |l| format!("{} %", 100.0 * LEVELS[l]));
        println!(
            "| `{effect}` | {} | {weakest} |",
            counts
                .iter()
                .map(|c| format!("{c}/10"))
                .collect::<Vec<_>>()
                .join(" | ")
        );
        if counts[LEVELS.len() - 1] < 8 {
            failures.push(format!(
                "{effect} at 5 %: named exactly in {}/10",
                counts[LEVELS.len() - 1]
            ));
        }
    }
    println!(
        "| nothing hidden: false alarms | {false_alarms}/10 {:?} |",
        alarms
    );
    println!(
        "wrong names in {} hidden-effect data sets: {}",
        cells.len(),
        wrong.len()
    );
    for &k in &wrong {
        let (e, l, seed) = cells[k];
        println!(
            "  {} at {} %, seed {seed}: named {:?}",
            EFFECTS[e],
            100.0 * LEVELS[l],
            answers[k]
        );
    }
    assert!(
        false_alarms <= 1,
        "false alarms {false_alarms}/10: {alarms:?}"
    );
    assert!(failures.is_empty(), "{failures:#?}");
    // Never the nearest wrong name: below its power an effect goes unnamed, it is not
    // mistaken for another.
    assert!(wrong.is_empty(), "{} wrong names", wrong.len());
}
