//! The naming rule's power table across base laws, with run-to-run scatter on and off:
//! for each catalogued effect hidden at 0.5 %, 1 % and 3 % of the peak
//! force in the ball's data generated with each base law — the data's own law as the
//! base, its parameters scattered 2 % run to run as `hcm generate` does — the share of
//! data sets in which it is named exactly, the false alarms with nothing hidden, the
//! wrong names (an effect named that was not hidden: must be none) and how often the
//! named parameter's 95 % interval holds the truth. Run with `--nocapture` for the
//! table the README shows.
//!
//! Strengths are scaled as in tests/diagnose/diagnose_power_curve.rs, from each law's own
//! no-effect runs.

use hcm_host::diagnose::BaseFreedom;
use hcm_host::diagnose::{contact_samples, noise_floor};
use hcm_host::identify::{identify, Method};
use hcm_host::progress::Silent;
use hcm_host::scenario::Model;
use hcm_tests::hidden::{decided, measured, model, EFFECTS};
use rayon::prelude::*;

/// Runs per data set.
const RUNS: usize = 16;
/// Seeds per cell: 6 at full size (`HCM_FULL_STUDIES=1`). In `cargo test`, 2 for the
/// README's table (scattered runs, the law's own parameters, 1 MHz): the same
/// assertions over a third of the data sets, every wrong name and false alarm failing
/// and each effect's intervals judged once it is named 20 times. 1 for the other three
/// set-ups, whose 120 cells each still fail on any wrong name or false alarm, their
/// intervals judged at full size only (fewer than 20 cases per effect): the four tables
/// at 2 seeds were the longest tests of the diagnose area (88, 65, 57 and 23 s, two
/// tests at a time under cargo nextest on the 2-core machine).
fn seeds(setup: Setup) -> u64 {
    let readme = setup.scatter && !setup.fitted && setup.period == 1e-6;
    hcm_tests::study_size(if readme { 2 } else { 1 }, 6)
}
/// Strengths, as fractions of the peak force.
const LEVELS: [f64; 3] = [0.005, 0.01, 0.03];

/// Base laws: (law, parameters, the parameters scattered 2 % run to run). Stiffness
/// 3.6·10⁹ N/m^1.5 is Hertz's 4/3·E*·√R of the paper's steel ball on concrete.
const LAWS: [(&str, &str, &str); 5] = [
    (
        "hertz",
        "{ stiffness = 3.6e9, exponent = 1.5 }",
        "{ stiffness = 0.02 }",
    ),
    (
        "variable_stiffness",
        "{ surface_loading = 2.0, damping = 987.9 }",
        "{ surface_loading = 0.02, damping = 0.02 }",
    ),
    (
        "lankarani_nikravesh",
        "{ stiffness = 3.6e9, exponent = 1.5, restitution = 0.9 }",
        "{ stiffness = 0.02, restitution = 0.02 }",
    ),
    (
        "hunt_crossley",
        "{ stiffness = 3.6e9, exponent = 1.5, damping = 0.11 }",
        "{ stiffness = 0.02, damping = 0.02 }",
    ),
    (
        "impact",
        "{ stiffness = 3.6e9, exponent = 1.5, max_damping = 300.0, full_damping_depth = 1e-5 }",
        "{ stiffness = 0.02, max_damping = 0.02 }",
    ),
];

/// How the data are recorded and what the base is.
#[derive(Clone, Copy, Debug)]
struct Setup {
    /// Force (and motion) sample period in contact (s).
    period: f64,
    /// The base as `hcm identify` fits it (least squares on the same runs, every
    /// parameter free, judged with [`BaseFreedom::Fitted`]) instead of the law's
    /// nominal parameters given by hand.
    fitted: bool,
    /// Whether the data's law parameters scatter 2 % run to run (else every run is the
    /// same contact, only the sensor's noise differs).
    scatter: bool,
}

/// The ball with base law `l`, its parameters scattered (`scatter`) or not, recorded
/// at `period` (s) in contact, and `extra` overrides.
fn ball(l: usize, scatter: bool, period: f64, extra: &str) -> Model {
    let (law, parameters, noise) = LAWS[l];
    let mut overrides = vec![
        format!("contact.0.law={law}"),
        format!("contact.0.parameters={parameters}"),
        format!("contact.0.noise={}", if scatter { noise } else { "{}" }),
        format!("record.contact_sample_period={period:e}"),
    ];
    if extra.starts_with("experiment.") {
        overrides.push(extra.to_owned());
    } else if !extra.is_empty() {
        overrides.push(format!("contact.0.effects=[{extra}]"));
    }
    model("bouncing_ball.toml", &overrides)
}

