//! The force sensor as the diagnosis models it: it reads the contact force τ late and
//! shifted by a constant b along the contact normal,
//!
//! f_read(t) = f(t − τ) + b  (N).
//!
//! Offset and delay are measurement effects, not physics: the re-fit finds them as
//! corrections of the prediction ([`Sensor::reads`]), and before a model is judged on
//! data the data are corrected ([`Sensor::correct`], [`Sensor::retime`]), so that the
//! extended model stays a contact law a controller can run.

use super::catalogue::Candidate;
use super::ContactSamples;
use crate::dataset::Run;
use crate::indicators::{contact_history, ContactHistory, IndicatorError};
use crate::scenario::Model;
use hcm_core::effect::ExtendedLaw;
use nalgebra::Vector3;
use serde::Serialize;

/// A force sensor with an offset and a delay; the default is an ideal sensor.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Sensor {
    /// Offset b of the normal force on body 1 (N): what the sensor reads with no
    /// contact.
    pub offset: f64,
    /// Delay τ of the force signal behind the recorded motion (s).
    pub delay: f64,
}

impl Sensor {
    /// Whether it reads the force as it is (b = 0 and τ = 0).
    pub fn is_ideal(&self) -> bool {
        self.offset == 0.0 && self.delay == 0.0
    }

    /// What it reads along `samples` when the contact follows `law` (N):
    /// f(t) − τ·ḟ(t) + b, first order in τ, ḟ by central differences within a run.
    pub fn reads(&self, samples: &ContactSamples, law: &ExtendedLaw<f64>) -> Vec<f64> {
        let f = samples.model_force(law);
        // The delay column is −ḟ: the sensitivity of the reading to τ.
        let slope = Candidate::SensorDelay.column(samples, law, &f, f64::NAN, f64::NAN);
        f.iter()
            .zip(&slope)
            .map(|(f, s)| f + self.delay * s + self.offset)
            .collect()
    }

    /// The recorded normal-force samples of `history` as the contact produced them:
    /// the reading at t is the force at t − τ less b, so each sample moves to
    /// (t − τ, f − b) (s, N). No value is interpolated, so the noise stays σ: what
    /// a force RMSE against these samples is compared with.
    pub fn retime(&self, history: &ContactHistory, i: usize) -> (f64, f64) {
        (history.time[i] - self.delay, history.force[i] - self.offset)
    }

    /// `run` with the sensor removed from the force track contact `c` reads: each
    /// force vector replaced by the one recorded τ later (linearly interpolated, the
    /// last held), then b taken off along that sample's contact normal (added back
    /// for body 2's reaction). Motion, torques and the other bodies stay as recorded.
    /// Interpolating two noisy samples averages their noise (down to σ/√2 half-way),
    /// so use it for means such as indicators, and [`Sensor::retime`] for force RMSE.
    pub fn correct(&self, model: &Model, run: &Run, c: usize) -> Result<Run, IndicatorError> {
        if self.is_ideal() {
            return Ok(run.clone());
        }
        let history = contact_history(model, run, c)?;
        let Some(body) = history.force_body else {
            return Ok(run.clone());
        };
        let sign = if body == model.contacts[c].body_1 {
            1.0
        } else {
            -1.0
        };
        let mut corrected = run.clone();
        let name = &model.bodies[body].name;
        let Some(track) = corrected.bodies.iter_mut().find(|t| &t.body == name) else {
            return Ok(corrected);
        };
        let times: Vec<f64> = track.samples.iter().map(|s| s.time).collect();
        let forces: Vec<Vector3<f64>> = track
            .samples
            .iter()
            .map(|s| Vector3::from(s.force))
            .collect();
        let mut j = 0;
        for (i, sample) in track.samples.iter_mut().enumerate() {
            let t = sample.time + self.delay;
            while j + 1 < times.len() && times[j + 1] <= t {
                j += 1;
            }
            let advanced = match (forces.get(j), forces.get(j + 1)) {
                (Some(a), Some(b)) if t > times[j] => {
                    a + (b - a) * ((t - times[j]) / (times[j + 1] - times[j]))
                }
                (Some(a), _) => *a,
                _ => forces[i],
            };
            let normal = history
                .normal
                .get(i)
                .copied()
                .unwrap_or_else(Vector3::zeros);
            sample.force = (advanced - normal * (sign * self.offset)).into();
        }
        Ok(corrected)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::Scenario;
    use std::path::Path;

    fn ball(overrides: &[String]) -> Model {
        let path = Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../scenarios/bouncing_ball.toml"
        ));
        Scenario::load(path, overrides)
            .unwrap()
            .resolve(path)
            .unwrap()
    }

    #[test]
    fn correcting_undoes_what_the_sensor_did() {
        // A noise-free run, and the same run through a sensor 40 N off and 2.5 µs late.
        let quiet = ["experiment.force_noise=0.0".to_owned()];
        let clean = ball(&quiet);
        let mut biased = quiet.to_vec();
        biased.push("experiment.force_offset=[0.0, 0.0, 40.0]".into());
        biased.push("experiment.sensor_delay=2.5e-6".into());
        let truth = crate::experiment::generate(&clean.scenario, 1, 1, || {}).unwrap();
        let read = crate::experiment::generate(&ball(&biased).scenario, 1, 1, || {}).unwrap();
        let sensor = Sensor {
            offset: 40.0,
            delay: 2.5e-6,
        };
        let corrected = sensor.correct(&clean, &read.runs[0], 0).unwrap();
        let (a, b, raw) = (
            contact_history(&clean, &truth.runs[0], 0).unwrap(),
            contact_history(&clean, &corrected, 0).unwrap(),
            contact_history(&clean, &read.runs[0], 0).unwrap(),
        );
        // RMS and worst difference from the true force over the contact (N).
        let inside: Vec<usize> = (0..a.force.len()).filter(|&i| a.depth[i] > 0.0).collect();
        let compare = |h: &ContactHistory| {
            let d: Vec<f64> = inside.iter().map(|&i| a.force[i] - h.force[i]).collect();
            let rms = (d.iter().map(|x| x * x).sum::<f64>() / d.len() as f64).sqrt();
            (rms, d.iter().fold(0.0_f64, |m, x| m.max(x.abs())))
        };
        let (fixed, biased) = (compare(&b), compare(&raw));
        eprintln!("corrected {fixed:?} N, raw {biased:?} N");
        // Delaying and then advancing by interpolation half a 1 µs step each way leaves
        // the curvature error h²·|f''|/8 ≈ 0.3 N of a 3000 N pulse twice over, more at
        // touch-down where the law's slope jumps; the raw reading is ~100 N off.
        assert!(fixed.0 < 1.0 && fixed.1 < 5.0, "corrected {fixed:?}");
        assert!(biased.0 > 50.0, "raw {biased:?}");
        // Re-timing moves each reading back by τ and takes b off.
        let k = raw.force.len() / 2;
        assert_eq!(
            sensor.retime(&raw, k),
            (raw.time[k] - 2.5e-6, raw.force[k] - 40.0)
        );
        // An ideal sensor changes nothing.
        let same = Sensor::default().correct(&clean, &read.runs[0], 0).unwrap();
        assert_eq!(same, read.runs[0]);
    }
}
