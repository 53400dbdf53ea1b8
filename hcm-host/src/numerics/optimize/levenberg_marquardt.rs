//! Levenberg–Marquardt for small bounded nonlinear least-squares problems.
//!
//! Minimises ½‖r(p)‖² over a handful of parameters (≤ 8 in practice) and up to about a
//! million residuals: after the separable search of `identify` has found
//! a good start, this refines every parameter of a contact law jointly and reports
//! their covariance.
//!
//! The method follows Moré 1978 (*The Levenberg–Marquardt algorithm: implementation
//! and theory*, Lecture Notes in Mathematics 630) and Nocedal & Wright 2006
//! (*Numerical Optimization*, 2nd ed., §10.3):
//! - parameters are handled internally as u_i = p_i / scale_i, so that a stiffness of
//!   1e10 N/m^n and an exponent of 1.5 are both of order one;
//! - each iteration reduces the Jacobian once, J = Q·R, and for every trial damping λ
//!   solves the small augmented problem min ‖R·z + (Qᵀr)₁‖² + λ‖D·z‖² (Moré §3), both
//!   with the host's one linear least-squares routine
//!   ([`crate::numerics::linear_least_squares()`], Householder QR), never forming JᵀJ;
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

mod problem;
mod step;
#[cfg(test)]
mod tests;

use super::search::LeastSquaresError;
use super::Bound;
use crate::numerics::{euclidean_norm, Covariance, Reduction};
use problem::Problem;
use step::Linearisation;

/// λ is kept at or above this (a relative damping at rounding level), so that a
/// rank-deficient R still gives a solvable augmented system.
const MIN_DAMPING: f64 = 1e-15;

/// A damping above this means no step along any direction reduces the cost.
const MAX_DAMPING: f64 = 1e32;

/// Settings of `levenberg_marquardt`.
#[derive(Clone, Debug, PartialEq)]
pub struct LmSettings {
    /// Maximum number of iterations (Jacobian evaluations).
    pub(crate) max_iterations: usize,
    /// Converged when, for every free parameter, the cosine of the angle between the
    /// residual vector and the Jacobian column is at most this (MINPACK's `gtol`; a
    /// scale-free gradient test).
    pub(crate) gradient_tolerance: f64,
    /// Converged when a step is shorter than this relative to the scaled parameter
    /// vector: ‖Δu‖ ≤ tol·(‖u‖ + tol), u_i = p_i/scale_i.
    pub(crate) step_tolerance: f64,
    /// Converged when both the actual and the predicted relative reduction of the cost
    /// of an accepted step are at most this.
    pub(crate) cost_tolerance: f64,
    /// Initial λ (dimensionless: the damping is λ·diag(JᵀJ)).
    pub(crate) initial_damping: f64,
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

/// Why `levenberg_marquardt` stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Termination {
    /// The residuals are exactly zero.
    ExactFit,
    /// For every free parameter the cosine between the residuals and its Jacobian
    /// column is at most `LmSettings::gradient_tolerance`.
    SmallGradient,
    /// Every parameter sits on a bound with the gradient pushing outward (or is fixed
    /// by equal bounds): no direction inside the box descends.
    HeldByBounds,
    /// A step shorter than `LmSettings::step_tolerance` was accepted, or none that
    /// short reduces the cost: a minimum to the tolerance.
    SmallStep,
    /// An accepted step's actual and predicted relative reductions of the cost were
    /// both at most `LmSettings::cost_tolerance`.
    SmallReduction,
    /// `LmSettings::max_iterations` iterations ran without meeting a tolerance.
    MaxIterations,
    /// The damping grew beyond 1e32 without a step that reduces the cost (a residual
    /// function that is not smooth, or NaN all around the point).
    DampingOverflow,
}

impl Termination {
    /// Whether a tolerance was met (rather than the iteration limit or a damping
    /// overflow).
    pub fn converged(self) -> bool {
        !matches!(
            self,
            Termination::MaxIterations | Termination::DampingOverflow
        )
    }
}

