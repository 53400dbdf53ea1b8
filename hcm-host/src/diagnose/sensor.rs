//! The force sensor as the diagnosis models it: it reads the contact force τ late,
//! shifted by a constant b along the contact normal and scaled by a gain g,
//!
//! f_read(t) = g·(f(t − τ) + b)  (N).
//!
//! Gain, offset and delay are measurement effects, not physics: the gain is measured
//! from the momentum balance ([`super::momentum`]), offset and delay are found by the
//! re-fit as corrections of the prediction ([`Sensor::reads`]), and before a model is
//! judged on data the data are corrected ([`Sensor::correct`], [`Sensor::retime`]), so
//! that the extended model stays a contact law a controller can run.

use super::ContactSamples;
use crate::dataset::Run;
use crate::indicators::{contact_history, ContactHistory, IndicatorError};
use crate::scenario::Model;
use hcm_core::effect::ExtendedLaw;
use nalgebra::Vector3;
use serde::Serialize;

/// A force sensor with a gain, an offset and a delay; the default is an ideal sensor.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Sensor {
    /// Offset b of the normal force on body 1 (N), before the gain: what the sensor
    /// reads with no contact, over g.
    pub(crate) offset: f64,
    /// Delay τ of the force signal behind the recorded motion (s).
    pub(crate) delay: f64,
    /// Gain g (–): the reading per newton of force.
    pub(crate) gain: f64,
}

impl Default for Sensor {
    fn default() -> Self {
        Sensor {
            offset: 0.0,
            delay: 0.0,
            gain: 1.0,
        }
    }
}

impl Sensor {
    /// Whether it reads the force as it is (b = 0, τ = 0 and g = 1).
    pub fn is_ideal(&self) -> bool {
        self.offset == 0.0 && self.delay == 0.0 && self.gain == 1.0
    }

    /// What it reads along `samples` when the contact follows `law` (N): the law's
    /// force along the recorded motion (0 outside contact) taken τ earlier, plus b,
    /// times g.
    /// The force between samples is a cubic Hermite curve through the samples of the
    /// same run with central-difference slopes, so the reading is smooth in τ (a fit
    /// can move τ by less than a sample) and off by O(h³·f⃛) only; before a run's first
    /// sample and after its last the end value is held.
    pub fn reads(&self, samples: &ContactSamples, law: &ExtendedLaw<f64>) -> Vec<f64> {
        let f = samples.model_force(law);
        let g = self.gain;
        if self.delay == 0.0 {
            return f.iter().map(|f| g * (f + self.offset)).collect();
        }
        let mut out = Vec::with_capacity(f.len());
        for range in samples.run_ranges() {
            let (t, v) = (&samples.time[range.clone()], &f[range]);
            out.extend(
                t.iter()
                    .map(|&ti| g * (hermite(t, v, ti - self.delay) + self.offset)),
            );
        }
        out
    }

    /// The recorded normal-force samples of `history` as the contact produced them:
    /// the reading at t over g is the force at t − τ plus b, so each sample moves to
    /// (t − τ, f/g − b) (s, N). No value is interpolated, so the noise stays σ/g: what
    /// a force RMSE against these samples is compared with, times g.
    pub fn retime(&self, history: &ContactHistory, i: usize) -> (f64, f64) {
        (
            history.time[i] - self.delay,
            history.force[i] / self.gain - self.offset,
        )
    }

    /// `run` with the sensor removed from the force track contact `c` reads: each
    /// force vector replaced by the one recorded τ later (linearly interpolated, the
    /// last held) over g, then b taken off along that sample's contact normal (added
    /// back for body 2's reaction). Motion, torques and the other bodies stay as recorded.
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
            sample.force = (advanced / self.gain - normal * (sign * self.offset)).into();
        }
        Ok(corrected)
    }
}

/// `v` sampled at ascending times `t`, at time `s`: cubic Hermite between the two
/// neighbouring samples with central-difference slopes (one-sided at the ends); the
/// end value outside.
fn hermite(t: &[f64], v: &[f64], s: f64) -> f64 {
    let n = t.len();
    let j = t.partition_point(|&x| x <= s);
    if j == 0 {
        return v.first().copied().unwrap_or(0.0);
    }
    if j == n {
        return v[n - 1];
    }
    let (a, b) = (j - 1, j);
    let slope = |i: usize| {
        let (l, r) = (i.saturating_sub(1), (i + 1).min(n - 1));
        if t[r] > t[l] {
            (v[r] - v[l]) / (t[r] - t[l])
        } else {
            0.0
        }
    };
    let h = t[b] - t[a];
    if h <= 0.0 {
        return v[b];
    }
    let x = (s - t[a]) / h;
    let (x2, x3) = (x * x, x * x * x);
    (2.0 * x3 - 3.0 * x2 + 1.0) * v[a]
        + (x3 - 2.0 * x2 + x) * h * slope(a)
        + (-2.0 * x3 + 3.0 * x2) * v[b]
        + (x3 - x2) * h * slope(b)
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
    fn hermite_is_exact_for_a_quadratic_and_holds_the_ends() {
        let t: Vec<f64> = (0..8).map(|k| 0.5 * k as f64).collect();
        let v: Vec<f64> = t.iter().map(|x| 3.0 * x * x - x + 2.0).collect();
        for s in [0.6, 1.25, 2.0, 2.9] {
            let exact = 3.0 * s * s - s + 2.0;
            assert!((hermite(&t, &v, s) - exact).abs() < 1e-12, "{s}");
        }
        assert_eq!(hermite(&t, &v, -1.0), v[0]);
        assert_eq!(hermite(&t, &v, 9.0), v[7]);
    }

    #[test]
    fn correcting_undoes_what_the_sensor_did() {
        // A noise-free run, and the same run through a sensor 40 N off and 2.5 µs late.
        let quiet = ["experiment.force_noise=0.0".to_owned()];
        let clean = ball(&quiet);
        let mut biased = quiet.to_vec();
        biased.push("experiment.force_offset=[0.0, 0.0, 40.0]".into());
        biased.push("experiment.sensor_delay=2.5e-6".into());
        let truth =
            crate::experiment::generate(&clean.scenario, 1, 1, &crate::progress::Silent).unwrap();
        let read =
            crate::experiment::generate(&ball(&biased).scenario, 1, 1, &crate::progress::Silent)
                .unwrap();
        let sensor = Sensor {
            offset: 40.0,
            delay: 2.5e-6,
            gain: 1.0,
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
