//! Whether motion recorded on every force row can be trusted through the contacts, and
//! what replaces it when it cannot.
//!
//! Full rows do not say how the motion was measured. A camera's frames splined onto the
//! force sensor's rows fill every cell, yet inside a 110 µs contact they are a curve
//! through two or three frames with µm-level noise, not the indentation of tens of µm a
//! contact law needs. The force sensor knows better: Newton's law fixes the motion
//! through each contact up to its start, x(t) = p0 + v0·s + ½·g·s² + D(t + τ)
//! (s = t − t0, D the force's double integral over m, `Implied`). The **check** fits
//! p0, v0 and a sensor delay τ (a lag is the sensor's business, named later, not a sign
//! of untrustworthy motion) to the recorded positions of the contact window and as much
//! flight on each side, weighted by what each row can be off by: the motion's own white
//! noise (from its second differences, as the force's) and the force noise integrated
//! (σ_f/m·√(h·s³/3), growing through the contact). The force's offset is taken off
//! first, read in flight where the contact force is 0. Motion that obeys Newton's law
//! with the recorded force leaves an RMS misfit of about 1 in those units; motion that
//! does not — a spline through frames — leaves many times more. Above
//! `MAX_MISFIT` the contact's motion is **replaced** by the force's: p0 and v0 fitted
//! by least squares to every recorded row of the contact and its flights (the spline's
//! frames, whatever their rate), with their uncertainty from the misfit itself and the
//! rows' correlation (`independent`), carried per row as an empty-cell reconstruction
//! carries its own.

use super::delay::Delay;
use super::implied::Implied;
use crate::numerics::optimize::minimize_scalar;

/// Largest RMS misfit (in standard deviations of what a row can be off by) at which
/// recorded motion is trusted through a contact (–). Measured on the independent rig
/// (tests/diagnose/diagnose_rig.rs): see `README.md`, "Diagnose".
pub(crate) const MAX_MISFIT: f64 = 10.0;

/// Delays tried by the check's coarse search, each side of 0, before refining (–).
const DELAY_GRID: usize = 20;

/// One contact's motion as Newton's law gives it from the recorded force.
pub(super) struct Replaced {
    /// Position (m) and velocity (m/s) at the window's samples.
    pub(crate) position: Vec<[f64; 3]>,
    pub(crate) velocity: Vec<[f64; 3]>,
    /// Their variances per axis (m², (m/s)²).
    pub(crate) position_variance: Vec<[f64; 3]>,
    pub(crate) velocity_variance: Vec<[f64; 3]>,
    /// Mean square of recorded − replaced position (m²) and velocity ((m/s)²) over the
    /// rows fitted, per axis: how far off the recorded motion is, in flight too.
    pub(crate) recorded_error: ([f64; 3], [f64; 3]),
}

/// The recorded motion of one track around one contact.
pub(super) struct Rows<'a> {
    /// Row times (s), the force series' (every row has force).
    pub(crate) time: &'a [f64],
    /// Recorded positions at those rows (m).
    pub(crate) position: &'a [[f64; 3]],
    /// Recorded velocities at those rows (m/s).
    pub(crate) velocity: &'a [[f64; 3]],
    /// White-noise σ of the recorded position per axis (m).
    pub(crate) noise: [f64; 3],
    /// Rows around the window that the fits read, in time order.
    pub(crate) rows: Vec<usize>,
}

/// White-noise σ per axis of positions `position` at times `time` (m), from second
/// differences of equally spaced rows (1.4826·median|Δ²x|/√6); 0 without such rows.
pub(super) fn position_noise(time: &[f64], position: &[[f64; 3]]) -> [f64; 3] {
    core::array::from_fn(|k| {
        let mut second: Vec<f64> = (2..time.len())
            .filter(|&j| {
                let (a, b) = (time[j - 1] - time[j - 2], time[j] - time[j - 1]);
                (a - b).abs() <= 1e-6 * a.abs()
            })
            .map(|j| (position[j - 2][k] - 2.0 * position[j - 1][k] + position[j][k]).abs())
            .collect();
        if second.is_empty() {
            return 0.0;
        }
        let middle = second.len() / 2;
        let (_, median, _) = second.select_nth_unstable_by(middle, f64::total_cmp);
        1.4826 * *median / 6f64.sqrt()
    })
}

/// Variance (m²) the force noise σ_f (N) adds to D at `s` (s) after a window start,
/// samples h (s) apart, mass m (kg): (σ_f/m)²·h·∫(s − u)² du over the window's force.
fn integrated_variance(sigma: f64, mass: f64, h: f64, s: f64, duration: f64) -> f64 {
    if s <= 0.0 {
        return 0.0;
    }
    let since = (s - duration).max(0.0);
    (sigma / mass).powi(2) * h * (s.powi(3) - since.powi(3)) / 3.0
}

