//! Air drag, read from the flight motion: in free flight the indentation's
//! acceleration δ̈ is gravity's component alone; quadratic drag −c·|v|·v on body 1
//! adds −(c/m)·|δ̇|·δ̇ to it when the motion is along the normal (the 1D examples).
//!
//! The recorded δ̇ itself is fitted, not a differentiated one: over each flight segment
//! (consecutive flight samples of one run, starting at t_s),
//!
//! δ̇(t) = δ̇_s + g·(t − t_s) + c·D(t),  D(t) = −∫_{t_s}^{t} |δ̇|·δ̇/m dt′  (trapezoid over
//! the recorded δ̇),
//!
//! linear in one start rate δ̇_s per segment, gravity's component g (fitted, so a tilted
//! normal needs no special case) and c (kg/m). The residual is then the recorded δ̇'s
//! own white noise, so ordinary least squares gives c's standard error directly
//! (differentiating first would make neighbouring rows' noise correlated and the
//! error bars wrong). The drag is named when its t-statistic exceeds [`T_MIN`], it
//! explains at least 2 % of what gravity alone leaves above the velocity noise σ_v
//! (from δ̇'s second differences), and at the fastest recorded speed it exceeds 0.1 %
//! of gravity's magnitude (the scene's, or the fitted component if larger) and it
//! changes the speed by at least 0.01 % over the longest flight: a rounding-level term
//! in exact motion would otherwise pass wherever gravity's component along the normal
//! is 0 (a horizontal approach, a scene without gravity).

use super::noise::white_noise;
use super::ContactSamples;
use crate::numerics::{Covariance, LinearFit, Reduction};
use hcm_core::effect::AirDrag;

/// Smallest |c / standard error| for air drag to be named.
pub const T_MIN: f64 = 5.0;

/// Smallest relative change of speed (–) the drag must make over the longest recorded
/// flight to be named: below it no contact indicator moves by more than a few 10⁻⁴.
const MIN_SLOWING: f64 = 1e-4;

/// The drag fit.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct DragFit {
    /// Drag coefficient c (kg/m).
    pub coefficient: f64,
    /// Its standard error (kg/m).
    pub standard_error: f64,
    /// Fitted gravity component along the approach direction (m/s²).
    pub(crate) gravity: f64,
    /// Share of the flight acceleration's structured variance (what the gravity-only
    /// fit leaves above the noise) the drag term explains.
    pub(crate) share: f64,
    /// White noise σ_v of the recorded δ̇ in flight (m/s), from its second differences.
    pub(crate) velocity_noise: f64,
    /// Flight samples used.
    pub(crate) samples: usize,
    /// Whether it passes the tests.
    pub significant: bool,
}

impl DragFit {
    /// The drag as a core body term when it passed the tests.
    pub fn air_drag(&self) -> Option<AirDrag<f64>> {
        self.significant.then_some(AirDrag {
            coefficient: self.coefficient,
        })
    }
}

