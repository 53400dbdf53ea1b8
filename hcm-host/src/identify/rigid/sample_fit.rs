//! PM2 of a rigid contact from its force samples: the law's free parameters
//! and its STEP friction's, fitted by Levenberg–Marquardt so that the wrench the
//! contact model gives at every recorded pose matches the measured one
//! ([`RecordedContact`]), with a standard error per parameter that holds where the runs
//! scatter.
//!
//! - **Objective**: ½ Σ over rows of ((F_meas − F)/F_rms)² + ((T_meas − T)/T_rms)²,
//!   force and torque each in units of its own RMS over the rows, so that neither
//!   dominates by its unit.
//! - **Coordinates**: a parameter searched on a log scale (stiffness, transition
//!   speeds) is fitted as its logarithm; the others as they are; both inside the box.
//! - **Starts**: the scenario's values (clamped into the box) and
//!   `EXTRA_STARTS` points of a Halton sequence in the box (deterministic: same data,
//!   same fit); the lowest cost wins. Friction is not linear in its transition speeds
//!   and the box spans decades, so one local search can stop in another valley.
//! - **Standard errors**: the larger of the asymptotic one (σ²(JᵀJ)⁻¹, samples taken
//!   as independent) and a delete-a-group jackknife over the runs (`GROUPS` groups,
//!   each re-fitted from the best): samples of one run share its scatter, which the
//!   asymptotic one does not see.

use super::quality::at_bounds;
use super::recorded::RecordedContact;
use super::scaled::ContactScales;
use super::{RigidIdentifyError, RigidParameters};
use crate::dataset::Dataset;
use crate::identify::bounds::BoundsOverrides;
use crate::numerics::optimize::levenberg_marquardt::{levenberg_marquardt, LmSettings};
use crate::numerics::optimize::{Bound, Parameters};
use crate::progress::{in_stage, Progress, Stage};
use crate::scenario::Model;
use std::time::Instant;

/// Starts beside the scenario's own values.
const EXTRA_STARTS: usize = 7;

/// Relative cost difference below which two starts' ends are a tie (–).
const TIE: f64 = 1e-9;

/// Groups of runs of the jackknife (fewer when there are fewer runs).
const GROUPS: usize = 8;

/// Relative standard error beyond which a parameter is said not to be fixed by the
/// data (–).
const LOOSE: f64 = 0.5;

/// Share of the measured force's mean square the fit must explain before it is taken
/// as a fit (–): below it, the law at its best is no better than no force at all.
const EXPLAINED_MIN: f64 = 0.2;

/// What the fit found.
#[derive(Clone, Debug)]
pub struct SampleFit {
    /// The given model with the fitted parameters.
    pub model: Model,
    /// The fitted values (SI units), the law's then friction's.
    pub parameters: Vec<(String, f64)>,
    /// Standard error of each (same units, same order).
    pub standard_errors: Vec<f64>,
    /// RMS of the force residual over the rows (N).
    pub force_rms: f64,
    /// RMS of the torque residual over the rows with torque (N·m).
    pub torque_rms: f64,
    /// Rows fitted (touching samples).
    pub rows: usize,
    /// Runs they come from.
    pub runs: usize,
    /// Residual evaluations.
    pub evaluations: usize,
    /// Wall-clock time (s).
    pub seconds: f64,
    /// The search box, in the order of the genes.
    pub bounds: Vec<Bound>,
    /// What the fit could not do, each with what to try.
    pub warnings: Vec<String>,
}

/// The whole fit from force samples, as `hcm identify --method lsq` runs it on a rigid
/// contact: what was recorded, how the box was scaled, what was found.
#[derive(Clone, Debug)]
pub struct SampleIdentification {
    /// The fit.
    pub fit: SampleFit,
    /// The scales read from the data.
    pub scales: ContactScales,
    /// The parameters whose box was scaled from the data.
    pub scaled: Vec<String>,
    /// Rows with a measured torque.
    pub torque_rows: usize,
}

