//! Linear least squares, min ‖A·x − b‖², by Householder QR (faer).
//!
//! Two steps, each with the QR variant that suits it:
//! 1. [`Reduction`]: plain (unpivoted, blocked) Householder QR of the tall matrix,
//!    A = Q·R, absorbing the rows in blocks (sequential accumulation, Lawson & Hanson
//!    1974, *Solving Least Squares Problems*, ch. 27). It keeps R (at most `columns`
//!    rows), the leading part of Qᵀb and the squared norm of the rest: everything a
//!    solve needs, in O(columns²) memory whatever the number of rows. Householder QR
//!    is backward stable column by column, so regressors ten orders of magnitude apart
//!    need no scaling here, and no pivoting is needed to reduce.
//! 2. `Reduction::solve`: column-pivoted QR (Businger & Golub 1965) of the small
//!    triangle with its columns scaled to unit norm. R's columns have A's column norms,
//!    so pivoting R is pivoting A; pivoting orders the diagonal of the new triangle by
//!    decreasing magnitude, which makes the rank decision reliable: a column whose
//!    diagonal entry is at or below `RANK_TOLERANCE` times the largest is dependent
//!    on the ones before it. Its coefficient is set to 0 (the "basic" solution of
//!    Golub & Van Loan, *Matrix Computations*, §5.5) instead of a huge value, and
//!    `LinearFit::rank` says so.
//!
//! The residual sum of squares is read from the trailing part of Qᵀb, so it does not
//! suffer the cancellation of ‖b‖² − ‖A·x‖²; the covariance, when asked, is
//! (AᵀA)⁻¹ = (RᵀR)⁻¹ from the triangle, never from AᵀA formed and inverted (which
//! squares the condition number).
//!
//! No row weights: no caller weights its rows; a weight w would multiply a row's
//! regressors and target by √w in the row closure.

mod reduction;
mod solve;
#[cfg(test)]
mod tests;

pub use reduction::Reduction;

/// A diagonal entry of the pivoted triangle at or below this fraction of the largest
/// one marks its column as numerically dependent on the columns before it (the
/// columns scaled to unit norm: a relative, unit-free threshold).
pub(crate) const RANK_TOLERANCE: f64 = 1e-12;

/// Which covariance of the coefficients `Reduction::solve` returns.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Covariance {
    /// (AᵀA)⁻¹ alone (the columns' units to the power −2): for a caller that scales it
    /// by its own variance, e.g. Levenberg–Marquardt's σ² from the nonlinear cost.
    Unscaled,
    /// σ̂²·(AᵀA)⁻¹ with σ̂² = RSS/(n − p) (n rows, p columns): the covariance of the
    /// coefficients for independent errors of equal variance (the square roots of its
    /// diagonal are the standard errors). Needs n > p.
    ResidualVariance,
}

/// The solution of a linear least-squares problem.
#[derive(Clone, Debug, PartialEq)]
pub struct LinearFit {
    /// The minimising x, one per column, in the target's unit over the column's unit.
    /// A coefficient of a column found dependent on the others (see
    /// [`LinearFit::rank`]) is exactly 0.
    pub(crate) coefficients: Vec<f64>,
    /// ‖A·x − b‖² at the solution (the target's unit squared).
    pub(crate) residual_sum_of_squares: f64,
    /// Numerical rank of A; less than the number of columns when some columns are
    /// (nearly) zero or (nearly) linear combinations of others.
    pub(crate) rank: usize,
    /// The coefficients' covariance as asked ([`Covariance`]), row by row; `None` when
    /// not asked, when A is rank-deficient (some combination of coefficients is not
    /// determined at all), when [`Covariance::ResidualVariance`] has no degree of
    /// freedom left (n = p), or when an entry is not finite.
    pub(crate) covariance: Option<Vec<Vec<f64>>>,
}

/// Why a linear least-squares problem could not be solved.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum LinearLeastSquaresError {
    /// The problem has no rows (no data).
    #[error("the least-squares problem has no rows")]
    NoRows,
    /// The problem has no unknowns.
    #[error("the least-squares problem has no unknowns")]
    NoUnknowns,
    /// Fewer rows (equations) than unknowns.
    #[error("{rows} rows cannot determine {unknowns} unknowns; at least as many rows as unknowns are needed")]
    TooFewRows {
        /// Rows (equations) given.
        rows: usize,
        /// Unknowns (columns) to determine.
        unknowns: usize,
    },
    /// A regressor or target of a row is NaN or infinite.
    #[error("row {row} has a non-finite regressor or target")]
    NonFiniteEntry {
        /// The row's index (from 0).
        row: usize,
    },
    /// A target index beyond the targets the problem was reduced with.
    #[error("target {target} asked of a problem with {targets} targets")]
    NoSuchTarget {
        /// The target index asked for (from 0).
        target: usize,
        /// Targets the problem was reduced with.
        targets: usize,
    },
}

/// Solves min ‖A·x − b‖² for a tall `rows × columns` matrix given row by row: `row(i,
/// regressors)` fills row i's `columns` regressors (zeroed before the call) and returns
/// its target. Called once per row, in order. See the module documentation for the
/// method; [`Reduction`] for several targets, stacked problems or the covariance.
// Inlined with `Reduction::from_rows`, so that the caller's row closure (a power
// law's δ^n per row) is compiled into the loop: without, the ball's least-squares
// identification ran 10 % slower (criterion, `identification`).
#[inline]
pub fn linear_least_squares(
    rows: usize,
    columns: usize,
    mut row: impl FnMut(usize, &mut [f64]) -> f64,
) -> Result<LinearFit, LinearLeastSquaresError> {
    Reduction::from_rows(rows, columns, 1, |i, regressors, target| {
        target[0] = row(i, regressors);
    })?
    .solve(0, None)
}
