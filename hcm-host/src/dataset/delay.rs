//! A force sensor that lags the camera, found and undone by the reconstruction.
//!
//! Integrating a force read τ late from the flight before the contact moves the whole
//! contact τ late: the ball leaves the ground late and lands on the camera's flight
//! after it off by the velocity change times τ. Since no force acts at the window's
//! ends, that gap is exactly linear in τ: at the window's end the integration taken
//! τ on (free motion past its last sample) less the flight before taken τ on gives
//!
//! gap(τ) = gap(0) + Δv·τ  (per axis; Δv the force's velocity change over the contact),
//!
//! so the delay that puts every contact on its after-flight is the weighted least
//! squares τ̂ = −Σ gap·Δv/sd² / Σ Δv²/sd² over contacts and axes, with variance
//! 1/Σ Δv²/sd² ([`fit`]); it is used when the gaps without it are too large or τ̂ is
//! more than `DELAY_SIGMAS` standard deviations from 0. The motion at each force sample t is then the integration
//! read at t + τ̂ with the flight before put back at t (`shift`): the motion as it
//! was, against which the force reads τ̂ late — what the diagnosis names as a sensor
//! delay. τ̂'s own uncertainty is carried per row: δ moves by Δv(t)·dτ and δ̇ by
//! a(t)·dτ. A delay does not change the velocity gap; data whose velocity misses the
//! after-flight (a wrong mass, a force scale) stay incoherent under any τ.

use super::flight::FlightFit;
use super::reconstruct::Completed;
use super::through_contact::Integrated;

/// Standard deviations from 0 beyond which a fitted delay is taken as real (–): by
/// chance a normal deviate passes 5 once in 1.7 million. Measured on the rig's camera
/// rows (tests/diagnose/diagnose_rig.rs, 20 data sets without a delay): |τ̂|/sd ≤ 1.7; a 1 µs
/// delay: 6.0–7.7.
pub(crate) const DELAY_SIGMAS: f64 = 5.0;

/// A sensor delay fitted by the reconstruction.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Delay {
    /// Delay τ of the force behind the camera (s).
    pub value: f64,
    /// Its standard deviation (s).
    pub sd: f64,
}

/// The delay that best closes the position gaps of every contact of `completed`
/// reconstructed from camera frames (see the module documentation); None without a
/// contact with a flight after it.
pub fn fit_delay(completed: &Completed<'_>) -> Option<Delay> {
    let (mut num, mut den) = (0.0, 0.0);
    let checks = completed
        .tracks
        .iter()
        .flatten()
        .flatten()
        .flat_map(|t| &t.contacts);
    for check in checks {
        let Some((gap, sd)) = check.position_gap else {
            continue;
        };
        for k in 0..3 {
            if sd[k] > 0.0 {
                let w = 1.0 / (sd[k] * sd[k]);
                num -= w * gap[k] * check.velocity_change[k];
                den += w * check.velocity_change[k].powi(2);
            }
        }
    }
    (den > 0.0).then(|| Delay {
        value: num / den,
        sd: den.sqrt().recip(),
    })
}