/// Contact `c` of `start` identified from the force samples of `data`: the law's free
/// parameters (the exponent too when `fit_exponent`) and friction's, in the box of the
/// scenario's `overrides` or else the defaults scaled from the data ([`ContactScales`]).
pub fn identify_from_samples(
    start: &Model,
    data: &Dataset,
    c: usize,
    overrides: &BoundsOverrides,
    fit_exponent: bool,
    progress: &dyn Progress,
) -> Result<SampleIdentification, RigidIdentifyError> {
    let mut parameters = RigidParameters::new(start, c, overrides)?;
    if fit_exponent {
        parameters = parameters.with_exponent(start, overrides)?;
    }
    let recorded = RecordedContact::from_data(start, data, c)?;
    let exponent = start.contacts[c].law().get("exponent").unwrap_or(1.5);
    let scales = ContactScales::of(&recorded, exponent);
    let scaled = scales.apply(start, c, &mut parameters);
    let fit = fit_samples(start, &recorded, &parameters, progress)?;
    Ok(SampleIdentification {
        fit,
        scales,
        scaled,
        torque_rows: (recorded.samples.iter())
            .filter(|s| s.measured[3].is_finite())
            .count(),
    })
}

/// Fits contact `recorded.contact`'s free `parameters` of `model` to `recorded`,
/// reporting [`Stage::Identify`] (one step per start) to `progress`.
pub fn fit_samples<P: Parameters<Target = Model> + Sync>(
    model: &Model,
    recorded: &RecordedContact,
    parameters: &P,
    progress: &dyn Progress,
) -> Result<SampleFit, RigidIdentifyError> {
    let started = Instant::now();
    let bounds = parameters.bounds();
    let space = Space::new(&bounds);
    let mut starts = vec![space.inside(&parameters.values(model))];
    starts.extend((1..=EXTRA_STARTS).map(|i| space.halton(i)));
    let mut evaluations = 0;
    let best = in_stage(progress, Stage::Identify, starts.len() as u64, || {
        let mut best: Option<(Vec<f64>, f64)> = None;
        for (k, start) in starts.iter().enumerate() {
            if let Ok(found) = space.fit(model, recorded, parameters, start, 60, &[]) {
                evaluations += found.evaluations;
                // A start that ends no lower than the best so far but for rounding
                // leaves it: parameters the data do not feel stay at the scenario's
                // values, not wherever a later start left them.
                if best.as_ref().is_none_or(|b| found.cost < b.1 * (1.0 - TIE)) {
                    best = Some((found.parameters, found.cost));
                }
            }
            progress.advance(k as u64 + 1, starts.len() as u64);
        }
        best
    })
    .ok_or_else(|| {
        RigidIdentifyError::Setup(
            "no start of the least-squares fit gave a finite wrench at the recorded poses"
                .to_owned(),
        )
    })?;
    let (z, _) = best;
    let genes = space.genes(&z);
    let fitted = parameters.apply(model, &genes);
    let named = parameters.named(&genes);
    let (jackknife, jack_evaluations) = space.jackknife(model, recorded, parameters, &z);
    evaluations += jack_evaluations;
    let covariance = space.covariance(model, recorded, parameters, &z);
    let asymptotic = space.named_errors(parameters, &z, covariance.as_deref());
    let unfelt: Vec<usize> = (covariance.iter())
        .flat_map(|c| (0..z.len()).filter(|&j| c[j][j].is_infinite()))
        .collect();
    let (confounded, profile_evaluations) =
        space.confounded(model, recorded, parameters, &z, &unfelt);
    evaluations += profile_evaluations;
    let (per_run, scaled_evaluations) = space.per_run_scaled(model, recorded, parameters, &z);
    evaluations += scaled_evaluations;
    let standard_errors: Vec<f64> = (0..named.len())
        .map(|i| {
            let se = jackknife[i].max(asymptotic[i]).max(confounded[i]);
            se + per_run.get(i).map_or(0.0, |v| 0.5 * (v - named[i].1).abs())
        })
        .collect();
    let (force_rms, torque_rms) = rms(recorded, &fitted);
    let mut fit = SampleFit {
        model: fitted,
        parameters: named,
        standard_errors,
        force_rms,
        torque_rms,
        rows: recorded.samples.len(),
        runs: recorded.runs,
        evaluations,
        seconds: 0.0,
        bounds,
        warnings: Vec::new(),
    };
    fit.warnings = warnings(&fit, &genes, recorded);
    fit.seconds = started.elapsed().as_secs_f64();
    Ok(fit)
}