/// Weighted least squares of y ≈ p0 + v0·s with weights w: (p0, v0, χ²).
fn line(s: &[f64], y: &[f64], w: &[f64]) -> (f64, f64, f64) {
    let (mut sw, mut ss, mut sss, mut sy, mut ssy) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for ((&s, &y), &w) in s.iter().zip(y).zip(w) {
        sw += w;
        ss += w * s;
        sss += w * s * s;
        sy += w * y;
        ssy += w * s * y;
    }
    let det = sw * sss - ss * ss;
    if det.abs() <= 0.0 || !det.is_finite() {
        return (f64::NAN, f64::NAN, f64::NAN);
    }
    let p0 = (sss * sy - ss * ssy) / det;
    let v0 = (sw * ssy - ss * sy) / det;
    let chi2 = s
        .iter()
        .zip(y)
        .zip(w)
        .map(|((&s, &y), &w)| w * (y - p0 - v0 * s).powi(2))
        .sum();
    (p0, v0, chi2)
}

/// The check's misfit (RMS in standard deviations, –) of `recorded` against the motion
/// `implied` gives, with gravity g (m/s²), force noise σ_f (N) per axis, the force
/// samples h (s) apart and mass m (kg), and the delay τ (s) fitted with it. Axes with
/// neither motion noise nor force noise (a 1D record's unused ones) are left out; None
/// if none is left.
pub(super) fn misfit(
    recorded: &Rows<'_>,
    implied: &Implied,
    gravity: [f64; 3],
    force_noise: [f64; 3],
    (h, mass): (f64, f64),
) -> Option<(f64, f64)> {
    let axes: Vec<usize> = (0..3)
        .filter(|&k| recorded.noise[k] > 0.0 || force_noise[k] > 0.0)
        .collect();
    let rows = recorded.rows.iter().copied();
    if axes.is_empty() || recorded.rows.len() < 4 {
        return None;
    }
    let t0 = implied.start();
    let s: Vec<f64> = rows.clone().map(|j| recorded.time[j] - t0).collect();
    // Weights at delay τ: the force noise integrated up to s + τ, the force's own clock.
    let weights = |k: usize, tau: f64| -> Vec<f64> {
        s.iter()
            .map(|&s| {
                let var = recorded.noise[k].powi(2)
                    + integrated_variance(force_noise[k], mass, h, s + tau, implied.duration());
                1.0 / var.max(f64::MIN_POSITIVE)
            })
            .collect()
    };
    let chi2 = |tau: f64, weighted: bool| -> f64 {
        axes.iter()
            .map(|&k| {
                let y: Vec<f64> = rows
                    .clone()
                    .zip(&s)
                    .map(|(j, &s)| {
                        let t = recorded.time[j];
                        recorded.position[j][k]
                            - 0.5 * gravity[k] * s * s
                            - implied.at(t + tau, k).0
                    })
                    .collect();
                let w = if weighted {
                    weights(k, tau)
                } else {
                    vec![1.0; s.len()]
                };
                line(&s, &y, &w).2
            })
            .sum()
    };
    // The delay by ordinary least squares (weights that change with τ would favour the
    // τ that makes every row least certain), then the misfit weighted at it.
    let tau = minimise(&|tau| chi2(tau, false), 0.5 * implied.duration());
    let dof = (axes.len() * (recorded.rows.len() - 3)) as f64;
    Some(((chi2(tau, true) / dof).sqrt(), tau))
}

/// Where `f` is smallest over τ ∈ [−span, span]: the identification's scalar search
/// (`minimize_scalar`: a grid of 2·[`DELAY_GRID`] + 1 delays, 0 among them, then Brent's
/// method around the best), to a billionth of the span.
fn minimise(f: &dyn Fn(f64) -> f64, span: f64) -> f64 {
    let points = 2 * DELAY_GRID + 1;
    minimize_scalar(f, -span, span, points, 1e-9 * span).0
}

/// Independent values among residuals `r` in time order (–): a residual of n
/// independent values changes sign about (n − 1)/2 times, one that follows a spline
/// through a few frames about as often as those frames do.
fn independent(r: &[f64]) -> f64 {
    let changes = r.windows(2).filter(|w| w[0] * w[1] < 0.0).count();
    ((2 * changes + 1) as f64).clamp(3.0, r.len() as f64)
}

