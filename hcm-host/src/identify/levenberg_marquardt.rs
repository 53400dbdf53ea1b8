//! Levenberg–Marquardt for small bounded nonlinear least-squares problems.
//!
//! Minimises ½‖r(p)‖² over a handful of parameters (≤ 8 in practice) and up to about a
//! million residuals: after the separable search of [`super::least_squares`] has found
//! a good start, this refines every parameter of a contact law jointly and reports
//! their covariance.
//!
//! The method follows Moré 1978 (*The Levenberg–Marquardt algorithm: implementation
//! and theory*, Lecture Notes in Mathematics 630) and Nocedal & Wright 2006
//! (*Numerical Optimization*, 2nd ed., §10.3):
//! - parameters are handled internally as u_i = p_i / scale_i, so that a stiffness of
//!   1e10 N/m^n and an exponent of 1.5 are both of order one;
//! - each iteration factorises the Jacobian once, J·P = Q·R (faer, Householder with
//!   column pivoting), and for every trial damping λ solves the small augmented
//!   problem min ‖R·z + (Qᵀr)₁‖² + λ‖D·z‖² by a second QR (Moré §3), never forming JᵀJ;
//! - D² = diag(JᵀJ) (Marquardt 1963, *An algorithm for least-squares estimation of
//!   nonlinear parameters*, SIAM J. Appl. Math. 11(2)), kept non-decreasing over the
//!   iterations as Moré's eq. (6.3) recommends;
//! - λ is updated from the gain ratio ρ = actual / predicted reduction as in Nielsen
//!   1999 (*Damping parameter in Marquardt's method*, IMM-REP-1999-05): on success
//!   λ ← λ·max(1/3, 1 − (2ρ − 1)³), on failure λ ← λ·ν, ν ← 2ν;
//! - bounds are enforced by projecting each trial point onto the box (the projected
//!   method of Kanzow, Yamashita & Fukushima 2004, *Levenberg–Marquardt methods with
//!   strong local convergence properties for solving nonlinear equations with convex
//!   constraints*, J. Comput. Appl. Math. 172); in addition, parameters that sit on a
//!   bound with the gradient pushing outward are frozen for the step, so that the
//!   projection does not distort the other parameters' step.

use super::least_squares::{apply_q_transpose, euclidean_norm, numerical_rank, LeastSquaresError};
use faer::prelude::SolveLstsq;
use faer::{Mat, MatRef};
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};

/// √ε of `f64`, the relative forward-difference step.
const SQRT_EPSILON: f64 = 1.490_116_119_384_765_6e-8;

/// λ is kept at or above this (a relative damping at rounding level), so that a
/// rank-deficient R still gives a solvable augmented system.
const MIN_DAMPING: f64 = 1e-15;

/// A damping above this means no step along any direction reduces the cost.
const MAX_DAMPING: f64 = 1e32;

/// Settings of [`levenberg_marquardt`].
#[derive(Clone, Debug, PartialEq)]
pub struct LmSettings {
    /// Maximum number of iterations (Jacobian evaluations).
    pub max_iterations: usize,
    /// Converged when, for every free parameter, the cosine of the angle between the
    /// residual vector and the Jacobian column is at most this (MINPACK's `gtol`; a
    /// scale-free gradient test).
    pub gradient_tolerance: f64,
    /// Converged when a step is shorter than this relative to the scaled parameter
    /// vector: ‖Δu‖ ≤ tol·(‖u‖ + tol), u_i = p_i/scale_i.
    pub step_tolerance: f64,
    /// Converged when both the actual and the predicted relative reduction of the cost
    /// of an accepted step are at most this.
    pub cost_tolerance: f64,
    /// Initial λ (dimensionless: the damping is λ·diag(JᵀJ)).
    pub initial_damping: f64,
}

impl Default for LmSettings {
    fn default() -> Self {
        Self {
            max_iterations: 200,
            gradient_tolerance: 1e-12,
            step_tolerance: 1e-12,
            cost_tolerance: 1e-14,
            initial_damping: 1e-3,
        }
    }
}

