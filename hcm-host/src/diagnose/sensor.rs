//! The force sensor as the diagnosis models it: it reads the contact force τ late,
//! through a first-order low-pass filter of time constant T, shifted by a constant b
//! along the contact normal and scaled by a gain g,
//!
//! f_read(t) = g·(y(t − τ) + b),  T·ẏ + y = f  (N).
//!
//! Gain, offset, delay and filter are measurement effects, not physics: the gain is measured
//! from the momentum balance ([`super::momentum`]), offset and delay are found by the
//! re-fit as corrections of the prediction ([`Sensor::reads`]), and before a model is
//! judged on data the data are corrected ([`Sensor::correct`], [`Sensor::retime`]), so
//! that the extended model stays a contact law a controller can run.

use super::ContactSamples;
use crate::dataset::Run;
use crate::indicators::{contact_history, ContactHistory, IndicatorError};
use crate::numerics::sampled::{delayed, low_pass};
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
    /// Time constant T of a first-order low-pass filter on the force (s), 0 for none.
    pub(crate) filter: f64,
}

impl Default for Sensor {
    fn default() -> Self {
        Sensor {
            offset: 0.0,
            delay: 0.0,
            gain: 1.0,
            filter: 0.0,
        }
    }
}

impl Sensor {
    /// Whether it reads the force as it is (b = 0, τ = 0, g = 1 and T = 0).
    pub fn is_ideal(&self) -> bool {
        self.offset == 0.0 && self.delay == 0.0 && self.gain == 1.0 && self.filter == 0.0
    }

    /// What it reads along `samples` when the contact follows `law` (N): the law's
    /// force along the recorded motion (0 outside contact) taken τ earlier, through the
    /// filter, plus b, times g.
    /// The force between samples is a cubic Hermite curve through the samples of the
    /// same run with central-difference slopes, so the reading is smooth in τ (a fit
    /// can move τ by less than a sample) and off by O(h³·f⃛) only; before a run's first
    /// sample and after its last the end value is held. The filter starts each run at
    /// rest on its first value and is exact for a force linear between samples.
    pub fn reads(&self, samples: &ContactSamples, law: &ExtendedLaw<f64>) -> Vec<f64> {
        let f = samples.model_force(law);
        let g = self.gain;
        if self.delay == 0.0 && self.filter <= 0.0 {
            return f.iter().map(|f| g * (f + self.offset)).collect();
        }
        let mut out = Vec::with_capacity(f.len());
        for range in samples.run_ranges() {
            let (t, v) = (&samples.time[range.clone()], &f[range]);
            let delayed: Vec<f64> = if self.delay == 0.0 {
                v.to_vec()
            } else {
                delayed(t, v, self.delay)
            };
            let read = low_pass(t, &delayed, self.filter);
            out.extend(read.iter().map(|y| g * (y + self.offset)));
        }
        out
    }

    /// The recorded normal-force samples of `history` as the contact produced them:
    /// the reading at t over g is the force at t − τ plus b, so each sample moves to
    /// (t − τ, f/g − b) (s, N). No value is interpolated, so the noise stays σ/g: what
    /// a force RMSE against these samples is compared with, times g. A filter is
    /// undone to first order, as the lag T it is for a slowly varying force (moving
    /// the sample to t − τ − T leaves T²·f̈/2, a few N on the paper's ball at T = 2 µs);
    /// inverting it exactly would amplify the noise the RMSE is judged against.
    pub fn retime(&self, history: &ContactHistory, i: usize) -> (f64, f64) {
        (
            history.time[i] - self.delay - self.filter,
            history.force[i] / self.gain - self.offset,
        )
    }

    /// `run` with the sensor removed from the force track contact `c` reads: the
    /// filter inverted (f = y + T·ẏ, ẏ by central differences), each force vector
    /// replaced by the one recorded τ later (linearly interpolated, the last held) over
    /// g, then b taken off along that sample's contact normal (added back for body 2's
    /// reaction). Motion, torques and the other bodies stay as recorded.
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
        let read: Vec<Vector3<f64>> = track
            .samples
            .iter()
            .map(|s| Vector3::from(s.force))
            .collect();
        let forces = unfiltered(&times, &read, self.filter);
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

/// The input of a first-order low-pass filter of time constant `tau` (s) whose output
/// `y` is sampled at `t`: u = y + T·ẏ, ẏ by central differences (one-sided at the
/// ends). `y` itself for T ≤ 0.
fn unfiltered(t: &[f64], y: &[Vector3<f64>], tau: f64) -> Vec<Vector3<f64>> {
    if !(tau > 0.0 && tau.is_finite()) {
        return y.to_vec();
    }
    let n = y.len();
    (0..n)
        .map(|i| {
            let (a, b) = (i.saturating_sub(1), (i + 1).min(n - 1));
            if t[b] > t[a] {
                y[i] + (y[b] - y[a]) * (tau / (t[b] - t[a]))
            } else {
                y[i]
            }
        })
        .collect()
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
    fn a_filter_is_read_as_generated_and_undone_by_correcting() {
        // The ball through a 2 µs low-pass, noise-free, beside the true force.
        let quiet = ["experiment.force_noise=0.0".to_owned()];
        let clean = ball(&quiet);
        let mut filtered = quiet.to_vec();
        filtered.push("experiment.sensor_filter=2e-6".into());
        let silent = &crate::progress::Silent;
        let truth = crate::experiment::generate(&clean.scenario, 1, 1, silent).unwrap();
        let read = crate::experiment::generate(&ball(&filtered).scenario, 1, 1, silent).unwrap();
        let sensor = Sensor {
            filter: 2e-6,
            ..Sensor::default()
        };
        let (a, raw) = (
            contact_history(&clean, &truth.runs[0], 0).unwrap(),
            contact_history(&clean, &read.runs[0], 0).unwrap(),
        );
        // The generator's filter and `low_pass` are one filter: the true force through
        // it is the reading.
        let through = low_pass(&a.time, &a.force, 2e-6);
        let worst = |x: &[f64], y: &[f64]| {
            x.iter()
                .zip(y)
                .fold(0.0_f64, |m, (p, q)| m.max((p - q).abs()))
        };
        assert!(
            worst(&through, &raw.force) < 1e-6,
            "{}",
            worst(&through, &raw.force)
        );
        // Correcting inverts it: within a few N of a 3 kN pulse (the central difference
        // of a curve), where the raw reading is off by ~100 N.
        let corrected = sensor.correct(&clean, &read.runs[0], 0).unwrap();
        let b = contact_history(&clean, &corrected, 0).unwrap();
        let (fixed, off) = (worst(&b.force, &a.force), worst(&raw.force, &a.force));
        eprintln!("corrected {fixed} N, raw {off} N");
        assert!(fixed < 5.0 && off > 50.0, "corrected {fixed}, raw {off}");
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
            filter: 0.0,
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
