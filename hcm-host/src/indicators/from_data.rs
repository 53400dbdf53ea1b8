//! Indicators read back from sampled data (simulated or measured).
//!
//! The indentation is recomputed from the bodies' recorded motion and the
//! scenario's geometry, so touch-down and lift-off are the interpolated δ = 0
//! crossings, not the nearest samples. Sampling error bounds (1 µs sampling, a
//! smooth contact of ~100 µs): δ between samples by cubic Hermite on (δ, δ̇), so
//! crossing times are exact to O(h⁴); δ̇ at a crossing extrapolated from the free
//! flight side, f_n there by linear interpolation; the impulse by the trapezoid rule (relative error ≈ (πh/T)²/12);
//! the peak by a local degree-4 least-squares fit around the maximum (see [`peak`]),
//! which removes the upward bias a noisy maximum has.

use super::{ContactEvent, RecordedEvent};
use crate::dataset::{BodyTrack, Run};
use crate::numerics::linear_least_squares;
use crate::scenario::pair_kinematics;
use crate::scenario::Model;
use hcm_core::integrate::hermite_zero;
use nalgebra::Vector3;

/// Why indicators could not be read from a run.
#[derive(Debug, thiserror::Error)]
pub enum IndicatorError {
    /// A moving body of a contact has no rows in the run.
    #[error("run `{run}` has no rows for body `{body}`, which the scenario's contacts need")]
    MissingBody {
        /// The run's id.
        run: String,
        /// The moving body's name.
        body: String,
    },
    /// Two moving bodies were sampled on different clocks.
    #[error("run `{run}`: bodies `{first}` and `{second}` are sampled at different times; resample them onto one clock")]
    DifferentClocks {
        /// The run's id.
        run: String,
        /// The first moving body's name.
        first: String,
        /// The second moving body's name.
        second: String,
    },
}

/// The sampled normal-direction history of one contact pair in one run.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactHistory {
    /// Sample times (s).
    pub(crate) time: Vec<f64>,
    /// Indentation δ from the recorded motion and the scenario's geometry (m).
    pub(crate) depth: Vec<f64>,
    /// Indentation rate δ̇ (m/s), > 0 approaching.
    pub(crate) rate: Vec<f64>,
    /// Recorded normal force f_n on body 1 along the normal (N).
    pub(crate) force: Vec<f64>,
    /// Unit contact normal n at each sample, world frame, from body 2 towards body 1
    /// (–).
    pub(crate) normal: Vec<Vector3<f64>>,
    /// The body (index in the model) whose recorded force `force` was read from: body
    /// 1, or body 2's reaction (sign flipped) when only body 2 was measured; None when
    /// neither track holds a force for every sample (`force` is then 0).
    pub(crate) force_body: Option<usize>,
}

/// One completed contact event located in a [`ContactHistory`].
#[derive(Clone, Debug, PartialEq)]
pub struct EventSpan {
    /// Indices of the samples inside the contact (δ > 0).
    pub(crate) inside: std::ops::Range<usize>,
    /// Interpolated touch-down time (s), δ̇ there (m/s) and f_n there (N).
    pub(crate) touch_down: (f64, f64, f64),
    /// Interpolated lift-off time (s), δ̇ there (m/s) and f_n there (N).
    pub(crate) lift_off: (f64, f64, f64),
}

impl EventSpan {
    /// Approach speed δ̇0 of the impact (m/s).
    pub fn approach_speed(&self) -> f64 {
        self.touch_down.1
    }

    /// The event of contact `contact` (its index in the model), `effective_mass` m_e
    /// (kg) for the energy loss: the peak of the smoothed normal force, the normal
    /// impulse closed at the crossings (its vector along the normal at the first sample
    /// inside), the crossings' δ̇ as the approach and separation speeds.
    pub fn event(&self, h: &ContactHistory, contact: usize, effective_mass: f64) -> ContactEvent {
        let ((t_in, rate_in, force_in), (t_out, rate_out, force_out)) =
            (self.touch_down, self.lift_off);
        let normal_impulse = impulse(h, self.inside.clone(), (t_in, force_in), (t_out, force_out));
        let normal = h.normal.get(self.inside.start).copied();
        ContactEvent {
            lift_off: Some(t_out),
            max_force: peak(h, self.inside.clone()),
            linear_impulse: normal.unwrap_or_else(Vector3::zeros) * normal_impulse,
            normal_impulse,
            approach_speed: rate_in,
            separation_speed: -rate_out,
            effective_mass,
            ..ContactEvent::starting(contact, t_in)
        }
    }
}

