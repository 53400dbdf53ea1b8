//! Quantisation-aware fine-tuning: an int8 twin of a trained network.
//!
//! The int8 blob stores the hidden → hidden layers (WIDTH × WIDTH weights each, the
//! bulk of the network) as int8 with one f32 scale per row ([`super::int8_row`]);
//! the input layer (INPUTS weights per row) and the linear output layer stay f32
//! (`hcm_core::residual::mlp`). Rounding moves each weight by up to half a level, and
//! those small moves add up. Measured on the flat shot's residual (`hcm reproduce
//! flat-shot`), RMS of the int8 network against the f32 one: all layers plainly rounded
//! 0.70 N; input layer kept f32 0.62 N; plus this fine-tuning 0.043 N (with an int8
//! input layer it stalled at 0.26 N: a per-row scale over only 3 weights rounds the
//! small ones by up to 100 %). So the int8 network is trained for its rounding:
//!
//! 1. the teacher is the trained f64 network; its outputs on the training inputs are
//!    the targets (distillation: the int8 twin learns the f32 model's function, not
//!    the noisy measurements again, so the two agree as closely as the levels allow);
//! 2. with the activation the core's int8 kernel runs: tanh becomes the quantised
//!    tanh (`hcm_core::residual::qtanh`, a table within 1.2e-4 of tanh), so the twin
//!    is fitted to it (the Q15 rounding of each activation, at most 1.5e-5, is not
//!    simulated); every forward pass uses the rounded weights, and the gradient taken there
//!    updates the unrounded shadow weights (the straight-through estimator, Bengio et
//!    al. 2013; Jacob et al., CVPR 2018, §3 "fake quantisation");
//! 3. Adam on batches of 1024 rows with a small step (1e-4) that halves after two
//!    epochs without improvement, keeping the rounded weights of the epoch whose
//!    mismatch to the teacher is smallest (single level flips move the output by
//!    tenths of a newton, so the mismatch jumps from epoch to epoch; small, few steps
//!    and keeping the best tame that);
//! 4. the output layer is then re-fitted by linear least squares on the last hidden
//!    layer's activations over all rows (the best linear read-out of the features the
//!    int8 layers actually compute).
//!
//! The result's int8 layers are already on their levels, so exporting it as int8
//! stores them exactly (to the f32 rounding of the scales). Deterministic for a seed,
//! like [`super::train`].

use super::adam::Adam;
use super::int8::int8_row;
use super::network::Layout;
use super::{shuffle, Network, Normalised, Objective, TrainError, CHUNK_ROWS};
use crate::numerics::{LinearFit, Reduction};
use hcm_core::residual::Activation;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::time::Instant;

/// How the fine-tuning went; errors are RMS over the rows (raw output units, N for the
/// force residual) of the int8 network against the teacher.
#[derive(Clone, Debug, PartialEq)]
pub struct QuantiseReport {
    /// RMS of plainly rounded weights (no fine-tuning) against the teacher.
    pub rounded_rms: f64,
    /// RMS of the fine-tuned int8 network against the teacher.
    pub tuned_rms: f64,
    /// Largest |int8 − teacher| over the rows after fine-tuning.
    pub tuned_max: f64,
    /// Epochs run.
    pub epochs: usize,
    /// Wall-clock time (s).
    pub seconds: f64,
}

/// The weights of the hidden → hidden layers rounded row by row to their int8 levels
/// (biases, the input layer and the output layer kept: f32 in the blob).
fn rounded(layout: &Layout, parameters: &[f64]) -> Vec<f64> {
    let mut layers = layout.layers(parameters);
    let output = layers.pop();
    let mut layers = layers
        .into_iter()
        .enumerate()
        .map(|(l, (weights, biases))| {
            if l == 0 {
                return (weights, biases);
            }
            let columns = weights.len() / biases.len().max(1);
            let weights = weights
                .chunks(columns.max(1))
                .flat_map(|row| {
                    let (levels, scale) = int8_row(row);
                    levels
                        .into_iter()
                        .map(move |q| f64::from(q) * f64::from(scale))
                })
                .collect();
            (weights, biases)
        })
        .collect::<Vec<_>>();
    layers.extend(output);
    layout.flatten(&layers)
}

