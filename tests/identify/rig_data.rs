//! Data as a rig records them: camera frames at 20 kfps with µm position noise and no
//! velocity, force rows at 1 MHz or 100 kHz, in one file with empty cells. The motion
//! reconstructed at the force samples against the generator's truth, `identify` on such
//! data against full-rate data, and the channel each command needs.

use hcm_host::dataset::complete;
use hcm_host::dataset::{BodyTrack, Channel, Dataset, Requirement, Sample};
use hcm_host::diagnose::contact_samples;
use hcm_host::experiment::generate;
use hcm_host::identify::{identify, Method};
use hcm_host::scenario::{Model, Scenario};
use hcm_tests::scenario;

/// Camera frame period (s): 20 kfps.
const FRAME: f64 = 5e-5;
/// Camera position noise σ (m).
const POSITION_NOISE: f64 = 3e-6;

/// The ball scenario with `law` and `parameters`, no parameter noise, force noise
/// `force_noise` (N), recorded at 1 MHz with a 0.5 ms margin and 20 kfps in flight, so
/// that frames and force rows can be cut from one generated run.
fn ball(law: &str, parameters: &str, force_noise: f64) -> Scenario {
    let overrides = [
        format!("contact.0.law={law}"),
        format!("contact.0.parameters={parameters}"),
        "contact.0.noise={}".into(),
        format!("experiment.force_noise={force_noise}"),
        format!("record.flight_sample_period={FRAME}"),
        "record.contact_margin=5e-4".into(),
    ];
    Scenario::load(&scenario("bouncing_ball.toml"), &overrides).unwrap()
}

/// A deterministic standard normal sequence (xorshift and Box–Muller).
struct Normal(u64);

