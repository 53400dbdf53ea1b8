//! The force sensor's gain from the momentum balance, before any physics is judged.
//!
//! A sensor that reads g·f instead of f cannot be told from a stiffer contact by the
//! force alone: every law's force scales with its stiffness. The motion tells them
//! apart. Over a window that holds one whole contact event, the impulse the contact
//! gave equals the change of the bodies' relative momentum along the normal,
//!
//! ∫ f dt = m_eff·(δ̇_before(t*) − δ̇_after(t*))  (N·s),
//!
//! with δ̇_before and δ̇_after the free flights on either side (lines in t, so that a
//! constant gravity or any other constant external acceleration cancels) evaluated at
//! the same instant t*, the event's middle. The reading's integral over the window,
//! less the sensor's offset (its mean reading in flight) times the window, is g times
//! that impulse whatever the contact law is: each event gives one ratio ĝ_e, and the
//! events' spread gives its uncertainty, so run-to-run scatter of the contact itself
//! never shows as a gain.
//!
//! Only motion recorded at the samples is used: a motion reconstructed from the force
//! through Newton's law ([`crate::dataset::newton`]) would give the force's own impulse
//! back. No gain is estimated without three events with flight samples on both sides.

use super::select::{Cause, Fitted, Refit};
use super::ContactSamples;
use super::Family;
use serde::Serialize;

/// Events a gain is estimated from at least.
pub const MIN_EVENTS: usize = 3;

/// Standard errors by which ĝ must differ from 1 to be named (–): a t-interval at
/// 99.99 % for a handful of events, so that a diagnosis of an ideal sensor names a
/// gain about once in ten thousand.
pub const GAIN_SIGMAS: f64 = 4.0;

/// Flight samples on each side of an event the flight line is fitted to, at most.
const FLIGHT_SAMPLES: usize = 32;

/// The gain the momentum balance gives.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SensorGain {
    /// ĝ, the mean of the events' ratios of read to delivered impulse (–).
    pub value: f64,
    /// Its standard error, the ratios' sd over √events (–).
    pub standard_error: f64,
    /// Contact events it is estimated from.
    pub events: usize,
    /// Whether it differs from 1 by more than [`GAIN_SIGMAS`] standard errors, and the
    /// sensor reads its offset in flight after the contacts: named.
    pub named: bool,
    /// The flight check's χ² and its threshold (–) where the sensor does not read its
    /// offset in flight after the contacts (`flight_after_contacts`): it rings or
    /// drifts, its impulse is not the contact's alone, and no gain is named.
    pub rings: Option<(f64, f64)>,
}

impl SensorGain {
    /// Its 95 % interval (–).
    pub fn interval(&self) -> (f64, f64) {
        let half = 1.96 * self.standard_error;
        (self.value - half, self.value + half)
    }
}

/// The sensor's gain from the events of `samples` (effective mass `mass` (kg) of the
/// contact's normal motion), or None where fewer than [`MIN_EVENTS`] events have
/// recorded flights on both sides.
pub fn sensor_gain(samples: &ContactSamples, mass: f64) -> Option<SensorGain> {
    if !(mass > 0.0 && mass.is_finite()) {
        return None;
    }
    // Each event as the indices of its first and last in-contact samples.
    let events: Vec<(usize, usize)> = samples
        .events()
        .iter()
        .map(|e| (e.start, e.end - 1))
        .collect();
    let windows: Vec<(usize, usize)> = events.iter().map(|&e| window(samples, e)).collect();
    let offset = flight_reading(samples, &windows)?;
    let ratios: Vec<Ratio> = events
        .iter()
        .zip(&windows)
        .enumerate()
        .filter_map(|(k, (&event, &window))| {
            // The flights: every sample apart between this event and its neighbours,
            // inside the window too (a lagging sensor delays the force, not the motion).
            let previous = k.checked_sub(1).map_or(0, |p| events[p].1 + 1);
            let next = events.get(k + 1).map_or(samples.len(), |e| e.0);
            let middle = 0.5 * (samples.time[event.0] + samples.time[event.1]);
            let run = samples.run[event.0];
            let before = flight_rate(samples, (previous..event.0).rev(), run, middle)?;
            let after = flight_rate(samples, event.1 + 1..next, run, middle)?;
            let delivered = mass * (before - after);
            let (read, quadrature) = impulse(samples, window, offset.0);
            let span = samples.time[window.1] - samples.time[window.0];
            (delivered > 0.0).then(|| Ratio {
                gain: read / delivered,
                quadrature: quadrature / delivered,
                offset_weight: span / delivered,
            })
        })
        .filter(|r| r.gain.is_finite() && r.quadrature.is_finite() && r.offset_weight.is_finite())
        .collect();
    let n = ratios.len();
    if n < MIN_EVENTS {
        return None;
    }
    let mean = |f: &dyn Fn(&Ratio) -> f64| ratios.iter().map(f).sum::<f64>() / n as f64;
    let value = mean(&|r| r.gain);
    let variance = mean(&|r| (r.gain - value).powi(2)) * n as f64 / (n - 1) as f64;
    // Two errors common to every event do not show in their spread and are added: the
    // trapezoids' (its estimate averaged over the events, where the noise in it
    // cancels), and the shared offset's, its standard error times the mean window
    // over delivered impulse.
    let systematic = mean(&|r| r.quadrature);
    let shared = offset.1 * mean(&|r| r.offset_weight);
    let standard_error = (variance / n as f64 + systematic.powi(2) + shared.powi(2)).sqrt();
    let rings = flight_after_contacts(samples, &events, offset.0);
    Some(SensorGain {
        value,
        standard_error,
        events: n,
        named: (value - 1.0).abs() > GAIN_SIGMAS * standard_error && rings.is_none(),
        rings,
    })
}

