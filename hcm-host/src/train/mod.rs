//! Residual training: the data-driven half of the hybrid contact model. A small
//! multilayer perceptron ([`network`]) learns what the identified physics law (PM2)
//! misses — for the 1D examples the normal-force error f_measured − f_PM2 from the
//! contact's motion state [δ, δ̇, δ̇0] ([`residual_pairs`]); for a rigid body the
//! force and torque error from its 13 state components ([`wrench_pairs`], trained
//! with [`wrench_settings`](fn@wrench_settings)). The contact-frame residual ([`point_residual`]) learns
//! from a force sensor's wrench ([`point_samples`]) or, from a camera's poses alone,
//! from the poses the physics misses a few frames on ([`motion_samples`],
//! [`motion_residual`]).
//!
//! [`train`] minimises the mean squared error on normalised inputs and outputs
//! (x̂ = (x − mean)/std, ŷ likewise, mean and std over the training rows) by
//! mini-batch Adam ([`adam`], Kingma & Ba 2015):
//!
//! 1. a seeded random `validation_fraction` of the **rows** is held out (the trainer
//!    sees rows, not runs; to hold out whole runs, split the data before calling it);
//! 2. weights start from Glorot (tanh) or He (relu) uniform draws, biases at 0;
//! 3. each epoch shuffles the training rows and takes one Adam step per mini-batch;
//! 4. after each epoch the validation MSE is measured; the step size is halved after
//!    `plateau` epochs without improvement, training stops when it has not improved
//!    for `patience` epochs, and the weights of the best epoch are returned.
//!
//! Reproducibility: every random draw (split, initial weights, shuffles) comes from one
//! `ChaCha8Rng` seeded with `seed`, in a fixed order on the calling thread. Gradients
//! are accumulated in parallel (rayon) over fixed chunks of [`CHUNK_ROWS`] rows and the
//! chunk sums are added in chunk order, so a seed gives bit-identical weights whatever
//! the number of threads.

mod adam;
mod envelope;
mod explained;
mod force_residual;
mod int8;
mod joint_residual;
mod joint_samples;
mod kind;
mod motion_residual;
mod motion_samples;
mod network;
mod per_output;
mod point_residual;
mod point_samples;
mod quantise;
mod reported;
mod samples;
mod summed;
mod trained;
mod wrench_residual;
mod wrench_samples;
mod wrench_settings;
pub use explained::{explained_variance, silence_outputs, EXPLAINED_MIN};
pub use joint_residual::{train_joint_residual, JOINT_UNITS};
pub use joint_samples::joint_rows;
pub use motion_residual::{train_motion_residual, HORIZON};
pub use motion_samples::motion_rows;
pub use network::Layout;
pub use wrench_residual::pairs_before_event;
pub use wrench_samples::{contact_wrench, moving_body, state_input};

pub use envelope::envelope_tolerance;
pub use force_residual::{
    train_force_network, train_force_residual, ResidualError, ResidualSettings,
};
pub use int8::int8_row;
pub use kind::ResidualKind;
pub use network::{Activation, Network};
pub use per_output::OutputNets;
pub use point_residual::{explains_nothing, train_point_residual};
pub use quantise::{quantisation_aware, QuantiseReport};
pub use samples::residual_pairs;
pub use summed::{train_summed, SummedRow};
pub use trained::{Trained, TrainedResidual};
pub use wrench_residual::train_wrench_residual;
pub use wrench_samples::{wrench_pairs, WrenchPairs};
pub use wrench_settings::wrench_settings;

use adam::Adam;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use std::time::Instant;

/// Rows per parallel gradient job; fixed (not derived from the thread count) so that
/// the floating-point summation order, and hence the result, never changes.
pub const CHUNK_ROWS: usize = 32;