/// `parameters` with the output layer replaced by the least-squares fit of the
/// normalised targets on the last hidden layer's activations (plus a bias), over `rows`.
fn refit_output(
    layout: &Layout,
    data: &Normalised,
    parameters: &[f64],
    rows: &[usize],
) -> Vec<f64> {
    let mut layers = layout.layers(parameters);
    let width = layout.sizes[layout.sizes.len() - 2];
    let n_out = data.n_out;
    // Features [h, 1] of each row: the last hidden layer = the network with an identity
    // read-out, computed by the forward pass of a layout without the output layer.
    let hidden = Layout::new(
        layout.sizes[0],
        width,
        layout.sizes.len() - 3,
        width,
        layout.activation,
    );
    let (last_weights, last_biases) = &layers[layers.len() - 2];
    let mut trunk = layers[..layers.len() - 2].to_vec();
    trunk.push((last_weights.clone(), last_biases.clone()));
    let trunk = hidden.flatten(&trunk);
    let mut scratch = hidden.scratch();
    // One reduction for every output: the features are computed once per row.
    let reduction = Reduction::from_rows(rows.len(), width + 1, n_out, |i, features, targets| {
        let (x, t) = data.row(rows[i]);
        // The trunk's "output layer" is the last hidden layer without its activation.
        let z = hidden.forward(&trunk, x, &mut scratch);
        for (f, &z) in features.iter_mut().zip(z) {
            *f = layout.activation.apply(z);
        }
        features[width] = 1.0;
        targets.copy_from_slice(t);
    });
    // A whisker of ridge, μ = 1e-9·(largest Σ feature²): the output layer is stored in
    // f32, so nearly coinciding features must not get the large weights of opposite
    // sign that an exact least-squares fit gives them (their f32 rounding would not
    // cancel; measured on the ball, the int8 blob then read 2 % off the host network).
    let solved = reduction.and_then(|r| {
        let largest = (0..=width)
            .map(|j| {
                (0..r.triangle_rows())
                    .map(|i| r.triangle(i, j).powi(2))
                    .sum()
            })
            .fold(0.0, f64::max);
        let ridge = 1e-9 * largest.max(1.0);
        (0..n_out).map(|o| r.solve_ridge(o, ridge)).collect()
    });
    let Ok(solution) = solved as Result<Vec<LinearFit>, _> else {
        return parameters.to_vec();
    };
    let output = layers.last_mut().expect("a network has an output layer");
    for (o, fit) in solution.iter().enumerate() {
        output.0[o * width..(o + 1) * width].copy_from_slice(&fit.coefficients[..width]);
        output.1[o] = fit.coefficients[width];
    }
    layout.flatten(&layers)
}

/// The int8 twin under training: the shadow weights the gradient moves, and the
/// rounded weights of the best epoch so far.
struct Twin<'a> {
    /// The network's shape.
    layout: &'a Layout,
    /// The training rows with the teacher's outputs as targets, normalised.
    data: &'a Normalised,
    /// Every row.
    rows: &'a [usize],
    /// Outputs per row.
    outputs: usize,
    /// The unrounded weights the gradient updates.
    shadow: Vec<f64>,
    /// The best rounded weights so far.
    best: Vec<f64>,
    /// Their mean squared mismatch to the teacher (normalised units).
    best_loss: f64,
    /// The optimiser.
    adam: Adam,
    /// The rows in this epoch's order.
    order: Vec<usize>,
    /// The last epoch that improved or halved the step.
    last_change: usize,
}

impl Twin<'_> {
    /// One epoch: Adam steps on shuffled batches with the gradient taken at the rounded
    /// weights (straight-through); the rounded weights reached and their loss on every
    /// row (normalised units), or Diverged.
    fn epoch(&mut self, epoch: usize, rng: &mut ChaCha8Rng) -> Result<(Vec<f64>, f64), TrainError> {
        let layout = self.layout;
        shuffle(&mut self.order, rng);
        for batch in self.order.chunks(32 * CHUNK_ROWS) {
            let (mut gradient, _) =
                self.data
                    .gradient(layout, &rounded(layout, &self.shadow), batch);
            let mean = 1.0 / (batch.len() * self.outputs) as f64;
            gradient.iter_mut().for_each(|g| *g *= mean);
            self.adam.step(&mut self.shadow, &gradient);
        }
        let candidate = rounded(layout, &self.shadow);
        let loss = self.data.loss(layout, &candidate, self.rows);
        if !loss.is_finite() {
            return Err(TrainError::Diverged { epoch });
        }
        Ok((candidate, loss))
    }

    /// Keeps `candidate` if its `loss` is the lowest yet, else halves the step after
    /// two epochs without improvement.
    fn keep(&mut self, candidate: Vec<f64>, loss: f64, epoch: usize) {
        if loss < self.best_loss {
            (self.best, self.best_loss, self.last_change) = (candidate, loss, epoch);
        } else if epoch - self.last_change >= 2 {
            self.adam.learning_rate *= 0.5;
            self.last_change = epoch;
        }
    }

    /// The best weights with the output layer re-fitted by least squares, if that
    /// lowers the loss; with their loss (normalised units).
    fn refitted(self) -> (Vec<f64>, f64) {
        let refitted = refit_output(self.layout, self.data, &self.best, self.rows);
        let refitted_loss = self.data.loss(self.layout, &refitted, self.rows);
        if refitted_loss < self.best_loss {
            (refitted, refitted_loss)
        } else {
            (self.best, self.best_loss)
        }
    }
}