/// Every completed contact event of every contact of `model` in `run`. Events still
/// open at the end of the data are left out.
pub fn from_run(model: &Model, run: &Run) -> Result<Vec<RecordedEvent>, IndicatorError> {
    let mut events = Vec::new();
    for (c, contact) in model.contacts.iter().enumerate() {
        let label = format!(
            "{}–{}",
            model.bodies[contact.body_1].name, model.bodies[contact.body_2].name
        );
        let history = contact_history(model, run, c)?;
        for (number, span) in event_spans(&history).into_iter().enumerate() {
            events.push(RecordedEvent {
                run: run.id.clone(),
                label: label.clone(),
                number,
                event: span.event(&history, c, contact.effective_mass),
            });
        }
    }
    Ok(events)
}

fn track<'a>(
    model: &Model,
    run: &'a Run,
    body: usize,
) -> Result<Option<&'a BodyTrack>, IndicatorError> {
    let spec = &model.bodies[body];
    match run.body(&spec.name) {
        Some(track) if !spec.fixed || !track.samples.is_empty() => Ok(Some(track)),
        _ if spec.fixed => Ok(None),
        _ => Err(IndicatorError::MissingBody {
            run: run.id.clone(),
            body: spec.name.clone(),
        }),
    }
}

/// The normal-direction history of contact `c` of `model` in `run`.
pub fn contact_history(
    model: &Model,
    run: &Run,
    c: usize,
) -> Result<ContactHistory, IndicatorError> {
    let contact = &model.contacts[c];
    let (t1, t2) = (
        track(model, run, contact.body_1)?,
        track(model, run, contact.body_2)?,
    );
    let clock = match (t1, t2) {
        (Some(a), Some(b)) if !model.bodies[contact.body_2].fixed => {
            if a.samples.len() != b.samples.len()
                || a.samples
                    .iter()
                    .zip(&b.samples)
                    .any(|(x, y)| x.time != y.time)
            {
                return Err(IndicatorError::DifferentClocks {
                    run: run.id.clone(),
                    first: a.body.clone(),
                    second: b.body.clone(),
                });
            }
            a
        }
        (Some(a), _) => a,
        (None, Some(b)) => b,
        (None, None) => unreachable!("resolve() rejects contacts between two fixed bodies"),
    };
    let motion = |track: Option<&BodyTrack>, body: usize, i: usize| match track {
        Some(t) if !model.bodies[body].fixed => {
            let s = &t.samples[i];
            (Vector3::from(s.position), Vector3::from(s.velocity))
        }
        _ => (model.bodies[body].position, Vector3::zeros()),
    };
    let n = clock.samples.len();
    // The force on body 1; body 2's reaction if only it was measured.
    let source = match (t1, t2) {
        (Some(a), _) if a.samples.len() == n => Some((a, contact.body_1, 1.0)),
        (_, Some(b)) if b.samples.len() == n => Some((b, contact.body_2, -1.0)),
        _ => None,
    };
    let mut history = ContactHistory {
        time: Vec::with_capacity(n),
        depth: Vec::with_capacity(n),
        rate: Vec::with_capacity(n),
        force: Vec::with_capacity(n),
        normal: Vec::with_capacity(n),
        force_body: source.map(|(_, body, _)| body),
    };
    for i in 0..n {
        let k = pair_kinematics(
            model,
            contact,
            motion(t1, contact.body_1, i),
            motion(t2, contact.body_2, i),
        );
        let force = source.map_or(0.0, |(track, _, sign)| {
            sign * Vector3::from(track.samples[i].force).dot(&k.normal)
        });
        history.time.push(clock.samples[i].time);
        history.depth.push(k.depth);
        history.rate.push(k.rate);
        history.force.push(force);
        history.normal.push(k.normal);
    }
    Ok(history)
}

