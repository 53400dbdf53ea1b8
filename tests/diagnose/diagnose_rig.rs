//! `hcm diagnose` on data from an independent rig (tests/common/rig.rs: its own laws,
//! fixed-step RK4, a force sensor at its own rate, motion at the force rows or at a
//! camera's frames) — the cases it must be shown to answer. The rig is first checked
//! against hcm's own simulator; then each case says what diagnose must answer.

use hcm_host::dataset::Dataset;
use hcm_host::diagnose::{diagnose, DiagnoseSettings, Diagnosis};
use hcm_host::scenario::Model;
use hcm_host::simulate::simulate;
use hcm_tests::hidden::model;
use hcm_tests::rig::{Base, Motion, Physical, Recording, Resonance, Rig};
use rayon::prelude::*;

/// Runs per data set (a quarter is held out for the gain).
const RUNS: usize = 16;
/// Concrete ground (E (Pa), ν (–)), as in the paper's ball.
const CONCRETE: (f64, f64) = (2.5193e10, 0.25);
/// Aluminium ground (E (Pa), ν (–)).
const ALUMINIUM: (f64, f64) = (7.0e10, 0.33);

/// The paper's steel ball (r = 12.7 mm) on concrete, 2 % scatter of the impact speed.
fn ball() -> Rig {
    Rig {
        speed_scatter: 0.02,
        ..Rig::steel_ball(0.0127, CONCRETE)
    }
}

/// A 5 mm steel ball on aluminium at 0.8 m/s (peak ≈ 240 N), the sensor's noise
/// σ_f = 2 N (0.8 % of the peak, as the paper's ball's 15 N is of its 2.1 kN).
fn small() -> Rig {
    let mut rig = Rig {
        impact_speed: 0.8,
        speed_scatter: 0.02,
        ..Rig::steel_ball(0.005, ALUMINIUM)
    };
    rig.sensor.noise = 2.0;
    rig
}

/// The scenario hcm diagnoses with: the rig's ball and its base law with the rig's
/// own parameters (what a user who identified them first would hold).
fn base_model(rig: &Rig) -> Model {
    base_model_with(rig, &[])
}

/// [`base_model`] with `extra` scenario overrides.
fn base_model_with(rig: &Rig, extra: &[String]) -> Model {
    let (k, n) = (rig.stiffness(), rig.exponent);
    let (law, parameters) = match rig.base {
        Base::Hertz => (
            "hertz",
            format!("{{ stiffness = {k:e}, exponent = {n:e} }}"),
        ),
        Base::LankaraniNikravesh(e) => (
            "lankarani_nikravesh",
            format!("{{ stiffness = {k:e}, exponent = {n:e}, restitution = {e:e} }}"),
        ),
        Base::HuntCrossley(chi) => (
            "hunt_crossley",
            format!("{{ stiffness = {k:e}, exponent = {n:e}, damping = {chi:e} }}"),
        ),
    };
    let mut overrides = vec![
        "contact.0.noise={}".to_owned(),
        format!("contact.0.law={law}"),
        format!("contact.0.parameters={parameters}"),
        format!("body.ball.mass={:e}", rig.mass),
        format!(
            "body.ball.shape={{ sphere = {{ radius = {:e} }} }}",
            rig.radius
        ),
        format!("gravity=[0.0, 0.0, {:e}]", -rig.gravity),
    ];
    overrides.extend_from_slice(extra);
    model("bouncing_ball.toml", &overrides)
}

/// The recording read back as `hcm diagnose` reads a file.
fn read(recording: &Recording) -> Dataset {
    Dataset::from_reader("rig.csv", recording.csv.as_bytes()).expect("the rig's CSV reads")
}

/// What `hcm diagnose` answers on `data` against `model` (its HCM comparison trained
/// for 2 epochs only: the tests judge the naming).
fn answer(model: &Model, data: &Dataset) -> Diagnosis {
    let settings = DiagnoseSettings {
        hcm_epochs: 2,
        ..DiagnoseSettings::default()
    };
    diagnose(model, data, &settings).expect("diagnose runs")
}

/// What `hcm diagnose` answers on `runs` runs of `rig` (seed `seed`) against the rig's
/// own base model.
fn answer_on(rig: &Rig, runs: usize, seed: u64) -> Diagnosis {
    answer(&base_model(rig), &read(&rig.record(runs, seed)))
}

/// What `hcm diagnose` answers on [`RUNS`] runs of `rig` (seed `seed`), printed.
fn diagnosed(label: &str, rig: &Rig, seed: u64) -> Diagnosis {
    let d = answer_on(rig, RUNS, seed);
    println!(
        "{label}: σ = {:.2} N, structured {}, unexplained {:.3}",
        d.noise.sigma, d.base_structured, d.unexplained_share
    );
    println!("  {:?}", d.data_quality);
    for t in &d.naming {
        println!(
            "  naming {} rss {:.4e} → {:.4e}, ΔRSS/σ² {:.1} vs {:.1}, accepted {}",
            t.effect, t.rss.0, t.rss.1, t.bic.0, t.bic.1, t.accepted
        );
    }
    for n in &d.not_accepted {
        println!("  not accepted {}: {}", n.effect, n.reason);
    }
    for c in &d.causes {
        let p: Vec<_> = c
            .parameters
            .iter()
            .map(|p| {
                format!(
                    "{} {:.4e} [{:.4e}, {:.4e}]",
                    p.name, p.value, p.ci.0, p.ci.1
                )
            })
            .collect();
        println!(
            "  named {} share {:.3}: {}",
            c.effect,
            c.share,
            p.join(", ")
        );
    }
    for s in &d.selection {
        println!(
            "  step {} {}{}: share {:.4}, ΔRSS/σ² {:.1} vs {:.1}, cv {:.4e} → {:.4e}, accepted {}",
            s.action,
            s.effect,
            s.shape.map_or(String::new(), |p| format!(" p={p}")),
            s.share,
            s.bic.0,
            s.bic.1,
            s.cv_rss.0,
            s.cv_rss.1,
            s.accepted
        );
    }
    d
}

/// [`diagnosed`] on each case in parallel: `case` gives its label, rig and seed.
fn diagnosed_each<C: Sync>(
    cases: &[C],
    case: impl Fn(&C) -> (String, Rig, u64) + Sync,
) -> Vec<Diagnosis> {
    cases
        .par_iter()
        .map(|c| {
            let (label, rig, seed) = case(c);
            diagnosed(&label, &rig, seed)
        })
        .collect()
}

/// The names diagnose gave, in its order.
fn names(d: &Diagnosis) -> Vec<&'static str> {
    d.causes.iter().map(|c| c.effect).collect()
}