/// Fits the drag of a body of mass `mass` (kg) from the flight samples, in a scene
/// whose gravity has magnitude `gravity` (m/s²); None with fewer than 10 usable samples
/// or a singular fit.
pub fn fit_drag(samples: &ContactSamples, mass: f64, gravity: f64) -> Option<DragFit> {
    let segments = flight_segments(samples);
    let rows = flight_rows(samples, &segments, mass);
    if rows.len() < 10
        || rows
            .iter()
            .any(|r| !(r.1.is_finite() && r.2.is_finite() && r.3.is_finite()))
    {
        return None;
    }
    let p = segments.len() + 2;
    let n = rows.len();
    let (with_drag, gravity_only) = (fit(&rows, p, true)?, fit(&rows, p - 1, false)?);
    let rss = with_drag.residual_sum_of_squares;
    let gravity_only = gravity_only.residual_sum_of_squares;
    let (coefficient, component) = (with_drag.coefficients[p - 1], with_drag.coefficients[p - 2]);
    // σ̂²·(XᵀX)⁻¹ with σ̂² = RSS/(n − p): the rows' residuals are the recorded δ̇'s white
    // noise (see the module documentation).
    let covariance = with_drag.covariance?;
    let standard_error = covariance[p - 1][p - 1].max(0.0).sqrt();
    // The recorded δ̇'s own white noise σ_v, from flight triples on one clock.
    let (mut run, mut time, mut rate) = (Vec::new(), Vec::new(), Vec::new());
    for j in segments.iter().flat_map(|s| s.clone()) {
        run.push(samples.run[j]);
        time.push(samples.time[j]);
        rate.push(samples.rate[j]);
    }
    let sigma_v = white_noise(&run, &time, &rate).sigma;
    let sigma_v = if sigma_v.is_finite() { sigma_v } else { 0.0 };
    // Of what gravity alone leaves above the noise, the part the drag explains.
    let explained = gravity_only - rss;
    let structured = (gravity_only - n as f64 * sigma_v * sigma_v).max(explained);
    let share = if structured > 0.0 {
        (explained / structured).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let t = coefficient.abs() / standard_error.max(f64::MIN_POSITIVE);
    // With noise-free motion both variances are rounding-level and t and the share are
    // meaningless; the drag must also matter: at the fastest recorded speed more than
    // 0.1 % of gravity (measured: on the flat shot's horizontal approach, where the
    // component is 0, a hidden adhesion's rounding-level 2.4e-12 kg/m passed against it).
    let fastest = rows.iter().map(|r| r.3 * r.3 / mass).fold(0.0, f64::max);
    // Over a segment of duration T at speed v the drag changes the speed by c·v·T/m.
    let slowing = (segments.iter())
        .map(|s| {
            let duration = samples.time[s.end - 1] - samples.time[s.start];
            let speed = s.clone().map(|j| samples.rate[j].abs()).fold(0.0, f64::max);
            coefficient * speed * duration / mass
        })
        .fold(0.0, f64::max);
    let matters =
        coefficient * fastest > 1e-3 * gravity.abs().max(component.abs()) && slowing >= MIN_SLOWING;
    Some(DragFit {
        coefficient,
        standard_error,
        gravity: component,
        share,
        velocity_noise: sigma_v,
        samples: n,
        significant: coefficient > 0.0 && t > T_MIN && share >= 0.02 && matters,
    })
}

/// Segments of consecutive flight samples of one run, at least three long. Samples
/// whose motion was reconstructed (`dataset::reconstruct`, `dataset::newton`) are not
/// flight measurements: their motion is gravity's alone by construction, and mixed
/// with recorded rows it would fake a drag.
fn flight_segments(samples: &ContactSamples) -> Vec<std::ops::Range<usize>> {
    let flight =
        |j: usize| !samples.in_contact[j] && samples.depth[j] < 0.0 && !samples.reconstructed(j);
    let mut segments = Vec::new();
    let mut i = 0;
    while i < samples.len() {
        if !flight(i) {
            i += 1;
            continue;
        }
        let start = i;
        while i + 1 < samples.len() && flight(i + 1) && samples.run[i + 1] == samples.run[start] {
            i += 1;
        }
        if i + 1 - start >= 3 {
            segments.push(start..i + 1);
        }
        i += 1;
    }
    segments
}

/// The fit's rows: (segment, t − t_s (s), D (m²/(kg·s), so that c·D is in m/s), δ̇
/// (m/s)), D by the trapezoid rule over the recorded δ̇.
fn flight_rows(
    samples: &ContactSamples,
    segments: &[std::ops::Range<usize>],
    mass: f64,
) -> Vec<(usize, f64, f64, f64)> {
    let mut rows = Vec::new();
    for (k, segment) in segments.iter().enumerate() {
        let t_s = samples.time[segment.start];
        let mut integral = 0.0;
        for j in segment.clone() {
            if j > segment.start {
                let q = |j: usize| samples.rate[j].abs() * samples.rate[j] / mass;
                integral -= 0.5 * (q(j) + q(j - 1)) * (samples.time[j] - samples.time[j - 1]);
            }
            rows.push((k, samples.time[j] - t_s, integral, samples.rate[j]));
        }
    }
    rows
}

/// The least-squares fit of δ̇ on the segments' start rates, t − t_s and, `with_drag`,
/// D (`columns` in all; with D also its covariance σ̂²·(XᵀX)⁻¹); `None` when the design
/// is rank-deficient or, with D, has no degree of freedom left.
fn fit(rows: &[(usize, f64, f64, f64)], columns: usize, with_drag: bool) -> Option<LinearFit> {
    let segments = if with_drag { columns - 2 } else { columns - 1 };
    let reduction = Reduction::from_rows(rows.len(), columns, 1, |r, regressors, target| {
        let (k, t, d, rate) = rows[r];
        regressors[k] = 1.0;
        regressors[segments] = t;
        if with_drag {
            regressors[segments + 1] = d;
        }
        target[0] = rate;
    })
    .ok()?;
    let covariance = with_drag.then_some(Covariance::ResidualVariance);
    let fit = reduction.solve(0, covariance).ok()?;
    (fit.rank == columns && fit.covariance.is_some() == with_drag).then_some(fit)
}
