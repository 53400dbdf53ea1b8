//! The reduced problem solved by column-pivoted QR of its triangle (see the module
//! documentation of [`super`]).

use super::{Covariance, LinearFit, LinearLeastSquaresError, Reduction, RANK_TOLERANCE};
use crate::numerics::euclidean_norm;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::householder;
use faer::linalg::solvers::ColPivQr;
use faer::{Conj, Mat, Par};

/// The triangle with unit-norm columns, factorised with column pivoting.
struct Pivoted {
    qr: ColPivQr<f64>,
    /// The triangle's (= A's) column norms; 0 for a zero column, left unscaled.
    norms: Vec<f64>,
    /// Numerical rank.
    rank: usize,
}

impl Reduction {
    /// Solves the reduced problem for target `target`: the coefficients (the basic
    /// solution when A is rank-deficient), the residual sum of squares, the rank and,
    /// if `covariance` asks, the coefficients' covariance (see [`LinearFit`]).
    ///
    /// Errors: no rows, fewer rows than columns, or a target the problem does not have.
    pub(crate) fn solve(
        &self,
        target: usize,
        covariance: Option<Covariance>,
    ) -> Result<LinearFit, LinearLeastSquaresError> {
        let (rows, columns) = (self.rows(), self.columns());
        if target >= self.targets() {
            return Err(LinearLeastSquaresError::NoSuchTarget {
                target,
                targets: self.targets(),
            });
        }
        if rows == 0 {
            return Err(LinearLeastSquaresError::NoRows);
        }
        if rows < columns {
            return Err(LinearLeastSquaresError::TooFewRows {
                rows,
                unknowns: columns,
            });
        }
        let pivoted = Pivoted::new(self.triangle_matrix());
        let mut projected = Mat::from_fn(columns, 1, |i, _| self.projected_target(i, target));
        pivoted.apply_q_transpose(&mut projected);
        let coefficients = pivoted.coefficients(&projected);
        let residual_sum_of_squares = self.orthogonal_sum_of_squares(target)
            + (pivoted.rank..columns)
                .map(|i| projected[(i, 0)] * projected[(i, 0)])
                .sum::<f64>();
        let variance = match covariance {
            Some(Covariance::Unscaled) => Some(1.0),
            Some(Covariance::ResidualVariance) if rows > columns => {
                Some(residual_sum_of_squares / (rows - columns) as f64)
            }
            _ => None,
        };
        Ok(LinearFit {
            coefficients,
            residual_sum_of_squares,
            rank: pivoted.rank,
            covariance: variance.and_then(|v| pivoted.covariance(v)),
        })
    }
}

impl Reduction {
    /// Solves min ‖A·x − b‖² + μ·‖x‖² for target `target` (Tikhonov regularisation,
    /// "ridge", μ = `ridge` ≥ 0 in the target's unit over the columns' unit, squared)
    /// as the least-squares problem [R; √μ·I]·x ≈ [(Qᵀb)₁; 0] through the same solve:
    /// for a caller that needs small coefficients more than the exact minimum, e.g. near
    /// collinear columns whose exact coefficients are large and cancel. The fit's RSS is
    /// ‖A·x − b‖² (without the penalty), its rank that of the stacked matrix, and it has
    /// no covariance. Needs no more rows than columns when μ > 0.
    pub(crate) fn solve_ridge(
        &self,
        target: usize,
        ridge: f64,
    ) -> Result<LinearFit, LinearLeastSquaresError> {
        if target >= self.targets() {
            return Err(LinearLeastSquaresError::NoSuchTarget {
                target,
                targets: self.targets(),
            });
        }
        let (triangle, columns) = (self.triangle_rows(), self.columns());
        let root = ridge.sqrt();
        let penalised = Reduction::from_rows(triangle + columns, columns, 1, |i, row, value| {
            if i < triangle {
                for (j, entry) in row.iter_mut().enumerate() {
                    *entry = self.triangle(i, j);
                }
                value[0] = self.projected_target(i, target);
            } else {
                row[i - triangle] = root;
            }
        })?;
        let mut fit = penalised.solve(0, None)?;
        let misfit: f64 = (0..triangle)
            .map(|i| {
                let fitted: f64 = (i..columns)
                    .map(|j| self.triangle(i, j) * fit.coefficients[j])
                    .sum();
                (fitted - self.projected_target(i, target)).powi(2)
            })
            .sum();
        fit.residual_sum_of_squares = misfit + self.orthogonal_sum_of_squares(target);
        Ok(fit)
    }
}

