//! The motion of one body through its contacts from the force sensor: where the
//! contacts are in the force samples, and Newton's law m·ẍ = f + m·g integrated through
//! each from the free flight fitted before it, with the uncertainty carried along.

use super::flight::FlightFit;

/// Multiple of the force noise σ above which a force sample is in a contact.
const NOISE_MULTIPLE: f64 = 6.0;
/// Share of the largest force above which a force sample is in a contact, so that
/// noise-free data (σ = 0) do not take rounding for contact.
const PEAK_SHARE: f64 = 0.01;

/// Share of a pulse's duration above the threshold added on each side of it.
const GUARD_SHARE: f64 = 0.5;

/// The force samples of one body: times (s), force on the body (N), per-axis noise σ (N).
pub(super) struct ForceSeries {
    /// Sample times (s), increasing.
    pub(crate) time: Vec<f64>,
    /// Force on the body (N).
    pub(crate) force: Vec<[f64; 3]>,
    /// White-noise σ per axis (N), from second differences.
    pub(crate) noise: [f64; 3],
}

impl ForceSeries {
    /// A series of (time, force) samples, its noise estimated robustly from second
    /// differences (σ = 1.4826·MAD(Δ²f)/√6, which the few curved samples of a
    /// contact do not move).
    pub fn new(samples: Vec<(f64, [f64; 3])>) -> Self {
        let (time, force): (Vec<f64>, Vec<[f64; 3]>) = samples.into_iter().unzip();
        let noise = core::array::from_fn(|k| {
            let mut second: Vec<f64> = force
                .windows(3)
                .map(|w| (w[0][k] - 2.0 * w[1][k] + w[2][k]).abs())
                .collect();
            if second.is_empty() {
                return 0.0;
            }
            let middle = second.len() / 2;
            let (_, median, _) = second.select_nth_unstable_by(middle, f64::total_cmp);
            1.4826 * *median / 6f64.sqrt()
        });
        ForceSeries { time, force, noise }
    }

    /// Index ranges (first..=last) of the contacts: maximal runs of samples whose force
    /// exceeds the threshold, widened by one sample and by half their duration each side
    /// (the threshold cuts the pulse's feet), and merged when no camera frame of `frames` lies between two.
    pub fn contacts(&self, frames: &[f64]) -> Vec<(usize, usize)> {
        let magnitude = |f: &[f64; 3]| f.iter().map(|x| x * x).sum::<f64>().sqrt();
        let largest = self.force.iter().map(magnitude).fold(0.0, f64::max);
        let sigma = self.noise.iter().map(|s| s * s).sum::<f64>().sqrt();
        let threshold = (NOISE_MULTIPLE * sigma).max(PEAK_SHARE * largest);
        let last = self.time.len().saturating_sub(1);
        let mut windows: Vec<(usize, usize)> = Vec::new();
        let mut start = None;
        for (j, f) in self.force.iter().enumerate() {
            let above = magnitude(f) > threshold;
            match (start, above) {
                (None, true) => start = Some(j),
                (Some(first), false) => {
                    windows.push((first.saturating_sub(1), j));
                    start = None;
                }
                _ => {}
            }
        }
        if let Some(first) = start {
            windows.push((first.saturating_sub(1), last));
        }
        // The threshold cuts the feet of the pulse (6σ of a 15 N noise is 5 % of a ball's
        // peak): widen each side by half the pulse's duration above it.
        for window in &mut windows {
            let guard = GUARD_SHARE * (self.time[window.1] - self.time[window.0]);
            let from = self.time[window.0] - guard;
            let to = self.time[window.1] + guard;
            window.0 = self.time.partition_point(|&t| t < from).min(window.0);
            window.1 = (self.time.partition_point(|&t| t <= to).saturating_sub(1)).max(window.1);
        }
        let mut merged: Vec<(usize, usize)> = Vec::new();
        for window in windows {
            match merged.last_mut() {
                Some(previous)
                    if !frames
                        .iter()
                        .any(|&t| t > self.time[previous.1] && t < self.time[window.0]) =>
                {
                    previous.1 = previous.1.max(window.1);
                }
                _ => merged.push(window),
            }
        }
        merged
    }
}

/// The state through one contact, sample by sample.
pub(super) struct Integrated {
    /// Position (m) at each sample of the window.
    pub(crate) position: Vec<[f64; 3]>,
    /// Velocity (m/s) at each sample of the window.
    pub(crate) velocity: Vec<[f64; 3]>,
    /// Variance of the position per axis (m²).
    pub(crate) position_variance: Vec<[f64; 3]>,
    /// Variance of the velocity per axis ((m/s)²).
    pub(crate) velocity_variance: Vec<[f64; 3]>,
}