/// How to train.
#[derive(Clone, Debug, PartialEq)]
pub struct TrainSettings {
    /// Hidden layers, 1–3. Default 2.
    pub hidden_layers: usize,
    /// Neurons per hidden layer (≥ 1). Default 16.
    pub width: usize,
    /// Hidden-layer activation. Default tanh (smooth, like contact forces).
    pub activation: Activation,
    /// Adam's step size α (> 0, finite). Default 1e-3.
    pub learning_rate: f64,
    /// Rows per mini-batch (≥ 1). Default 64: with 256, a 2000-row data set gets only
    /// 1600 Adam steps in 200 epochs and stops short (sine test: validation MSE 8e-4
    /// against 4e-6 with 64); per-epoch cost on 100 000 rows rises by about a fifth.
    pub batch_size: usize,
    /// Largest number of passes over the training rows (≥ 1). Default 200.
    pub max_epochs: usize,
    /// Stop when the validation loss has not improved for this many epochs; 0 never
    /// stops early. Default 20.
    pub patience: usize,
    /// Share of the rows (not runs) held out for validation, in (0, 1). Default 0.1.
    pub validation_fraction: f64,
    /// Halve Adam's step size when the validation loss has not improved for this many
    /// epochs (reduce-on-plateau); 0 keeps it constant. Default 5: with a constant
    /// step the weights keep jittering at the mini-batch noise level, and the HCM's
    /// energy loss — a small difference of two large works — inherits that jitter.
    pub plateau: usize,
    /// Seed of the random number generator. Default 0.
    pub seed: u64,
    /// One network for all outputs ([`OutputNets::Joint`], the default) or one per
    /// output, merged into one block-diagonal network ([`OutputNets::PerOutput`], the
    /// paper's choice). See [`per_output`] for the measured comparison.
    pub output_nets: OutputNets,
    /// Input columns that are the components of one vector (one unit), e.g. a
    /// body's position, quaternion, velocity, angular velocity. A component whose
    /// spread is below `VECTOR_CONSTANT` of its vector's largest counts as constant
    /// and is normalised by that largest spread, its vector's scale: the peg's y, q_x,
    /// q_z, v_y, ω_x, ω_z are 0 up to rounding (its motion is planar; standard
    /// deviations 1e-20 to 1e-10), and dividing by such a spread would turn that
    /// rounding noise into O(1) network inputs and an envelope the simulation leaves
    /// at once. With the vector's scale, their envelope tolerance
    /// ([`envelope_tolerance`]) is a fraction of the vector's own spread (ω_z may reach
    /// 0.14 rad/s where ω_y spans 5 rad/s), in the vector's unit. Default: none.
    pub input_vectors: Vec<std::ops::Range<usize>>,
}

/// Below this fraction of its vector's largest spread a component is constant.
pub(crate) const VECTOR_CONSTANT: f64 = 1e-6;

impl Default for TrainSettings {
    fn default() -> Self {
        Self {
            hidden_layers: 2,
            width: 16,
            activation: Activation::Tanh,
            learning_rate: 1e-3,
            batch_size: 64,
            max_epochs: 200,
            patience: 20,
            validation_fraction: 0.1,
            plateau: 5,
            seed: 0,
            output_nets: OutputNets::Joint,
            input_vectors: Vec::new(),
        }
    }
}

/// How training went. Losses are mean squared errors in raw output units² (N² for the
/// force residual), averaged over rows and outputs.
#[derive(Clone, Debug, PartialEq)]
pub struct TrainReport {
    /// Epochs run.
    pub epochs: usize,
    /// Epoch (1-based) whose weights were kept: the lowest validation loss.
    pub best_epoch: usize,
    /// MSE of the returned network over the training rows.
    pub train_loss: f64,
    /// MSE of the returned network over the validation rows.
    pub validation_loss: f64,
    /// Wall-clock time (s).
    pub seconds: f64,
    /// Per epoch: (mean training MSE over that epoch's mini-batches, as the weights
    /// moved; validation MSE at the end of the epoch).
    pub history: Vec<(f64, f64)>,
}

