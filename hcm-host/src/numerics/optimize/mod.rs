//! Bounded minimisers, away from any contact law: each takes a function of a parameter
//! vector, the box to search (one [`Bound`] per parameter) and, where it runs long, an
//! [`Observer`] of its progress.
//!
//! - [`mod@genetic`]: the paper's global search (a bounded real-coded GA, parallel and
//!   bit-identical whatever the thread count);
//! - [`mod@levenberg_marquardt`]: bounded nonlinear least squares with the estimates'
//!   covariance;
//! - [`search`]: one- and two-variable bounded searches (grid, then Brent / Powell);
//! - [`nelder_mead`]: the derivative-free local polish of a noisy fitness.
//!
//! [`Parameters`] is what a problem implements to be searched: a vector of named
//! parameters with bounds, read from and written into a value of the problem's own
//! type (a contact law, a scenario's model).

mod bound;
pub mod genetic;
pub mod levenberg_marquardt;
pub mod nelder_mead;
pub mod search;

pub use bound::Bound;
pub use genetic::{GeneticError, GeneticSettings};
pub use search::{minimize_box2, minimize_scalar, LeastSquaresError};

/// Receives an optimiser's progress: after each step, the steps done so far (the
/// genetic algorithm's generations, Nelder–Mead's fitness evaluations) and the best
/// fitness so far. Any `FnMut(usize, f64)` is one, so a caller passes a closure.
pub trait Observer {
    /// `done` steps so far, `best` the lowest fitness found.
    fn step(&mut self, done: usize, best: f64);
}

impl<F: FnMut(usize, f64)> Observer for F {
    fn step(&mut self, done: usize, best: f64) {
        self(done, best)
    }
}

/// A vector of named parameters with bounds: what the genetic algorithm, Nelder–Mead
/// and Levenberg–Marquardt search, read from and written into a value of type
/// [`Parameters::Target`] (a contact law, a scenario's model). The physics law's
/// bounds, the rigid fit, the fit from motion and the diagnosis's candidates implement
/// it, so that typed values — not `--set`-style strings — pass between stages.
pub trait Parameters {
    /// What the parameters are read from and written into.
    type Target;

    /// One bound per parameter, in order; their names are the parameters' names.
    fn bounds(&self) -> Vec<Bound>;

    /// The parameters' current values in `target`, in the order of
    /// [`Parameters::bounds`].
    fn values(&self, target: &Self::Target) -> Vec<f64>;

    /// `target` with the parameters set to `values` (in the order of
    /// [`Parameters::bounds`]).
    fn apply(&self, target: &Self::Target, values: &[f64]) -> Self::Target;

    /// The parameters' names, in order.
    fn names(&self) -> Vec<String> {
        self.bounds().into_iter().map(|b| b.name).collect()
    }

    /// Each parameter's name beside its value in `values`.
    fn named(&self, values: &[f64]) -> Vec<(String, f64)> {
        self.names()
            .into_iter()
            .zip(values.iter().copied())
            .collect()
    }
}