/// Integrates m·ẍ = f + m·g over samples `first..=last` of `series`, from the flight
/// `before` fitted with t_ref at sample `first`, the force taken piecewise linear between
/// samples (trapezoid rule for the velocity, and for the position its exact double
/// integral, Δp = v_j·h + h²·(2a_j + a_{j+1})/6).
///
/// The variance is the flight fit's, propagated exactly (p_j = p_0 + v_0·τ + known
/// terms), plus the force noise's: σ_f²/m² times the sum of squares of each force
/// sample's weight in p_j and v_j.
pub(super) fn integrate(
    series: &ForceSeries,
    (first, last): (usize, usize),
    before: &FlightFit,
    mass: f64,
) -> Integrated {
    let count = last + 1 - first;
    let (mut p, mut v) = before.state(series.time[first]);
    let acceleration = |j: usize| -> [f64; 3] {
        core::array::from_fn(|k| series.force[j][k] / mass + before.gravity[k])
    };
    // Weights of each force sample (1/m left out) in the current v and p (s, s²).
    let mut weight_v = vec![0.0; count];
    let mut weight_p = vec![0.0; count];
    let mut out = Integrated {
        position: Vec::with_capacity(count),
        velocity: Vec::with_capacity(count),
        position_variance: Vec::with_capacity(count),
        velocity_variance: Vec::with_capacity(count),
    };
    for j in first..=last {
        if j > first {
            let h = series.time[j] - series.time[j - 1];
            let (a0, a1) = (acceleration(j - 1), acceleration(j));
            for k in 0..3 {
                p[k] += v[k] * h + h * h * (2.0 * a0[k] + a1[k]) / 6.0;
                v[k] += 0.5 * h * (a0[k] + a1[k]);
            }
            let i = j - first;
            for (wp, wv) in weight_p.iter_mut().zip(&weight_v) {
                *wp += h * wv;
            }
            weight_p[i - 1] += h * h / 3.0;
            weight_p[i] += h * h / 6.0;
            weight_v[i - 1] += 0.5 * h;
            weight_v[i] += 0.5 * h;
        }
        let (fit_p, fit_v) = before.variance(series.time[j]);
        let squares = |w: &[f64]| w.iter().map(|x| x * x).sum::<f64>();
        let (sp, sv) = (squares(&weight_p), squares(&weight_v));
        let noise = |k: usize| (series.noise[k] / mass).powi(2);
        out.position.push(p);
        out.velocity.push(v);
        out.position_variance
            .push(core::array::from_fn(|k| fit_p[k] + noise(k) * sp));
        out.velocity_variance
            .push(core::array::from_fn(|k| fit_v[k] + noise(k) * sv));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A ball of mass m falling at 1.4 m/s onto a half-sine force pulse of peak F and
    /// duration T starting at t0, sampled every h: (times, forces, exact p and v).
    /// Force samples (time (s), force (N)).
    type Samples = Vec<(f64, [f64; 3])>;

    fn pulse(h: f64) -> (Samples, impl Fn(f64) -> (f64, f64)) {
        let (m, peak, duration, t0, g) = (0.067, 2900.0, 1.1e-4, 2e-4, -9.81);
        let force = move |t: f64| {
            if t > t0 && t < t0 + duration {
                peak * (std::f64::consts::PI * (t - t0) / duration).sin()
            } else {
                0.0
            }
        };
        let w = std::f64::consts::PI / duration;
        // Exact motion: free fall plus the double integral of the half sine.
        let exact = move |t: f64| {
            let (mut p, mut v) = (-1.4 * t + 0.5 * g * t * t, -1.4 + g * t);
            let s = (t - t0).clamp(0.0, duration);
            let dv = peak / m / w * (1.0 - (w * s).cos());
            let dp = peak / m / w * (s - (w * s).sin() / w);
            let after = (t - t0 - duration).max(0.0);
            p += dp + after * 2.0 * peak / m / w;
            v += dv;
            (p, v)
        };
        let samples = (0..(5e-4 / h) as usize)
            .map(|j| {
                let t = j as f64 * h;
                (t, [0.0, 0.0, force(t)])
            })
            .collect();
        (samples, exact)
    }

    #[test]
    fn integration_through_a_half_sine_pulse_follows_newtons_law() {
        // (step (s), share of Δv, position (m)): δ is tens of µm.
        for (h, tolerance, metres) in [(1e-6, 2e-4, 1e-7), (1e-5, 2e-2, 5e-6)] {
            let (samples, exact) = pulse(h);
            let series = ForceSeries::new(samples);
            let windows = series.contacts(&[0.0, 1e-4, 4e-4]);
            assert_eq!(windows.len(), 1, "h = {h}");
            let (first, last) = windows[0];
            let frames: Vec<(f64, [f64; 3])> = (0..4)
                .map(|i| {
                    let t = i as f64 * 5e-5;
                    (t, [0.0, 0.0, exact(t).0])
                })
                .collect();
            let fit = FlightFit::fit(&frames, [0.0, 0.0, -9.81], series.time[first]).unwrap();
            let out = integrate(&series, (first, last), &fit, 0.067);
            let end = series.time[last];
            let (p, v) = exact(end);
            let dv = 2.0 * 2900.0 / 0.067 / (std::f64::consts::PI / 1.1e-4);
            assert!(
                (out.velocity[last - first][2] - v).abs() < tolerance * dv,
                "h = {h}: v {} vs {v}",
                out.velocity[last - first][2]
            );
            assert!(
                (out.position[last - first][2] - p).abs() < metres,
                "h = {h}: p {} vs {p}",
                out.position[last - first][2]
            );
        }
    }

    #[test]
    fn the_noise_of_a_flat_force_is_estimated_from_second_differences() {
        let samples: Vec<(f64, [f64; 3])> = (0..4000)
            .map(|j| {
                // A deterministic ±σ sequence with a slow trend the differences remove.
                let sign = if (j * 7919) % 13 < 6 { 1.0 } else { -1.0 };
                (j as f64 * 1e-6, [0.0, 0.0, 0.01 * j as f64 + 15.0 * sign])
            })
            .collect();
        let series = ForceSeries::new(samples);
        assert!(
            series.noise[2] > 5.0 && series.noise[2] < 40.0,
            "{:?}",
            series.noise
        );
        assert_eq!(series.noise[0], 0.0);
    }
}