/// Why training could not run.
#[derive(Debug, thiserror::Error)]
pub enum TrainError {
    /// No rows.
    #[error("no training data: the input and target lists are empty")]
    NoData,
    /// Inputs and targets hold different numbers of rows.
    #[error("{inputs} input rows but {targets} target rows")]
    RowCountMismatch {
        /// Input rows.
        inputs: usize,
        /// Target rows.
        targets: usize,
    },
    /// The first row has no columns.
    #[error("the {which} rows have no columns")]
    NoColumns {
        /// Which rows: `input` or `target`.
        which: &'static str,
    },
    /// A row's length differs from the first row's.
    #[error("{which} row {row} has {found} values, the first row has {expected}")]
    RaggedRow {
        /// Which rows: `input` or `target`.
        which: &'static str,
        /// The row's index (from 0).
        row: usize,
        /// Values of the first row.
        expected: usize,
        /// Values of this row.
        found: usize,
    },
    /// A NaN or infinity in the data.
    #[error("{which} row {row}, column {column} is {value}: every value must be finite")]
    NonFinite {
        /// Which rows: `input` or `target`.
        which: &'static str,
        /// The row's index (from 0).
        row: usize,
        /// The column's index (from 0).
        column: usize,
        /// The value found (NaN or ±∞).
        value: f64,
    },
    /// A setting outside its allowed range.
    #[error("bad training setting `{name}`: {reason}")]
    BadSetting {
        /// The setting's name.
        name: &'static str,
        /// The range it must lie in, and what it was.
        reason: String,
    },
    /// Too few rows to hold out a validation set and still train.
    #[error("{rows} rows cannot be split into training and validation rows (validation fraction {fraction})")]
    TooFewRows {
        /// Rows of the data.
        rows: usize,
        /// Share of the rows held out for validation (–).
        fraction: f64,
    },
    /// The loss became NaN or infinite (learning rate too large?).
    #[error("training diverged at epoch {epoch} (non-finite loss); try a smaller learning rate")]
    Diverged {
        /// The epoch whose loss was not finite (from 1).
        epoch: usize,
    },
}

/// Trains a network on (inputs, targets) rows — every input row of the same length
/// n_in ≥ 1, every target row of the same length n_out ≥ 1 — and reports how it went.
/// Deterministic for a seed, whatever the number of threads. `progress` is called after
/// each epoch with (epoch, training MSE, validation MSE).
pub fn train(
    inputs: &[Vec<f64>],
    targets: &[Vec<f64>],
    settings: &TrainSettings,
    mut progress: impl FnMut(usize, f64, f64),
) -> Result<(Network, TrainReport), TrainError> {
    let started = Instant::now();
    let (n_in, n_out) = check_data(inputs, targets)?;
    check_settings(settings)?;
    if settings.output_nets == OutputNets::PerOutput && n_out > 1 {
        return per_output::train_each(inputs, targets, settings, &mut progress);
    }
    let mut rng = ChaCha8Rng::seed_from_u64(settings.seed);
    let (training, validation) = split(inputs.len(), settings.validation_fraction, &mut rng)?;
    let data = Normalised::new(inputs, targets, &training, &settings.input_vectors);
    let (layout, best, report) = fit_new(
        &data,
        (n_in, n_out),
        (training, &validation),
        settings,
        (&mut rng, started),
        &mut progress,
    )?;
    Ok((data.network(&layout, &best, settings, inputs), report))
}

/// Σ over `rows` of each row's gradient and squared error, as `row` adds the one and
/// returns the other (row, work space, gradient so far): summed in parallel over fixed
/// chunks of [`CHUNK_ROWS`] rows, the chunks added in order — bit-identical whatever
/// rayon's scheduling.
pub(crate) fn chunked_gradient(
    layout: &Layout,
    parameters: usize,
    rows: &[usize],
    row: impl Fn(usize, &mut network::Scratch, &mut [f64]) -> f64 + Sync,
) -> (Vec<f64>, f64) {
    let chunks: Vec<(Vec<f64>, f64)> = rows
        .par_chunks(CHUNK_ROWS)
        .map(|chunk| {
            let mut gradient = vec![0.0; parameters];
            let mut scratch = layout.scratch();
            let error = (chunk.iter())
                .map(|&r| row(r, &mut scratch, &mut gradient))
                .sum::<f64>();
            (gradient, error)
        })
        .collect();
    let mut chunks = chunks.into_iter();
    let (mut total, mut squared_error) = chunks.next().unwrap_or_default();
    for (gradient, error) in chunks {
        total.iter_mut().zip(&gradient).for_each(|(a, b)| *a += b);
        squared_error += error;
    }
    (total, squared_error)
}

