//! The tall problem reduced to its triangle by unpivoted Householder QR, block by
//! block (see the module documentation of [`super`]).

use super::LinearLeastSquaresError;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::householder;
use faer::linalg::qr::no_pivoting::factor;
use faer::prelude::{Reborrow, ReborrowMut};
use faer::{Conj, Mat, MatMut, Par};

/// Rows absorbed per QR (or twice the columns, if more): the triangle carried from one
/// block to the next costs `columns / BLOCK_ROWS` of the work, and memory stays at
/// (columns + BLOCK_ROWS) × (columns + targets) values.
const BLOCK_ROWS: usize = 1024;

/// A least-squares problem min ‖A·x − b_t‖² (one or several targets b_t) reduced by
/// Householder QR, A = Q·R, to R, the leading part of Qᵀb_t and the squared norm of
/// the rest. Any column subset of R with the same Qᵀb is the reduction of the same
/// column subset of A, and stacking the triangles of several row blocks gives the
/// problem of all their rows: that is how the diagnosis' cross-validation fits every
/// subset of its folds without revisiting the data.
#[derive(Clone, Debug)]
pub struct Reduction {
    /// Rows absorbed (n).
    rows: usize,
    /// R, upper trapezoidal, min(n, columns) × columns.
    triangle: Mat<f64>,
    /// The leading min(n, columns) entries of Qᵀb, one column per target.
    projected: Mat<f64>,
    /// Per target, the squared norm of the other entries of Qᵀb.
    orthogonal: Vec<f64>,
}

/// The rows of one block on top of the triangle so far, and the targets beside them.
struct Work {
    regressors: Mat<f64>,
    targets: Mat<f64>,
    /// Rows at the top holding the triangle so far.
    kept: usize,
    /// Rows filled below them.
    filled: usize,
}

impl Reduction {
    /// Reduces the `rows × columns` problem with `targets` targets given row by row:
    /// `fill(i, regressors, targets)` writes row i's regressors and targets (both
    /// zeroed before the call). Called once per row, in order. Zero rows give an empty
    /// reduction (to stack with others); solving needs at least `columns` rows.
    #[inline]
    pub(crate) fn from_rows(
        rows: usize,
        columns: usize,
        targets: usize,
        mut fill: impl FnMut(usize, &mut [f64], &mut [f64]),
    ) -> Result<Reduction, LinearLeastSquaresError> {
        if columns == 0 {
            return Err(LinearLeastSquaresError::NoUnknowns);
        }
        let mut work = Work::new(rows, columns, targets);
        let mut orthogonal = vec![0.0; targets];
        let (mut regressors, mut values) = (vec![0.0; columns], vec![0.0; targets]);
        for i in 0..rows {
            regressors.fill(0.0);
            values.fill(0.0);
            fill(i, &mut regressors, &mut values);
            if regressors.iter().chain(&values).any(|v| !v.is_finite()) {
                return Err(LinearLeastSquaresError::NonFiniteEntry { row: i });
            }
            work.push(&regressors, &values);
            if work.room() == 0 {
                work.absorb(&mut orthogonal);
            }
        }
        Ok(work.finish(rows, orthogonal))
    }

    /// Reduces the `rows × columns.len()` problem with one target given column by
    /// column (each slice `rows` long), the same reduction as [`Reduction::from_rows`]
    /// would give bit for bit (the same blocks, absorbed at the same rows) without a
    /// call per row: the least-squares search's Jacobian is stored by columns.
    pub(crate) fn from_columns(
        columns: &[&[f64]],
        target: &[f64],
    ) -> Result<Reduction, LinearLeastSquaresError> {
        let (rows, n) = (target.len(), columns.len());
        if n == 0 {
            return Err(LinearLeastSquaresError::NoUnknowns);
        }
        assert!(columns.iter().all(|c| c.len() == rows));
        // The first row with a non-finite entry, each column scanned where it lies.
        let first_bad = (columns.iter().chain([&target]))
            .filter_map(|c| c.iter().position(|v| !v.is_finite()))
            .min();
        if let Some(row) = first_bad {
            return Err(LinearLeastSquaresError::NonFiniteEntry { row });
        }
        let mut work = Work::new(rows, n, 1);
        let mut orthogonal = vec![0.0];
        let mut start = 0;
        while start < rows {
            let at = work.kept + work.filled;
            let end = rows.min(start + work.room());
            for (j, column) in columns.iter().enumerate() {
                work.regressors.col_as_slice_mut(j)[at..at + end - start]
                    .copy_from_slice(&column[start..end]);
            }
            work.targets.col_as_slice_mut(0)[at..at + end - start]
                .copy_from_slice(&target[start..end]);
            work.filled += end - start;
            start = end;
            if work.room() == 0 {
                work.absorb(&mut orthogonal);
            }
        }
        Ok(work.finish(rows, orthogonal))
    }

    /// Rows absorbed (n).
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Columns (unknowns) of the problem.
    pub fn columns(&self) -> usize {
        self.triangle.ncols()
    }