/// Asserts that `effect` alone is named, its parameter `index` within `tolerance`
/// (relative) of `truth`, with a finite 95 % interval.
fn named_alone(d: &Diagnosis, effect: &str, index: usize, truth: f64, tolerance: f64) {
    assert_eq!(names(d), [effect], "{:#?}", d.causes);
    let p = &d.causes[0].parameters[index];
    assert!(
        (p.value - truth).abs() <= tolerance * truth.abs(),
        "{effect} {}: {} vs true {truth}",
        p.name,
        p.value
    );
    assert!(
        p.ci.0.is_finite() && p.ci.1.is_finite() && p.ci.0 < p.ci.1,
        "{effect} {} interval {:?}",
        p.name,
        p.ci
    );
}

// ---------------------------------------------------------------------------------
// The rig against hcm's simulator and the closed form.

/// The same impact simulated by hcm: the ball released 100 µm above the plane with the
/// speed that brings it down at `speed` (m/s).
fn hcm_impact(rig: &Rig, speed: f64) -> hcm_host::simulate::ContactEvent {
    let gap = 1e-4;
    let start = -(speed * speed - 2.0 * rig.gravity * gap).sqrt();
    let m = base_model_with(
        rig,
        &[
            format!("body.ball.position=[0.0, 0.0, {:e}]", rig.radius + gap),
            format!("body.ball.velocity=[0.0, 0.0, {start:e}]"),
        ],
    );
    let simulation = simulate(&m).unwrap();
    simulation.events[0].clone()
}

#[test]
fn the_rig_agrees_with_hcms_simulator_on_a_plain_impact() {
    let cases = [
        ("steel 12.7 mm on concrete, LN e = 0.9", ball()),
        (
            "steel 5 mm on aluminium, Hunt–Crossley χ = 0.2 s/m",
            Rig {
                base: Base::HuntCrossley(0.2),
                impact_speed: 0.8,
                ..Rig::steel_ball(0.005, ALUMINIUM)
            },
        ),
    ];
    for (label, rig) in cases {
        let speed = rig.impact_speed;
        let ours = rig.impact(speed);
        let peak = ours.force.iter().copied().fold(0.0, f64::max);
        let theirs = hcm_impact(&rig, speed);
        let figures = [
            ("peak force", peak, theirs.max_force),
            (
                "duration",
                ours.lift_off,
                theirs.lift_off.unwrap() - theirs.touch_down,
            ),
            (
                "restitution",
                ours.separation_speed / speed,
                theirs.separation_speed / theirs.approach_speed,
            ),
        ];
        for (name, a, b) in figures {
            let error = (a / b - 1.0).abs();
            println!("{label}: {name} rig {a:.6e}, hcm {b:.6e}, {:.2e}", error);
            assert!(error < 1e-3, "{label}: {name} rig {a} vs hcm {b}");
        }
    }
}

#[test]
fn the_rigs_hertz_impact_matches_the_closed_form() {
    // Without gravity and damping: δ_max = (5·m·v²/(4·k))^(2/5), T = 2.9432·δ_max/v.
    let rig = Rig {
        base: Base::Hertz,
        gravity: 0.0,
        ..Rig::steel_ball(0.0127, CONCRETE)
    };
    let (v, k) = (rig.impact_speed, rig.stiffness());
    let contact = rig.impact(v);
    let max_depth = (5.0 * rig.mass * v * v / (4.0 * k)).powf(0.4);
    let deepest = contact.depth.iter().copied().fold(0.0, f64::max);
    let peak = contact.force.iter().copied().fold(0.0, f64::max);
    println!(
        "δ_max {deepest:.6e} (closed {max_depth:.6e}), T {:.6e} s, e {:.9}",
        contact.lift_off,
        contact.separation_speed / v
    );
    assert!((deepest / max_depth - 1.0).abs() < 1e-6);
    assert!((peak / (k * max_depth.powf(1.5)) - 1.0).abs() < 1e-5);
    assert!((contact.lift_off / (2.943_2 * max_depth / v) - 1.0).abs() < 1e-4);
    assert!((contact.separation_speed / v - 1.0).abs() < 1e-9);
}

#[test]
fn a_recording_is_deterministic_and_carries_its_truth() {
    let rig = Rig {
        sensor: hcm_tests::rig::Sensor {
            delay: 5e-6,
            offset: 20.0,
            ..ball().sensor
        },
        ..ball()
    };
    let a = rig.record(3, 7);
    assert_eq!(a.csv, rig.record(3, 7).csv);
    assert_ne!(a.csv, rig.record(3, 8).csv);
    let data = read(&a);
    assert_eq!(data.runs.len(), 3);
    for (run, truth) in data.runs.iter().zip(&a.runs) {
        let samples = &run.bodies[0].samples;
        // The ball is apart before touch-down and after lift-off, and δ_max is reached.
        let depth = |s: &hcm_host::dataset::Sample| rig.radius - s.position[2];
        for s in samples {
            let inside = s.time > truth.touch_down && s.time < truth.lift_off;
            assert_eq!(depth(s) > 0.0, inside, "run {} t = {}", truth.id, s.time);
        }
        let deepest = samples.iter().map(depth).fold(0.0, f64::max);
        assert!(deepest <= truth.max_depth && deepest > 0.999 * truth.max_depth);
        // In flight the sensor reads its offset; the largest reading comes τ late.
        let flight: Vec<f64> = samples
            .iter()
            .filter(|s| s.time < truth.touch_down)
            .map(|s| s.force[2])
            .collect();
        let mean = flight.iter().sum::<f64>() / flight.len() as f64;
        assert!((mean - 20.0).abs() < 5.0 * 15.0 / (flight.len() as f64).sqrt());
        println!(
            "run {}: touch-down {:.3e} s, v0 {:.4} m/s, δ_max {:.3e} m, peak {:.1} N",
            truth.id, truth.touch_down, truth.impact_speed, truth.max_depth, truth.peak_force
        );
    }
}

#[test]
fn camera_rows_leave_the_force_cells_empty_and_force_rows_the_motion_cells() {
    let rig = Rig {
        motion: Motion::Camera {
            frame_rate: 20e3,
            position_noise: 3e-6,
            velocity_noise: None,
        },
        ..ball()
    };
    let recording = rig.record(2, 1);
    let (mut camera, mut force) = (0, 0);
    for line in recording.csv.lines().skip(1) {
        let cells: Vec<&str> = line.split(',').collect();
        assert_eq!(cells.len(), 22, "{line}");
        let motion_empty = cells[3..16].iter().all(|c| c.is_empty());
        let force_empty = cells[16..22].iter().all(|c| c.is_empty());
        assert!(motion_empty != force_empty, "{line}");
        if force_empty {
            camera += 1;
            assert!(
                cells[5].parse::<f64>().is_ok() && cells[12].is_empty(),
                "{line}"
            );
        } else {
            force += 1;
        }
    }
    let span: f64 = recording.runs.iter().map(|r| r.lift_off + 100e-6).sum();
    println!("{camera} camera rows, {force} force rows over {span:.3e} s");
    assert!((camera as f64 - span * 20e3).abs() <= 2.0 * 2.0);
    assert!((force as f64 - span * 1e6).abs() <= 2.0 * 2.0);
}