/// The outcome of [`levenberg_marquardt`].
#[derive(Clone, Debug, PartialEq)]
pub struct LmResult {
    /// The best parameters found, in the caller's units.
    pub parameters: Vec<f64>,
    /// ½‖r‖² at `parameters` (half the residuals' unit squared).
    pub cost: f64,
    /// Iterations (Jacobian evaluations) performed, not counting the one for the
    /// covariance.
    pub iterations: usize,
    /// Calls of the residual function, Jacobian and covariance included.
    pub evaluations: usize,
    /// σ²·(JᵀJ)⁻¹ at `parameters` with σ² = 2·cost/(m − p), in the parameters' units
    /// squared: the asymptotic covariance of the estimates for independent residuals of
    /// equal variance (its diagonal's square roots are the standard errors). `None`
    /// when JᵀJ is numerically singular (a parameter without effect or two with the
    /// same effect), when m = p, or when the Jacobian there is not finite. Bounds are
    /// ignored: a parameter ending on its bound gets the unconstrained value.
    pub covariance: Option<Vec<Vec<f64>>>,
    /// Whether a tolerance was met (rather than the iteration limit or a damping
    /// overflow).
    pub converged: bool,
}

/// Minimises ½‖r(p)‖² for `residuals(p, out)` filling `m` residuals.
///
/// The Jacobian is taken by forward differences with per-parameter step
/// √ε·max(|p_i|, scale_i) (backward where the forward point would leave the box), its
/// columns evaluated in parallel (rayon). `scales` gives each parameter's typical
/// magnitude (> 0); the iteration works on p_i / scale_i, which matters when parameters
/// differ by 10 orders of magnitude. Bounds: optional per-parameter (lower, upper),
/// either may be infinite; the start is projected onto the box and so is every trial
/// point. Marquardt's scaling (damping λ·diag(JᵀJ)); the damped step solves the QR of
/// the augmented system with faer. See the module documentation for the references.
///
/// Never panics; a NaN or infinite residual at a trial point is a rejected step. The
/// residual function must fill all `m` entries of `out` and must be a pure function of
/// `p`. Memory: the Jacobian, m × p values, plus a copy while factorising.
///
/// Errors: no parameters, no residuals, fewer residuals than parameters, slices of the
/// wrong length, a non-positive scale, a bound that is not an interval, a non-finite
/// start or a non-finite residual there, a setting outside its domain, or a derivative
/// that is non-finite on both sides of a point.
pub fn levenberg_marquardt(
    residuals: impl Fn(&[f64], &mut [f64]) + Sync,
    m: usize,
    initial: &[f64],
    scales: &[f64],
    bounds: Option<&[(f64, f64)]>,
    settings: &LmSettings,
) -> Result<LmResult, LeastSquaresError> {
    let n = initial.len();
    if n == 0 {
        return Err(LeastSquaresError::NoUnknowns);
    }
    if m == 0 {
        return Err(LeastSquaresError::NoRows);
    }
    if m < n {
        return Err(LeastSquaresError::TooFewRows {
            rows: m,
            unknowns: n,
        });
    }
    check_settings(settings)?;
    if scales.len() != n {
        return Err(LeastSquaresError::LengthMismatch {
            what: "scales",
            expected: n,
            found: scales.len(),
        });
    }
    for (index, &scale) in scales.iter().enumerate() {
        if !(scale.is_finite() && scale > 0.0) {
            return Err(LeastSquaresError::InvalidScale { index, scale });
        }
    }
    for (index, &value) in initial.iter().enumerate() {
        if !value.is_finite() {
            return Err(LeastSquaresError::NonFiniteInitial { index, value });
        }
    }
    // Box in scaled coordinates.
    // The box in the caller's units and in scaled coordinates.
    let mut box_p = vec![(f64::NEG_INFINITY, f64::INFINITY); n];
    let mut lower = vec![f64::NEG_INFINITY; n];
    let mut upper = vec![f64::INFINITY; n];
    if let Some(bounds) = bounds {
        if bounds.len() != n {
            return Err(LeastSquaresError::LengthMismatch {
                what: "bounds",
                expected: n,
                found: bounds.len(),
            });
        }
        for (index, &(low, high)) in bounds.iter().enumerate() {
            if low.is_nan()
                || high.is_nan()
                || low > high
                || low == f64::INFINITY
                || high == f64::NEG_INFINITY
            {
                return Err(LeastSquaresError::InvalidBounds {
                    index,
                    lower: low,
                    upper: high,
                });
            }
            box_p[index] = (low, high);
            lower[index] = low / scales[index];
            upper[index] = high / scales[index];
        }
    }

    let problem = Problem {
        residuals: &residuals,
        scales,
        m,
        box_p: &box_p,
        lower: &lower,
        upper: &upper,
        evaluations: AtomicUsize::new(0),
    };
    let mut u: Vec<f64> = (0..n)
        .map(|i| (initial[i] / scales[i]).clamp(lower[i], upper[i]))
        .collect();
    let mut r = vec![0.0; m];
    problem.eval(&u, &mut r);
    if let Some(index) = r.iter().position(|v| !v.is_finite()) {
        return Err(LeastSquaresError::NonFiniteInitialResidual { index });
    }
    let mut cost = half_sum_of_squares(&r);

    let mut jacobian = vec![0.0; m * n];
    let mut trial_u = vec![0.0; n];
    let mut trial_r = vec![0.0; m];
    let mut diagonal = vec![0.0_f64; n];
    let mut damping = settings.initial_damping.max(MIN_DAMPING);
    let mut growth = 2.0;
    let mut iterations = 0;
    let mut converged = false;

    'iterations: while iterations < settings.max_iterations {
        if cost == 0.0 {
            converged = true;
            break;
        }
        iterations += 1;
        problem.jacobian(&u, &r, &mut jacobian)?;
        let column = |j: usize| &jacobian[j * m..(j + 1) * m];

        // Gradient Jᵀr, Marquardt's diagonal, the free set and the gradient test.
        let residual_norm = euclidean_norm(&r);
        let mut free = Vec::with_capacity(n);
        let mut largest_cosine = 0.0_f64;
        for j in 0..n {
            let norm = euclidean_norm(column(j));
            let gradient: f64 = column(j).iter().zip(&r).map(|(a, b)| a * b).sum();
            diagonal[j] = diagonal[j].max(if norm > 0.0 { norm } else { 1.0 });
            let held = lower[j] == upper[j]
                || (u[j] <= lower[j] && gradient > 0.0)
                || (u[j] >= upper[j] && gradient < 0.0);
            if !held {
                free.push(j);
                if norm > 0.0 {
                    largest_cosine = largest_cosine.max(gradient.abs() / (norm * residual_norm));
                }
            }
        }
        if free.is_empty() || largest_cosine <= settings.gradient_tolerance {
            converged = true;
            break;
        }

        // J_free·P = Q·R and (Qᵀr)₁ (faer copies the matrix it factorises).
        let qr = if free.len() == n {
            MatRef::from_column_major_slice(&jacobian, m, n).col_piv_qr()
        } else {
            Mat::from_fn(m, free.len(), |i, k| jacobian[free[k] * m + i]).col_piv_qr()
        };
        let mut qtr = Mat::from_fn(m, 1, |i, _| r[i]);
        apply_q_transpose(&qr, &mut qtr);
        let size = free.len();
        let rf = qr.thin_R();
        let (forward, _) = qr.P().arrays();
        let qtr_top: Vec<f64> = (0..size).map(|k| qtr[(k, 0)]).collect();
        let top_norm_squared: f64 = qtr_top.iter().map(|v| v * v).sum();
        let u_norm = euclidean_norm(&u);

        loop {
            // min ‖R·z + (Qᵀr)₁‖² + λ‖D_P·z‖²  ⇔  [R; √λ·D_P]·z ≈ [−(Qᵀr)₁; 0].
            let root = damping.sqrt();
            let augmented = Mat::from_fn(2 * size, size, |i, k| {
                if i < size {
                    if k >= i {
                        rf[(i, k)]
                    } else {
                        0.0
                    }
                } else if i - size == k {
                    root * diagonal[free[forward[k]]]
                } else {
                    0.0
                }
            });
            let rhs = Mat::from_fn(2 * size, 1, |i, _| if i < size { -qtr_top[i] } else { 0.0 });
            let z = augmented.qr().solve_lstsq(&rhs);

            trial_u.copy_from_slice(&u);
            let mut finite = true;
            for k in 0..size {
                let j = free[forward[k]];
                finite &= z[(k, 0)].is_finite();
                trial_u[j] = (u[j] + z[(k, 0)]).clamp(lower[j], upper[j]);
            }
            let step: Vec<f64> = trial_u.iter().zip(&u).map(|(t, x)| t - x).collect();
            let step_norm = euclidean_norm(&step);
            let small_step =
                step_norm <= settings.step_tolerance * (u_norm + settings.step_tolerance);

            // Predicted reduction of the projected step from the linear model:
            // ½(‖(Qᵀr)₁‖² − ‖(Qᵀr)₁ + R·z‖²).
            let predicted = if finite {
                let mut after = 0.0;
                for i in 0..size {
                    let mut entry = qtr_top[i];
                    for k in i..size {
                        entry += rf[(i, k)] * step[free[forward[k]]];
                    }
                    after += entry * entry;
                }
                0.5 * (top_norm_squared - after)
            } else {
                f64::NAN
            };

            let trial_cost = if finite && step_norm > 0.0 {
                problem.eval(&trial_u, &mut trial_r);
                half_sum_of_squares(&trial_r)
            } else {
                f64::INFINITY
            };
            let actual = cost - trial_cost;

            if trial_cost.is_finite() && actual > 0.0 {
                let ratio = if predicted > 0.0 {
                    actual / predicted
                } else {
                    0.5
                };
                damping = (damping * (1.0 / 3.0_f64).max(1.0 - (2.0 * ratio - 1.0).powi(3)))
                    .max(MIN_DAMPING);
                growth = 2.0;
                let previous_cost = cost;
                std::mem::swap(&mut u, &mut trial_u);
                std::mem::swap(&mut r, &mut trial_r);
                cost = trial_cost;
                if small_step
                    || (actual <= settings.cost_tolerance * previous_cost
                        && predicted.abs() <= settings.cost_tolerance * previous_cost)
                {
                    converged = true;
                    break 'iterations;
                }
                continue 'iterations;
            }

            // Rejected: more damping, shorter and more gradient-like step.
            if small_step {
                // No representable step improves the cost: a minimum to the tolerance.
                converged = true;
                break 'iterations;
            }
            damping *= growth;
            growth *= 2.0;
            if damping > MAX_DAMPING || damping.is_nan() {
                break 'iterations;
            }
        }
    }

    let covariance = if m > n {
        match problem.jacobian(&u, &r, &mut jacobian) {
            Ok(()) => {
                let variance = 2.0 * cost / (m - n) as f64;
                covariance(&jacobian, m, n, variance, scales)
            }
            Err(_) => None,
        }
    } else {
        None
    };

    Ok(LmResult {
        parameters: problem.unscale(&u),
        cost,
        iterations,
        evaluations: problem.evaluations.load(Ordering::Relaxed),
        covariance,
        converged,
    })
}