    /// Targets the problem was reduced with.
    pub fn targets(&self) -> usize {
        self.orthogonal.len()
    }

    /// Rows of the triangle R: min(n, columns).
    pub(crate) fn triangle_rows(&self) -> usize {
        self.triangle.nrows()
    }

    /// R[i, j] (0 below the diagonal); RᵀR = AᵀA.
    pub(crate) fn triangle(&self, i: usize, j: usize) -> f64 {
        self.triangle[(i, j)]
    }

    /// Entry i of (Qᵀb)₁ for target `target`, i < [`Reduction::triangle_rows`];
    /// Rᵀ·(Qᵀb)₁ = Aᵀb.
    pub(crate) fn projected_target(&self, i: usize, target: usize) -> f64 {
        self.projected[(i, target)]
    }

    /// ‖b‖² − ‖(Qᵀb)₁‖² of target `target`, accumulated without cancellation: what no
    /// combination of the columns fits (the RSS of the least-squares solution when A
    /// has full rank), in the target's unit squared.
    pub(crate) fn orthogonal_sum_of_squares(&self, target: usize) -> f64 {
        self.orthogonal[target]
    }

    pub(super) fn triangle_matrix(&self) -> &Mat<f64> {
        &self.triangle
    }
}

impl Work {
    /// Room for `columns` + [`BLOCK_ROWS`] rows (or twice the columns, if more; no more
    /// than the problem's `rows`) of `columns` regressors and `targets` targets.
    fn new(rows: usize, columns: usize, targets: usize) -> Work {
        let capacity = columns + BLOCK_ROWS.max(2 * columns).min(rows.max(1));
        Work {
            regressors: Mat::zeros(capacity, columns),
            targets: Mat::zeros(capacity, targets),
            kept: 0,
            filled: 0,
        }
    }

    /// Rows that can still be filled before the block must be absorbed.
    fn room(&self) -> usize {
        self.regressors.nrows() - self.kept - self.filled
    }

    /// The reduction of the `rows` rows pushed: the rows left absorbed, R and the
    /// leading part of Qᵀb kept, `orthogonal` beside them.
    fn finish(mut self, rows: usize, mut orthogonal: Vec<f64>) -> Reduction {
        self.absorb(&mut orthogonal);
        let kept = self.kept;
        Reduction {
            rows,
            triangle: self.regressors.get(..kept, ..).to_owned(),
            projected: self.targets.get(..kept, ..).to_owned(),
            orthogonal,
        }
    }

    /// Copies one row below the rows already there.
    fn push(&mut self, regressors: &[f64], targets: &[f64]) {
        let at = self.kept + self.filled;
        for (j, &value) in regressors.iter().enumerate() {
            self.regressors[(at, j)] = value;
        }
        for (t, &value) in targets.iter().enumerate() {
            self.targets[(at, t)] = value;
        }
        self.filled += 1;
    }

    /// QR of the kept triangle and the filled rows: the new triangle replaces them at
    /// the top, Qᵀ is applied to the targets and the squares of the targets' entries
    /// below the triangle are added to `orthogonal`.
    fn absorb(&mut self, orthogonal: &mut [f64]) {
        if self.filled == 0 {
            return;
        }
        let m = self.kept + self.filled;
        let n = self.regressors.ncols();
        let size = m.min(n);
        let mut a = self.regressors.get_mut(..m, ..);
        let mut b = self.targets.get_mut(..m, ..);
        householder_qr(a.rb_mut(), b.rb_mut());
        for (t, sum) in orthogonal.iter_mut().enumerate() {
            *sum += (size..m).map(|i| b[(i, t)] * b[(i, t)]).sum::<f64>();
        }
        // Keep R alone: clear the Householder vectors stored below its diagonal.
        for j in 0..size {
            for i in j + 1..size {
                a[(i, j)] = 0.0;
            }
        }
        (self.kept, self.filled) = (size, 0);
    }
}

/// Factorises `a` = Q·R in place (R in the upper part, Householder vectors below) and
/// overwrites `b` by Qᵀ·b. Sequential: the same inputs give the same bits.
fn householder_qr(mut a: MatMut<'_, f64>, mut b: MatMut<'_, f64>) {
    let (m, n) = a.shape();
    let block = factor::recommended_block_size::<f64>(m, n);
    let mut coefficients = Mat::<f64>::zeros(block, m.min(n));
    let scratch =
        factor::qr_in_place_scratch::<f64>(m, n, block, Par::Seq, Default::default()).or(
            householder::apply_block_householder_sequence_transpose_on_the_left_in_place_scratch::<
                f64,
            >(m, block, b.ncols()),
        );
    let mut memory = MemBuffer::new(scratch);
    factor::qr_in_place(
        a.rb_mut(),
        coefficients.as_mut(),
        Par::Seq,
        MemStack::new(&mut memory),
        Default::default(),
    );
    householder::apply_block_householder_sequence_transpose_on_the_left_in_place_with_conj(
        a.rb(),
        coefficients.as_ref(),
        Conj::No,
        b.rb_mut(),
        Par::Seq,
        MemStack::new(&mut memory),
    );
}