// ---------------------------------------------------------------------------------
// Sensor delays of 2, 5 and 10 µs.

fn delayed(delay: f64) -> Rig {
    let mut rig = ball();
    rig.sensor.delay = delay;
    rig
}

#[test]
fn a_2_us_sensor_delay_is_named_with_its_value() {
    let d = diagnosed("delay 2 µs", &delayed(2e-6), 11);
    named_alone(&d, "sensor_delay", 0, 2e-6, 0.1);
}

#[test]
fn a_5_us_sensor_delay_is_named_with_its_value() {
    let d = diagnosed("delay 5 µs", &delayed(5e-6), 12);
    named_alone(&d, "sensor_delay", 0, 5e-6, 0.1);
}

#[test]
#[ignore = "study, over 12 s on 2 cores: cargo test -- --include-ignored"]
fn a_10_us_sensor_delay_is_named_with_its_value() {
    let d = diagnosed("delay 10 µs", &delayed(10e-6), 13);
    named_alone(&d, "sensor_delay", 0, 10e-6, 0.1);
}

// ---------------------------------------------------------------------------------
// A force sensor reading high: told from physics by the momentum balance.

fn scaled(gain: f64) -> Rig {
    let mut rig = ball();
    rig.sensor.gain = gain;
    rig
}

/// A sensor reading 3 % high used to be named `stiffness_exponent`. The
/// read impulse over the motion's momentum change gives the gain whatever the law:
/// named alone, within 0.3 %, its interval holding it; the physics judged on the
/// corrected readings names nothing.
#[test]
fn a_force_sensor_reading_3_percent_high_is_named_as_its_gain() {
    let d = diagnosed("gain 1.03", &scaled(1.03), 14);
    named_alone(&d, "sensor_gain", 0, 1.03, 0.003);
    let p = &d.causes[0].parameters[0];
    assert!(p.ci.0 <= 1.03 && 1.03 <= p.ci.1, "{:?}", p.ci);
}

/// The momentum balance's blind spot, said rather than hidden: an ideal sensor and a
/// scenario whose ball is 3 % heavier than the rig's read exactly as a sensor 3 % low
/// (the read impulse over m_scenario·Δv is m_true/m_scenario). The answer names the gain
/// with that ratio and says it may be the mass.
#[test]
fn a_wrong_mass_with_motion_at_the_force_rows_is_answered_as_gain_or_mass() {
    let rig = ball();
    let data = read(&rig.record(RUNS, 16));
    let heavier = base_model_with(&rig, &[format!("body.ball.mass={:e}", 1.03 * rig.mass)]);
    let d = answer(&heavier, &data);
    named_alone(&d, "sensor_gain", 0, 1.0 / 1.03, 0.003);
    let line = hcm_host::diagnose::answer_line(&d);
    assert!(
        line.contains("effective mass is g times the scenario's"),
        "{line}"
    );
}

#[test]
fn a_force_sensor_reading_half_a_percent_low_is_named_as_its_gain() {
    let d = diagnosed("gain 0.995", &scaled(0.995), 15);
    named_alone(&d, "sensor_gain", 0, 0.995, 0.002);
}

// ---------------------------------------------------------------------------------
// Out of the catalogue: a decaying ringing of the sensor mount.

#[test]
fn a_ringing_sensor_mount_is_unexplained_and_nothing_is_named() {
    let mut rig = ball();
    let peak = rig
        .impact(rig.impact_speed)
        .force
        .iter()
        .copied()
        .fold(0.0, f64::max);
    rig.sensor.resonance = Some(Resonance {
        amplitude: 0.05 * peak,
        decay: 60e-6,
        frequency: 40e3,
    });
    let d = diagnosed("resonance 5 % at 40 kHz", &rig, 21);
    assert!(d.causes.is_empty(), "{:#?}", d.causes);
    assert!(
        d.unexplained_share > 0.5,
        "unexplained {}",
        d.unexplained_share
    );
    // One verdict: not "ambiguous (a or b) + unexplained".
    let answer = hcm_host::diagnose::answer(&d);
    assert!(
        answer.starts_with("unexplained (") && !answer.contains('+'),
        "{answer}"
    );
    assert!(d.ambiguous.is_empty(), "{:?}", d.ambiguous);
}

/// Mounts that ring at other rates and decays: never a gain, never any name. A ringing
/// through the contact reads as a gain in the momentum balance (1.003 at 5 % of the
/// peak and 40 kHz, seed 501, before the gain obeyed the rule every cause does); one
/// that rings on after lift-off is seen in flight (`SensorGain::rings`). A true gain
/// behind a 10 µs filter, whose tail also reads after lift-off, is still named.
#[test]
#[ignore = "study, over 12 s on 2 cores: cargo test -- --include-ignored"]
fn a_mount_ringing_at_any_rate_is_never_a_gain() {
    let peak = ball()
        .impact(ball().impact_speed)
        .force
        .iter()
        .copied()
        .fold(0.0, f64::max);
    let cases = [
        (0.05, 40e3, 60e-6, 501),
        (0.02, 15e3, 200e-6, 503),
        (0.03, 20e3, 100e-6, 504),
    ];
    let answers = diagnosed_each(&cases, |&(share, frequency, decay, seed)| {
        let mut rig = ball();
        rig.sensor.resonance = Some(Resonance {
            amplitude: share * peak,
            decay,
            frequency,
        });
        let label = format!("mount ringing {share} of the peak at {frequency} Hz, {decay} s");
        (label, rig, seed)
    });
    for (case, d) in cases.iter().zip(&answers) {
        assert!(d.causes.is_empty(), "{case:?}: {:#?}", d.causes);
    }
    // At 15 kHz over 200 µs the flight after lift-off shows it.
    assert!(answers[1].sensor_gain.is_some_and(|g| g.rings.is_some()));
    let mut rig = ball();
    rig.sensor.gain = 1.03;
    rig.sensor.filter = 10e-6;
    let d = diagnosed("gain 3 % behind a 10 µs filter", &rig, 505);
    assert!(d.sensor_gain.is_some_and(|g| g.rings.is_none() && g.named));
    assert!(names(&d).contains(&"sensor_gain"), "{:#?}", d.causes);
}

