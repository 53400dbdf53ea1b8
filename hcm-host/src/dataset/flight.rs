//! A free flight fitted to camera frames: per axis k, the parabola
//! p_k(t) = a_k + b_k·τ + ½·g_k·τ² (τ = t − t_ref) with the scenario's gravity g known,
//! a_k and b_k by linear least squares, and their covariance.
//!
//! Between contacts only gravity acts on the body (air drag is ≲ 0.05 % of g for a
//! steel ball at a few m/s), so the parabola is the exact model of the flight and its
//! two parameters per axis are the position and velocity at t_ref. With N frames of
//! white position noise σ_k, Cov(a_k, b_k) = σ_k²·(AᵀA)⁻¹ for A = [1, τ_i]; σ_k² is
//! estimated by the residual sum of squares over N − 2.

/// Least frames a flight fit needs: two parameters per axis and one to estimate σ.
pub(crate) const MIN_FRAMES: usize = 3;

/// A free flight fitted to frames, referred to `t_ref`.
#[derive(Clone, Debug, PartialEq)]
pub struct FlightFit {
    /// Reference time t_ref (s): the fit's position and velocity are given there.
    pub(crate) t_ref: f64,
    /// Position at t_ref, a_k (m).
    pub(crate) position: [f64; 3],
    /// Velocity at t_ref, b_k (m/s).
    pub(crate) velocity: [f64; 3],
    /// Gravity g (m/s²).
    pub(crate) gravity: [f64; 3],
    /// (AᵀA)⁻¹ as [[c_aa, c_ab], [c_ab, c_bb]] (1, s, s²): times σ_k² the covariance
    /// of (a_k, b_k).
    pub(crate) unscaled: [[f64; 2]; 2],
    /// Residual variance σ_k² per axis (m²).
    pub(crate) noise: [f64; 3],
    /// Frames fitted.
    pub(crate) frames: usize,
}

impl FlightFit {
    /// Fits `frames` (time (s), position (m)) with gravity `gravity` (m/s²), referred to
    /// `t_ref`. None with fewer than `MIN_FRAMES` frames or frames all at one time.
    pub fn fit(frames: &[(f64, [f64; 3])], gravity: [f64; 3], t_ref: f64) -> Option<FlightFit> {
        let n = frames.len();
        if n < MIN_FRAMES {
            return None;
        }
        // Normal equations of [1, τ]; τ is centred for the solve (well conditioned)
        // and the result moved back to t_ref.
        let mean = frames.iter().map(|f| f.0 - t_ref).sum::<f64>() / n as f64;
        let s_uu: f64 = frames.iter().map(|f| (f.0 - t_ref - mean).powi(2)).sum();
        if s_uu <= 0.0 || !s_uu.is_finite() {
            return None;
        }
        let mut position = [0.0; 3];
        let mut velocity = [0.0; 3];
        let mut noise = [0.0; 3];
        for k in 0..3 {
            let y = |f: &(f64, [f64; 3])| {
                let tau = f.0 - t_ref;
                f.1[k] - 0.5 * gravity[k] * tau * tau
            };
            let y_mean = frames.iter().map(y).sum::<f64>() / n as f64;
            let s_uy: f64 = frames
                .iter()
                .map(|f| (f.0 - t_ref - mean) * (y(f) - y_mean))
                .sum();
            let slope = s_uy / s_uu;
            let intercept = y_mean - slope * mean;
            let rss: f64 = frames
                .iter()
                .map(|f| (y(f) - intercept - slope * (f.0 - t_ref)).powi(2))
                .sum();
            position[k] = intercept;
            velocity[k] = slope;
            noise[k] = rss / (n - 2) as f64;
        }
        // (AᵀA)⁻¹ for A = [1, τ]: c_bb = 1/S_uu, c_ab = −mean/S_uu,
        // c_aa = 1/n + mean²/S_uu.
        let c_bb = 1.0 / s_uu;
        let c_ab = -mean * c_bb;
        let c_aa = 1.0 / n as f64 + mean * mean * c_bb;
        Some(FlightFit {
            t_ref,
            position,
            velocity,
            gravity,
            unscaled: [[c_aa, c_ab], [c_ab, c_bb]],
            noise,
            frames: n,
        })
    }

    /// Position (m) and velocity (m/s) at time `t` (s) along the parabola.
    pub fn state(&self, t: f64) -> ([f64; 3], [f64; 3]) {
        let tau = t - self.t_ref;
        let position = core::array::from_fn(|k| {
            self.position[k] + tau * (self.velocity[k] + 0.5 * self.gravity[k] * tau)
        });
        let velocity = core::array::from_fn(|k| self.velocity[k] + self.gravity[k] * tau);
        (position, velocity)
    }

    /// Variances per axis of the position (m²) and velocity ((m/s)²) the fit gives at
    /// time `t` (s): σ_k²·[1, τ]·(AᵀA)⁻¹·[1, τ]ᵀ and σ_k²·c_bb.
    pub(crate) fn variance(&self, t: f64) -> ([f64; 3], [f64; 3]) {
        let tau = t - self.t_ref;
        let [[c_aa, c_ab], [_, c_bb]] = self.unscaled;
        let shape = c_aa + 2.0 * tau * c_ab + tau * tau * c_bb;
        (self.noise.map(|s| s * shape), self.noise.map(|s| s * c_bb))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_exact_parabola_is_fitted_exactly_with_no_noise() {
        let g = [0.0, 0.0, -9.81];
        let frames: Vec<(f64, [f64; 3])> = (0..20)
            .map(|i| {
                let t = i as f64 * 5e-5;
                (t, [1e-3, 0.0, 0.1 - 1.4 * t - 0.5 * 9.81 * t * t])
            })
            .collect();
        let fit = FlightFit::fit(&frames, g, 1e-3).unwrap();
        let (p, v) = fit.state(1e-3);
        assert!(
            (p[2] - (0.1 - 1.4e-3 - 0.5 * 9.81e-6)).abs() < 1e-15,
            "{p:?}"
        );
        assert!((v[2] + 1.4 + 9.81e-3).abs() < 1e-11, "{v:?}");
        assert!((p[0] - 1e-3).abs() < 1e-16);
        assert!(fit.noise.iter().all(|&s| s < 1e-28), "{:?}", fit.noise);
    }

    #[test]
    fn the_covariance_matches_the_textbook_line_fit() {
        // A straight-line fit at n equally spaced points h apart, referred to the
        // last: var(b) = 12σ²/(h²·n(n²−1)), var(a) = σ²(4n−2)/(n(n+1)).
        let n = 11;
        let h = 1e-4;
        let frames: Vec<(f64, [f64; 3])> = (0..n)
            .map(|i| {
                (
                    i as f64 * h,
                    [0.0, 0.0, if i % 2 == 0 { 1e-6 } else { -1e-6 }],
                )
            })
            .collect();
        let t_end = (n - 1) as f64 * h;
        let fit = FlightFit::fit(&frames, [0.0; 3], t_end).unwrap();
        let nf = n as f64;
        let c_bb = 12.0 / (h * h * nf * (nf * nf - 1.0));
        let c_aa = (4.0 * nf - 2.0) / (nf * (nf + 1.0));
        assert!((fit.unscaled[1][1] / c_bb - 1.0).abs() < 1e-9);
        assert!((fit.unscaled[0][0] / c_aa - 1.0).abs() < 1e-9);
        assert!(FlightFit::fit(&frames[..2], [0.0; 3], 0.0).is_none());
    }
}