/// One Levenberg–Marquardt fit of `parameters` to `recorded` from `start` (genes, in
/// the box), at most `iterations` Jacobians: the genes found and the cost (½ the sum
/// of the weighted residuals squared); `None` if it fails. The building block of a
/// diagnosis' many fits.
pub fn least_squares<P: Parameters<Target = Model> + Sync>(
    model: &Model,
    recorded: &RecordedContact,
    parameters: &P,
    start: &[f64],
    iterations: usize,
) -> Option<(Vec<f64>, f64)> {
    let space = Space::new(&parameters.bounds());
    let z = space.inside(start);
    let found = space
        .fit(model, recorded, parameters, &z, iterations, &[])
        .ok()?;
    Some((space.genes(&found.parameters), found.cost))
}

/// RMS of the force (N) and torque (N·m) residuals of `candidate` over `recorded`.
fn rms(recorded: &RecordedContact, candidate: &Model) -> (f64, f64) {
    let (mut f, mut t, mut nf, mut nt) = (0.0, 0.0, 0usize, 0usize);
    for (sample, got) in recorded.samples.iter().zip(recorded.readings(candidate)) {
        let e: Vec<f64> = (0..6).map(|k| sample.measured[k] - got[k]).collect();
        if e[..3].iter().all(|x| x.is_finite()) {
            f += e[..3].iter().map(|x| x * x).sum::<f64>();
            nf += 1;
        }
        if e[3..].iter().all(|x| x.is_finite()) {
            t += e[3..].iter().map(|x| x * x).sum::<f64>();
            nt += 1;
        }
    }
    let root = |sum: f64, n: usize| {
        if n == 0 {
            f64::NAN
        } else {
            (sum / n as f64).sqrt()
        }
    };
    (root(f, nf), root(t, nt))
}

/// The fit's warnings: a parameter at its bound, one the data leave loose, a law that
/// explains less of the force than [`EXPLAINED_MIN`].
fn warnings(fit: &SampleFit, genes: &[f64], recorded: &RecordedContact) -> Vec<String> {
    let mut out = at_bounds(&fit.bounds, genes);
    for ((name, value), se) in fit.parameters.iter().zip(&fit.standard_errors) {
        if !(se.is_finite() && *se <= LOOSE * value.abs()) {
            let spread = if *se <= 10.0 * value.abs() {
                format!("± {se:.2e}, one standard error over {LOOSE} of its value")
            } else {
                "the wrench hardly changes with it".to_owned()
            };
            out.push(format!(
                "`{name}` is not fixed by the data ({value:.4e}: {spread}) — the recorded \
                 samples barely feel it: record the phase that does (impacts for damping, \
                 sliding for friction, slow slip for the transition speeds), or keep the \
                 scenario's value, which is where the fit left it"
            ));
        }
    }
    let between = recorded.samples.iter().filter(|s| s.between_frames).count();
    if between > 0 {
        out.push(format!(
            "{between} of {} rows read the moving body's state between its frames \
             (interpolated, velocities differentiated where the tracker gives none): the \
             fit is only as good as that reading — friction near sticking needs slip \
             speeds of mm/s. Measured on a ball at 20 kHz: velocities differentiated from \
             frames at the force rate took the stiffness 39 % low; record the state at \
             the force's instants, or its velocities",
            recorded.samples.len()
        ));
    }
    let explained = 1.0 - (fit.force_rms / recorded.force_scale).powi(2);
    if explained.is_nan() || explained < EXPLAINED_MIN {
        out.push(format!(
            "the fitted law explains {:.0} % of the measured force's mean square ({:.3e} N \
             RMS left of {:.3e} N): nothing was fitted — check that the scenario's \
             geometry places the bodies where the data do, and the force's sign and frame \
             (world, on the moving body)",
            100.0 * explained,
            fit.force_rms,
            recorded.force_scale
        ));
    }
    out
}

/// The coordinates the search works in: log(value) for log-scaled genes.
struct Space {
    bounds: Vec<Bound>,
}

impl Space {
    fn new(bounds: &[Bound]) -> Space {
        Space {
            bounds: bounds.to_vec(),
        }
    }

    /// The named parameters' values (SI units) at coordinates `z`.
    fn named_values<P: Parameters<Target = Model>>(&self, parameters: &P, z: &[f64]) -> Vec<f64> {
        let named = parameters.named(&self.genes(z));
        named.into_iter().map(|(_, v)| v).collect()
    }

    /// Genes (the parameters' units) of coordinates `z`.
    fn genes(&self, z: &[f64]) -> Vec<f64> {
        (self.bounds.iter().zip(z))
            .map(|(b, &v)| if b.log_scale { v.exp() } else { v })
            .collect()
    }