/// Bins of time since lift-off in which [`flight_after_contacts`] averages the
/// readings over the events (–).
const FLIGHT_BINS: usize = 8;

/// Standard deviations of χ² (√(2·dof)) beyond its degrees of freedom at which the
/// readings after the contacts are not the offset (–): the residual structure test's
/// margin (`structure`).
const FLIGHT_SIGMAS: f64 = 5.0;

/// Whether the sensor reads its offset `offset` (N) in flight after the contacts
/// `events` (first, last in-contact index): None if it does, else the χ² of the
/// readings' means less the offset and its threshold (–). A gain scales the force and
/// nothing else; a mount that rings after the touch-down, or an offset that drifts with
/// the load, reads in flight too, and its impulse in the gain's window is not the
/// contact's. The readings apart from contact from ¼ to 1¼ of the event's duration
/// after its lift-off (past the lag the re-fit's delay search reaches, `select`) are
/// averaged over the events in [`FLIGHT_BINS`] bins of time since lift-off, each mean
/// judged against the noise σ/√n (σ from the readings' second differences,
/// [`super::noise`]): χ² = Σ mean²/(σ²/n) beyond dof + [`FLIGHT_SIGMAS`]·√(2·dof).
/// Measured on the rig (tests/diagnose/diagnose_rig.rs): a mount ringing at 2 % of the peak at
/// 15 kHz, decaying over 200 µs, gives χ² 235 against 18. One ringing at 8 kHz that is
/// gone a quarter of a contact after lift-off is not seen, and still reads as a gain
/// of 1.005.
fn flight_after_contacts(
    samples: &ContactSamples,
    events: &[(usize, usize)],
    offset: f64,
) -> Option<(f64, f64)> {
    let sigma = super::noise::noise_floor(samples).sigma;
    if !(sigma > 0.0 && sigma.is_finite()) {
        return None;
    }
    let mut bins = [(0.0, 0usize); FLIGHT_BINS];
    for (k, &(first, last)) in events.iter().enumerate() {
        let (lift_off, run) = (samples.time[last], samples.run[last]);
        let duration = lift_off - samples.time[first];
        let next = events.get(k + 1).map_or(samples.len(), |e| e.0);
        let flight = (last + 1..next).take_while(|&i| samples.run[i] == run);
        for i in flight.filter(|&i| !samples.in_contact[i]) {
            let since = (samples.time[i] - lift_off) / duration - 0.25;
            if (0.0..1.0).contains(&since) {
                let b = &mut bins[(since * FLIGHT_BINS as f64) as usize];
                b.0 += samples.measured[i] - offset;
                b.1 += 1;
            }
        }
    }
    let filled = bins.iter().filter(|b| b.1 > 0);
    let dof = filled.clone().count() as f64;
    let chi_squared: f64 = filled
        .map(|&(sum, n)| sum * sum / (n as f64 * sigma * sigma))
        .sum();
    let threshold = dof + FLIGHT_SIGMAS * (2.0 * dof).sqrt();
    (dof > 0.0 && chi_squared > threshold).then_some((chi_squared, threshold))
}