/// Largest |network − target| over every output of every row (raw output units).
fn largest_error(network: &Network, inputs: &[Vec<f64>], targets: &[Vec<f64>]) -> f64 {
    inputs
        .iter()
        .zip(targets)
        .flat_map(|(x, t)| {
            let y = network.evaluate(x);
            y.into_iter()
                .zip(t)
                .map(|(a, b)| (a - b).abs())
                .collect::<Vec<_>>()
        })
        .fold(0.0_f64, f64::max)
}

/// The distillation problem: the teacher's outputs on `inputs` as the targets (raw
/// units), the rows normalised with the teacher's own scales, and its layout.
fn distillation(teacher: &Network, inputs: &[Vec<f64>]) -> (Vec<Vec<f64>>, Normalised, Layout) {
    let targets: Vec<Vec<f64>> = inputs.iter().map(|x| teacher.evaluate(x)).collect();
    let data = Normalised::with(
        inputs,
        &targets,
        (teacher.input_mean.clone(), teacher.input_scale.clone()),
        (teacher.output_mean.clone(), teacher.output_scale.clone()),
    );
    let layout = Layout::new(
        teacher.inputs,
        teacher.width,
        teacher.hidden_layers,
        teacher.outputs,
        twin_activation(teacher.activation),
    );
    (targets, data, layout)
}

/// The int8 twin's activation for a teacher's: tanh becomes the quantised tanh, the
/// table the core's integer kernel evaluates ([`Activation::QuantisedTanh`]), so that
/// the twin is fitted to the function the controller runs; ReLU stays ReLU.
fn twin_activation(teacher: Activation) -> Activation {
    match teacher {
        Activation::Tanh | Activation::QuantisedTanh => Activation::QuantisedTanh,
        Activation::Relu => Activation::Relu,
    }
}

/// Fine-tunes an int8 twin of `teacher` on the rows `inputs` (raw units, the training
/// inputs) for at most `epochs` epochs, then returns it with a report. `progress` is
/// called after each epoch with (epoch, RMS against the teacher).
pub fn quantisation_aware(
    teacher: &Network,
    inputs: &[Vec<f64>],
    epochs: usize,
    seed: u64,
    mut progress: impl FnMut(usize, f64),
) -> Result<(Network, QuantiseReport), TrainError> {
    let started = Instant::now();
    if inputs.is_empty() {
        return Err(TrainError::NoData);
    }
    let (targets, data, layout) = distillation(teacher, inputs);
    let rows: Vec<usize> = (0..inputs.len()).collect();
    let shadow = layout.flatten(&teacher.layers);
    let best = rounded(&layout, &shadow);
    let best_loss = data.loss(&layout, &best, &rows);
    let rounded_rms = best_loss.sqrt();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    // The trainer's default step: the shadow weights must move across rounding levels.
    let adam = Adam::new(shadow.len(), 1e-4);
    let mut twin = Twin {
        layout: &layout,
        data: &data,
        rows: &rows,
        outputs: teacher.outputs,
        shadow,
        best,
        best_loss,
        adam,
        order: rows.clone(),
        last_change: 0,
    };
    let mut run = 0;
    for epoch in 1..=epochs {
        run = epoch;
        let (candidate, loss) = twin.epoch(epoch, &mut rng)?;
        progress(epoch, loss.sqrt());
        twin.keep(candidate, loss, epoch);
    }
    let (best, best_loss) = twin.refitted();
    let network = Network {
        layers: layout.layers(&best),
        activation: layout.activation,
        ..teacher.clone()
    };
    let report = QuantiseReport {
        rounded_rms,
        tuned_rms: best_loss.sqrt(),
        tuned_max: largest_error(&network, inputs, &targets),
        epochs: run,
        seconds: started.elapsed().as_secs_f64(),
    };
    Ok((network, report))
}
