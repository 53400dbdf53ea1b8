//! The displacement a body's measured contact force implies through one contact:
//! Newton's law m·ẍ = f integrated from rest at the window's start, the force taken as a
//! cubic between its samples (Hermite with central-difference slopes): a smooth 113 µs
//! pulse sampled at 100 kHz — ten samples per contact — integrates to within 3e-8 m,
//! where the piecewise linear force of [`super::through_contact`] is off by 3.5e-7 m.
//!
//! Gravity and the state at the start are left out: they are what a fit to recorded
//! motion supplies (`p0 + v0·s + ½·g·s² + D(t)`, s = t − t0).

use super::through_contact::ForceSeries;

/// D(t) and V(t) = Ḋ(t) (m, m/s) of one contact window, from rest at its first sample.
pub(super) struct Implied {
    /// Sample times of the window (s).
    time: Vec<f64>,
    /// Displacement D at each sample (m).
    displacement: Vec<[f64; 3]>,
    /// Velocity change V at each sample (m/s).
    velocity: Vec<[f64; 3]>,
    /// Acceleration (f − b)/m at each sample (m/s²).
    acceleration: Vec<[f64; 3]>,
}

impl Implied {
    /// Over samples `first..=last` of `series`, the force less `offset` (N) — what the
    /// sensor reads without contact — on a body of mass `mass` (kg).
    pub fn new(
        series: &ForceSeries,
        (first, last): (usize, usize),
        offset: [f64; 3],
        mass: f64,
    ) -> Self {
        let (t, f) = (&series.time, &series.force);
        let n = t.len();
        let a = |j: usize| -> [f64; 3] { core::array::from_fn(|k| (f[j][k] - offset[k]) / mass) };
        // Central-difference slope of the acceleration at sample j (one-sided at the ends).
        let slope = |j: usize| -> [f64; 3] {
            let (l, r) = (j.saturating_sub(1), (j + 1).min(n - 1));
            let h = t[r] - t[l];
            core::array::from_fn(|k| {
                if h > 0.0 {
                    (a(r)[k] - a(l)[k]) / h
                } else {
                    0.0
                }
            })
        };
        let mut out = Implied {
            time: vec![t[first]],
            displacement: vec![[0.0; 3]],
            velocity: vec![[0.0; 3]],
            acceleration: vec![a(first)],
        };
        let (mut d, mut v) = ([0.0; 3], [0.0; 3]);
        for j in first + 1..=last {
            let h = t[j] - t[j - 1];
            let (a0, a1, s0, s1) = (a(j - 1), a(j), slope(j - 1), slope(j));
            for k in 0..3 {
                // Exact integrals of the cubic Hermite piece: ∫a and ∫(h − u)·a(u) du.
                d[k] += v[k] * h
                    + h * h * (7.0 * a0[k] + 3.0 * a1[k]) / 20.0
                    + h * h * h * (s0[k] / 20.0 - s1[k] / 30.0);
                v[k] += h * (a0[k] + a1[k]) / 2.0 + h * h * (s0[k] - s1[k]) / 12.0;
            }
            out.time.push(t[j]);
            out.displacement.push(d);
            out.velocity.push(v);
            out.acceleration.push(a1);
        }
        out
    }

    /// The window's first sample time t0 (s).
    pub fn start(&self) -> f64 {
        self.time[0]
    }

    /// The window's duration (s).
    pub fn duration(&self) -> f64 {
        self.time[self.time.len() - 1] - self.time[0]
    }

    /// (D, V) along axis `k` at time `t` (s): 0 before the window, a cubic Hermite
    /// between its samples (D with slopes V, V with slopes the acceleration), and free
    /// motion after it.
    pub fn at(&self, t: f64, k: usize) -> (f64, f64) {
        let n = self.time.len();
        if t <= self.time[0] {
            return (0.0, 0.0);
        }
        if t >= self.time[n - 1] {
            let (d, v) = (self.displacement[n - 1][k], self.velocity[n - 1][k]);
            return (d + v * (t - self.time[n - 1]), v);
        }
        let j = self.time.partition_point(|&x| x <= t);
        let (i, h) = (j - 1, self.time[j] - self.time[j - 1]);
        let x = (t - self.time[i]) / h;
        let hermite = |y0: f64, y1: f64, d0: f64, d1: f64| {
            let (x2, x3) = (x * x, x * x * x);
            (2.0 * x3 - 3.0 * x2 + 1.0) * y0
                + (x3 - 2.0 * x2 + x) * h * d0
                + (-2.0 * x3 + 3.0 * x2) * y1
                + (x3 - x2) * h * d1
        };
        let (d, v, a) = (&self.displacement, &self.velocity, &self.acceleration);
        (
            hermite(d[i][k], d[j][k], v[i][k], v[j][k]),
            hermite(v[i][k], v[j][k], a[i][k], a[j][k]),
        )
    }

    /// The acceleration (f − b)/m along axis `k` at time `t` (m/s²): linear between the
    /// window's samples, 0 outside it.
    pub fn acceleration(&self, t: f64, k: usize) -> f64 {
        let n = self.time.len();
        if t <= self.time[0] || t >= self.time[n - 1] {
            return 0.0;
        }
        let j = self.time.partition_point(|&x| x <= t);
        let (i, h) = (j - 1, self.time[j] - self.time[j - 1]);
        let x = (t - self.time[i]) / h;
        let a = &self.acceleration;
        a[i][k] + x * (a[j][k] - a[i][k])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_smooth_pulse_integrates_to_its_closed_form_at_100_khz() {
        // F·sin²(w·s) over T = π/w (starting and ending with zero slope, as a contact
        // law's force does): V = F/m·(s/2 − sin(2ws)/(4w)),
        // D = F/m·(s²/4 + (cos(2ws) − 1)/(8w²)). Linear interpolation of the same
        // samples is off by 3.5e-7 m in D and 1e-2 m/s in V (measured).
        let (m, peak, duration, h) = (0.067, 2900.0, 1.13e-4, 1e-5);
        let w = std::f64::consts::PI / duration;
        let samples: Vec<(f64, [f64; 3])> = (0..40)
            .map(|j| {
                let t = j as f64 * h - 1e-4;
                let f = if t > 0.0 && t < duration {
                    peak * (w * t).sin().powi(2)
                } else {
                    0.0
                };
                (t, [0.0, 0.0, f])
            })
            .collect();
        let series = ForceSeries::new(samples);
        let implied = Implied::new(&series, (5, 30), [0.0; 3], m);
        for t in [3e-5_f64, 6e-5, 1.1e-4, 1.5e-4] {
            let s = t.min(duration);
            let v = peak / m * (s / 2.0 - (2.0 * w * s).sin() / (4.0 * w));
            let d = peak / m * (s * s / 4.0 + ((2.0 * w * s).cos() - 1.0) / (8.0 * w * w));
            let (di, vi) = implied.at(t, 2);
            assert!(
                (di - (d + v * (t - s))).abs() < 3e-8,
                "t = {t}: D {di} vs {d}"
            );
            assert!((vi - v).abs() < 1e-3, "t = {t}: V {vi} vs {v}");
        }
        assert_eq!(implied.at(-2e-4, 2), (0.0, 0.0));
    }
}