// ---------------------------------------------------------------------------------
// A sensor's lag: a delay or a first-order low-pass filter (the measurement
// family).

/// Asserts that `d` answers a sensor lag: `effect` (`sensor_delay` or
/// `sensor_filter`) alone named — true —, or nothing named and "ambiguous between
/// `sensor_delay` and `sensor_filter`" — false. To first order a delay τ and a filter
/// T = τ are one correction, −τ·df/dt; the second order, τ²·f̈/2 against T²·f̈, tells
/// them apart only where it stands out of the noise.
fn lag_named_or_ambiguous(d: &Diagnosis, effect: &str) -> bool {
    if d.causes.is_empty() {
        let mut pair = d.ambiguous.clone();
        pair.sort_unstable();
        assert_eq!(
            pair,
            ["sensor_delay", "sensor_filter"],
            "{:#?}",
            d.not_accepted
        );
        // The answer still says how long the lag is, either way.
        let line = hcm_host::diagnose::answer_line(d);
        assert!(
            line.contains("sensor_delay (delay = ")
                && line.contains("sensor_filter (time_constant = "),
            "{line}"
        );
        false
    } else {
        assert_eq!(names(d), [effect], "{:#?}", d.causes);
        true
    }
}

/// A delay at half a percent of the peak force (≈ 0.15 µs on the paper's ball): a lag
/// the data cannot tell from a filter's; never a physical name.
#[test]
#[ignore = "study, about 6 to 10 s of both cores: kept out of CI's 15 minutes (docs/tests.md); cargo test -- --include-ignored"]
fn a_sensor_delay_at_half_a_percent_is_a_lag_a_delay_or_a_filter() {
    let (rig, name, _, truth) = hide(ball(), Effect::Delay, 0.005);
    let d = diagnosed(&format!("delay {truth:.3e} s"), &rig, 54);
    if lag_named_or_ambiguous(&d, name) {
        let p = &d.causes[0].parameters[0];
        assert!((p.value / truth - 1.0).abs() < 0.3, "{p:?} vs {truth}");
    }
}

/// A force sensor behind a first-order low-pass filter: named `sensor_filter` with its
/// time constant where the lag stands out (2.5 and 5 µs on a 110 µs contact), else
/// ambiguous with a delay (0.5 and 1 µs) — never a physical effect, never the delay
/// alone.
#[test]
fn a_low_pass_filtered_sensor_is_named_with_its_time_constant() {
    let cases = [(0.5e-6, 126), (1e-6, 127), (2.5e-6, 128), (5e-6, 129)];
    let answers = diagnosed_each(&cases, |&(tau, seed)| {
        let mut rig = ball();
        rig.sensor.filter = tau;
        (format!("filter {tau:e} s"), rig, seed)
    });
    for (&(tau, _), d) in cases.iter().zip(&answers) {
        let named = lag_named_or_ambiguous(d, "sensor_filter");
        assert!(named || tau < 2.5e-6, "{tau}: {:?}", d.ambiguous);
        if named {
            let p = &d.causes[0].parameters[0];
            assert!((p.value / tau - 1.0).abs() < 0.05, "{p:?} vs {tau}");
            assert!(p.ci.0 <= tau && tau <= p.ci.1, "{p:?} vs {tau}");
        }
    }
}

// ---------------------------------------------------------------------------------
// A force sensor whose gain grows with the force: measurement, never physics.

/// A sensor reading f + κ·f² (κ·F_peak from −6 % to +21 %): once the momentum balance
/// has taken its mean gain off, its shape is a stiffness-exponent change's, and the
/// force alone cannot tell them. The balance saw the sensor off, so no physical effect
/// is named — the answer is the gain with "ambiguous (stiffness_exponent or
/// sensor_nonlinearity)", or "unexplained" (the gain, beside a residual no cause
/// explains, not named either). Before `diagnose::nonlinearity`, κ·F_peak = 2.1 % was
/// answered `sensor_gain + stiffness_exponent`.
#[test]
fn a_sensor_whose_gain_grows_with_the_force_is_never_a_stiffness_change() {
    let cases = [(1e-5, 108), (3e-5, 109), (-3e-5, 123), (1e-4, 124)];
    let answers = diagnosed_each(&cases, |&(kappa, seed)| {
        let mut rig = ball();
        rig.sensor.nonlinearity = kappa;
        (format!("nonlinearity {kappa:e}/N"), rig, seed)
    });
    for (&(kappa, _), d) in cases.iter().zip(&answers) {
        let expected: &[&str] = if d.unexplained_share > 0.0 {
            &[]
        } else {
            &["sensor_gain"]
        };
        assert_eq!(names(d), expected, "{kappa}: {:#?}", d.causes);
        if !d.ambiguous.is_empty() {
            assert!(
                d.ambiguous.contains(&"sensor_nonlinearity"),
                "{kappa}: {:?}",
                d.ambiguous
            );
        }
    }
}

// ---------------------------------------------------------------------------------
// Close to the catalogue, not equal: partial answers.

/// The plain ball's peak force (N).
fn peak_force(rig: &Rig) -> f64 {
    plain(rig).0
}

/// `rig` with `effect` hidden.
fn with(mut rig: Rig, effect: Physical) -> Rig {
    rig.effects.push(effect);
    rig
}

/// A plastic set unloading along another curve than the catalogue's (which unloads
/// along the base law shifted) and damping nonlinear in the rate (the catalogue's is
/// linear in δ̇): their catalogue relative removes most of what is wrong, not all. The
/// answer names it, partially — the share it leaves is unexplained and said — and
/// nothing else: the effects that only fitted what it left are not named.
#[test]
#[ignore = "study, about 6 to 12 s of both cores: kept out of CI's 15 minutes (docs/tests.md); cargo test -- --include-ignored"]
fn a_shape_close_to_a_catalogued_one_gets_a_partial_answer() {
    let peak = peak_force(&ball());
    let cases = [
        (
            "plastic set unloading as δ^2",
            Physical::PlasticCurve(0.05, 2.0),
            "plasticity",
            103,
        ),
        (
            "plastic set unloading as δ^3",
            Physical::PlasticCurve(0.05, 3.0),
            "plasticity",
            104,
        ),
        (
            "plastic set 2 % unloading as δ^2",
            Physical::PlasticCurve(0.02, 2.0),
            "plasticity",
            117,
        ),
        (
            "damping as |δ̇|^0.5 at 3 % of the peak",
            Physical::RateDamping(0.03 * peak / 1.4_f64.sqrt(), 0.0, 0.5),
            "viscous_damping",
            105,
        ),
        (
            "damping as |δ̇|^0.7 at 3 % of the peak",
            Physical::RateDamping(0.03 * peak / 1.4_f64.powf(0.7), 0.0, 0.7),
            "viscous_damping",
            106,
        ),
    ];
    let answers = diagnosed_each(&cases, |&(label, effect, _, seed)| {
        (label.to_owned(), with(ball(), effect), seed)
    });
    for ((label, _, name, _), d) in cases.iter().zip(&answers) {
        assert_eq!(names(d), [*name], "{label}: {:#?}", d.causes);
        assert!(d.partial, "{label}");
        assert!(
            d.unexplained_share > 0.0 && d.unexplained_share < 0.1,
            "{label}: unexplained {}",
            d.unexplained_share
        );
        let line = hcm_host::diagnose::answer_line(d);
        assert!(
            line.contains("a partial answer") && line.contains("left unexplained"),
            "{line}"
        );
        assert!(d.ambiguous.is_empty(), "{label}: {:?}", d.ambiguous);
    }
}