impl Normal {
    fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        ((self.0 >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }
    fn next(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    }
}

/// What a rig records of `full` (1 µs ticks): camera frames every 50 µs (position and
/// orientation, position noised by σ = 3 µm per axis, no velocity) and force rows every
/// `force_ticks` µs where the generator sampled at 1 MHz (motion empty); a frame that
/// falls on a force row carries both.
fn as_rig(full: &Dataset, force_ticks: u64, seed: u64) -> Dataset {
    let mut noise = Normal(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1);
    let mut rig = full.clone();
    for run in &mut rig.runs {
        for track in &mut run.bodies {
            let ticks: Vec<u64> = track
                .samples
                .iter()
                .map(|s| (s.time / 1e-6).round() as u64)
                .collect();
            let fine = |i: usize| {
                (i > 0 && ticks[i] - ticks[i - 1] == 1)
                    || (i + 1 < ticks.len() && ticks[i + 1] - ticks[i] == 1)
            };
            let samples = track.samples.iter().enumerate().filter_map(|(i, s)| {
                let frame = ticks[i].is_multiple_of(50);
                let force = fine(i) && ticks[i].is_multiple_of(force_ticks);
                let mut row = Sample::unsampled(s.time);
                if frame {
                    row.position = s.position.map(|p| p + POSITION_NOISE * noise.next());
                    row.orientation = s.orientation;
                }
                if force {
                    row.force = s.force;
                    row.torque = s.torque;
                }
                (frame || force).then_some(row)
            });
            *track = BodyTrack {
                body: track.body.clone(),
                samples: samples.collect(),
            };
        }
    }
    rig
}

/// The largest errors of the reconstructed δ (m) and δ̇ (m/s) in contact against the
/// generator's, the peak δ and the impact speed, and the largest |error|/sd.
fn reconstruction_errors(model: &Model, full: &Dataset, rig: &Dataset) -> [f64; 5] {
    let truth = contact_samples(model, full, 0).unwrap();
    let rebuilt = contact_samples(model, rig, 0).unwrap();
    let (mut depth, mut rate, mut peak, mut speed, mut z) =
        (0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64);
    let mut matched = 0;
    for i in (0..rebuilt.len()).filter(|&i| rebuilt.in_contact[i]) {
        let Some(j) = (0..truth.len()).find(|&j| {
            truth.run[j] == rebuilt.run[i] && (truth.time[j] - rebuilt.time[i]).abs() < 1e-9
        }) else {
            continue;
        };
        matched += 1;
        let (dd, dr) = (
            rebuilt.depth[i] - truth.depth[j],
            rebuilt.rate[i] - truth.rate[j],
        );
        depth = depth.max(dd.abs());
        rate = rate.max(dr.abs());
        peak = peak.max(truth.depth[j]);
        speed = speed.max(truth.approach_speed[j]);
        assert!(rebuilt.depth_sd[i] > 0.0 && rebuilt.rate_sd[i] > 0.0);
        z = z.max((dd / rebuilt.depth_sd[i]).abs());
    }
    assert!(matched > 8, "{matched} in-contact samples matched");
    [depth, rate, peak, speed, z]
}

#[test]
fn camera_frames_and_force_rows_reconstruct_the_contact_motion() {
    let scenario = ball(
        "variable_stiffness",
        "{ surface_loading = 2.0, damping = 987.9 }",
        15.0,
    );
    let model = scenario.model().unwrap();
    let full = generate(&scenario, 3, 5, &hcm_host::progress::Silent).unwrap();
    for (force_ticks, depth_share, rate_share) in [(1, 0.03, 0.01), (10, 0.05, 0.03)] {
        let rig = as_rig(&full, force_ticks, 9);
        // Written with empty cells and read back, as a user's file would be.
        let mut bytes = Vec::new();
        rig.to_writer(&mut bytes).unwrap();
        let rig = Dataset::from_reader("rig.csv", &bytes[..]).unwrap();
        assert!(rig.runs[0].bodies[0]
            .samples
            .iter()
            .any(|s| s.lacks(Channel::Position)));
        let [depth, rate, peak, speed, z] = reconstruction_errors(&model, &full, &rig);
        eprintln!(
            "force every {force_ticks} µs: δ error {:.3} µm of peak {:.2} µm ({:.2} %), \
             δ̇ error {:.4} m/s of {:.3} m/s ({:.2} %), largest |error|/sd {z:.2}",
            depth * 1e6,
            peak * 1e6,
            100.0 * depth / peak,
            rate,
            speed,
            100.0 * rate / speed
        );
        assert!(depth < depth_share * peak, "δ error {depth:e} of {peak:e}");
        assert!(rate < rate_share * speed, "δ̇ error {rate:e} of {speed:e}");
        assert!(z < 5.0, "the error is {z} standard deviations");
        // The integration agrees with the flight after the contact.
        let completed = complete(&model, &rig).unwrap();
        for run in 0..rig.runs.len() {
            let track = completed.track(run, "ball").unwrap();
            let (gap, sd) = track.contacts[0].velocity_gap.unwrap();
            assert!(
                gap[2].abs() < 5.0 * sd[2] + 0.01 * speed,
                "gap {gap:?} sd {sd:?}"
            );
        }
    }
}

#[test]
fn full_rate_data_are_read_as_recorded_with_no_uncertainty() {
    let scenario = ball("hertz", "{ stiffness = 3.6e9, exponent = 1.5 }", 15.0);
    let model = scenario.model().unwrap();
    let full = generate(&scenario, 2, 3, &hcm_host::progress::Silent).unwrap();
    let completed = complete(&model, &full).unwrap();
    assert!(!completed.reconstructed());
    assert!(matches!(completed.data, std::borrow::Cow::Borrowed(_)));
    let samples = contact_samples(&model, &full, 0).unwrap();
    assert!(samples
        .depth_sd
        .iter()
        .chain(&samples.rate_sd)
        .all(|&sd| sd == 0.0));
}

/// Relative errors of the identified parameters against the truth, and of the
/// stiffness force K·δ^n at δ = 50 µm (K and n trade against each other).
fn identified(scenario: &Scenario, data: &Dataset, law: &str) -> Vec<(String, f64)> {
    let model = scenario.model().unwrap();
    let truth = *model.contacts[0].law();
    let found = identify(
        scenario,
        &model,
        data,
        0,
        law,
        Method::Lsq,
        &hcm_host::progress::Silent,
    )
    .unwrap();
    let force = |named: Vec<(&str, f64)>| {
        let value = |name: &str| named.iter().find(|n| n.0 == name).unwrap().1;
        value("stiffness") * 5e-5f64.powf(value("exponent"))
    };
    let (expected, value) = (
        force(truth.named().collect()),
        force(found.law.named().collect()),
    );
    let mut errors: Vec<(String, f64)> = truth
        .named()
        .zip(found.law.named())
        .map(|((name, expected), (_, value))| {
            (name.to_owned(), ((value - expected) / expected).abs())
        })
        .collect();
    errors.push((
        "K·δ^n at 50 µm".to_owned(),
        ((value - expected) / expected).abs(),
    ));
    errors
}

#[test]
fn identify_on_camera_frames_recovers_the_law_about_as_well_as_on_full_rate_data() {
    let law = "hunt_crossley";
    let scenario = ball(
        law,
        "{ stiffness = 6.86e9, exponent = 1.5, damping = 0.07 }",
        15.0,
    );
    let full = generate(&scenario, 6, 21, &hcm_host::progress::Silent).unwrap();
    let on_full = identified(&scenario, &full, law);
    for force_ticks in [1, 10] {
        let rig = as_rig(&full, force_ticks, 4);
        let on_rig = identified(&scenario, &rig, law);
        eprintln!("{law}, force every {force_ticks} µs: full rate {on_full:.4?}, rig {on_rig:.4?}");
        for ((name, full), (_, rig)) in on_full.iter().zip(&on_rig) {
            // The stiffness alone moves with the exponent (a 1 % change of n at 50 µm
            // is 10 % of K): judged through K·δ^n.
            let bound = if name == "stiffness" { 0.3 } else { 0.03 };
            assert!(
                *rig < bound,
                "{name}: {rig} off on rig data (full rate {full})"
            );
        }
    }
}

#[test]
fn commands_name_the_channel_they_miss() {
    let scenario = ball("hertz", "{ stiffness = 3.6e9, exponent = 1.5 }", 0.0);
    let model = scenario.model().unwrap();
    let full = generate(&scenario, 1, 3, &hcm_host::progress::Silent).unwrap();
    let mut filmed = full.clone();
    for sample in &mut filmed.runs[0].bodies[0].samples {
        sample.clear(Channel::Force);
        sample.clear(Channel::Torque);
    }
    let error = filmed
        .require("tosses.csv", &model, &[0], &Requirement::IDENTIFY)
        .unwrap_err();
    let message = error.to_string();
    for word in [
        "tosses.csv",
        "hcm identify",
        "force channel (fx, fy, fz)",
        "run `0`",
        "ball",
        "add the force sensor's rows",
    ] {
        assert!(
            message.contains(word),
            "`{message}` should mention `{word}`"
        );
    }
    assert_eq!(error.column.as_deref(), Some("fx"));
    // The library says the same when called directly.
    let error = contact_samples(&model, &filmed, 0).unwrap_err().to_string();
    assert!(
        error.contains("no force samples") && error.contains("ball"),
        "{error}"
    );

    let mut blind = full.clone();
    for sample in &mut blind.runs[0].bodies[0].samples {
        sample.clear(Channel::Position);
    }
    let message = blind
        .require("f.csv", &model, &[0], &Requirement::DIAGNOSE)
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("position channel (px, py, pz)") && message.contains("camera's frames"),
        "{message}"
    );
    let message = blind
        .require("f.csv", &model, &[0], &Requirement::INDICATORS_RIGID)
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("every row") && message.contains("t = 0.0 s"),
        "{message}"
    );
    full.require("f.csv", &model, &[0], &Requirement::INDICATORS_RIGID)
        .unwrap();
}