impl std::fmt::Display for Termination {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Termination::ExactFit => "the residuals are zero",
            Termination::SmallGradient => "the gradient is below its tolerance",
            Termination::HeldByBounds => "every parameter is held by a bound",
            Termination::SmallStep => "the step is below its tolerance",
            Termination::SmallReduction => "the cost reduction is below its tolerance",
            Termination::MaxIterations => "the iteration limit was reached",
            Termination::DampingOverflow => "no damping gave a step that reduces the cost",
        })
    }
}

/// The outcome of `levenberg_marquardt`.
#[derive(Clone, Debug, PartialEq)]
pub struct LmResult {
    /// The best parameters found, in the caller's units.
    pub(crate) parameters: Vec<f64>,
    /// ½‖r‖² at `parameters` (half the residuals' unit squared).
    pub(crate) cost: f64,
    /// Iterations (Jacobian evaluations) performed, not counting the one for the
    /// covariance.
    pub(crate) iterations: usize,
    /// Calls of the residual function, Jacobian and covariance included.
    pub(crate) evaluations: usize,
    /// σ²·(JᵀJ)⁻¹ at `parameters` with σ² = 2·cost/(m − p), in the parameters' units
    /// squared: the asymptotic covariance of the estimates for independent residuals of
    /// equal variance (its diagonal's square roots are the standard errors). `None`
    /// when JᵀJ is numerically singular (a parameter without effect or two with the
    /// same effect), when m = p, or when the Jacobian there is not finite. Bounds are
    /// ignored: a parameter ending on its bound gets the unconstrained value.
    pub(crate) covariance: Option<Vec<Vec<f64>>>,
    /// Why the iteration stopped: a tolerance met (see [`Termination::converged`]),
    /// the iteration limit or a damping overflow.
    pub(crate) termination: Termination,
}

/// Minimises ½‖r(p)‖² for `residuals(p, out)` filling `m` residuals.
///
/// The Jacobian is taken by forward differences with per-parameter step
/// √ε·max(|p_i|, scale_i) (backward where the forward point would leave the box), its
/// columns evaluated in parallel (rayon). `scales` gives each parameter's typical
/// magnitude (> 0); the iteration works on p_i / scale_i, which matters when parameters
/// differ by 10 orders of magnitude. Bounds: optional per-parameter (lower, upper),
/// either may be infinite; the start is projected onto the box and so is every trial
/// point. Marquardt's scaling (damping λ·diag(JᵀJ)); the damped step solves the
/// augmented system by linear least squares. See the module documentation for the
/// references; [`LmResult::termination`] says why it stopped.
///
/// Never panics; a NaN or infinite residual at a trial point is a rejected step. The
/// residual function must fill all `m` entries of `out` and must be a pure function of
/// `p`. Memory: the Jacobian, m × p values, plus a block of at most 1024 of its rows
/// while reducing it.
///
/// Errors: no parameters, no residuals, fewer residuals than parameters, slices of the
/// wrong length, a non-positive scale, a bound that is not an interval, a non-finite
/// start or a non-finite residual there, a setting outside its domain, or a derivative
/// that is non-finite on both sides of a point.
pub(crate) fn levenberg_marquardt(
    residuals: impl Fn(&[f64], &mut [f64]) + Sync,
    m: usize,
    initial: &[f64],
    scales: &[f64],
    bounds: Option<&[Bound]>,
    settings: &LmSettings,
) -> Result<LmResult, LeastSquaresError> {
    let problem = Problem::new(&residuals, m, initial, scales, bounds, settings)?;
    let mut search = Search::start(&problem, initial, settings)?;
    let termination = search.run(&problem, settings)?;
    let covariance = search.covariance(&problem);
    Ok(LmResult {
        parameters: problem.unscale(&search.u),
        cost: search.cost,
        iterations: search.iterations,
        evaluations: problem.evaluations(),
        covariance,
        termination,
    })
}

/// The iteration's state: the current point and what the damping has learnt.
struct Search {
    /// Current point, scaled (u = p / scale), inside the box.
    u: Vec<f64>,
    /// Residuals there.
    r: Vec<f64>,
    /// ½‖r‖².
    cost: f64,
    /// Marquardt's D: per parameter the largest Jacobian column norm seen (1 for a
    /// column that was always zero).
    diagonal: Vec<f64>,
    /// λ, and the factor it grows by at the next rejected step (Nielsen's ν).
    damping: f64,
    growth: f64,
    /// Iterations (Jacobian evaluations) so far.
    iterations: usize,
    /// The Jacobian, column-major m × n.
    jacobian: Vec<f64>,
    /// A trial point and its residuals.
    trial_u: Vec<f64>,
    trial_r: Vec<f64>,
}