/// The window of `event` (first, last in-contact index) the read impulse is summed
/// over: the event widened on each side through the run's samples apart, as long as
/// they follow at most 1.5 in-contact sample steps apart and lie within a quarter of
/// the event's duration of it — room for a sensor lagging as much as the re-fit's
/// delay search reaches (`select`), without integrating across a sparse flight's gaps
/// or leaving too few samples outside to read the offset from.
fn window(samples: &ContactSamples, (first, last): (usize, usize)) -> (usize, usize) {
    let t = &samples.time;
    let run = samples.run[first];
    let step = if last > first {
        (t[last] - t[first]) / (last - first) as f64
    } else {
        f64::INFINITY
    };
    let reach = 0.25 * (t[last] - t[first]);
    let apart = |j: usize| samples.run[j] == run && !samples.in_contact[j];
    let (mut a, mut b) = (first, last);
    while a > 0 && apart(a - 1) && t[a] - t[a - 1] <= 1.5 * step && t[first] - t[a - 1] <= reach {
        a -= 1;
    }
    while b + 1 < samples.len()
        && apart(b + 1)
        && t[b + 1] - t[b] <= 1.5 * step
        && t[b + 1] - t[last] <= reach
    {
        b += 1;
    }
    (a, b)
}

/// One event's ratio of read to delivered impulse (–), the trapezoids' error of it
/// (–), and its sensitivity to the offset, window length over delivered impulse (1/N).
struct Ratio {
    gain: f64,
    quadrature: f64,
    offset_weight: f64,
}

/// The sensor's mean reading apart from contact, outside every window, and its
/// standard error (N): its offset. None without two such samples (an offset could not
/// be told from a gain).
fn flight_reading(samples: &ContactSamples, windows: &[(usize, usize)]) -> Option<(f64, f64)> {
    let mut inside = vec![false; samples.len()];
    for &(a, b) in windows {
        inside[a..=b].iter_mut().for_each(|x| *x = true);
    }
    let readings: Vec<f64> = (0..samples.len())
        .filter(|&i| !inside[i] && !samples.in_contact[i])
        .map(|i| samples.measured[i])
        .collect();
    let n = readings.len() as f64;
    if readings.len() < 2 {
        return None;
    }
    let mean = readings.iter().sum::<f64>() / n;
    let variance = readings.iter().map(|y| (y - mean).powi(2)).sum::<f64>() / (n - 1.0);
    Some((mean, (variance / n).sqrt()))
}

/// The read impulse over `window` less the offset's share (N·s), by trapezoids
/// between successive samples, and the trapezoids' error estimated by Richardson's
/// rule, (T_h − T_2h)/3 over the window's even-length part (N·s).
fn impulse(samples: &ContactSamples, (a, b): (usize, usize), offset: f64) -> (f64, f64) {
    let trapezoids = |stride: usize, end: usize| -> f64 {
        (a..end)
            .step_by(stride)
            .map(|i| {
                let j = i + stride;
                let h = samples.time[j] - samples.time[i];
                0.5 * h * (samples.measured[i] + samples.measured[j] - 2.0 * offset)
            })
            .sum()
    };
    let even = b - (b - a) % 2;
    let quadrature = if even > a {
        (trapezoids(1, even) - trapezoids(2, even)) / 3.0
    } else {
        0.0
    };
    (trapezoids(1, b), quadrature)
}

/// The flight's δ̇ at `at` (m/s): a least-squares line through up to
/// [`FLIGHT_SAMPLES`] samples of run `run` apart from contact, taken in the order of
/// `indices` (outward from the event) until a sample is in contact or of another run.
/// None with fewer than two, or if any of them was reconstructed rather than recorded.
fn flight_rate(
    samples: &ContactSamples,
    indices: impl Iterator<Item = usize>,
    run: usize,
    at: f64,
) -> Option<f64> {
    let mut points = Vec::with_capacity(FLIGHT_SAMPLES);
    for i in indices {
        if samples.run[i] != run || samples.in_contact[i] || points.len() == FLIGHT_SAMPLES {
            break;
        }
        if samples.reconstructed(i) {
            return None;
        }
        points.push((samples.time[i] - at, samples.rate[i]));
    }
    let n = points.len() as f64;
    if points.len() < 2 {
        return None;
    }
    let (mt, mv) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), (t, v)| (a + t / n, b + v / n));
    let (stt, stv) = points.iter().fold((0.0, 0.0), |(a, b), (t, v)| {
        (a + (t - mt).powi(2), b + (t - mt) * (v - mv))
    });
    if stt <= 0.0 {
        return None;
    }
    // The line's value at t = `at`, i.e. at 0 in the shifted times.
    Some(mv - stv / stt * mt)
}