/// Rejects settings outside their domain.
fn check_settings(settings: &LmSettings) -> Result<(), LeastSquaresError> {
    let checks = [
        ("gradient_tolerance", settings.gradient_tolerance),
        ("step_tolerance", settings.step_tolerance),
        ("cost_tolerance", settings.cost_tolerance),
    ];
    for (name, value) in checks {
        if !(value.is_finite() && value >= 0.0) {
            return Err(LeastSquaresError::InvalidSetting {
                name,
                value,
                expected: "finite and ≥ 0",
            });
        }
    }
    let value = settings.initial_damping;
    if !(value.is_finite() && value > 0.0) {
        return Err(LeastSquaresError::InvalidSetting {
            name: "initial_damping",
            value,
            expected: "finite and > 0",
        });
    }
    Ok(())
}

/// ½Σr², +∞ if any residual is not finite.
fn half_sum_of_squares(r: &[f64]) -> f64 {
    let sum: f64 = r.iter().map(|v| v * v).sum();
    if sum.is_finite() {
        0.5 * sum
    } else {
        f64::INFINITY
    }
}

/// The residual function seen in scaled coordinates u = p / scale.
struct Problem<'a, F> {
    residuals: &'a F,
    scales: &'a [f64],
    m: usize,
    /// The bounds in the caller's units.
    box_p: &'a [(f64, f64)],
    /// The bounds in scaled coordinates.
    lower: &'a [f64],
    upper: &'a [f64],
    /// Calls of the residual function so far.
    evaluations: AtomicUsize,
}