/// Σ over `rows` of what `row` returns (row, work space): summed in parallel over fixed
/// chunks of 16 × [`CHUNK_ROWS`] rows, the chunks added in order — bit-identical
/// whatever rayon's scheduling.
pub(crate) fn chunked_sum(
    layout: &Layout,
    rows: &[usize],
    row: impl Fn(usize, &mut network::Scratch) -> f64 + Sync,
) -> f64 {
    let sums: Vec<f64> = rows
        .par_chunks(16 * CHUNK_ROWS)
        .map(|chunk| {
            let mut scratch = layout.scratch();
            chunk.iter().map(|&r| row(r, &mut scratch)).sum::<f64>()
        })
        .collect();
    sums.iter().sum::<f64>()
}

/// What the epoch loop ([`fit`]) minimises: a squared error over rows, each row with
/// `columns` target values.
pub(crate) trait Objective: Sync {
    /// Target values per row (the divisor of the mean beside the rows).
    fn columns(&self) -> usize;

    /// (Σ over `rows` of ∂/∂θ of the row's squared error in normalised units, the raw
    /// squared error summed over `rows`), in a fixed summation order.
    fn gradient(&self, layout: &Layout, parameters: &[f64], rows: &[usize]) -> (Vec<f64>, f64);

    /// Mean squared error over `rows` and columns, raw units².
    fn loss(&self, layout: &Layout, parameters: &[f64], rows: &[usize]) -> f64;
}

/// A network of `settings`' shape between `sizes` (inputs, outputs), from fresh
/// weights drawn from `clock.0`, fitted by [`fit`] on `rows` (training, validation):
/// its layout, best parameters and report (`seconds` since `clock.1`).
pub(crate) fn fit_new(
    objective: &impl Objective,
    (inputs, outputs): (usize, usize),
    rows: (Vec<usize>, &[usize]),
    settings: &TrainSettings,
    (rng, started): (&mut ChaCha8Rng, Instant),
    progress: &mut impl FnMut(usize, f64, f64),
) -> Result<(Layout, Vec<f64>, TrainReport), TrainError> {
    let layout = Layout::new(
        inputs,
        settings.width,
        settings.hidden_layers,
        outputs,
        settings.activation,
    );
    let parameters = layout.initial_parameters(rng);
    let (best, report) = fit(
        objective, &layout, parameters, rows, settings, rng, progress,
    )?;
    let report = TrainReport {
        seconds: started.elapsed().as_secs_f64(),
        ..report
    };
    Ok((layout, best, report))
}

/// Mini-batch Adam epochs on the `rows.0` (training) from `parameters`, with the
/// reduce-on-plateau step and early stopping of [`TrainSettings`] judged on `rows.1`
/// (validation): the parameters of the best epoch and the report (its `seconds` 0,
/// for the caller to fill).
pub(crate) fn fit(
    objective: &impl Objective,
    layout: &Layout,
    mut parameters: Vec<f64>,
    (mut training, validation): (Vec<usize>, &[usize]),
    settings: &TrainSettings,
    rng: &mut ChaCha8Rng,
    progress: &mut impl FnMut(usize, f64, f64),
) -> Result<(Vec<f64>, TrainReport), TrainError> {
    let columns = objective.columns();
    let mut adam = Adam::new(parameters.len(), settings.learning_rate);
    let (mut best, mut best_epoch, mut best_loss) = (parameters.clone(), 0, f64::INFINITY);
    let mut history = Vec::new();
    // Epoch of the last improvement or step-size cut.
    let mut last_change = 0;
    for epoch in 1..=settings.max_epochs {
        shuffle(&mut training, rng);
        // The epoch on a thread of rayon's pool: each mini-batch's chunks are then
        // handed to the pool's other thread directly, not injected from outside and
        // waited for on a lock (from outside, a fifth of the peg's training samples were
        // in the kernel's scheduler; alternated runs of `hcm reproduce peg-in-hole`:
        // training 57.2 and 58.4 s from outside, 51.9 and 53.3 s on the pool).
        let sum = rayon::scope(|_| {
            let mut sum = 0.0;
            for batch in training.chunks(settings.batch_size) {
                let (mut gradient, squared_error) = objective.gradient(layout, &parameters, batch);
                // ∂/∂θ of the batch mean over rows and columns.
                let mean = 1.0 / (batch.len() * columns) as f64;
                gradient.iter_mut().for_each(|g| *g *= mean);
                adam.step(&mut parameters, &gradient);
                sum += squared_error;
            }
            sum
        });
        let train_loss = sum / (training.len() * columns) as f64;
        let validation_loss = objective.loss(layout, &parameters, validation);
        if !(train_loss.is_finite() && validation_loss.is_finite()) {
            return Err(TrainError::Diverged { epoch });
        }
        history.push((train_loss, validation_loss));
        progress(epoch, train_loss, validation_loss);
        if validation_loss < best_loss {
            (best_loss, best_epoch, last_change) = (validation_loss, epoch, epoch);
            best.copy_from_slice(&parameters);
        } else if settings.patience > 0 && epoch - best_epoch >= settings.patience {
            break;
        } else if settings.plateau > 0 && epoch - last_change >= settings.plateau {
            adam.learning_rate *= 0.5;
            last_change = epoch;
        }
    }
    let report = TrainReport {
        epochs: history.len(),
        best_epoch,
        train_loss: objective.loss(layout, &best, &training),
        validation_loss: best_loss,
        seconds: 0.0,
        history,
    };
    Ok((best, report))
}