/// The contact's motion from `implied` with p0 and v0 fitted by ordinary least squares
/// to every row of `recorded` (see the module documentation), at the window's samples
/// `window` (times, s); variances from the fit's misfit scaled by the rows'
/// correlation, plus the force noise integrated. With a `delay`, the force is taken as
/// read τ late: the motion at t is the force's integral read at t + τ (the motion as it
/// was, against which the sensor lags), and τ's variance is carried per row, δ moving
/// by V(t + τ)·sd(τ) and δ̇ by A(t + τ)·sd(τ).
pub(super) fn replace(
    recorded: &Rows<'_>,
    implied: &Implied,
    window: &[f64],
    (gravity, force_noise): ([f64; 3], [f64; 3]),
    (h, mass): (f64, f64),
    delay: Option<Delay>,
) -> Replaced {
    let (lag, lag_variance) = delay.map_or((0.0, 0.0), |d| (d.value, d.sd * d.sd));
    let t0 = implied.start();
    let rows = recorded.rows.iter().copied();
    let s: Vec<f64> = rows.clone().map(|j| recorded.time[j] - t0).collect();
    let n = s.len() as f64;
    let ones = vec![1.0; s.len()];
    let mean = s.iter().sum::<f64>() / n;
    let s_uu: f64 = s.iter().map(|x| (x - mean).powi(2)).sum();
    let mut out = Replaced {
        position: vec![[0.0; 3]; window.len()],
        velocity: vec![[0.0; 3]; window.len()],
        position_variance: vec![[0.0; 3]; window.len()],
        velocity_variance: vec![[0.0; 3]; window.len()],
        recorded_error: ([0.0; 3], [0.0; 3]),
    };
    for k in 0..3 {
        let y: Vec<f64> = rows
            .clone()
            .zip(&s)
            .map(|(j, &s)| {
                recorded.position[j][k]
                    - 0.5 * gravity[k] * s * s
                    - implied.at(recorded.time[j] + lag, k).0
            })
            .collect();
        let (p0, v0, rss) = line(&s, &y, &ones);
        let residual: Vec<f64> = s.iter().zip(&y).map(|(&s, &y)| y - p0 - v0 * s).collect();
        let rate_error: f64 = rows
            .clone()
            .zip(&s)
            .map(|(j, &s)| {
                let v = v0 + gravity[k] * s + implied.at(recorded.time[j] + lag, k).1;
                (recorded.velocity[j][k] - v).powi(2)
            })
            .sum();
        out.recorded_error.0[k] = rss / n;
        out.recorded_error.1[k] = rate_error / n;
        // σ² of one row, then (AᵀA)⁻¹ for n rows of which only n_eff are independent.
        let scale = rss / (n - 2.0).max(1.0) * n / independent(&residual);
        let (c_bb, c_ab) = (1.0 / s_uu, -mean / s_uu);
        let c_aa = 1.0 / n + mean * mean / s_uu;
        for (i, &t) in window.iter().enumerate() {
            let u = t - t0;
            let (d, v) = implied.at(t + lag, k);
            out.position[i][k] = p0 + v0 * u + 0.5 * gravity[k] * u * u + d;
            out.velocity[i][k] = v0 + gravity[k] * u + v;
            let force = integrated_variance(force_noise[k], mass, h, u, implied.duration());
            let a = implied.acceleration(t + lag, k);
            out.position_variance[i][k] =
                scale * (c_aa + 2.0 * u * c_ab + u * u * c_bb) + force + v * v * lag_variance;
            out.velocity_variance[i][k] = scale * c_bb
                + (force_noise[k] / mass).powi(2) * h * u.min(implied.duration())
                + a * a * lag_variance;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn white_noise_changes_sign_as_often_as_its_values_and_a_smooth_curve_seldom() {
        // A linear congruential sequence's top bit: signs as good as random.
        let mut state: u64 = 12345;
        let white: Vec<f64> = (0..1000)
            .map(|_| {
                state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                if state >> 63 == 1 {
                    1.0
                } else {
                    -1.0
                }
            })
            .collect();
        assert!(independent(&white) > 600.0, "{}", independent(&white));
        let smooth: Vec<f64> = (0..1000).map(|i| (i as f64 / 80.0).sin()).collect();
        assert!(independent(&smooth) < 30.0, "{}", independent(&smooth));
    }

    #[test]
    fn the_search_finds_a_delay_between_grid_points() {
        let best = minimise(&|tau: f64| ((tau - 3.3e-6) / 1e-6).powi(2) + 1.0, 5e-5);
        assert!((best - 3.3e-6).abs() < 1e-11, "{best}");
    }
}