/// A plastic set unloading linearly is far from the catalogue's Hertzian unloading: a
/// stiffness-exponent change removes 66–72 % of what is wrong and a delay much of the
/// rest, together — no single effect is its shape, so nothing is named.
#[test]
#[ignore = "study, over 12 s on 2 cores: cargo test -- --include-ignored"]
fn a_shape_the_catalogue_mimics_only_in_combination_is_unexplained() {
    for (rho, seed) in [(0.05, 102), (0.1, 118)] {
        let rig = with(ball(), Physical::PlasticCurve(rho, 1.0));
        let d = diagnosed(&format!("plastic set {rho}, linear unloading"), &rig, seed);
        assert!(d.causes.is_empty(), "{:#?}", d.causes);
        assert!(!d.partial);
        assert!(d.unexplained_share > 0.5, "{}", d.unexplained_share);
    }
}

// ---------------------------------------------------------------------------------
// No effect.

#[test]
fn no_hidden_effect_names_none() {
    let small = Rig {
        base: Base::HuntCrossley(0.2),
        ..small()
    };
    for (label, rig, seed) in [
        ("none, steel on concrete", ball(), 31),
        ("none, 5 mm on aluminium", small, 32),
    ] {
        let d = diagnosed(label, &rig, seed);
        assert!(d.causes.is_empty(), "{label}: {:#?}", d.causes);
        assert_eq!(d.unexplained_share, 0.0, "{label}");
    }
}

// ---------------------------------------------------------------------------------
// Each catalogued effect at 0.5 % and at 5 % of the peak force.

/// A catalogued effect to hide.
#[derive(Clone, Copy, Debug)]
enum Effect {
    Viscous,
    /// c·δ^0.5·δ̇.
    Hysteresis,
    /// c·δ·δ̇.
    HysteresisLinear,
    /// c·δ^1.5·δ̇: Hunt–Crossley's shape on a Hertzian law.
    HysteresisHertzian,
    StiffnessExponent,
    Adhesion,
    Plasticity,
    Offset,
    Delay,
}

/// The plain impact of `rig` at its mean speed: (peak force (N), δ_max (m), nodes).
fn plain(rig: &Rig) -> (f64, f64, hcm_tests::rig::Contact) {
    let clean = Rig {
        effects: Vec::new(),
        ..rig.clone()
    };
    let c = clean.impact(rig.impact_speed);
    let peak = c.force.iter().copied().fold(0.0, f64::max);
    let deepest = c.depth.iter().copied().fold(0.0, f64::max);
    (peak, deepest, c)
}

/// The largest |g| over the plain impact's nodes `i` (with δ > 0) of `g(δ, δ̇, f, i)`.
fn largest(c: &hcm_tests::rig::Contact, g: impl Fn(f64, f64, f64, usize) -> f64) -> f64 {
    (1..c.depth.len())
        .filter(|&i| c.depth[i] > 0.0)
        .map(|i| g(c.depth[i], c.rate[i], c.force[i], i).abs())
        .fold(0.0, f64::max)
}

/// `rig` with `effect` hidden at a strength whose term peaks at `share` of the plain
/// peak force (at first order), and (catalogue name, checked parameter, its true value).
fn hide(mut rig: Rig, effect: Effect, share: f64) -> (Rig, &'static str, usize, f64) {
    let (peak, deepest, c) = plain(&rig);
    let target = share * peak;
    let (k, n, v0) = (rig.stiffness(), rig.exponent, rig.impact_speed);
    let (name, index, truth) = match effect {
        Effect::Viscous => {
            let coefficient = target / v0;
            rig.effects.push(Physical::Viscous(coefficient));
            ("viscous_damping", 0, coefficient)
        }
        Effect::Hysteresis | Effect::HysteresisLinear | Effect::HysteresisHertzian => {
            let p = match effect {
                Effect::Hysteresis => 0.5,
                Effect::HysteresisLinear => 1.0,
                _ => 1.5,
            };
            let coefficient = target / largest(&c, |d, v, _, _| d.powf(p) * v);
            rig.effects.push(Physical::Hysteresis(coefficient, p));
            ("hysteresis_damping", 1, p)
        }
        Effect::StiffnessExponent => {
            let change = target / largest(&c, |d, _, _, _| k * d.powf(n) * (d / deepest).ln());
            rig.effects
                .push(Physical::StiffnessExponent(change, deepest));
            ("stiffness_exponent", 0, change)
        }
        Effect::Adhesion => {
            rig.effects.push(Physical::Adhesion(target));
            ("adhesion", 0, target)
        }
        Effect::Plasticity => {
            let slope = largest(&c, |d, v, _, _| {
                if v < 0.0 {
                    (deepest - d) * n * k * d.powf(n - 1.0)
                } else {
                    0.0
                }
            });
            rig.effects.push(Physical::Plasticity(target / slope));
            ("plasticity", 0, target / slope)
        }
        Effect::Offset => {
            rig.sensor.offset = target;
            ("force_offset", 0, target)
        }
        Effect::Delay => {
            let h = c.step;
            let rate = largest(&c, |_, _, f, i| (f - c.force[i - 1]) / h);
            rig.sensor.delay = target / rate;
            ("sensor_delay", 0, target / rate)
        }
    };
    (rig, name, index, truth)
}

/// Hides `effect` at `share` of the peak force in the paper's ball and checks that it
/// alone is named, its parameter within `tolerance`.
fn catalogued(effect: Effect, share: f64, seed: u64, tolerance: f64) {
    let (rig, name, index, truth) = hide(ball(), effect, share);
    let label = format!("{effect:?} at {:.1} % (true {truth:.4e})", 100.0 * share);
    let d = diagnosed(&label, &rig, seed);
    named_alone(&d, name, index, truth, tolerance);
}