/// (n_in, n_out) after checking that the rows are non-empty, rectangular and finite.
fn check_data(inputs: &[Vec<f64>], targets: &[Vec<f64>]) -> Result<(usize, usize), TrainError> {
    if inputs.is_empty() && targets.is_empty() {
        return Err(TrainError::NoData);
    }
    if inputs.len() != targets.len() {
        return Err(TrainError::RowCountMismatch {
            inputs: inputs.len(),
            targets: targets.len(),
        });
    }
    let n_in = check_rows("input", inputs)?;
    let n_out = check_rows("target", targets)?;
    Ok((n_in, n_out))
}

fn check_rows(which: &'static str, rows: &[Vec<f64>]) -> Result<usize, TrainError> {
    let expected = rows[0].len();
    if expected == 0 {
        return Err(TrainError::NoColumns { which });
    }
    for (row, values) in rows.iter().enumerate() {
        if values.len() != expected {
            let found = values.len();
            return Err(TrainError::RaggedRow {
                which,
                row,
                expected,
                found,
            });
        }
        if let Some((column, &value)) = values.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(TrainError::NonFinite {
                which,
                row,
                column,
                value,
            });
        }
    }
    Ok(expected)
}

pub(crate) fn check_settings(s: &TrainSettings) -> Result<(), TrainError> {
    let bad = |name, reason: &str| {
        Err(TrainError::BadSetting {
            name,
            reason: reason.to_owned(),
        })
    };
    if !(1..=3).contains(&s.hidden_layers) {
        return bad("hidden_layers", "must be 1, 2 or 3");
    }
    if s.width == 0 {
        return bad("width", "must be at least 1");
    }
    if !(s.learning_rate.is_finite() && s.learning_rate > 0.0) {
        return bad("learning_rate", "must be positive and finite");
    }
    if s.batch_size == 0 {
        return bad("batch_size", "must be at least 1");
    }
    if s.max_epochs == 0 {
        return bad("max_epochs", "must be at least 1");
    }
    if !(s.validation_fraction > 0.0 && s.validation_fraction < 1.0) {
        return bad("validation_fraction", "must lie strictly between 0 and 1");
    }
    Ok(())
}

/// (training rows, validation rows): a seeded random `fraction` of the rows (at least
/// one) for validation, the rest (at least one) for training, each in ascending order.
pub(crate) fn split(
    rows: usize,
    fraction: f64,
    rng: &mut ChaCha8Rng,
) -> Result<(Vec<usize>, Vec<usize>), TrainError> {
    let held_out = ((rows as f64 * fraction).round() as usize).max(1);
    if held_out >= rows {
        return Err(TrainError::TooFewRows { rows, fraction });
    }
    let mut order: Vec<usize> = (0..rows).collect();
    shuffle(&mut order, rng);
    let (validation, training) = order.split_at_mut(held_out);
    validation.sort_unstable();
    training.sort_unstable();
    Ok((training.to_vec(), validation.to_vec()))
}