/// A δ = 0 crossing between samples i − 1 and i: (time, δ̇, f_n) there.
///
/// δ̇ at the crossing is extrapolated from the two neighbouring samples on the
/// out-of-contact side, where no contact force acts and δ̇ is linear in time (free
/// flight under constant gravity), so the extrapolation is exact there; a lone
/// out-of-contact sample falls back to linear interpolation across the crossing.
fn crossing(h: &ContactHistory, i: usize) -> (f64, f64, f64) {
    let dt = h.time[i] - h.time[i - 1];
    let s = hermite_zero(dt, (h.depth[i - 1], h.rate[i - 1]), (h.depth[i], h.rate[i]));
    let time = h.time[i - 1] + s * dt;
    let lerp = |v: &[f64]| v[i - 1] + s * (v[i] - v[i - 1]);
    let apart = |j: usize| h.depth[j] <= 0.0;
    let line = |a: usize, b: usize| {
        h.rate[a] + (time - h.time[a]) * (h.rate[b] - h.rate[a]) / (h.time[b] - h.time[a])
    };
    let rate = if apart(i - 1) && i >= 2 && apart(i - 2) {
        line(i - 2, i - 1)
    } else if apart(i) && i + 1 < h.time.len() && apart(i + 1) {
        line(i, i + 1)
    } else {
        lerp(&h.rate)
    };
    (time, rate, lerp(&h.force))
}

/// The completed contact events of a history, in time order. An event still open
/// at the end of the data is left out.
pub fn event_spans(h: &ContactHistory) -> Vec<EventSpan> {
    let mut events = Vec::new();
    let n = h.time.len();
    let in_contact = |i: usize| h.depth[i] > 0.0;
    let mut start = match n {
        0 => return events,
        _ if in_contact(0) || (h.depth[0] == 0.0 && h.rate[0] > 0.0) => {
            Some(((h.time[0], h.rate[0], h.force[0]), 0))
        }
        _ => None,
    };
    for i in 1..n {
        match start {
            None if !in_contact(i - 1) && in_contact(i) => start = Some((crossing(h, i), i)),
            Some((touch_down, first)) if !in_contact(i) => {
                start = None;
                if in_contact(i - 1) {
                    events.push(EventSpan {
                        inside: first..i,
                        touch_down,
                        lift_off: crossing(h, i),
                    });
                }
            }
            _ => {}
        }
    }
    events
}

/// Trapezoid rule over the samples inside the contact, closed by the crossings.
fn impulse(
    h: &ContactHistory,
    inside: std::ops::Range<usize>,
    (t_in, f_in): (f64, f64),
    (t_out, f_out): (f64, f64),
) -> f64 {
    let mut points = vec![(t_in, f_in)];
    points.extend(
        inside
            .map(|i| (h.time[i], h.force[i]))
            .filter(|&(t, _)| t > t_in && t < t_out),
    );
    points.push((t_out, f_out));
    points
        .windows(2)
        .map(|w| 0.5 * (w[1].0 - w[0].0) * (w[0].1 + w[1].1))
        .sum()
}

/// Half-width of the peak window as a share of the contact duration.
const PEAK_WINDOW: f64 = 0.1;

