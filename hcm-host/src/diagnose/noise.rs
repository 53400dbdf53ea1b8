//! The noise floor: how large the sensor's white force noise is, read from the data's
//! own high-frequency content, so that it works on real measurements where the noise-free
//! force is unknown.
//!
//! Method (the second-difference estimator of e.g. Rice 1984, "Bandwidth choice for
//! nonparametric regression", with a robust scale): for three consecutive samples of one
//! run on a uniform clock,
//!
//! d_i = f_{i+1} − 2·f_i + f_{i−1}  (N).
//!
//! White noise of standard deviation σ gives Var(d_i) = (1 + 4 + 1)·σ² = 6σ², and a smooth
//! force f(t) adds only its curvature h²·f''(t) (h the sampling interval, s). The
//! median of |d| of a normal variable is 0.6745·√6·σ, hence
//!
//! σ = 1.4826 · median|d| / √6  (N).
//!
//! The median ignores the few large second differences where the contact force bends
//! sharply (touch-down and lift-off, where f jumps from 0 to its contact law), and any
//! jump between runs never enters: a triple is taken only within one run.
//!
//! **Bias from the signal's curvature.** A smooth pulse of peak F (N) and duration T (s)
//! sampled every h (s) — e.g. a half-sine F·sin(πt/T) — adds up to b = F·(πh/T)² (N) to
//! d. A deterministic shift b of a normal variable of standard deviation s = √6·σ raises
//! the median of its magnitude by the relative amount b²/(2s²) = b²/(12σ²). The bias is
//! therefore below 1 % wherever F·(πh/T)² < σ/3, and it stays small even where the
//! curvature is larger as long as such samples are a minority (the median only moves by
//! their fraction). Example: 3000 N over 115 samples gives b ≈ 2.3 N, against σ = 15 N a
//! bias of 0.2 % at the peak and less elsewhere. Sampling a contact with fewer than
//! about π·√(3F/σ) samples (≈ 80 for F = 3000 N, σ = 15 N) makes it noticeable.

use super::ContactSamples;
use crate::numerics::median;
use hcm_core::effect::ExtendedLaw;

/// Largest relative difference between the two intervals of a triple for the clock to
/// count as uniform there (–).
const UNIFORM_CLOCK: f64 = 0.01;
/// 1/Φ⁻¹(3/4): the median of |N(0, s²)| is s/1.4826 (–).
const MAD_TO_SIGMA: f64 = 1.482_6;

/// The estimated force noise of a record.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct NoiseFloor {
    /// Standard deviation σ of the white noise (the signal's unit: N for the force);
    /// NaN when no triple qualified.
    pub sigma: f64,
    /// Number of second differences the estimate rests on (–).
    pub(crate) samples: usize,
    /// How σ was obtained, in words.
    pub(crate) method: &'static str,
}

/// The standard deviation of the white force noise in `samples`, estimated from the
/// second differences of consecutive samples of the same run on a uniform clock (the
/// three times equally spaced within 1 %). The samples of one run must be in time order,
/// as [`super::contact_samples`] records them.
pub fn noise_floor(samples: &ContactSamples) -> NoiseFloor {
    white_noise(&samples.run, &samples.time, &samples.measured)
}

/// The standard deviation of white noise on any recorded signal (its unit), by the same
/// second differences: `values[i]` of run `run[i]` at time `time[i]` (s), each run's
/// samples in time order. Triples that straddle two runs or a change of clock are
/// skipped, as are non-finite values.
pub fn white_noise(run: &[usize], time: &[f64], values: &[f64]) -> NoiseFloor {
    let same_run = |i: usize| run[i - 1] == run[i] && run[i] == run[i + 1];
    let mut magnitudes: Vec<f64> = (1..values.len().saturating_sub(1))
        .filter(|&i| same_run(i) && uniform_clock(&time[i - 1..=i + 1]))
        .map(|i| (values[i + 1] - 2.0 * values[i] + values[i - 1]).abs())
        .filter(|d| d.is_finite())
        .collect();
    let count = magnitudes.len();
    NoiseFloor {
        sigma: MAD_TO_SIGMA * median(&mut magnitudes) / 6.0_f64.sqrt(),
        samples: count,
        method:
            "1.4826·median|x[i+1] − 2x[i] + x[i−1]|/√6 over triples of one run on a uniform clock",
    }
}

/// Whether the three times `t` (s) advance by two positive intervals equal within
/// [`UNIFORM_CLOCK`].
fn uniform_clock(t: &[f64]) -> bool {
    let (h1, h2) = (t[1] - t[0], t[2] - t[1]);
    h1 > 0.0 && h2 > 0.0 && (h1 - h2).abs() <= UNIFORM_CLOCK * h1.max(h2)
}

