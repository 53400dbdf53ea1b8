//! 3D contact indicators read back from sampled data (simulated or measured): the
//! pair's separation is recomputed from the recorded poses and the scenario's
//! shapes, an event is a stretch of samples in which it is negative, and its
//! indicators come from the moving body's recorded force and torque.
//!
//! Touch-down and lift-off are the linearly interpolated zero crossings of the
//! separation; the impulses integrate the recorded wrench by the trapezoid rule with
//! the wrench taken as zero at the two crossings (every law gives zero force at
//! δ = 0); the maxima are the largest recorded ‖**F**‖ and ‖**T**‖. The recorded wrench
//! is the body's total contact load, so two pairs of one body touching at once share
//! it: each pair is credited with the whole load over its own events.

use super::{ContactEvent, IndicatorError, RecordedEvent};
use crate::dataset::{Run, Sample};
use crate::scenario::Model;
use crate::scenario::{pair_separation, Pose};
use nalgebra::{Quaternion, UnitQuaternion, Vector3};

/// Every completed 3D contact event of every contact of `model` in `run`; events
/// still open at the end of the data are left out.
pub fn pair_events_from_run(
    model: &Model,
    run: &Run,
) -> Result<Vec<RecordedEvent>, IndicatorError> {
    let mut found = Vec::new();
    for (c, contact) in model.contacts.iter().enumerate() {
        let (b1, b2) = (&model.bodies[contact.body_1], &model.bodies[contact.body_2]);
        let label = format!("{}–{}", b1.name, b2.name);
        let mover = if b1.fixed { b2 } else { b1 };
        let track = |name: &str| {
            run.body(name).ok_or_else(|| IndicatorError::MissingBody {
                run: run.id.clone(),
                body: name.to_owned(),
            })
        };
        let moving = &track(&mover.name)?.samples;
        let other = if b1.fixed || b2.fixed {
            None
        } else {
            let other_name = if mover.name == b1.name {
                &b2.name
            } else {
                &b1.name
            };
            let samples = &track(other_name)?.samples;
            if samples.len() != moving.len()
                || samples.iter().zip(moving).any(|(a, b)| a.time != b.time)
            {
                return Err(IndicatorError::DifferentClocks {
                    run: run.id.clone(),
                    first: b1.name.clone(),
                    second: b2.name.clone(),
                });
            }
            Some(samples)
        };
        let separation: Vec<f64> = (0..moving.len())
            .map(|i| {
                let pose_of = |b: &crate::scenario::Body, sample: Option<&Sample>| match sample {
                    Some(s) if !b.fixed => pose(s),
                    _ => fixed_pose(b),
                };
                let s1 = if b1.name == mover.name {
                    Some(&moving[i])
                } else {
                    other.map(|o| &o[i])
                };
                let s2 = if b2.name == mover.name {
                    Some(&moving[i])
                } else {
                    other.map(|o| &o[i])
                };
                pair_separation(model, contact, &pose_of(b1, s1), &pose_of(b2, s2))
            })
            .collect();
        for (number, (touch_down, lift_off, inside)) in
            spans(moving, &separation).into_iter().enumerate()
        {
            found.push(RecordedEvent {
                run: run.id.clone(),
                label: label.clone(),
                number,
                event: wrench_event(
                    (c, contact.effective_mass),
                    moving,
                    inside,
                    (touch_down, lift_off),
                ),
            });
        }
    }
    Ok(found)
}

/// A recorded sample's pose (velocities as recorded).
fn pose(s: &Sample) -> Pose {
    let [w, x, y, z] = s.orientation;
    Pose {
        position: Vector3::from(s.position),
        orientation: UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z)),
        velocity: Vector3::from(s.velocity),
        angular_velocity: Vector3::from(s.angular_velocity),
    }
}

fn fixed_pose(b: &crate::scenario::Body) -> Pose {
    Pose {
        position: b.position,
        orientation: b.orientation,
        velocity: Vector3::zeros(),
        angular_velocity: Vector3::zeros(),
    }
}

/// The completed stretches of negative separation: (touch-down (s), lift-off (s),
/// indices of the samples inside).
fn spans(samples: &[Sample], separation: &[f64]) -> Vec<(f64, f64, std::ops::Range<usize>)> {
    let crossing = |i: usize| {
        let (g0, g1) = (separation[i], separation[i + 1]);
        let (t0, t1) = (samples[i].time, samples[i + 1].time);
        t0 + (t1 - t0) * g0 / (g0 - g1)
    };
    let mut found = Vec::new();
    let mut start: Option<(f64, usize)> = None;
    for i in 0..separation.len().saturating_sub(1) {
        let (now, next) = (separation[i] < 0.0, separation[i + 1] < 0.0);
        if !now && next {
            start = Some((crossing(i), i + 1));
        } else if now && !next {
            if let Some((touch_down, first)) = start.take() {
                found.push((touch_down, crossing(i), first..i + 1));
            }
        }
    }
    found
}