/// The hysteresis damping of [`hysteresis_damping_below_its_power_is_never_misnamed`]
/// (p = 0.5 at 0.5 %, a sensor delay's first-order shape) is told from the delay by its
/// second-order difference once there are enough contacts: from 128 runs (96 trained)
/// it is named, with its exponent (measured on seeds 44, 62, 63: p = 0.48, 0.46, 0.64,
/// each interval holding 0.5).
#[test]
fn hysteresis_damping_at_half_a_percent_is_named_from_128_runs() {
    let (rig, name, index, truth) = hide(ball(), Effect::Hysteresis, 0.005);
    let d = answer_on(&rig, 128, 62);
    named_alone(&d, name, index, truth, 0.4);
    let p = &d.causes[0].parameters[index];
    assert!(p.ci.0 < truth && truth < p.ci.1, "p {p:?}");
}

macro_rules! catalogued {
    ($($(#[$meta:meta])* $test:ident: $effect:ident, $share:expr, $seed:expr, $tolerance:expr;)*) => {
        $(
            $(#[$meta])*
            #[test]
            fn $test() {
                catalogued(Effect::$effect, $share, $seed, $tolerance);
            }
        )*
    };
}

catalogued! {
    viscous_damping_at_5_percent_is_named: Viscous, 0.05, 41, 0.15;
    viscous_damping_at_half_a_percent_is_named: Viscous, 0.005, 42, 0.3;
    hysteresis_damping_at_5_percent_is_named: Hysteresis, 0.05, 43, 0.4;
    hysteresis_damping_linear_at_5_percent_is_named: HysteresisLinear, 0.05, 55, 0.2;
    stiffness_exponent_at_5_percent_is_named: StiffnessExponent, 0.05, 45, 0.15;
    stiffness_exponent_at_half_a_percent_is_named: StiffnessExponent, 0.005, 46, 0.3;
    adhesion_at_5_percent_is_named: Adhesion, 0.05, 47, 0.15;
    adhesion_at_half_a_percent_is_named: Adhesion, 0.005, 48, 0.3;
    plasticity_at_5_percent_is_named: Plasticity, 0.05, 49, 0.15;
    plasticity_at_half_a_percent_is_named: Plasticity, 0.005, 50, 0.3;
    force_offset_at_5_percent_is_named: Offset, 0.05, 51, 0.15;
    force_offset_at_half_a_percent_is_named: Offset, 0.005, 52, 0.3;
    sensor_delay_at_5_percent_is_named: Delay, 0.05, 53, 0.15;
}

/// A hysteresis damping at 0.5 % of the peak (15 N, the sensor noise) lies, to first
/// order, in the span of what the Lankarani–Nikravesh base and the catalogue already
/// offer: with p = 0.5 it is a sensor reading early on a Hertzian law (f(t + τ) − f(t)
/// ≈ τ·1.5·k·δ^0.5·δ̇), with p = 1.5 the base's own damping (k·δ^1.5·δ̇ through its
/// restitution), and p = 1 lies between. 12 runs cannot name it (the power curve in the
/// README: 2 %; the 5 % tests name it, and 128 runs name p = 0.5 at 0.5 %:
/// [`hysteresis_damping_at_half_a_percent_is_named_from_128_runs`]); the answer must
/// then name nothing — "none" or
/// "ambiguous" between the damping family and the delay — never another cause.
#[test]
#[ignore = "study, over 12 s on 2 cores: cargo test -- --include-ignored"]
fn hysteresis_damping_below_its_power_is_never_misnamed() {
    for (effect, seed) in [
        (Effect::Hysteresis, 44),
        (Effect::Hysteresis, 57),
        (Effect::Hysteresis, 58),
        (Effect::HysteresisLinear, 56),
        (Effect::HysteresisHertzian, 59),
    ] {
        let (rig, _, _, _) = hide(ball(), effect, 0.005);
        let label = format!("{effect:?} at 0.5 %, seed {seed}");
        let d = diagnosed(&label, &rig, seed);
        assert!(d.causes.is_empty(), "{label}: {:#?}", d.causes);
        // The damping family (viscous is hysteresis with p = 0) against the delay.
        let mut pair = d.ambiguous.clone();
        pair.sort();
        assert!(
            pair.is_empty()
                || pair == ["hysteresis_damping", "sensor_delay"]
                || pair == ["sensor_delay", "viscous_damping"],
            "{label}: ambiguous {pair:?}"
        );
    }
}

/// The exponent is the stiffness-exponent effect's, not the base re-fit's
/// (`hcm_host::diagnose::select::free_parameters`): its power and false alarms on the
/// rig, 10 seeds per cell, counted when the answer is `stiffness_exponent` alone. The
/// base (Lankarani–Nikravesh, n = 1.5) is the rig's own, so any other answer with
/// nothing hidden is a false alarm. Run with `--nocapture` for the table in the README.
#[test]
#[ignore = "study, over 12 s on 2 cores: cargo test -- --include-ignored"]
fn a_stiffness_exponent_change_has_power_without_false_alarms() {
    let seeds: Vec<u64> = (300..310).collect();
    let shares = [0.0, 0.0025, 0.005];
    let cells: Vec<(f64, u64)> = shares
        .iter()
        .flat_map(|&x| seeds.iter().map(move |&s| (x, s)))
        .collect();
    let answers: Vec<Vec<&'static str>> = cells
        .par_iter()
        .map(|&(share, seed)| {
            let rig = if share > 0.0 {
                hide(ball(), Effect::StiffnessExponent, share).0
            } else {
                ball()
            };
            names(&answer_on(&rig, RUNS, seed))
        })
        .collect();
    let mut wrong = 0;
    for (k, &share) in shares.iter().enumerate() {
        let cell = &answers[k * seeds.len()..(k + 1) * seeds.len()];
        let named = cell
            .iter()
            .filter(|a| **a == ["stiffness_exponent"])
            .count();
        let other = cell
            .iter()
            .filter(|a| !a.is_empty() && **a != ["stiffness_exponent"])
            .count();
        wrong += other;
        println!(
            "exponent change at {:.2} % of the peak: named alone {named}/10, another name {other}/10 {:?}",
            100.0 * share,
            cell
        );
        if share == 0.0 {
            assert!(named + other <= 1, "false alarms: {cell:?}");
        }
        if share >= 0.005 {
            assert!(named >= 8, "power at {share}: {cell:?}");
        }
    }
    assert_eq!(wrong, 0, "wrong names");
}

// ---------------------------------------------------------------------------------
// Two effects of different kinds, another ball and ground.

#[test]
fn viscous_damping_and_a_force_offset_are_both_named_on_a_small_ball_on_aluminium() {
    let (rig, _, _, coefficient) = hide(small(), Effect::Viscous, 0.05);
    let (rig, _, _, offset) = hide(rig, Effect::Offset, 0.05);
    let d = diagnosed("viscous 5 % + offset 5 %, 5 mm on aluminium", &rig, 61);
    let mut found = names(&d);
    found.sort();
    assert_eq!(
        found,
        ["force_offset", "viscous_damping"],
        "{:#?}",
        d.causes
    );
    for c in &d.causes {
        let truth = if c.effect == "force_offset" {
            offset
        } else {
            coefficient
        };
        let value = c.parameters[0].value;
        assert!(
            (value / truth - 1.0).abs() < 0.15,
            "{}: {value} vs {truth}",
            c.effect
        );
    }
}

// ---------------------------------------------------------------------------------
// How the rig samples: force at 100 kHz; motion filmed at 20 kfps.

/// The paper's ball with its force sampled at 100 kHz.
fn at_100_khz() -> Rig {
    let mut rig = ball();
    rig.sensor.rate = 100e3;
    rig.margin = 300e-6;
    rig
}

#[test]
fn no_effect_at_100_khz_names_none() {
    let d = diagnosed("none at 100 kHz", &at_100_khz(), 71);
    assert!(d.causes.is_empty(), "{:#?}", d.causes);
}

#[test]
fn viscous_damping_at_100_khz_is_named() {
    let (rig, name, index, truth) = hide(at_100_khz(), Effect::Viscous, 0.05);
    let d = diagnosed("viscous 5 % at 100 kHz", &rig, 72);
    named_alone(&d, name, index, truth, 0.15);
}

/// The paper's ball filmed at 20 kfps with 3 µm of position noise, splined onto the
/// force rows.
fn filmed() -> Rig {
    Rig {
        motion: Motion::CameraSplined {
            frame_rate: 20e3,
            position_noise: 3e-6,
        },
        ..ball()
    }
}

#[test]
fn filmed_motion_without_an_effect_names_nothing() {
    let d = diagnosed("none, filmed 20 kfps splined", &filmed(), 81);
    assert!(d.causes.is_empty(), "{:#?}", d.causes);
}

#[test]
fn filmed_motion_without_an_effect_is_answered_none() {
    let d = diagnosed("none, filmed 20 kfps splined", &filmed(), 81);
    assert!(d.causes.is_empty(), "{:#?}", d.causes);
    assert_eq!(d.unexplained_share, 0.0);
}

#[test]
fn filmed_motion_with_viscous_damping_names_it() {
    let (rig, name, index, truth) = hide(filmed(), Effect::Viscous, 0.05);
    let d = diagnosed("viscous 5 %, filmed 20 kfps splined", &rig, 82);
    named_alone(&d, name, index, truth, 0.15);
}

/// A sensor lag behind a camera's frames splined onto the force rows. The motion through
/// the contacts is replaced by the force's, on the clock the check's pooled delay puts
/// the force on where that delay is real; a lag named has an interval that holds the
/// truth, also where the replacement stays on the force's clock and follows part of the
/// lag (before the replacement read the check's delay, a 5 µs delay was named
/// 2.74 µs [2.63, 2.85]).
#[test]
#[ignore = "study, about 6 to 10 s of both cores: kept out of CI's 15 minutes (docs/tests.md); cargo test -- --include-ignored"]
fn a_lag_behind_splined_camera_frames_is_measured_against_the_frames() {
    let cases = [(5e-6, 0.0, 91), (3e-6, 0.0, 92), (0.0, 5e-6, 93)];
    let answers = diagnosed_each(&cases, |&(delay, filter, seed)| {
        let mut rig = filmed();
        rig.sensor.delay = delay;
        rig.sensor.filter = filter;
        let label = format!("delay {delay:e} s, filter {filter:e} s, filmed and splined");
        (label, rig, seed)
    });
    for (&(delay, filter, _), d) in cases.iter().zip(&answers) {
        let (effect, truth) = if filter > 0.0 {
            ("sensor_filter", filter)
        } else {
            ("sensor_delay", delay)
        };
        if lag_named_or_ambiguous(d, effect) {
            let p = &d.causes[0].parameters[0];
            assert!(
                p.ci.0 <= truth && truth <= p.ci.1,
                "{effect} {truth:e}: {:e} {:?}",
                p.value,
                p.ci
            );
        }
    }
}

/// The paper's ball filmed at 20 kfps (3 µm noise, no velocity), the camera's rows and
/// the force sensor's (1 MHz) in one file with empty cells, 2 ms of flight on each side
/// (40 frames to fit the flight before and after each contact).
fn camera() -> Rig {
    Rig {
        motion: Motion::Camera {
            frame_rate: 20e3,
            position_noise: 3e-6,
            velocity_noise: None,
        },
        margin: 2e-3,
        ..ball()
    }
}

#[test]
fn camera_frames_with_a_hidden_viscous_damping_name_it() {
    let (rig, name, index, truth) = hide(camera(), Effect::Viscous, 0.05);
    let d = diagnosed("viscous 5 %, camera rows with empty cells", &rig, 84);
    named_alone(&d, name, index, truth, 0.15);
}

/// Hides a sensor lag of `delay` (s) behind the camera rows and checks that the
/// reconstruction finds it (the motion integrated from the read force lands late on
/// the camera's flight after each contact) and the diagnosis names it, with a finite
/// interval that covers it.
fn delay_behind_camera_rows_is_named(label: &str, delay: f64, seed: u64) {
    let mut rig = camera();
    rig.sensor.delay = delay;
    let d = diagnosed(label, &rig, seed);
    assert!(d.data_quality.sufficient, "{:?}", d.data_quality);
    let found = d
        .data_quality
        .sensor_delay
        .expect("the reconstruction finds the delay");
    assert!(
        (found.value - delay).abs() < 4.0 * found.sd,
        "{found:?} vs {delay}"
    );
    assert_eq!(names(&d), ["sensor_delay"], "{:#?}", d.causes);
    // The named delay is the reconstruction's alignment, with its uncertainty: the
    // interval covers the truth and is informative (narrower than ±25 %).
    let p = &d.causes[0].parameters[0];
    assert!(
        (p.value / delay - 1.0).abs() < 0.15,
        "{} vs {delay}",
        p.value
    );
    assert!(
        p.ci.0.is_finite() && p.ci.1.is_finite() && p.ci.0 <= delay && delay <= p.ci.1,
        "interval {:?} vs {delay}",
        p.ci
    );
    assert!(p.ci.1 - p.ci.0 < 0.5 * delay, "interval {:?}", p.ci);
}

#[test]
fn a_2_us_sensor_delay_behind_camera_rows_is_named() {
    delay_behind_camera_rows_is_named("delay 2 µs, camera rows", 2e-6, 86);
}

#[test]
#[ignore = "study, over 12 s on 2 cores: cargo test -- --include-ignored"]
fn a_5_us_sensor_delay_behind_camera_rows_is_named() {
    delay_behind_camera_rows_is_named("delay 5 µs, camera rows", 5e-6, 87);
}

#[test]
fn a_1_us_sensor_delay_behind_camera_rows_is_a_lag_a_delay_or_a_filter() {
    // Too small to move the landing by 3 standard deviations (gap 1.74), but the delay
    // that closes the gaps is over 5 of its standard deviations from 0. A 1 µs
    // first-order filter lags the force as much (the camera's timing cannot tell them
    // either), so "ambiguous between the two" is a right answer too.
    let mut rig = camera();
    rig.sensor.delay = 1e-6;
    let d = diagnosed("delay 1 µs, camera rows", &rig, 89);
    if lag_named_or_ambiguous(&d, "sensor_delay") {
        let p = &d.causes[0].parameters[0];
        assert!(
            p.ci.0.is_finite() && p.ci.1.is_finite() && p.ci.0 <= 1e-6 && 1e-6 <= p.ci.1,
            "interval {:?}",
            p.ci
        );
    }
}

#[test]
#[ignore = "study, about 6 to 12 s of both cores: kept out of CI's 15 minutes (docs/tests.md); cargo test -- --include-ignored"]
fn camera_frames_behind_a_lagging_force_sensor_name_the_delay() {
    // Before the reconstruction fitted the delay this gave the data-quality verdict
    // (gap 3.9 standard deviations): the motion integrated from the delayed force
    // landed late on the camera's flight after each contact.
    let (_, _, _, truth) = hide(camera(), Effect::Delay, 0.05);
    delay_behind_camera_rows_is_named("delay 5 %, camera rows with empty cells", truth, 85);
}

#[test]
fn camera_frames_with_a_wrong_mass_get_a_verdict_not_a_wrong_name() {
    // The scenario's ball 10 % heavier than the filmed one: the force integrated
    // through each contact changes the velocity 10 % too little, which no sensor delay
    // undoes. The data-quality check sees the gap and names nothing.
    let rig = camera();
    let data = read(&rig.record(RUNS, 88));
    let heavier = base_model_with(&rig, &[format!("body.ball.mass={:e}", 1.1 * rig.mass)]);
    let d = answer(&heavier, &data);
    println!("wrong mass, camera rows: {:?}", d.data_quality);
    assert!(!d.data_quality.sufficient, "{:?}", d.data_quality);
    assert!(d.causes.is_empty(), "{:#?}", d.causes);
    assert!(
        d.data_quality
            .reasons
            .iter()
            .any(|r| r.contains("camera's flight")),
        "{:?}",
        d.data_quality.reasons
    );
}

#[test]
fn camera_frames_with_empty_cells_are_read_and_diagnosed() {
    let rig = camera();
    let recording = rig.record(RUNS, 83);
    let data = Dataset::from_reader("camera.csv", recording.csv.as_bytes());
    let data = data.expect("empty cells read as not sampled");
    let d = diagnose(&base_model(&rig), &data, &DiagnoseSettings::default()).unwrap();
    println!("no effect, camera rows: {:?}", d.data_quality);
    assert!(d.causes.is_empty(), "{:#?}", d.causes);
}

/// What `hcm diagnose` answers on the paper's ball (Lankarani–Nikravesh, e = 0.9) when
/// the base model holds another law, `base` (its stiffness and exponent the rig's).
fn with_base(label: &str, base: Model, seed: u64) -> Diagnosis {
    let d = answer(&base, &read(&ball().record(RUNS, seed)));
    println!(
        "{label}: causes {:?}, ambiguous {:?}, unexplained {:.3}",
        d.causes
            .iter()
            .map(|c| (
                c.effect,
                c.parameters.iter().map(|p| p.value).collect::<Vec<_>>()
            ))
            .collect::<Vec<_>>(),
        d.ambiguous,
        d.unexplained_share
    );
    d
}

#[test]
fn a_hertz_base_on_damped_data_names_the_missing_damping_as_what_it_is() {
    // Lankarani–Nikravesh's damping is k·δⁿ·3(1 − e²)/(4·δ̇0)·δ̇: a hysteresis damping
    // with p = n = 1.5, missing from Hertz.
    let rig = ball();
    let hertz = Rig {
        base: Base::Hertz,
        ..rig.clone()
    };
    let d = with_base("LN data, Hertz base", base_model(&hertz), 91);
    let names: Vec<&str> = d.causes.iter().map(|c| c.effect).collect();
    assert_eq!(names, ["hysteresis_damping"], "{:#?}", d.causes);
    let p = d.causes[0].parameters[1].value;
    assert!((p - rig.exponent).abs() < 0.25, "p = {p}");
}

#[test]
fn a_hunt_crossley_base_on_lankarani_nikravesh_data_lacks_nothing() {
    // The same damping shape, k·δⁿ·χ·δ̇: re-tuning χ absorbs it, nothing is missing.
    let rig = ball();
    let chi = 3.0 * (1.0 - 0.9_f64.powi(2)) / (4.0 * rig.impact_speed);
    let hunt_crossley = Rig {
        base: Base::HuntCrossley(chi * 0.8),
        ..rig
    };
    let d = with_base(
        "LN data, Hunt–Crossley base",
        base_model(&hunt_crossley),
        92,
    );
    assert!(d.causes.is_empty(), "{:#?}", d.causes);
    assert!(d.ambiguous.is_empty(), "{:?}", d.ambiguous);
}

#[test]
#[ignore = "study, over 12 s on 2 cores: cargo test -- --include-ignored"]
fn an_impact_base_on_lankarani_nikravesh_data_names_no_wrong_cause() {
    // IMPACT's damping ramps to d_max over δ_max and stays: not LN's δ^1.5·δ̇. A sensible
    // answer names a damping term or nothing (unexplained), never another cause.
    let rig = ball();
    let (k, n) = (rig.stiffness(), rig.exponent);
    let impact = base_model_with(
        &rig,
        &[
            "contact.0.law=impact".to_owned(),
            format!(
                "contact.0.parameters={{ stiffness = {k:e}, exponent = {n:e}, max_damping = 1e4, full_damping_depth = 1e-5 }}"
            ),
        ],
    );
    let d = with_base("LN data, IMPACT base", impact, 93);
    for cause in &d.causes {
        assert!(
            matches!(cause.effect, "hysteresis_damping" | "viscous_damping"),
            "{:#?}",
            d.causes
        );
    }
}