/// `fit`, re-fitted on samples whose readings were divided by `gain`'s ĝ, with the
/// gain put back: its sensor reads with ĝ, and the gain becomes a cause whose share is
/// the RSS it removes in the reading's units, Σ(ĝ·y − p)² − ĝ²·Σ(y − p)² (N²), the
/// other shares rescaled so that all still add up to 1 with the unexplained one.
pub(crate) fn with_gain(fit: &mut Refit, corrected: &ContactSamples, gain: &SensorGain) -> Cause {
    let g = gain.value;
    let predicted = fit.sensor.reads(corrected, &fit.law);
    let without: f64 = predicted
        .iter()
        .zip(&corrected.measured)
        .map(|(p, y)| (g * y - p).powi(2))
        .sum();
    let removed = (without - g * g * fit.rss).max(0.0);
    let total = g * g * fit.structured + removed;
    let keep = if total > 0.0 {
        g * g * fit.structured / total
    } else {
        1.0
    };
    fit.causes.iter_mut().for_each(|c| c.share *= keep);
    fit.left_share *= keep;
    fit.structured = total;
    fit.sensor.gain = g;
    Cause {
        effect: "sensor_gain",
        family: Family::Measurement,
        parameters: vec![Fitted {
            name: "gain".into(),
            value: g,
            ci: gain.interval(),
        }],
        share: if total > 0.0 { removed / total } else { 0.0 },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs of a unit-mass body bouncing at 2 m/s under gravity 9.81 m/s²: a half-sine
    /// force pulse of impulse 4 N·s (+ the gravity's share) over 1 ms, read with `gain`
    /// and offset 3 N, sampled every 10 µs with 80 flight samples on each side.
    fn bounces(gain: f64, runs: usize) -> ContactSamples {
        let mut s = ContactSamples::default();
        let (duration, g, v0) = (1e-3, 9.81, 2.0);
        let peak = (2.0 * v0 + g * duration) * std::f64::consts::PI / (2.0 * duration);
        for r in 0..runs {
            let jitter = 1.0 + 0.02 * (r as f64 - 1.0); // run-to-run scatter of the speed
            for k in -80..=180 {
                let t = k as f64 * 1e-5;
                let inside = (0.0..=duration).contains(&t) && k > 0 && k < 100;
                let f = if inside {
                    jitter * peak * (std::f64::consts::PI * t / duration).sin()
                } else {
                    0.0
                };
                // δ̇ = v0 + g·t − ∫f/m, integrated in closed form.
                let pulse = if t <= 0.0 {
                    0.0
                } else if t >= duration {
                    2.0 * jitter * peak * duration / std::f64::consts::PI
                } else {
                    jitter * peak * duration / std::f64::consts::PI
                        * (1.0 - (std::f64::consts::PI * t / duration).cos())
                };
                s.run.push(r);
                s.time.push(t);
                s.depth.push(if inside { 1e-6 } else { -1e-6 });
                s.rate.push(jitter * v0 + g * t - pulse);
                s.approach_speed.push(if inside { v0 } else { 0.0 });
                s.max_depth.push(0.0);
                s.in_contact.push(inside);
                s.measured.push(gain * f + 3.0);
                s.depth_sd.push(0.0);
                s.rate_sd.push(0.0);
            }
        }
        s
    }

    #[test]
    fn the_gain_is_the_read_over_the_delivered_impulse() {
        for gain in [1.0, 1.03, 0.97] {
            let found = sensor_gain(&bounces(gain, 4), 1.0).unwrap();
            assert_eq!(found.events, 4);
            // Trapezoids over 100 steps of a half sine: relative error ~ (π/100)²/12.
            assert!((found.value - gain).abs() < 2e-4, "{gain}: {found:?}");
            assert_eq!(found.named, gain != 1.0, "{gain}: {found:?}");
        }
    }

    #[test]
    fn reconstructed_motion_or_too_few_events_give_no_gain() {
        assert!(sensor_gain(&bounces(1.03, 2), 1.0).is_none());
        let mut s = bounces(1.03, 4);
        s.rate_sd.iter_mut().for_each(|x| *x = 1e-3);
        assert!(sensor_gain(&s, 1.0).is_none());
        assert!(sensor_gain(&bounces(1.03, 4), f64::NAN).is_none());
    }
}