/// The maximum normal force of one event, read from a smoothed signal
/// (docs/reconstruction.md: the mean of per-run maxima of a noisy force is
/// biased upwards, +0.5 % for the ball at σ = 15 N, so the raw largest sample is not used).
///
/// A degree-4 polynomial in time is fitted by least squares to the samples within
/// ±[`PEAK_WINDOW`]·T of the largest 5-sample moving average (T = contact duration), and
/// its maximum over the window is the peak. For a smooth Hertz-like pulse the
/// polynomial's own error is about 1e-6 of the peak; with white noise of σ (N) and n
/// samples in the window the estimate's standard deviation is ≈ σ·√(3.5/n), without
/// the upward bias of a raw maximum. Fewer than 7 samples in the window (coarse
/// sampling) fall back to the vertex of the parabola through the three highest samples.
fn peak(h: &ContactHistory, inside: std::ops::Range<usize>) -> f64 {
    if inside.is_empty() {
        return 0.0;
    }
    let smoothed = |i: usize| {
        let lo = i.saturating_sub(2).max(inside.start);
        let hi = (i + 3).min(inside.end);
        h.force[lo..hi].iter().sum::<f64>() / (hi - lo) as f64
    };
    let centre = inside
        .clone()
        .max_by(|&a, &b| smoothed(a).total_cmp(&smoothed(b)))
        .unwrap_or(inside.start);
    let duration = h.time[inside.end - 1] - h.time[inside.start];
    let half = PEAK_WINDOW * duration;
    let window: Vec<usize> = inside
        .clone()
        .filter(|&i| (h.time[i] - h.time[centre]).abs() <= half)
        .collect();
    if window.len() < 7 || half <= 0.0 {
        return three_point_peak(h, inside);
    }
    let t0 = h.time[centre];
    let u = |i: usize| (h.time[i] - t0) / half;
    // The degree-4 fit in u ∈ [−1, 1] (well conditioned there).
    let fit = linear_least_squares(window.len(), 5, |j, powers| {
        for (k, power) in powers.iter_mut().enumerate() {
            *power = u(window[j]).powi(k as i32);
        }
        h.force[window[j]]
    });
    let c = match fit {
        Ok(fit) if fit.rank == 5 => fit.coefficients,
        _ => return three_point_peak(h, inside),
    };
    let p = |x: f64| c[0] + x * (c[1] + x * (c[2] + x * (c[3] + x * c[4])));
    let dp = |x: f64| c[1] + x * (2.0 * c[2] + x * (3.0 * c[3] + x * 4.0 * c[4]));
    let d2p = |x: f64| 2.0 * c[2] + x * (6.0 * c[3] + x * 12.0 * c[4]);
    let (lo, hi) = (u(window[0]), u(window[window.len() - 1]));
    // Best of a fine scan, then Newton on p′ = 0 if it stays inside the window.
    let mut x = (0..=400)
        .map(|k| lo + (hi - lo) * k as f64 / 400.0)
        .max_by(|&x, &y| p(x).total_cmp(&p(y)))
        .unwrap_or(0.0);
    for _ in 0..4 {
        let curvature = d2p(x);
        if curvature >= 0.0 {
            break;
        }
        let next = x - dp(x) / curvature;
        if !(lo..=hi).contains(&next) {
            break;
        }
        x = next;
    }
    p(x)
}

/// Largest sampled f_n inside the contact, refined by the vertex of the parabola
/// through it and its two neighbours (kept only if it lies between them).
fn three_point_peak(h: &ContactHistory, inside: std::ops::Range<usize>) -> f64 {
    let Some(j) = inside
        .clone()
        .max_by(|&a, &b| h.force[a].total_cmp(&h.force[b]))
    else {
        return 0.0;
    };
    let best = h.force[j];
    if j == 0 || j + 1 >= h.time.len() || j == inside.start || j + 1 == inside.end {
        return best;
    }
    let (t0, t1, t2) = (h.time[j - 1], h.time[j], h.time[j + 1]);
    let (f0, f1, f2) = (h.force[j - 1], h.force[j], h.force[j + 1]);
    // Divided differences of the interpolating parabola f = f1 + b·(t − t1) + a·(t − t1)².
    let (d01, d12) = ((f1 - f0) / (t1 - t0), (f2 - f1) / (t2 - t1));
    let a = (d12 - d01) / (t2 - t0);
    if a >= 0.0 {
        return best;
    }
    let b = d01 + a * (t1 - t0);
    let dt = -b / (2.0 * a);
    if t1 + dt <= t0 || t1 + dt >= t2 {
        return best;
    }
    f1 + b * dt + a * dt * dt
}