impl Search {
    /// The state at the (projected) start; an error if a residual is not finite there.
    fn start<F: Fn(&[f64], &mut [f64]) + Sync>(
        problem: &Problem<'_, F>,
        initial: &[f64],
        settings: &LmSettings,
    ) -> Result<Search, LeastSquaresError> {
        let (m, n) = (problem.m, initial.len());
        let u = problem.start(initial);
        let mut r = vec![0.0; m];
        problem.eval(&u, &mut r);
        if let Some(index) = r.iter().position(|v| !v.is_finite()) {
            return Err(LeastSquaresError::NonFiniteInitialResidual { index });
        }
        Ok(Search {
            cost: half_sum_of_squares(&r),
            u,
            r,
            diagonal: vec![0.0; n],
            damping: settings.initial_damping.max(MIN_DAMPING),
            growth: 2.0,
            iterations: 0,
            jacobian: vec![0.0; m * n],
            trial_u: vec![0.0; n],
            trial_r: vec![0.0; m],
        })
    }

    /// Iterates until a stopping test holds: each iteration linearises at the current
    /// point and tries damped steps until one reduces the cost.
    fn run<F: Fn(&[f64], &mut [f64]) + Sync>(
        &mut self,
        problem: &Problem<'_, F>,
        settings: &LmSettings,
    ) -> Result<Termination, LeastSquaresError> {
        while self.iterations < settings.max_iterations {
            if self.cost == 0.0 {
                return Ok(Termination::ExactFit);
            }
            self.iterations += 1;
            problem.jacobian(&self.u, &self.r, &mut self.jacobian)?;
            let free = match self.free_parameters(problem, settings) {
                Ok(free) => free,
                Err(termination) => return Ok(termination),
            };
            let model = Linearisation::new(&self.jacobian, &self.r, free)?;
            if let Some(termination) = self.damped_steps(problem, &model, settings) {
                return Ok(termination);
            }
        }
        Ok(Termination::MaxIterations)
    }

    /// Updates Marquardt's diagonal from the Jacobian and returns the parameters free
    /// to move: not on a bound the gradient Jᵀr pushes against. Stops (`Err`) when none
    /// is, or when the largest cosine between r and a free column is within the
    /// gradient tolerance.
    fn free_parameters<F>(
        &mut self,
        problem: &Problem<'_, F>,
        settings: &LmSettings,
    ) -> Result<Vec<usize>, Termination> {
        let m = problem.m;
        let residual_norm = euclidean_norm(&self.r);
        let mut free = Vec::with_capacity(self.u.len());
        let mut largest_cosine = 0.0_f64;
        for j in 0..self.u.len() {
            let column = &self.jacobian[j * m..(j + 1) * m];
            let norm = euclidean_norm(column);
            let gradient: f64 = column.iter().zip(&self.r).map(|(a, b)| a * b).sum();
            self.diagonal[j] = self.diagonal[j].max(if norm > 0.0 { norm } else { 1.0 });
            let (u, lower, upper) = (self.u[j], problem.lower[j], problem.upper[j]);
            let held =
                lower == upper || (u <= lower && gradient > 0.0) || (u >= upper && gradient < 0.0);
            if !held {
                free.push(j);
                if norm > 0.0 {
                    largest_cosine = largest_cosine.max(gradient.abs() / (norm * residual_norm));
                }
            }
        }
        if free.is_empty() {
            Err(Termination::HeldByBounds)
        } else if largest_cosine <= settings.gradient_tolerance {
            Err(Termination::SmallGradient)
        } else {
            Ok(free)
        }
    }