/// The noise the naming rule judges against (N): the sensor's σ and, where the contact's
/// motion was reconstructed (`dataset::reconstruct`), what that reconstruction's own
/// uncertainty does to the model force, σ_eff² = σ² + mean over the contact of
/// (∂f/∂δ·sd(δ))² + (∂f/∂δ̇·sd(δ̇))², the slopes of `law` by central differences.
///
/// A flight fit's δ error is one offset per run rather than white noise, so this is the
/// conservative side of it: the criterion then asks more of every effect, and a term a
/// few hundredths of a percent of the force (a δ offset's shape) is not named. On data
/// whose motion shares every row with the force the sds are 0 and σ_eff = σ.
pub fn effective_sigma(samples: &ContactSamples, law: &ExtendedLaw<f64>, sigma: f64) -> f64 {
    let contact: Vec<usize> = (0..samples.len())
        .filter(|&i| samples.in_contact[i] && samples.reconstructed(i))
        .collect();
    if contact.is_empty() {
        return sigma;
    }
    let force = |i: usize, depth: f64, rate: f64| {
        let (mut state, memory) = samples.state(i);
        state.depth = depth;
        state.rate = rate;
        law.normal_force(&state, &memory)
    };
    let variance: f64 = contact
        .iter()
        .map(|&i| {
            let (d, r) = (samples.depth[i], samples.rate[i]);
            let (sd_d, sd_r) = (samples.depth_sd[i], samples.rate_sd[i]);
            let slope_d = (force(i, d + sd_d, r) - force(i, d - sd_d, r)) / 2.0;
            let slope_r = (force(i, d, r + sd_r) - force(i, d, r - sd_r)) / 2.0;
            slope_d * slope_d + slope_r * slope_r
        })
        .filter(|v| v.is_finite())
        .sum::<f64>()
        / contact.len() as f64;
    (sigma * sigma + variance).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use rand_distr::Normal;

    const SIGMA: f64 = 15.0;

    /// Appends one sample; only run, time and measured force matter to the estimator.
    fn push(s: &mut ContactSamples, run: usize, time: f64, force: f64, in_contact: bool) {
        s.run.push(run);
        s.time.push(time);
        s.depth.push(0.0);
        s.rate.push(0.0);
        s.approach_speed.push(0.0);
        s.max_depth.push(0.0);
        s.in_contact.push(in_contact);
        s.measured.push(force);
    }

    fn assert_close(estimate: &NoiseFloor, sigma: f64) {
        let error = (estimate.sigma - sigma).abs() / sigma;
        assert!(
            error < 0.05,
            "σ estimated {} N from {} differences, true {sigma} N ({:.1} %)",
            estimate.sigma,
            estimate.samples,
            100.0 * error
        );
    }

    #[test]
    fn white_noise_on_a_constant() {
        let noise = Normal::new(0.0, SIGMA).unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let mut s = ContactSamples::default();
        for i in 0..20_000 {
            push(&mut s, 0, 1e-6 * i as f64, 250.0 + rng.sample(noise), false);
        }
        let estimate = noise_floor(&s);
        assert_eq!(estimate.samples, 19_998);
        assert_close(&estimate, SIGMA);
    }

    #[test]
    fn white_noise_on_contact_pulses_and_flight_at_another_spacing() {
        let noise = Normal::new(0.0, SIGMA).unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(12);
        let (peak, contact) = (3000.0, 115);
        let mut s = ContactSamples::default();
        for run in 0..120 {
            // 40 flight samples 1 ms apart, the pulse 1 µs apart, 40 more 1 ms apart.
            let mut t = 0.0;
            for _ in 0..40 {
                push(&mut s, run, t, rng.sample(noise), false);
                t += 1e-3;
            }
            for j in 0..contact {
                let phase = std::f64::consts::PI * (j as f64 + 0.5) / contact as f64;
                push(&mut s, run, t, peak * phase.sin() + rng.sample(noise), true);
                t += 1e-6;
            }
            for _ in 0..40 {
                t += 1e-3;
                push(&mut s, run, t, rng.sample(noise), false);
            }
        }
        assert!(s.len() >= 20_000);
        let estimate = noise_floor(&s);
        // Each run has 193 interior samples; the two triples whose intervals are 1 ms
        // and 1 µs do not count.
        assert_eq!(estimate.samples, 120 * (193 - 2));
        assert_close(&estimate, SIGMA);
    }

    #[test]
    fn runs_are_not_mixed() {
        // Runs of three samples on one continuing clock, each run 10⁴ N above the last:
        // only the one triple inside each run counts, and the jumps do not inflate σ.
        let noise = Normal::new(0.0, SIGMA).unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(13);
        let mut s = ContactSamples::default();
        let runs = 20_000;
        for run in 0..runs {
            for j in 0..3 {
                let t = 1e-6 * (3 * run + j) as f64;
                push(&mut s, run, t, 1e4 * run as f64 + rng.sample(noise), true);
            }
        }
        let estimate = noise_floor(&s);
        assert_eq!(estimate.samples, runs);
        assert_close(&estimate, SIGMA);
    }

    #[test]
    fn a_non_uniform_clock_is_skipped_and_no_triple_gives_nan() {
        let mut s = ContactSamples::default();
        for (t, f) in [(0.0, 0.0), (1.0, 1.0), (2.5, 2.0), (3.0, 0.0)] {
            push(&mut s, 0, t, f, false);
        }
        let estimate = noise_floor(&s);
        assert_eq!(estimate.samples, 0);
        assert!(estimate.sigma.is_nan());
    }
}