    /// Coordinates of `genes`, each clamped into its box (a NaN gene: the box's middle).
    fn inside(&self, genes: &[f64]) -> Vec<f64> {
        (self.bounds.iter().zip(genes))
            .map(|(b, &g)| {
                let at = if g.is_nan() { 0.5 } else { b.fraction_of(g) };
                self.coordinate(b, b.value_at(at))
            })
            .collect()
    }

    fn coordinate(&self, b: &Bound, gene: f64) -> f64 {
        if b.log_scale {
            gene.ln()
        } else {
            gene
        }
    }

    /// Point `i` (≥ 1) of the Halton sequence in the box.
    fn halton(&self, i: usize) -> Vec<f64> {
        const PRIMES: [usize; 10] = [2, 3, 5, 7, 11, 13, 17, 19, 23, 29];
        (self.bounds.iter().enumerate())
            .map(|(d, b)| {
                let base = PRIMES[d % PRIMES.len()];
                let (mut f, mut r, mut n) = (1.0, 0.0, i);
                while n > 0 {
                    f /= base as f64;
                    r += f * (n % base) as f64;
                    n /= base;
                }
                self.coordinate(b, b.value_at(r))
            })
            .collect()
    }

    /// The box in coordinates, and each coordinate's scale.
    fn lm_box(&self) -> (Vec<Bound>, Vec<f64>) {
        let boxed = (self.bounds.iter())
            .map(|b| {
                let (lo, hi) = (self.coordinate(b, b.lower), self.coordinate(b, b.upper));
                Bound::linear(b.name.clone(), lo, hi)
            })
            .collect();
        let scales = (self.bounds.iter())
            .map(|b| {
                if b.log_scale {
                    1.0
                } else {
                    (b.upper - b.lower).abs().max(f64::MIN_POSITIVE)
                }
            })
            .collect();
        (boxed, scales)
    }

    /// Levenberg–Marquardt from `start` (coordinates), at most `iterations` Jacobians.
    fn fit<P: Parameters<Target = Model> + Sync>(
        &self,
        model: &Model,
        recorded: &RecordedContact,
        parameters: &P,
        start: &[f64],
        iterations: usize,
        held: &[(usize, f64)],
    ) -> Result<crate::numerics::optimize::levenberg_marquardt::LmResult, RigidIdentifyError> {
        use crate::numerics::optimize::levenberg_marquardt::{LmResult, Termination};
        let m = 6 * recorded.samples.len();
        if start.is_empty() {
            // Nothing free (a model diagnosed as given, before any effect): the cost
            // where the model stands.
            let mut out = vec![0.0; m];
            recorded.residuals(&parameters.apply(model, &[]), &mut out);
            let cost = 0.5 * out.iter().map(|r| r * r).sum::<f64>();
            return match cost.is_finite() {
                true => Ok(LmResult {
                    parameters: Vec::new(),
                    cost,
                    iterations: 0,
                    evaluations: 1,
                    covariance: None,
                    termination: Termination::HeldByBounds,
                }),
                false => Err(RigidIdentifyError::Setup(
                    "the model's wrench is not finite".into(),
                )),
            };
        }
        let (mut boxed, scales) = self.lm_box();
        let mut start = start.to_vec();
        for &(j, value) in held {
            (boxed[j].lower, boxed[j].upper, start[j]) = (value, value, value);
        }
        let settings = LmSettings {
            max_iterations: iterations,
            gradient_tolerance: 1e-10,
            step_tolerance: 1e-10,
            cost_tolerance: 1e-12,
            ..LmSettings::default()
        };
        let residuals = |z: &[f64], out: &mut [f64]| {
            let candidate = parameters.apply(model, &self.genes(z));
            recorded.residuals(&candidate, out);
        };
        levenberg_marquardt(residuals, m, &start, &scales, Some(&boxed), &settings)
            .map_err(|e| RigidIdentifyError::Setup(format!("least squares: {e}")))
    }

