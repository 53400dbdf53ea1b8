//! Generic numerics: nothing here knows about contact laws, and nothing prints.
//!
//! - [`mod@linear_least_squares`]: the one linear least-squares routine of the host
//!   (Householder QR with faer), with the residual sum of squares and, when asked, the
//!   coefficients' covariance. Identification, Levenberg–Marquardt's damped steps, the
//!   air-drag fit, the int8 output-layer re-fit, the diagnosis' effect selection and
//!   the peak-force polynomial all solve through it.
//! - [`euclidean_norm`]: ‖x‖₂ without overflow.
//! - [`median`]: of a list, in place (the noise floors, the data-quality checks, the
//!   toss scores' summaries).
//! - [`sampled`]: a signal between its samples (cubic Hermite) and through a
//!   first-order low-pass filter.
//! - [`scores`]: proper scores of an ensemble forecast (CRPS, energy score, Brier, log)
//!   and the coverage of its central bands.
//! - [`optimize`]: the bounded minimisers (genetic algorithm, Levenberg–Marquardt,
//!   scalar and two-variable searches, Nelder–Mead) behind one bounds type, one
//!   progress observer and one trait for a vector of named parameters.

pub mod linear_least_squares;
mod median;
mod norm;
pub mod optimize;
pub mod sampled;
pub mod scores;

pub use linear_least_squares::{
    linear_least_squares, Covariance, LinearFit, LinearLeastSquaresError, Reduction,
};
pub use median::median;
pub use norm::euclidean_norm;