/// One event of contact `c` (effective mass m_e, kg) from the samples `inside` it and
/// its crossing times (s).
fn wrench_event(
    (c, effective_mass): (usize, f64),
    samples: &[Sample],
    inside: std::ops::Range<usize>,
    (touch_down, lift_off): (f64, f64),
) -> ContactEvent {
    let wrench = |s: &Sample| {
        let mut w = [0.0; 6];
        w[..3].copy_from_slice(&s.force);
        w[3..].copy_from_slice(&s.torque);
        w
    };
    let mut points: Vec<(f64, [f64; 6])> = vec![(touch_down, [0.0; 6])];
    points.extend(samples[inside.clone()].iter().map(|s| (s.time, wrench(s))));
    points.push((lift_off, [0.0; 6]));
    let mut impulse = [0.0; 6];
    for pair in points.windows(2) {
        let dt = pair[1].0 - pair[0].0;
        for (k, total) in impulse.iter_mut().enumerate() {
            *total += 0.5 * dt * (pair[0].1[k] + pair[1].1[k]);
        }
    }
    let norm = |v: &[f64; 3]| Vector3::from(*v).norm();
    let inner = &samples[inside];
    let times: Vec<f64> = inner.iter().map(|s| s.time).collect();
    let forces: Vec<f64> = inner.iter().map(|s| norm(&s.force)).collect();
    let torques: Vec<f64> = inner.iter().map(|s| norm(&s.torque)).collect();
    ContactEvent {
        lift_off: Some(lift_off),
        max_force: local_peak(&times, &forces),
        max_torque: local_peak(&times, &torques),
        linear_impulse: Vector3::new(impulse[0], impulse[1], impulse[2]),
        angular_impulse: Vector3::new(impulse[3], impulse[4], impulse[5]),
        effective_mass,
        ..ContactEvent::starting(c, touch_down)
    }
}

/// Half-width of the peak fit, in samples (±50 µs at the contact rate of 10 µs).
const PEAK_HALF_WIDTH: usize = 5;

/// The maximum of a noisy sampled magnitude, unbiased: the vertex of the least-squares
/// parabola through the 2·[`PEAK_HALF_WIDTH`] + 1 samples around the largest 5-sample
/// moving average. The raw largest sample of noisy data is biased upwards (by about
/// 1.5 σ: 0.8 % of the peg's first wall contact at σ = 0.2 N), which a noise-free
/// model's replay does not share; the 1D indicators smooth their peak for the same
/// reason. The window is kept short because a sliding contact's force has spikes of a
/// few hundred µs, which a wider fit would flatten. Falls back to the largest sample
/// when the window is short, the fit is not a cap, or its vertex lies outside.
fn local_peak(times: &[f64], values: &[f64]) -> f64 {
    let raw = values.iter().copied().fold(0.0, f64::max);
    let n = values.len();
    if n < 2 * PEAK_HALF_WIDTH + 1 {
        return raw;
    }
    let average = |i: usize| {
        let (lo, hi) = (i.saturating_sub(2), (i + 3).min(n));
        values[lo..hi].iter().sum::<f64>() / (hi - lo) as f64
    };
    let centre = (0..n)
        .max_by(|&a, &b| average(a).total_cmp(&average(b)))
        .unwrap_or(0)
        .clamp(PEAK_HALF_WIDTH, n - 1 - PEAK_HALF_WIDTH);
    let window = centre - PEAK_HALF_WIDTH..centre + PEAK_HALF_WIDTH + 1;
    let (t0, half) = (times[centre], times[window.end - 1] - times[centre]);
    if half <= 0.0 {
        return raw;
    }
    let u = |i: usize| (times[i] - t0) / half;
    let fit = crate::numerics::linear_least_squares(window.len(), 3, |j, powers| {
        let x = u(window.start + j);
        powers.copy_from_slice(&[1.0, x, x * x]);
        values[window.start + j]
    });
    let Ok(fit) = fit else { return raw };
    let [c0, c1, c2] = [
        fit.coefficients[0],
        fit.coefficients[1],
        fit.coefficients[2],
    ];
    let vertex = -c1 / (2.0 * c2);
    if fit.rank < 3 || c2 >= 0.0 || !(u(window.start)..=u(window.end - 1)).contains(&vertex) {
        return raw;
    }
    let peak = c0 + vertex * (c1 + vertex * c2);
    // A peak sharper than the window (the bottom landing's torque: the parabola read
    // 4.5 of 8.4 N·m) is not noise to remove: beyond PEAK_DROP below the raw maximum
    // the fit is refused. The noise bias it corrects is ~1 % on the peg's contacts.
    if peak < (1.0 - PEAK_DROP) * raw {
        return raw;
    }
    peak
}

/// Largest share of the raw maximum [`local_peak`]'s fit may remove.
const PEAK_DROP: f64 = 0.03;
