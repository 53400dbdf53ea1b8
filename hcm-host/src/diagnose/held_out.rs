//! Held-out evidence by runs: how much better one set of causes predicts runs it was not
//! fitted on than another, run by run, with the runs as the independent units.
//!
//! An information criterion over all samples counts every sample as independent
//! evidence. Run-to-run scatter of the contact (each run its own stiffness and damping,
//! 2 % apart with `hcm generate`'s scatter) makes a run's residuals move together: a
//! cause can fit that run-level pattern better than the true one and win the criterion
//! by hundreds of σ², run after run of the same data set. Scored on held-out runs and
//! compared run by run, such a win has the runs' own spread as its yardstick: it is
//! told from the true cause only when it wins consistently.
//!
//! The runs are dealt into [`FOLDS`] folds by their order; each fold's runs are predicted
//! by the model re-fitted on the other folds' runs, and each run's RSS is summed over
//! its samples. Two such per-run vectors are compared by a paired t over the runs
//! ([`super::paired::Paired`], the motion diagnosis's yardstick too).

use super::catalogue::Candidate;
use super::paired::t_975;
use super::select::{refit, BaseFreedom, Refit};
use super::ContactSamples;
use hcm_core::effect::ExtendedLaw;
use rayon::prelude::*;

/// Folds of the runs (–).
pub const FOLDS: usize = 4;

/// What the held-out fits give.
#[derive(Clone, Debug)]
pub struct HeldOut {
    /// Per-run held-out RSS (N²), in the order of the runs' first samples; empty with
    /// fewer than two runs (nothing to hold out).
    pub rss: Vec<f64>,
    /// Each fold's re-fit on the other folds' runs.
    pub fits: Vec<Refit>,
}

impl HeldOut {
    /// `fit`'s causes with each parameter's 95 % interval widened, where the folds'
    /// fits scatter more than it says, to the grouped jackknife's: the folds' estimates
    /// θ_f about their mean, variance (K − 1)/K·Σ(θ_f − θ̄)², half-width Student's t
    /// with K − 1 degrees of freedom times its root. A covariance knows the sample
    /// noise; the folds also know how the runs scatter.
    pub fn widen(&self, fit: &mut Refit) {
        let k = self.fits.len();
        if k < 2 {
            return;
        }
        for (c, cause) in fit.causes.iter_mut().enumerate() {
            for (j, p) in cause.parameters.iter_mut().enumerate() {
                let values: Vec<f64> = self
                    .fits
                    .iter()
                    .filter_map(|f| f.causes.get(c).and_then(|fc| fc.parameters.get(j)))
                    .map(|q| q.value)
                    .collect();
                if values.len() != k || values.iter().any(|v| !v.is_finite()) {
                    continue;
                }
                let n = k as f64;
                let mean = values.iter().sum::<f64>() / n;
                let variance =
                    (n - 1.0) / n * values.iter().map(|v| (v - mean).powi(2)).sum::<f64>();
                let half = t_975(k - 1) * variance.sqrt();
                let (lo, hi) = (p.value - half, p.value + half);
                p.ci = (p.ci.0.min(lo), p.ci.1.max(hi));
            }
        }
    }
}

/// The base law re-fitted with `causes` on each fold's complement and scored on the
/// fold (see [`HeldOut`]).
pub fn held_out_rss(
    samples: &ContactSamples,
    (base, freedom): (&ExtendedLaw<f64>, BaseFreedom),
    causes: &[(Candidate, f64)],
    sigma: f64,
) -> HeldOut {
    // Runs in order, each with its fold; run indices are the data set's, so a table by
    // index maps a run to its place here.
    let runs: Vec<usize> = samples
        .run_ranges()
        .iter()
        .map(|r| samples.run[r.start])
        .collect();
    if runs.len() < 2 {
        return HeldOut {
            rss: Vec::new(),
            fits: Vec::new(),
        };
    }
    let folds = FOLDS.min(runs.len());
    let mut place = vec![0; runs.iter().max().map_or(0, |m| m + 1)];
    for (k, &r) in runs.iter().enumerate() {
        place[r] = k;
    }
    let fold_of = |r: usize| place[r] % folds;
    let per_fold: Vec<(Vec<(usize, f64)>, Refit)> = (0..folds)
        .into_par_iter()
        .map(|f| {
            let train = samples.select(|r| fold_of(r) != f);
            let test = samples.select(|r| fold_of(r) == f);
            let fit = refit(&train, (base, freedom), causes, sigma);
            let predicted = fit.sensor.reads(&test, &fit.law);
            (per_run_rss(&test, &predicted), fit)
        })
        .collect();
    let mut rss = vec![0.0; runs.len()];
    for &(r, e) in per_fold.iter().flat_map(|(per_run, _)| per_run) {
        rss[place[r]] += e;
    }
    HeldOut {
        rss,
        fits: per_fold.into_iter().map(|(_, fit)| fit).collect(),
    }
}

/// Each run's RSS of `predicted` against `test` (N²), in run order, the prediction in
/// contact first scaled by the run's own least-squares factor Σp·y/Σp² over its
/// in-contact samples: each run's contact is its own (its stiffness scatters), and a
/// cause must predict the run's shape, not its scale — else an effect that grows
/// with the deepest indentation (a plasticity's set) wins by following the runs'
/// stiffness, which sets their depth.
fn per_run_rss(test: &ContactSamples, predicted: &[f64]) -> Vec<(usize, f64)> {
    let mut rss: Vec<(usize, f64)> = Vec::new();
    for (range, py, pp) in test.run_scale_sums(predicted, 0.0, |i| test.in_contact[i]) {
        let scale = if pp > 0.0 && (py / pp).is_finite() {
            py / pp
        } else {
            1.0
        };
        let run = test.run[range.start];
        let sum = range
            .map(|i| {
                let p = if test.in_contact[i] {
                    scale * predicted[i]
                } else {
                    predicted[i]
                };
                (p - test.measured[i]).powi(2)
            })
            .sum();
        rss.push((run, sum));
    }
    rss
}