/// Fisher–Yates shuffle (written out so the sequence depends only on the generator).
pub(crate) fn shuffle(items: &mut [usize], rng: &mut ChaCha8Rng) {
    for i in (1..items.len()).rev() {
        let j = rng.random_range(0..=i);
        items.swap(i, j);
    }
}

/// Per-column mean and standard deviation over `rows` of `table`. A constant column
/// gets scale 1, so it normalises to 0 instead of dividing by zero; "constant" means a
/// spread below 1e-4 of its mean, because the exported network runs in f32
/// (ε ≈ 1.2e-7), where dividing by a rounding-level spread (e.g. 5e-15 for an impact
/// speed identical in every run) would turn f32 rounding into huge inputs.
///
/// Both are rounded to `f32` values: the exported blob stores them as `f32`, so the host
/// network trains and evaluates with exactly the constants the controller holds (a
/// unit quaternion's w ≈ 0.9988 with spread 8.5e-4 would otherwise be shifted by
/// 3e-8/8.5e-4 ≈ 4e-5 of a normalised unit by the rounding of its mean alone).
pub(crate) fn normalisation(table: &[Vec<f64>], rows: &[usize]) -> (Vec<f64>, Vec<f64>) {
    let (mean, scale) = exact_normalisation(table, rows);
    let stored = |v: Vec<f64>| v.into_iter().map(|x| f64::from(x as f32)).collect();
    (stored(mean), stored(scale))
}

/// Mean and standard deviation per column over `rows` (scale 1 for a constant column).
fn exact_normalisation(table: &[Vec<f64>], rows: &[usize]) -> (Vec<f64>, Vec<f64>) {
    let columns = table[0].len();
    let n = rows.len() as f64;
    let mean: Vec<f64> = (0..columns)
        .map(|c| rows.iter().map(|&r| table[r][c]).sum::<f64>() / n)
        .collect();
    let scale = (0..columns)
        .map(|c| {
            let variance = rows
                .iter()
                .map(|&r| (table[r][c] - mean[c]).powi(2))
                .sum::<f64>()
                / n;
            let std = variance.sqrt();
            if std > 1e-4 * mean[c].abs() && std.is_finite() {
                std
            } else {
                1.0
            }
        })
        .collect();
    (mean, scale)
}

/// Gives each component of `vectors` whose scale (its standard deviation) is below
/// [`VECTOR_CONSTANT`] of the largest in its vector that largest scale (rounded to
/// `f32`, as every stored constant). Ranges beyond the columns are ignored.
pub(crate) fn constant_components(scale: &mut [f64], vectors: &[std::ops::Range<usize>]) {
    for vector in vectors {
        let Some(components) = scale.get_mut(vector.clone()) else {
            continue;
        };
        // Scale 1 marks a column already found constant: not a spread.
        let spread = |s: f64| if s == 1.0 { 0.0 } else { s };
        let largest = components.iter().map(|s| spread(*s)).fold(0.0, f64::max);
        let vector_scale = if largest > 0.0 {
            f64::from(largest as f32)
        } else {
            1.0
        };
        for s in components.iter_mut() {
            if spread(*s) < VECTOR_CONSTANT * largest {
                *s = vector_scale;
            }
        }
    }
}

/// The rows in normalised units, flat and row-major, with the normalisation.
struct Normalised {
    x: Vec<f64>,
    t: Vec<f64>,
    n_in: usize,
    n_out: usize,
    input: (Vec<f64>, Vec<f64>),
    output: (Vec<f64>, Vec<f64>),
}

impl Normalised {
    fn new(
        inputs: &[Vec<f64>],
        targets: &[Vec<f64>],
        training: &[usize],
        vectors: &[std::ops::Range<usize>],
    ) -> Self {
        let mut input = normalisation(inputs, training);
        constant_components(&mut input.1, vectors);
        let output = normalisation(targets, training);
        Self::with(inputs, targets, input, output)
    }