/// Law `l`'s no-effect scales: peak force F (N), δ_max (m), impact speed v0 (m/s),
/// contact duration t_c (s).
fn scales(l: usize) -> (f64, f64, f64, f64) {
    let truth = ball(l, false, 1e-6, "");
    let data = measured(&truth, 2, 100);
    let s = contact_samples(&truth, &data, 0).unwrap();
    let contact: Vec<usize> = (0..s.len()).filter(|&i| s.in_contact[i]).collect();
    let max = |v: &[f64]| contact.iter().map(|&i| v[i]).fold(0.0, f64::max);
    let first: Vec<usize> = contact.iter().copied().filter(|&i| s.run[i] == 0).collect();
    let duration = s.time[*first.last().unwrap()] - s.time[first[0]];
    (
        max(&s.measured),
        max(&s.depth),
        max(&s.approach_speed),
        duration,
    )
}

/// The override hiding `effect` at fraction `x` of the peak, and its true first
/// parameter.
fn hide(effect: &str, x: f64, (f, depth, speed, duration): (f64, f64, f64, f64)) -> (String, f64) {
    match effect {
        "viscous_damping" => {
            let c = x * f / speed;
            (
                format!("{{ viscous_damping = {{ coefficient = {c} }} }}"),
                c,
            )
        }
        "hysteresis_damping" => {
            let c = x * f / (depth.sqrt() * speed);
            (
                format!("{{ hysteresis_damping = {{ coefficient = {c}, exponent = 0.5 }} }}"),
                c,
            )
        }
        "adhesion" => (
            format!("{{ adhesion = {{ pull_off_force = {} }} }}", x * f),
            x * f,
        ),
        "plasticity" => (format!("{{ plasticity = {{ permanent_ratio = {x} }} }}"), x),
        "stiffness_exponent" => (
            format!(
                "{{ stiffness_exponent = {{ exponent_change = {x}, reference_depth = {} }} }}",
                depth / 2.0
            ),
            x,
        ),
        "force_offset" => (
            format!("experiment.force_offset=[0.0, 0.0, {}]", x * f),
            x * f,
        ),
        "sensor_delay" => {
            let tau = x * duration / std::f64::consts::PI;
            (format!("experiment.sensor_delay={tau}"), tau)
        }
        // A filter lags by T to first order: the delay's strength.
        "sensor_filter" => {
            let tau = x * duration / std::f64::consts::PI;
            (format!("experiment.sensor_filter={tau}"), tau)
        }
        _ => (String::new(), f64::NAN),
    }
}

/// What the decision names on `RUNS` scattered runs of law `l` with `hidden` (seed
/// `seed`), recorded and judged as `setup` says: (name, first parameter's value and
/// 95 % interval) per named cause.
fn named(setup: Setup, l: usize, hidden: &str, seed: u64) -> Vec<(&'static str, f64, (f64, f64))> {
    let truth = ball(l, setup.scatter, setup.period, hidden);
    let mut base = ball(l, false, setup.period, "");
    let data = measured(&truth, RUNS, seed);
    let freedom = if setup.fitted {
        let fit = identify(
            &base.scenario,
            &base,
            &data,
            0,
            LAWS[l].0,
            Method::Lsq,
            &Silent,
        )
        .unwrap();
        base.contacts[0].model.normal.base = fit.law;
        BaseFreedom::Fitted
    } else {
        BaseFreedom::Given
    };
    let samples = contact_samples(&base, &data, 0).unwrap();
    let sigma = noise_floor(&samples).sigma;
    let naming = decided(&base, &samples, freedom, sigma);
    naming
        .fit
        .causes
        .iter()
        .take(naming.chosen.len())
        .map(|c| (c.effect, c.parameters[0].value, c.parameters[0].ci))
        .collect()
}

/// One data set of the table: law, effect (None: nothing hidden), level, seed.
type Cell = (usize, Option<usize>, usize, u64);

#[test]
#[ignore = "study, over 12 s on 2 cores: cargo test -- --include-ignored"]
fn no_effect_is_ever_misnamed_across_base_laws_with_scatter() {
    table(Setup {
        period: 1e-6,
        fitted: false,
        scatter: true,
    });
}

/// The same against bases fitted by `hcm identify` on the same runs: a change of the
/// exponent is then the base's own freedom, not a candidate, where the law has a free
/// exponent (its row names nothing there).
#[test]
#[ignore = "study, over 12 s on 2 cores: cargo test -- --include-ignored"]
fn no_effect_is_ever_misnamed_against_fitted_bases() {
    table(Setup {
        period: 1e-6,
        fitted: true,
        scatter: true,
    });
}

/// The same without run-to-run scatter of the contact: the samples are independent
/// evidence there, and the rivals are judged by the information criterion's margin.
#[test]
#[ignore = "study, over 12 s on 2 cores: cargo test -- --include-ignored"]
fn no_effect_is_ever_misnamed_without_scatter() {
    table(Setup {
        period: 1e-6,
        fitted: false,
        scatter: false,
    });
}

