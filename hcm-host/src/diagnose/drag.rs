//! Air drag, read from the flight motion: in free flight the indentation's
//! acceleration δ̈ is gravity's component alone; quadratic drag −c·|v|·v on body 1
//! adds −(c/m)·|δ̇|·δ̇ to it when the motion is along the normal (the 1D examples).
//!
//! δ̈ is taken by central differences of the recorded δ̇ over flight samples of one run
//! (the three on a uniform clock), and regressed on [1, −|δ̇|·δ̇/m] by least squares
//! weighted for the differences' noise (∝ 1/h²): the intercept is gravity's component
//! (fitted, so a tilted normal needs no special case), the slope is c (kg/m). The drag
//! is named when its t-statistic exceeds [`T_MIN`], it explains at least 2 % of what
//! gravity alone leaves above the velocity noise, and at the fastest recorded speed it
//! exceeds 0.1 % of the gravity component.

use super::noise::white_noise;
use super::ContactSamples;
use hcm_core::effect::AirDrag;
use nalgebra::{Matrix2, Vector2};

/// Smallest |c / standard error| for air drag to be named.
pub const T_MIN: f64 = 5.0;

/// The drag fit.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct DragFit {
    /// Drag coefficient c (kg/m).
    pub coefficient: f64,
    /// Its standard error (kg/m).
    pub standard_error: f64,
    /// Fitted gravity component along the approach direction (m/s²).
    pub gravity: f64,
    /// Share of the flight acceleration's structured variance (what the gravity-only
    /// fit leaves above the noise) the drag term explains.
    pub share: f64,
    /// White noise σ_v of the recorded δ̇ in flight (m/s), from its second differences.
    pub velocity_noise: f64,
    /// Flight samples used.
    pub samples: usize,
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

/// Fits the drag of a body of mass `mass` (kg) from the flight samples; None with
/// fewer than 10 usable samples.
pub fn fit_drag(samples: &ContactSamples, mass: f64) -> Option<DragFit> {
    let mut rows = Vec::new();
    for i in 1..samples.len().saturating_sub(1) {
        let (a, b) = (i - 1, i + 1);
        let flight = |j: usize| !samples.in_contact[j] && samples.depth[j] < 0.0;
        if samples.run[a] != samples.run[i] || samples.run[b] != samples.run[i] {
            continue;
        }
        if !(flight(a) && flight(i) && flight(b)) {
            continue;
        }
        let (h1, h2) = (
            samples.time[i] - samples.time[a],
            samples.time[b] - samples.time[i],
        );
        if !(h1 > 0.0 && (h2 - h1).abs() <= 0.01 * h1) {
            continue;
        }
        let acceleration = (samples.rate[b] - samples.rate[a]) / (h1 + h2);
        let rate = samples.rate[i];
        rows.push((
            acceleration,
            -rate.abs() * rate / mass,
            (h1 + h2).powi(2) / 2.0,
        ));
    }
    if rows.len() < 10 {
        return None;
    }
    // The recorded δ̇'s own white noise σ_v, from flight triples on one clock.
    let (mut run, mut time, mut rate) = (Vec::new(), Vec::new(), Vec::new());
    for i in (0..samples.len()).filter(|&i| !samples.in_contact[i] && samples.depth[i] < 0.0) {
        run.push(samples.run[i]);
        time.push(samples.time[i]);
        rate.push(samples.rate[i]);
    }
    let sigma_v = white_noise(&run, &time, &rate).sigma;
    let sigma_v = if sigma_v.is_finite() { sigma_v } else { 0.0 };
    // A central difference over h1 + h2 has noise variance 2σ_v²/(h1 + h2)²: weighting
    // each row by (h1 + h2)²/2 gives every row the noise σ_v², so the few rows recorded
    // at the contact rate around an impact do not drown the flight at the flight rate.
    let (mut gram, mut cross) = (Matrix2::<f64>::zeros(), Vector2::<f64>::zeros());
    for &(y, x, w) in &rows {
        let v = Vector2::new(1.0, x);
        gram += w * v * v.transpose();
        cross += w * v * y;
    }
    let inverse = gram.try_inverse()?;
    let beta = inverse * cross;
    let rss: f64 = rows
        .iter()
        .map(|&(y, x, w)| w * (y - beta[0] - beta[1] * x).powi(2))
        .sum();
    let weight: f64 = rows.iter().map(|r| r.2).sum();
    let mean = rows.iter().map(|r| r.2 * r.0).sum::<f64>() / weight;
    let gravity_only: f64 = rows.iter().map(|r| r.2 * (r.0 - mean).powi(2)).sum();
    let n = rows.len() as f64;
    let variance = rss / (n - 2.0).max(1.0);
    let standard_error = (variance * inverse[(1, 1)]).max(0.0).sqrt();
    // Of what gravity alone leaves above the noise, the part the drag explains.
    let structured = (gravity_only - n * sigma_v * sigma_v).max(gravity_only - rss);
    let share = if structured > 0.0 {
        ((gravity_only - rss) / structured).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let t = beta[1].abs() / standard_error.max(f64::MIN_POSITIVE);
    // With noise-free motion both variances are rounding-level and t and the share are
    // meaningless; the drag must also matter: at the fastest recorded speed more than
    // 0.1 % of the gravity component.
    let fastest = rows.iter().map(|r| r.1.abs()).fold(0.0, f64::max);
    let matters = beta[1] * fastest > 1e-3 * beta[0].abs();
    Some(DragFit {
        coefficient: beta[1],
        standard_error,
        gravity: beta[0],
        share,
        velocity_noise: sigma_v,
        samples: rows.len(),
        significant: beta[1] > 0.0 && t > T_MIN && share >= 0.02 && matters,
    })
}
