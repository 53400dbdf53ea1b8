//! One iteration's Gauss–Newton model and its damped steps (Moré 1978, §3).

use super::LeastSquaresError;
use crate::numerics::{linear_least_squares, Reduction};

/// The linear model of the residuals at the current point over the free parameters:
/// J_free = Q·R reduced once per iteration, so that every trial damping solves only a
/// small system.
pub(super) struct Linearisation {
    /// Indices of the free parameters (the columns of R).
    free: Vec<usize>,
    /// R and (Qᵀr)₁ of J_free and the residuals r.
    reduction: Reduction,
    /// ‖(Qᵀr)₁‖²: twice the cost the linear model can remove.
    reachable: f64,
}

impl Linearisation {
    /// Reduces the columns `free` of `jacobian` (column-major, m × n) with the
    /// residuals `r` as target.
    pub(super) fn new(
        jacobian: &[f64],
        r: &[f64],
        free: Vec<usize>,
    ) -> Result<Linearisation, LeastSquaresError> {
        let m = r.len();
        let columns: Vec<&[f64]> = free
            .iter()
            .map(|&j| &jacobian[j * m..(j + 1) * m])
            .collect();
        let reduction = Reduction::from_columns(&columns, r)?;
        let reachable = (0..reduction.triangle_rows())
            .map(|k| reduction.projected_target(k, 0).powi(2))
            .sum();
        Ok(Linearisation {
            free,
            reduction,
            reachable,
        })
    }

    /// The point u + z projected onto the box [lower, upper], z the damped step of
    /// [`Linearisation::damped_step`], into `trial`; false when z is not finite.
    pub(super) fn trial_point(
        &self,
        damping: f64,
        diagonal: &[f64],
        (u, lower, upper): (&[f64], &[f64], &[f64]),
        trial: &mut [f64],
    ) -> bool {
        let z = self.damped_step(damping, diagonal);
        trial.copy_from_slice(u);
        let mut finite = true;
        for (&j, &z) in self.free.iter().zip(&z) {
            finite &= z.is_finite();
            trial[j] = (u[j] + z).clamp(lower[j], upper[j]);
        }
        finite
    }

    /// min ‖R·z + (Qᵀr)₁‖² + λ‖D·z‖²  ⇔  [R; √λ·D]·z ≈ [−(Qᵀr)₁; 0], the augmented
    /// system solved by the linear least-squares routine (never forming JᵀJ); D the
    /// free parameters' entries of `diagonal`. NaN entries if it cannot be solved.
    fn damped_step(&self, damping: f64, diagonal: &[f64]) -> Vec<f64> {
        let (size, triangle) = (self.free.len(), self.reduction.triangle_rows());
        let root = damping.sqrt();
        let solved = linear_least_squares(triangle + size, size, |i, row| {
            if i < triangle {
                for (k, value) in row.iter_mut().enumerate() {
                    *value = self.reduction.triangle(i, k);
                }
                -self.reduction.projected_target(i, 0)
            } else {
                let k = i - triangle;
                row[k] = root * diagonal[self.free[k]];
                0.0
            }
        });
        solved.map_or_else(|_| vec![f64::NAN; size], |fit| fit.coefficients)
    }

    /// Reduction of the cost the linear model predicts for `step` (all parameters,
    /// scaled): ½(‖(Qᵀr)₁‖² − ‖(Qᵀr)₁ + R·step_free‖²).
    pub(super) fn predicted_reduction(&self, step: &[f64]) -> f64 {
        let after: f64 = (0..self.reduction.triangle_rows())
            .map(|i| {
                let entry = self.reduction.projected_target(i, 0)
                    + (i..self.free.len())
                        .map(|k| self.reduction.triangle(i, k) * step[self.free[k]])
                        .sum::<f64>();
                entry * entry
            })
            .sum();
        0.5 * (self.reachable - after)
    }
}