/// The same with the force sampled at 100 kHz (≈ 11 samples per contact).
#[test]
fn no_effect_is_ever_misnamed_at_100_khz() {
    table(Setup {
        period: 1e-5,
        fitted: false,
        scatter: true,
    });
}

/// The table of `setup`, printed; panics on any wrong name or false alarm.
fn table(setup: Setup) {
    println!("{setup:?}");
    let seeds = seeds(setup);
    let scales: Vec<_> = (0..LAWS.len()).map(scales).collect();
    let mut cells: Vec<Cell> = Vec::new();
    for l in 0..LAWS.len() {
        for seed in 1..=seeds {
            cells.push((l, None, 0, seed));
            for e in 0..EFFECTS.len() {
                for v in 0..LEVELS.len() {
                    cells.push((l, Some(e), v, seed));
                }
            }
        }
    }
    let answers: Vec<_> = cells
        .par_iter()
        .map(|&(l, e, v, seed)| match e {
            None => (f64::NAN, named(setup, l, "", seed)),
            Some(e) => {
                let (hidden, truth) = hide(EFFECTS[e], LEVELS[v], scales[l]);
                (truth, named(setup, l, &hidden, seed))
            }
        })
        .collect();
    let (mut wrong, mut misses) = (Vec::new(), Vec::new());
    // Per effect, across laws: named cases whose interval holds the truth, named cases.
    let mut coverage = vec![(0, 0); EFFECTS.len()];
    println!(
        "| base law | effect | {} | 95 % interval holds the truth |",
        LEVELS.map(|x| format!("{} %", 100.0 * x)).join(" | ")
    );
    println!("|---|---|{}---|", "---|".repeat(LEVELS.len()));
    for (l, (law, _, _)) in LAWS.iter().enumerate() {
        for (e, effect) in EFFECTS.iter().enumerate() {
            let mut row = Vec::new();
            let (mut held, mut named_count) = (0, 0);
            for (v, level) in LEVELS.iter().enumerate() {
                let mut exact = 0;
                for (k, &(cl, ce, cv, seed)) in cells.iter().enumerate() {
                    if (cl, ce, cv) != (l, Some(e), v) {
                        continue;
                    }
                    let (truth, names) = &answers[k];
                    if names.iter().any(|n| n.0 != *effect) {
                        wrong.push(format!(
                            "{law}, {effect} at {} %, seed {seed}: {names:?}",
                            100.0 * level
                        ));
                    }
                    if names.len() == 1 && names[0].0 == *effect {
                        exact += 1;
                        named_count += 1;
                        let (lo, hi) = names[0].2;
                        if lo <= *truth && *truth <= hi {
                            held += 1;
                        } else {
                            misses.push(format!(
                                "{law}, {effect} at {} %, seed {seed}: {:.4e} [{lo:.4e}, \
                                 {hi:.4e}], truth {truth:.4e}",
                                100.0 * level,
                                names[0].1
                            ));
                        }
                    }
                }
                row.push(format!("{exact}/{seeds}"));
            }
            println!(
                "| {law} | `{effect}` | {} | {held}/{named_count} |",
                row.join(" | ")
            );
            coverage[e].0 += held;
            coverage[e].1 += named_count;
        }
        let alarms: Vec<_> = cells
            .iter()
            .zip(&answers)
            .filter(|((cl, ce, _, _), (_, names))| *cl == l && ce.is_none() && !names.is_empty())
            .map(|(c, (_, names))| format!("seed {}: {names:?}", c.3))
            .collect();
        println!(
            "| {law} | nothing hidden: false alarms | {}/{seeds} {alarms:?} |",
            alarms.len()
        );
        wrong.extend(alarms.iter().map(|a| format!("{law}, nothing hidden, {a}")));
    }
    println!("intervals missing the truth: {}", misses.len());
    for m in &misses {
        println!("  {m}");
    }
    println!("wrong names or false alarms: {}", wrong.len());
    for w in &wrong {
        println!("  {w}");
    }
    assert!(wrong.is_empty(), "{wrong:#?}");
    // Calibrated intervals: per effect named at least COVERAGE_CASES times, at least
    // COVERAGE of its 95 % intervals hold the truth.
    for (effect, &(held, named)) in EFFECTS.iter().zip(&coverage) {
        println!("{effect}: {held}/{named} intervals hold the truth");
        assert!(
            named < COVERAGE_CASES || held as f64 >= COVERAGE * named as f64,
            "{effect}: only {held} of {named} intervals hold the truth: {misses:#?}"
        );
    }
}

/// Named cases of one effect (across laws) from which its coverage is judged.
const COVERAGE_CASES: usize = 20;
/// Least share of an effect's 95 % intervals that hold the truth (–): 0.9 leaves room
/// for the sampling of ~20–90 cases about 0.95, and fails the 79–85 % an interval
/// blind to the runs' scatter gave (stiffness exponent, adhesion, plasticity).
const COVERAGE: f64 = 0.9;