impl<F: Fn(&[f64], &mut [f64]) + Sync> Problem<'_, F> {
    /// r at scaled point `u`.
    fn eval(&self, u: &[f64], out: &mut [f64]) {
        let p = self.unscale(u);
        self.evaluations.fetch_add(1, Ordering::Relaxed);
        (self.residuals)(&p, out);
    }

    /// p = u·scale, kept inside the caller's bounds (rounding in p/scale·scale could
    /// otherwise leave them by an ulp, where a law may be undefined).
    fn unscale(&self, u: &[f64]) -> Vec<f64> {
        u.iter()
            .zip(self.scales)
            .zip(self.box_p)
            .map(|((u, s), &(low, high))| (u * s).clamp(low, high))
            .collect()
    }

    /// Forward-difference ∂r/∂u into `jacobian` (column-major, m × n), given r(u).
    /// The step is √ε·max(|u_j|, 1), i.e. √ε·max(|p_j|, scale_j) in p; it goes
    /// backward where the forward point would leave the box or gives a non-finite
    /// residual, and is shortened to the room left in a box narrower than it.
    fn jacobian(
        &self,
        u: &[f64],
        r: &[f64],
        jacobian: &mut [f64],
    ) -> Result<(), LeastSquaresError> {
        let failure = jacobian
            .par_chunks_mut(self.m)
            .enumerate()
            .find_map_any(|(j, column)| {
                let nominal = SQRT_EPSILON * u[j].abs().max(1.0);
                let room_up = self.upper[j] - u[j];
                let room_down = u[j] - self.lower[j];
                let mut steps = if room_up >= nominal {
                    [nominal, -nominal.min(room_down)]
                } else if room_down >= nominal {
                    [-nominal, room_up]
                } else if room_up >= room_down {
                    [room_up, -room_down]
                } else {
                    [-room_down, room_up]
                };
                let mut shifted = u.to_vec();
                for step in &mut steps {
                    if *step == 0.0 {
                        continue;
                    }
                    shifted[j] = u[j] + *step;
                    // The step actually taken, exactly representable.
                    let h = shifted[j] - u[j];
                    if h == 0.0 {
                        continue;
                    }
                    self.eval(&shifted, column);
                    column
                        .iter_mut()
                        .zip(r)
                        .for_each(|(c, r0)| *c = (*c - r0) / h);
                    if column.iter().all(|v| v.is_finite()) {
                        return None;
                    }
                }
                if room_up == 0.0 && room_down == 0.0 {
                    // Fixed by its bounds: no derivative, no movement.
                    column.fill(0.0);
                    return None;
                }
                Some(j)
            });
        match failure {
            None => Ok(()),
            Some(parameter) => Err(LeastSquaresError::NonFiniteJacobian {
                parameter,
                value: u[parameter] * self.scales[parameter],
            }),
        }
    }
}