    /// Tries steps of growing damping until one reduces the cost (then `None`: go on
    /// iterating, unless that step met a tolerance) or a stopping test holds.
    fn damped_steps<F: Fn(&[f64], &mut [f64]) + Sync>(
        &mut self,
        problem: &Problem<'_, F>,
        model: &Linearisation,
        settings: &LmSettings,
    ) -> Option<Termination> {
        let u_norm = euclidean_norm(&self.u);
        let tolerance = settings.step_tolerance;
        loop {
            let bounds = (&self.u[..], &problem.lower[..], &problem.upper[..]);
            let finite = model.trial_point(self.damping, &self.diagonal, bounds, &mut self.trial_u);
            let step: Vec<f64> = self
                .trial_u
                .iter()
                .zip(&self.u)
                .map(|(t, x)| t - x)
                .collect();
            let step_norm = euclidean_norm(&step);
            let small_step = step_norm <= tolerance * (u_norm + tolerance);
            let predicted = if finite {
                model.predicted_reduction(&step)
            } else {
                f64::NAN
            };
            let trial_cost = if finite && step_norm > 0.0 {
                problem.eval(&self.trial_u, &mut self.trial_r);
                half_sum_of_squares(&self.trial_r)
            } else {
                f64::INFINITY
            };
            let actual = self.cost - trial_cost;
            if trial_cost.is_finite() && actual > 0.0 {
                return self.accept(trial_cost, (actual, predicted), small_step, settings);
            }
            if small_step {
                // No representable step improves the cost: a minimum to the tolerance.
                return Some(Termination::SmallStep);
            }
            // Rejected: more damping, a shorter and more gradient-like step.
            self.damping *= self.growth;
            self.growth *= 2.0;
            if self.damping > MAX_DAMPING || self.damping.is_nan() {
                return Some(Termination::DampingOverflow);
            }
        }
    }

    /// Moves to the trial point, whose cost `trial_cost` is lower by `actual` against
    /// the `predicted` reduction, and updates λ from their ratio ρ (Nielsen 1999):
    /// λ ← λ·max(1/3, 1 − (2ρ − 1)³). Returns the tolerance the step met, if any.
    fn accept(
        &mut self,
        trial_cost: f64,
        (actual, predicted): (f64, f64),
        small_step: bool,
        settings: &LmSettings,
    ) -> Option<Termination> {
        let ratio = if predicted > 0.0 {
            actual / predicted
        } else {
            0.5
        };
        self.damping = (self.damping * (1.0 / 3.0_f64).max(1.0 - (2.0 * ratio - 1.0).powi(3)))
            .max(MIN_DAMPING);
        self.growth = 2.0;
        let previous_cost = self.cost;
        std::mem::swap(&mut self.u, &mut self.trial_u);
        std::mem::swap(&mut self.r, &mut self.trial_r);
        self.cost = trial_cost;
        let tolerance = settings.cost_tolerance * previous_cost;
        if small_step {
            Some(Termination::SmallStep)
        } else if actual <= tolerance && predicted.abs() <= tolerance {
            Some(Termination::SmallReduction)
        } else {
            None
        }
    }

    /// σ²·(JᵀJ)⁻¹ at the current point in the caller's units, σ² = 2·cost/(m − n); `None`
    /// when m = n, when the Jacobian there is not finite, or when JᵀJ is numerically
    /// singular (see [`LmResult::covariance`]).
    fn covariance<F: Fn(&[f64], &mut [f64]) + Sync>(
        &mut self,
        problem: &Problem<'_, F>,
    ) -> Option<Vec<Vec<f64>>> {
        let (m, n) = (problem.m, self.u.len());
        if m <= n {
            return None;
        }
        problem
            .jacobian(&self.u, &self.r, &mut self.jacobian)
            .ok()?;
        let variance = 2.0 * self.cost / (m - n) as f64;
        let jacobian = &self.jacobian;
        let unscaled = Reduction::from_rows(m, n, 1, |i, row, target| {
            for (j, value) in row.iter_mut().enumerate() {
                *value = jacobian[j * m + i];
            }
            target[0] = self.r[i];
        })
        .ok()?
        .solve(0, Some(Covariance::Unscaled))
        .ok()?
        .covariance?;
        let scales = problem.scales();
        let scaled: Vec<Vec<f64>> = unscaled
            .iter()
            .enumerate()
            .map(|(i, row)| {
                row.iter()
                    .enumerate()
                    .map(|(l, c)| variance * c * scales[i] * scales[l])
                    .collect()
            })
            .collect();
        scaled
            .iter()
            .flatten()
            .all(|v| v.is_finite())
            .then_some(scaled)
    }
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