    /// Each named parameter's delete-a-group jackknife standard error over the runs,
    /// and the residual evaluations it took.
    fn jackknife<P: Parameters<Target = Model> + Sync>(
        &self,
        model: &Model,
        recorded: &RecordedContact,
        parameters: &P,
        z: &[f64],
    ) -> (Vec<f64>, usize) {
        let count = parameters.named(&self.genes(z)).len();
        let groups = GROUPS.min(recorded.runs);
        if groups < 2 {
            return (vec![0.0; count], 0);
        }
        let mut evaluations = 0;
        let mut estimates: Vec<Vec<f64>> = Vec::new();
        for g in 0..groups {
            let part = recorded.part(|r| r % groups != g);
            if part.samples.len() * 6 <= z.len() {
                continue;
            }
            if let Ok(found) = self.fit(model, &part, parameters, z, 30, &[]) {
                evaluations += found.evaluations;
                estimates.push(self.named_values(parameters, &found.parameters));
            }
        }
        let n = estimates.len() as f64;
        if n < 2.0 {
            return (vec![f64::INFINITY; count], evaluations);
        }
        let errors = (0..count)
            .map(|i| {
                let mean = estimates.iter().map(|e| e[i]).sum::<f64>() / n;
                let sum: f64 = estimates.iter().map(|e| (e[i] - mean).powi(2)).sum();
                ((n - 1.0) / n * sum).sqrt()
            })
            .collect();
        (errors, evaluations)
    }

    /// The named parameters re-fitted (from `z`) after each run's measured wrench is
    /// divided by its own least-squares scale against the fit, normalised by their
    /// mean: where a rig's runs scatter (each its own stiffness), the deep samples come
    /// from the soft runs and a pooled fit leans with them — a bias every jackknife
    /// group shares. The distance to the re-fit is added to each standard error, so
    /// that its interval (±2 SE) holds both. Empty when the re-fit fails.
    fn per_run_scaled<P: Parameters<Target = Model> + Sync>(
        &self,
        model: &Model,
        recorded: &RecordedContact,
        parameters: &P,
        z: &[f64],
    ) -> (Vec<f64>, usize) {
        let fitted = parameters.apply(model, &self.genes(z));
        let mut sums = vec![(0.0, 0.0); recorded.runs];
        for sample in &recorded.samples {
            let got = recorded.predicted(&fitted, sample);
            for (m, g) in sample.measured[..3].iter().zip(&got[..3]) {
                sums[sample.run].0 += m * g;
                sums[sample.run].1 += g * g;
            }
        }
        let scale: Vec<f64> = sums
            .iter()
            .map(|&(mp, pp)| if pp > 0.0 { mp / pp } else { f64::NAN })
            .collect();
        let finite: Vec<f64> = scale
            .iter()
            .copied()
            .filter(|s| s.is_finite() && *s > 0.0)
            .collect();
        if finite.len() < 2 {
            return (Vec::new(), 0);
        }
        let mean = finite.iter().sum::<f64>() / finite.len() as f64;
        let mut scaled = recorded.clone();
        for sample in &mut scaled.samples {
            let s = scale[sample.run];
            if s.is_finite() && s > 0.0 {
                sample.measured.iter_mut().for_each(|m| *m *= mean / s);
            }
        }
        match self.fit(model, &scaled, parameters, z, 30, &[]) {
            Ok(found) => {
                let named = parameters.named(&self.genes(&found.parameters));
                (
                    named.into_iter().map(|(_, v)| v).collect(),
                    found.evaluations,
                )
            }
            Err(_) => (Vec::new(), 0),
        }
    }

    /// How far each named parameter moves when a coordinate the data do not feel
    /// (`unfelt`) is held elsewhere in its box (at 10, 50 and 90 % of it) and the rest
    /// re-fitted: a parameter fixed only given an unfelt one (STEP's μ_s, read where the
    /// slip passes transition speeds that nothing fixes) is no better known than that.
    /// The largest move per parameter (its units; 0 for none), and the evaluations.
    fn confounded<P: Parameters<Target = Model> + Sync>(
        &self,
        model: &Model,
        recorded: &RecordedContact,
        parameters: &P,
        z: &[f64],
        unfelt: &[usize],
    ) -> (Vec<f64>, usize) {
        let values = |z: &[f64]| self.named_values(parameters, z);
        let at = values(z);
        let mut moved = vec![0.0_f64; at.len()];
        let mut evaluations = 0;
        for &j in unfelt {
            let bound = &self.bounds[j];
            for share in [0.1, 0.5, 0.9] {
                let held = self.coordinate(bound, bound.value_at(share));
                if let Ok(found) = self.fit(model, recorded, parameters, z, 30, &[(j, held)]) {
                    evaluations += found.evaluations;
                    let other = values(&found.parameters);
                    for ((m, o), a) in moved.iter_mut().zip(&other).zip(&at) {
                        *m = m.max((o - a).abs());
                    }
                }
            }
        }
        (moved, evaluations)
    }