    /// The rows normalised by a given (mean, scale) of the inputs and of the targets.
    fn with(
        inputs: &[Vec<f64>],
        targets: &[Vec<f64>],
        input: (Vec<f64>, Vec<f64>),
        output: (Vec<f64>, Vec<f64>),
    ) -> Self {
        let flatten = |table: &[Vec<f64>], (mean, scale): &(Vec<f64>, Vec<f64>)| -> Vec<f64> {
            table
                .iter()
                .flat_map(|row| {
                    row.iter()
                        .zip(mean.iter().zip(scale))
                        .map(|(v, (m, s))| (v - m) / s)
                })
                .collect()
        };
        Self {
            x: flatten(inputs, &input),
            t: flatten(targets, &output),
            n_in: inputs[0].len(),
            n_out: targets[0].len(),
            input,
            output,
        }
    }

    fn row(&self, r: usize) -> (&[f64], &[f64]) {
        (
            &self.x[r * self.n_in..(r + 1) * self.n_in],
            &self.t[r * self.n_out..(r + 1) * self.n_out],
        )
    }

    /// Squared error of ŷ against row r's target in raw output units², summed over outputs.
    fn raw_squared_error(&self, y_hat: &[f64], r: usize) -> f64 {
        let (_, t) = self.row(r);
        y_hat
            .iter()
            .zip(t)
            .zip(&self.output.1)
            .map(|((y, t), s)| ((y - t) * s).powi(2))
            .sum()
    }
}

/// Row by row, target by target: (ŷ − t̂)² in normalised units.
impl Objective for Normalised {
    fn columns(&self) -> usize {
        self.n_out
    }

    /// (Σ over `rows` of ∂/∂θ Σ_o (ŷ_o − t̂_o)², raw squared error summed over `rows`).
    fn gradient(&self, layout: &Layout, parameters: &[f64], rows: &[usize]) -> (Vec<f64>, f64) {
        chunked_gradient(layout, parameters.len(), rows, |r, scratch, gradient| {
            let (x, t) = self.row(r);
            layout.accumulate_gradient(parameters, x, t, scratch, gradient);
            self.raw_squared_error(scratch.output(), r)
        })
    }

    /// MSE over `rows` and outputs in raw output units².
    fn loss(&self, layout: &Layout, parameters: &[f64], rows: &[usize]) -> f64 {
        let sum = chunked_sum(layout, rows, |r, scratch| {
            let y_hat = layout.forward(parameters, self.row(r).0, scratch);
            self.raw_squared_error(y_hat, r)
        });
        sum / (rows.len() * self.n_out) as f64
    }
}

impl Normalised {
    /// The exportable network: weights, normalisation and the envelope of all `inputs`.
    fn network(
        &self,
        layout: &Layout,
        parameters: &[f64],
        settings: &TrainSettings,
        inputs: &[Vec<f64>],
    ) -> Network {
        exportable(
            layout,
            parameters,
            settings,
            (&self.input, &self.output),
            inputs,
        )
    }
}

/// Per column: (mean, scale), raw units.
pub(crate) type Scaling = (Vec<f64>, Vec<f64>);

/// The network of `layout` at `parameters` as it is exported: its (input, output)
/// normalisation `scaling` and the envelope of all `inputs` (raw units).
pub(crate) fn exportable(
    layout: &Layout,
    parameters: &[f64],
    settings: &TrainSettings,
    scaling: (&Scaling, &Scaling),
    inputs: &[Vec<f64>],
) -> Network {
    let (input, output) = scaling;
    let n_in = input.0.len();
    let envelope = |pick: fn(f64, f64) -> f64, start: f64| -> Vec<f64> {
        (0..n_in)
            .map(|c| inputs.iter().map(|row| row[c]).fold(start, pick))
            .collect()
    };
    let (envelope_min, envelope_max) = (
        envelope(f64::min, f64::INFINITY),
        envelope(f64::max, f64::NEG_INFINITY),
    );
    Network {
        envelope_tolerance: envelope_tolerance(
            &envelope_min,
            &envelope_max,
            &input.1,
            &settings.input_vectors,
        ),
        inputs: n_in,
        width: settings.width,
        outputs: output.0.len(),
        hidden_layers: settings.hidden_layers,
        activation: settings.activation,
        layers: layout.layers(parameters),
        input_mean: input.0.clone(),
        input_scale: input.1.clone(),
        output_mean: output.0.clone(),
        output_scale: output.1.clone(),
        envelope_min,
        envelope_max,
    }
}