/// σ²·(JᵀJ)⁻¹ in the caller's units from ∂r/∂u (column-major m × n), or `None` if
/// JᵀJ is numerically singular. Columns are equilibrated before a pivoted QR; then
/// (JᵀJ)⁻¹ = N⁻¹·P·R⁻¹·R⁻ᵀ·Pᵀ·N⁻¹ with N the column norms.
fn covariance(
    jacobian: &[f64],
    m: usize,
    n: usize,
    variance: f64,
    scales: &[f64],
) -> Option<Vec<Vec<f64>>> {
    let norms: Vec<f64> = jacobian.chunks(m).map(euclidean_norm).collect();
    if norms.iter().any(|&v| !(v > 0.0 && v.is_finite())) || !variance.is_finite() {
        return None;
    }
    let j = MatRef::from_column_major_slice(jacobian, m, n);
    let qr = Mat::from_fn(m, n, |i, k| j[(i, k)] / norms[k]).col_piv_qr();
    if numerical_rank(&qr) < n {
        return None;
    }
    let r = qr.thin_R().to_owned();
    let mut inverse = Mat::<f64>::identity(n, n);
    r.solve_upper_triangular_in_place(&mut inverse);
    let (forward, _) = qr.P().arrays();
    let mut result = vec![vec![0.0; n]; n];
    for a in 0..n {
        for b in 0..n {
            // (R⁻¹R⁻ᵀ)[a, b] = Σ_k R⁻¹[a, k]·R⁻¹[b, k]; R⁻¹ is upper triangular.
            let inner: f64 = (a.max(b)..n)
                .map(|k| inverse[(a, k)] * inverse[(b, k)])
                .sum();
            let (i, l) = (forward[a], forward[b]);
            result[i][l] = variance * inner / (norms[i] * norms[l]) * scales[i] * scales[l];
        }
    }
    result
        .iter()
        .flatten()
        .all(|v| v.is_finite())
        .then_some(result)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use rand_distr::Normal;

    fn relative(a: f64, b: f64) -> f64 {
        ((a - b) / b).abs()
    }

    #[test]
    fn rosenbrock_from_the_classic_start() {
        let result = levenberg_marquardt(
            |p, r| {
                r[0] = 10.0 * (p[1] - p[0] * p[0]);
                r[1] = 1.0 - p[0];
            },
            2,
            &[-1.2, 1.0],
            &[1.0, 1.0],
            None,
            &LmSettings::default(),
        )
        .unwrap();
        eprintln!(
            "rosenbrock: error ({:.1e}, {:.1e}), cost {:.1e}, {} iterations, {} evaluations",
            result.parameters[0] - 1.0,
            result.parameters[1] - 1.0,
            result.cost,
            result.iterations,
            result.evaluations
        );
        assert!(result.converged, "{result:?}");
        assert!((result.parameters[0] - 1.0).abs() < 1e-8, "{result:?}");
        assert!((result.parameters[1] - 1.0).abs() < 1e-8, "{result:?}");
        // m = p: no degrees of freedom left for σ².
        assert_eq!(result.covariance, None);
    }

    /// y = a·exp(−b·t) on 40 points of [0, 3].
    fn exponential(p: &[f64], t: f64) -> f64 {
        p[0] * (-p[1] * t).exp()
    }
    const TIMES: usize = 40;
    fn time(i: usize) -> f64 {
        3.0 * i as f64 / (TIMES - 1) as f64
    }

    #[test]
    fn exponential_standard_errors_match_the_spread_of_estimates() {
        let truth = [2.0, 1.3];
        let sigma = 0.05;
        let noise = Normal::new(0.0, sigma).unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(20_240_611);
        let realisations = 50;
        let mut estimates = Vec::new();
        let mut reported = [0.0; 2];
        for _ in 0..realisations {
            let data: Vec<f64> = (0..TIMES)
                .map(|i| exponential(&truth, time(i)) + rng.sample(noise))
                .collect();
            let result = levenberg_marquardt(
                |p, r| {
                    for (i, r) in r.iter_mut().enumerate() {
                        *r = exponential(p, time(i)) - data[i];
                    }
                },
                TIMES,
                &[1.0, 0.5],
                &[1.0, 1.0],
                None,
                &LmSettings::default(),
            )
            .unwrap();
            assert!(result.converged, "{result:?}");
            let covariance = result.covariance.unwrap();
            for (k, total) in reported.iter_mut().enumerate() {
                *total += covariance[k][k].sqrt() / realisations as f64;
            }
            estimates.push(result.parameters);
        }
        for k in 0..2 {
            let mean = estimates.iter().map(|e| e[k]).sum::<f64>() / realisations as f64;
            let spread = (estimates.iter().map(|e| (e[k] - mean).powi(2)).sum::<f64>()
                / (realisations - 1) as f64)
                .sqrt();
            let ratio = reported[k] / spread;
            eprintln!(
                "exponential parameter {k}: mean {mean:.4} (true {}), spread {spread:.4e}, mean reported standard error {:.4e}, ratio {ratio:.3}",
                truth[k], reported[k]
            );
            assert!((0.5..2.0).contains(&ratio), "parameter {k}: ratio {ratio}");
        }
    }

    #[test]
    fn linear_model_covariance_is_the_analytic_one() {
        // y = c0 + c1·t: covariance σ²(XᵀX)⁻¹ with σ² = RSS/(m − 2), in closed form.
        let data = [
            (0.0, 0.1),
            (1.0, 1.26),
            (2.0, 1.92),
            (3.0, 3.18),
            (4.0, 4.04),
        ];
        let result = levenberg_marquardt(
            |p, r| {
                for (r, (t, y)) in r.iter_mut().zip(data) {
                    *r = p[0] + p[1] * t - y;
                }
            },
            data.len(),
            &[0.0, 0.0],
            &[1.0, 1.0],
            None,
            &LmSettings::default(),
        )
        .unwrap();
        // Solution 0.14 + 0.98·t, RSS = 0.064; XᵀX = [[5, 10], [10, 30]], det 50.
        let variance = 0.064 / 3.0;
        let analytic = [
            [variance * 30.0 / 50.0, -variance * 10.0 / 50.0],
            [-variance * 10.0 / 50.0, variance * 5.0 / 50.0],
        ];
        let covariance = result.covariance.clone().unwrap();
        let worst = (0..4)
            .map(|e| relative(covariance[e / 2][e % 2], analytic[e / 2][e % 2]))
            .fold(0.0, f64::max);
        eprintln!("linear covariance: worst relative error {worst:.2e}");
        assert!((result.parameters[0] - 0.14).abs() < 1e-10, "{result:?}");
        assert!((result.parameters[1] - 0.98).abs() < 1e-10, "{result:?}");
        assert!(worst < 1e-6, "{covariance:?} vs {analytic:?}");
    }

    #[test]
    fn bounds_hold_the_solution_on_the_boundary() {
        // Noise-free decay with b = 1.3, but b is bounded to [0, 1]: the constrained
        // optimum has b = 1 and a = Σy·e^{−t}/Σe^{−2t}.
        let data: Vec<f64> = (0..TIMES)
            .map(|i| exponential(&[2.0, 1.3], time(i)))
            .collect();
        let result = levenberg_marquardt(
            |p, r| {
                for (i, r) in r.iter_mut().enumerate() {
                    *r = exponential(p, time(i)) - data[i];
                }
            },
            TIMES,
            &[1.0, 0.5],
            &[1.0, 1.0],
            Some(&[(0.0, 10.0), (0.0, 1.0)]),
            &LmSettings::default(),
        )
        .unwrap();
        let numerator: f64 = (0..TIMES).map(|i| data[i] * (-time(i)).exp()).sum();
        let denominator: f64 = (0..TIMES).map(|i| (-2.0 * time(i)).exp()).sum();
        let a = numerator / denominator;
        eprintln!(
            "bounded: b = {}, a error {:.1e}, {} iterations",
            result.parameters[1],
            result.parameters[0] - a,
            result.iterations
        );
        assert!(result.converged, "{result:?}");
        assert_eq!(result.parameters[1], 1.0, "{result:?}");
        assert!(
            relative(result.parameters[0], a) < 1e-9,
            "{result:?} vs a = {a}"
        );

        // Starting outside the box: projected in, and the lower bound holds.
        let result = levenberg_marquardt(
            |p, r| {
                r[0] = p[0] - 3.0;
                r[1] = p[1] + 2.0;
                r[2] = p[0] + p[1] - 1.0;
            },
            3,
            &[10.0, 0.5],
            &[1.0, 1.0],
            Some(&[(-1.0, 2.0), (-0.5, f64::INFINITY)]),
            &LmSettings::default(),
        )
        .unwrap();
        assert!(result.converged, "{result:?}");
        assert_eq!(result.parameters[1], -0.5, "{result:?}");
        // With p1 = −0.5: minimise (p0 − 3)² + (p0 − 1.5)² → p0 = 2.25, above 2.
        assert_eq!(result.parameters[0], 2.0, "{result:?}");

        // A law undefined beyond its bound, with a scale that does not divide the bound
        // exactly (0.7/0.3·0.3 rounds above 0.7): the bound is still met exactly.
        let result = levenberg_marquardt(
            |p, r| r[0] = if p[0] > 0.7 { f64::NAN } else { p[0] - 5.0 },
            1,
            &[0.5],
            &[0.3],
            Some(&[(0.0, 0.7)]),
            &LmSettings::default(),
        )
        .unwrap();
        assert!(result.converged, "{result:?}");
        assert_eq!(result.parameters[0], 0.7, "{result:?}");
    }

    #[test]
    fn parameters_ten_orders_apart_converge_from_30_percent_off() {
        // A Hertz law f = k·δ^n, k = 7e9 N/m^n, n = 1.45, δ ∈ (0, 30 µm].
        let (k, n) = (7e9, 1.45);
        let m = 500;
        let depth = |i: usize| 3e-5 * (i + 1) as f64 / m as f64;
        let force: Vec<f64> = (0..m).map(|i| k * depth(i).powf(n)).collect();
        for start in [[1.3 * k, 0.7 * n], [0.7 * k, 1.3 * n]] {
            let result = levenberg_marquardt(
                |p, r| {
                    for (i, r) in r.iter_mut().enumerate() {
                        *r = p[0] * depth(i).powf(p[1]) - force[i];
                    }
                },
                m,
                &start,
                &[1e9, 1.0],
                None,
                &LmSettings::default(),
            )
            .unwrap();
            eprintln!(
                "hertz from {start:?}: k rel {:.1e}, n error {:.1e}, {} iterations, {} evaluations",
                relative(result.parameters[0], k),
                result.parameters[1] - n,
                result.iterations,
                result.evaluations
            );
            assert!(result.converged, "{result:?}");
            assert!(relative(result.parameters[0], k) < 1e-8, "{result:?}");
            assert!((result.parameters[1] - n).abs() < 1e-9, "{result:?}");
        }
    }

    #[test]
    fn nan_at_a_trial_point_is_a_rejected_step() {
        // r = ln p − ln 2 from p = 10: the Gauss–Newton step goes to p ≈ −6 (NaN).
        let result = levenberg_marquardt(
            |p, r| r[0] = p[0].ln() - 2.0_f64.ln(),
            1,
            &[10.0],
            &[1.0],
            None,
            &LmSettings {
                initial_damping: 1e-9,
                ..LmSettings::default()
            },
        )
        .unwrap();
        assert!(result.converged, "{result:?}");
        assert!((result.parameters[0] - 2.0).abs() < 1e-10, "{result:?}");
    }

    #[test]
    fn invalid_inputs_are_errors() {
        let residuals = |p: &[f64], r: &mut [f64]| r[0] = p[0];
        let settings = LmSettings::default();
        assert!(matches!(
            levenberg_marquardt(residuals, 1, &[1.0], &[0.0], None, &settings),
            Err(LeastSquaresError::InvalidScale { index: 0, .. })
        ));
        assert!(matches!(
            levenberg_marquardt(residuals, 1, &[1.0], &[1.0], Some(&[(2.0, 1.0)]), &settings),
            Err(LeastSquaresError::InvalidBounds { index: 0, .. })
        ));
        assert!(matches!(
            levenberg_marquardt(residuals, 1, &[1.0, 2.0], &[1.0, 1.0], None, &settings),
            Err(LeastSquaresError::TooFewRows {
                rows: 1,
                unknowns: 2
            })
        ));
        assert!(matches!(
            levenberg_marquardt(|_, r| r[0] = f64::NAN, 1, &[1.0], &[1.0], None, &settings),
            Err(LeastSquaresError::NonFiniteInitialResidual { index: 0 })
        ));
    }
}