    /// σ²(JᵀJ)⁻¹ in coordinates at `z`, σ² = ‖r‖²/(m − p), J by central differences;
    /// a coordinate whose column is negligible (the data do not feel it) gets an
    /// infinite variance and no covariance with the others, which are inverted
    /// without it. `None` when the rest is singular too.
    fn covariance<P: Parameters<Target = Model> + Sync>(
        &self,
        model: &Model,
        recorded: &RecordedContact,
        parameters: &P,
        z: &[f64],
    ) -> Option<Vec<Vec<f64>>> {
        let m = 6 * recorded.samples.len();
        let p = z.len();
        let residuals = |z: &[f64]| {
            let mut out = vec![0.0; m];
            recorded.residuals(&parameters.apply(model, &self.genes(z)), &mut out);
            out
        };
        let (_, scales) = self.lm_box();
        let at = residuals(z);
        let columns: Vec<Vec<f64>> = (0..p)
            .map(|j| {
                let h = 1e-5 * scales[j];
                let (mut up, mut down) = (z.to_vec(), z.to_vec());
                up[j] += h;
                down[j] -= h;
                let (a, b) = (residuals(&up), residuals(&down));
                a.iter().zip(&b).map(|(a, b)| (a - b) / (2.0 * h)).collect()
            })
            .collect();
        let norms: Vec<f64> = columns
            .iter()
            .map(|c| crate::numerics::euclidean_norm(c))
            .collect();
        let largest = norms.iter().copied().fold(0.0, f64::max);
        let felt: Vec<usize> = (0..p).filter(|&j| norms[j] > 1e-8 * largest).collect();
        let n = felt.len();
        let normal = nalgebra::DMatrix::from_fn(n, n, |a, b| {
            let (x, y) = (&columns[felt[a]], &columns[felt[b]]);
            x.iter().zip(y).map(|(x, y)| x * y).sum::<f64>()
        });
        let inverse = normal.try_inverse()?;
        let sigma2 = at.iter().map(|r| r * r).sum::<f64>() / (m.saturating_sub(p).max(1)) as f64;
        let mut cov = vec![vec![0.0; p]; p];
        for (j, row) in cov.iter_mut().enumerate() {
            row[j] = f64::INFINITY;
        }
        for (a, &i) in felt.iter().enumerate() {
            for (b, &j) in felt.iter().enumerate() {
                cov[i][j] = sigma2 * inverse[(a, b)];
            }
        }
        Some(cov)
    }

    /// The named parameters' asymptotic standard errors from the coordinates'
    /// covariance (delta method, central differences of the names' values); infinite
    /// without a covariance (a parameter the data do not feel).
    fn named_errors<P: Parameters<Target = Model> + Sync>(
        &self,
        parameters: &P,
        z: &[f64],
        covariance: Option<&[Vec<f64>]>,
    ) -> Vec<f64> {
        let values = |z: &[f64]| self.named_values(parameters, z);
        let count = values(z).len();
        let Some(cov) = covariance else {
            return vec![f64::INFINITY; count];
        };
        let p = z.len();
        let mut jacobian = vec![vec![0.0; p]; count];
        for j in 0..p {
            let h = 1e-6 * z[j].abs().max(1e-3);
            let (mut up, mut down) = (z.to_vec(), z.to_vec());
            up[j] += h;
            down[j] -= h;
            let (a, b) = (values(&up), values(&down));
            for i in 0..count {
                jacobian[i][j] = (a[i] - b[i]) / (2.0 * h);
            }
        }
        (0..count)
            .map(|i| {
                let row = &jacobian[i];
                let mut var = 0.0;
                // A coordinate the name does not depend on adds nothing, even where its
                // own variance is infinite.
                for a in (0..p).filter(|&a| row[a] != 0.0) {
                    for b in (0..p).filter(|&b| row[b] != 0.0) {
                        var += row[a] * cov[a][b] * row[b];
                    }
                }
                if var.is_nan() {
                    f64::INFINITY
                } else {
                    var.max(0.0).sqrt()
                }
            })
            .collect()
    }
}