/// The delay behind motion recorded on every row (a camera's frames splined onto the
/// force rows, `super::newton`): the delays its contacts' checks fitted, `delays` (s),
/// pooled — their mean, its standard deviation their spread over √n (each contact's is
/// fitted against its own frames, so they are independent); None with fewer than 2
/// contacts. Taken as real, as the camera rows' ([`fit`]), beyond [`DELAY_SIGMAS`]
/// standard deviations from 0 (`Delay::real`).
pub(crate) fn pooled(delays: &[f64]) -> Option<Delay> {
    let n = delays.len();
    if n < 2 {
        return None;
    }
    let mean = delays.iter().sum::<f64>() / n as f64;
    let variance = delays.iter().map(|d| (d - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
    Some(Delay {
        value: mean,
        sd: (variance / n as f64).sqrt(),
    })
}

impl Delay {
    /// Whether it lies beyond [`DELAY_SIGMAS`] standard deviations from 0.
    pub(crate) fn real(&self) -> bool {
        self.value.abs() > DELAY_SIGMAS * self.sd
    }
}

/// `through` (integrated over samples at `time`, from the flight `before`, with
/// accelerations `acceleration` (m/s², gravity included) at those samples) as it is
/// when the force read `delay` late: state at t from the integration at t + τ, the
/// flight before put back at t; τ's variance added (see the module documentation).
pub(super) fn shift(
    through: &mut Integrated,
    time: &[f64],
    acceleration: &[[f64; 3]],
    before: &FlightFit,
    delay: Delay,
) {
    let original = (through.position.clone(), through.velocity.clone());
    let n = time.len();
    let g = before.gravity;
    // State of the integration at time s: Hermite between samples, free motion after.
    let at = |s: f64| -> ([f64; 3], [f64; 3], [f64; 3]) {
        let (p, v) = (&original.0, &original.1);
        if s <= time[0] {
            let (bp, bv) = before.state(s);
            return (bp, bv, g);
        }
        if s >= time[n - 1] {
            let d = s - time[n - 1];
            let pos = core::array::from_fn(|k| p[n - 1][k] + v[n - 1][k] * d + 0.5 * g[k] * d * d);
            let vel = core::array::from_fn(|k| v[n - 1][k] + g[k] * d);
            return (pos, vel, g);
        }
        let j = time.partition_point(|&x| x <= s);
        let (i, h) = (j - 1, time[j] - time[j - 1]);
        let x = (s - time[i]) / h;
        let cubic = |y0: f64, y1: f64, d0: f64, d1: f64| {
            let (x2, x3) = (x * x, x * x * x);
            (2.0 * x3 - 3.0 * x2 + 1.0) * y0
                + (x3 - 2.0 * x2 + x) * h * d0
                + (-2.0 * x3 + 3.0 * x2) * y1
                + (x3 - x2) * h * d1
        };
        let (a0, a1) = (acceleration[i], acceleration[j]);
        (
            core::array::from_fn(|k| cubic(p[i][k], p[j][k], v[i][k], v[j][k])),
            core::array::from_fn(|k| cubic(v[i][k], v[j][k], a0[k], a1[k])),
            core::array::from_fn(|k| a0[k] + x * (a1[k] - a0[k])),
        )
    };
    let variance = delay.sd * delay.sd;
    for (i, &t) in time.iter().enumerate() {
        let s = t + delay.value;
        let (p, v, a) = at(s);
        let (later_p, later_v) = before.state(s);
        let (now_p, now_v) = before.state(t);
        for k in 0..3 {
            let change = v[k] - later_v[k];
            through.position[i][k] = p[k] - later_p[k] + now_p[k];
            through.velocity[i][k] = change + now_v[k];
            through.position_variance[i][k] += change * change * variance;
            through.velocity_variance[i][k] += (a[k] - g[k]).powi(2) * variance;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contacts_delays_pool_to_their_mean_with_its_standard_error() {
        let d = pooled(&[1e-6, 2e-6, 3e-6]).unwrap();
        assert!((d.value - 2e-6).abs() < 1e-18, "{d:?}");
        assert!((d.sd - 1e-6 / 3f64.sqrt()).abs() < 1e-18, "{d:?}");
        // 3.5 standard deviations from 0: not taken as real; a tighter spread is.
        assert!(!d.real());
        assert!(pooled(&[1.9e-6, 2e-6, 2.1e-6]).unwrap().real());
        assert_eq!(pooled(&[2e-6]), None);
    }
    use crate::dataset::through_contact::{integrate, ForceSeries};

    #[test]
    fn shifting_the_integration_of_a_late_force_gives_the_motion_as_it_was() {
        // A sin² pulse of peak F over T on a ball falling at 1.4 m/s, read τ late at
        // 1 MHz; the flight before is exact (no noise). The shift moves the motion by
        // up to Δv·τ = 7 µm; what is left is the linear force's integration error
        // (the trapezoid's, 1e-4 m/s of the 2.45 m/s pulse).
        let (m, peak, duration, g, tau) = (0.067, 2900.0, 1.13e-4, -9.81, 3e-6);
        let (t0, w) = (5e-5, std::f64::consts::PI / duration);
        let force = |t: f64| {
            let s = t - t0;
            if s > 0.0 && s < duration {
                peak * (w * s).sin().powi(2)
            } else {
                0.0
            }
        };
        // The true motion: free fall plus the pulse's closed-form integrals.
        let exact = |t: f64| {
            let s = (t - t0).clamp(0.0, duration);
            let v = peak / m * (s / 2.0 - (2.0 * w * s).sin() / (4.0 * w));
            let d = peak / m * (s * s / 4.0 + ((2.0 * w * s).cos() - 1.0) / (8.0 * w * w));
            let after = (t - t0 - duration).max(0.0);
            (-1.4 * t + 0.5 * g * t * t + d + v * after, -1.4 + g * t + v)
        };
        let samples: Vec<(f64, [f64; 3])> = (0..300)
            .map(|j| {
                let t = j as f64 * 1e-6;
                (t, [0.0, 0.0, force(t - tau)])
            })
            .collect();
        let series = ForceSeries::new(samples);
        let frames: Vec<(f64, [f64; 3])> = (0..5)
            .map(|i| {
                let t = i as f64 * 1e-5;
                (t, [0.0, 0.0, exact(t).0])
            })
            .collect();
        let (first, last) = (40, 200);
        let before = FlightFit::fit(&frames, [0.0, 0.0, g], series.time[first]).unwrap();
        let mut through = integrate(&series, (first, last), &before, m);
        let acceleration: Vec<[f64; 3]> = (first..=last)
            .map(|j| [0.0, 0.0, series.force[j][2] / m + g])
            .collect();
        let time = &series.time[first..=last];
        let delay = Delay {
            value: tau,
            sd: 1e-7,
        };
        shift(&mut through, time, &acceleration, &before, delay);
        for (i, &t) in time.iter().enumerate() {
            let (p, v) = exact(t);
            assert!(
                (through.position[i][2] - p).abs() < 1e-8,
                "t = {t}: {}",
                through.position[i][2] - p
            );
            assert!(
                (through.velocity[i][2] - v).abs() < 5e-4,
                "t = {t}: {}",
                through.velocity[i][2] - v
            );
        }
        // τ's variance: δ moves by Δv·sd(τ) at the end, 2.45 m/s × 0.1 µs.
        let end = time.len() - 1;
        let spread = through.position_variance[end][2].sqrt();
        assert!((spread / (2.446 * 1e-7) - 1.0).abs() < 0.01, "{spread}");
    }
}