impl Pivoted {
    /// Scales the triangle's columns to unit norm (pivoting and the rank threshold then
    /// compare directions, not units) and factorises it with column pivoting.
    fn new(triangle: &Mat<f64>) -> Pivoted {
        let norms: Vec<f64> = (0..triangle.ncols())
            .map(|j| euclidean_norm(triangle.col_as_slice(j)))
            .collect();
        let scaled = Mat::from_fn(triangle.nrows(), triangle.ncols(), |i, j| {
            if norms[j] > 0.0 {
                triangle[(i, j)] / norms[j]
            } else {
                triangle[(i, j)]
            }
        });
        let qr = scaled.col_piv_qr();
        let rank = numerical_rank(&qr);
        Pivoted { qr, norms, rank }
    }

    /// Overwrites `rhs` (as many rows as the triangle) by Qᵀ·rhs.
    fn apply_q_transpose(&self, rhs: &mut Mat<f64>) {
        let (rows, block, columns) = (rhs.nrows(), self.qr.Q_coeff().nrows(), rhs.ncols());
        let mut memory = MemBuffer::new(
            householder::apply_block_householder_sequence_transpose_on_the_left_in_place_scratch::<
                f64,
            >(rows, block, columns),
        );
        householder::apply_block_householder_sequence_transpose_on_the_left_in_place_with_conj(
            self.qr.Q_basis(),
            self.qr.Q_coeff(),
            Conj::No,
            rhs.as_mut(),
            Par::Seq,
            MemStack::new(&mut memory),
        );
    }

    /// Back substitution on the leading rank × rank block of the pivoted triangle, the
    /// dependent columns' coefficients 0, then the pivoting and the scaling undone.
    fn coefficients(&self, projected: &Mat<f64>) -> Vec<f64> {
        let r = self.qr.thin_R();
        let mut solution = vec![0.0; self.rank];
        for k in (0..self.rank).rev() {
            let mut sum = projected[(k, 0)];
            for (j, &x) in solution.iter().enumerate().skip(k + 1) {
                sum -= r[(k, j)] * x;
            }
            solution[k] = sum / r[(k, k)];
        }
        let (forward, _) = self.qr.P().arrays();
        let mut coefficients = vec![0.0; self.norms.len()];
        for (k, &y) in solution.iter().enumerate() {
            let column = forward[k];
            coefficients[column] = y / self.norms[column];
        }
        coefficients
    }

    /// variance·(AᵀA)⁻¹ = variance·N⁻¹·P·R⁻¹·R⁻ᵀ·Pᵀ·N⁻¹ (N the column norms), or `None`
    /// when A is rank-deficient or an entry is not finite.
    fn covariance(&self, variance: f64) -> Option<Vec<Vec<f64>>> {
        let n = self.norms.len();
        if self.rank < n || !variance.is_finite() {
            return None;
        }
        let r = self.qr.thin_R().to_owned();
        let mut inverse = Mat::<f64>::identity(n, n);
        r.solve_upper_triangular_in_place(&mut inverse);
        let (forward, _) = self.qr.P().arrays();
        let mut result = vec![vec![0.0; n]; n];
        for a in 0..n {
            for b in 0..n {
                // (R⁻¹R⁻ᵀ)[a, b] = Σ_k R⁻¹[a, k]·R⁻¹[b, k]; R⁻¹ is upper triangular.
                let inner: f64 = (a.max(b)..n)
                    .map(|k| inverse[(a, k)] * inverse[(b, k)])
                    .sum();
                let (i, l) = (forward[a], forward[b]);
                result[i][l] = variance * inner / (self.norms[i] * self.norms[l]);
            }
        }
        result
            .iter()
            .flatten()
            .all(|v| v.is_finite())
            .then_some(result)
    }
}

/// Number of leading diagonal entries of a column-pivoted R above [`RANK_TOLERANCE`]
/// times the largest one (pivoting orders them by decreasing magnitude).
fn numerical_rank(qr: &ColPivQr<f64>) -> usize {
    let r = qr.thin_R();
    let size = r.nrows().min(r.ncols());
    let largest = (0..size).map(|k| r[(k, k)].abs()).fold(0.0, f64::max);
    if largest.is_nan() || largest == 0.0 {
        return 0;
    }
    (0..size)
        .position(|k| r[(k, k)].is_nan() || r[(k, k)].abs() <= RANK_TOLERANCE * largest)
        .unwrap_or(size)
}
