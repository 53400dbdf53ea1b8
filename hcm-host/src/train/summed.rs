//! Training a network that is evaluated at several points of one sample and whose
//! outputs add up to what was measured: the contact-frame residual
//! ([`hcm_core::model::point_residual`]), one evaluation per touching point, judged
//! on the whole body's wrench — no sensor measures the force at one corner of a box.
//!
//! A row holds the points touching at one sample, each with its inputs x_p and its
//! *lever* L_p (targets × outputs): the target each unit output makes there (for the
//! contact-frame residual, the wrench on the moving body of a unit k_n, r_f, c_t, c_n,
//! c_r at that point). The prediction is Σ_p L_p·y(x_p), linear in the outputs, and
//! the loss is its squared error against the row's target, each target column over
//! its RMS. Backpropagation: ∂L/∂ŷ_p = σ_y ⊙ L_pᵀ·(2e/s), e the row's error.
//!
//! The rest is [`super::train`]'s: the same seeded split (by row), initial weights,
//! shuffles, Adam, reduce-on-plateau and early stopping (`super::fit`), gradients
//! summed over fixed chunks of rows in chunk order (bit-identical whatever the thread
//! count). The outputs are not centred (μ_y = 0: a correction with no target is
//! zero), and each output's scale is the one at which it alone would carry the
//! targets, each column in units of its RMS (in raw units, a rolling ball's couple
//! coefficient, whose lever is only torque, got the scale of the force's newtons and
//! started at couples of 15 N·m against targets of 0.01: the training never recovered).

use super::network::Layout;
use super::{
    check_settings, chunked_gradient, chunked_sum, exportable, fit_new, normalisation, split,
    Network, Objective, TrainError, TrainReport, TrainSettings,
};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::ops::Range;
use std::time::Instant;

/// One sample: the points the network is evaluated at, and what their outputs add up
/// to.
#[derive(Clone, Debug, PartialEq)]
pub struct SummedRow {
    /// Each point's inputs (raw units) and lever: the target each unit output makes at
    /// that point, row-major targetoutput.
    pub points: Vec<(Vec<f64>, Vec<f64>)>,
    /// The row's target (raw units).
    pub target: Vec<f64>,
}

/// Trains a network of `outputs` outputs on `rows` (every point's inputs of one length,
/// every target of one length, every lever targets × outputs long; rows without
/// points predict zero) and reports how it went; the report's losses are mean squared
/// errors over rows and target columns, raw units². Deterministic for a seed,
/// whatever the number of threads.
///
/// An output the fit does not need — fixed at 0, the training loss rises by less than
/// `UNNEEDED` of what the network gains over a zero output — is fixed at 0 and
/// listed last: nothing in the data says what it should be, and its scale, set by a
/// lever that is tiny throughout training, would turn the network's arbitrary value
/// there into a huge one wherever the lever is not tiny (measured on the peg, planar: a
/// spin coefficient scaled by spin rates of 1e-10 rad/s broke every replay of a
/// held-out condition). The test is unit-free: comparing the outputs' levers with each
/// other (tried) silenced the normal stiffness, whose lever δ is 1e-4 m.
pub fn train_summed(
    rows: &[SummedRow],
    outputs: usize,
    settings: &TrainSettings,
    mut progress: impl FnMut(usize, f64, f64),
) -> Result<(Network, TrainReport, Vec<usize>), TrainError> {
    let started = Instant::now();
    check_settings(settings)?;
    let data = Summed::new(rows, outputs)?;
    let mut rng = ChaCha8Rng::seed_from_u64(settings.seed);
    let (training, validation) = split(rows.len(), settings.validation_fraction, &mut rng)?;
    let data = data.normalised(&training, &settings.input_vectors);
    let (layout, best, report) = fit_new(
        &data,
        (data.n_in, outputs),
        (training, &validation),
        settings,
        (&mut rng, started),
        &mut progress,
    )?;
    let scaling = (
        &data.input,
        &(vec![0.0; outputs], data.output_scale.clone()),
    );
    let unneeded = data.unneeded(&layout, &best, &training_rows(rows.len(), &validation));
    let network = exportable(&layout, &best, settings, scaling, &data.raw_inputs);
    let network = super::explained::silence_outputs(&network, &unneeded);
    Ok((network, report, unneeded))
}

/// An output is unneeded when fixing it at 0 costs less than this share of the
/// network's gain over a zero output, on the training rows.
const UNNEEDED: f64 = 0.01;

/// The rows of `0..rows` not in `validation` (ascending).
fn training_rows(rows: usize, validation: &[usize]) -> Vec<usize> {
    (0..rows)
        .filter(|r| validation.binary_search(r).is_err())
        .collect()
}

/// Every point's inputs of `rows`, in row order: what the network is evaluated on (its
/// envelope, and the int8 twin's distillation inputs).
pub fn point_inputs(rows: &[SummedRow]) -> Vec<Vec<f64>> {
    rows.iter()
        .flat_map(|r| r.points.iter().map(|(x, _)| x.clone()))
        .collect()
}

/// The rows flattened, then normalised.
struct Summed {
    /// Every point's raw inputs, rows in order.
    raw_inputs: Vec<Vec<f64>>,
    /// Every point's normalised inputs, flat.
    x: Vec<f64>,
    /// Each row's points: a range of point indices.
    points: Vec<Range<usize>>,
    /// Each point's lever, flat ([target][output]).
    levers: Vec<f64>,
    /// Each row's raw target, flat.
    targets: Vec<f64>,
    /// Input (mean, scale).
    input: (Vec<f64>, Vec<f64>),
    /// σ_y of each output.
    output_scale: Vec<f64>,
    /// RMS of each target column over the training rows (1 for an all-zero column).
    target_scale: Vec<f64>,
    n_in: usize,
    n_out: usize,
    n_target: usize,
}

impl Summed {
    /// The rows checked (lengths, finiteness) and flattened; not yet normalised.
    fn new(rows: &[SummedRow], n_out: usize) -> Result<Summed, TrainError> {
        let first_point = rows.iter().flat_map(|r| r.points.first()).next();
        let (Some(first), Some((x0, _))) = (rows.first(), first_point) else {
            return Err(TrainError::NoData);
        };
        let (n_in, n_target) = (x0.len(), first.target.len());
        if n_in == 0 || n_target == 0 || n_out == 0 {
            let which = if n_in == 0 { "input" } else { "target" };
            return Err(TrainError::NoColumns { which });
        }
        let mut data = Summed {
            raw_inputs: Vec::new(),
            x: Vec::new(),
            points: Vec::with_capacity(rows.len()),
            levers: Vec::new(),
            targets: Vec::with_capacity(rows.len() * n_target),
            input: (Vec::new(), Vec::new()),
            output_scale: Vec::new(),
            target_scale: Vec::new(),
            n_in,
            n_out,
            n_target,
        };
        for (r, row) in rows.iter().enumerate() {
            check("target", r, &row.target, n_target)?;
            let start = data.raw_inputs.len();
            for (x, lever) in &row.points {
                check("input", r, x, n_in)?;
                check("lever", r, lever, n_target * n_out)?;
                data.raw_inputs.push(x.clone());
                data.levers.extend_from_slice(lever);
            }
            data.points.push(start..data.raw_inputs.len());
            data.targets.extend_from_slice(&row.target);
        }
        Ok(data)
    }

    /// The normalisation from the `training` rows applied: inputs by mean and spread
    /// over their points, targets by RMS, outputs by the scale at which one output
    /// alone carries the targets' RMS.
    fn normalised(mut self, training: &[usize], vectors: &[Range<usize>]) -> Summed {
        let training_points: Vec<usize> = training
            .iter()
            .flat_map(|&r| self.points[r].clone())
            .collect();
        // A row set without points (none touched) keeps a neutral normalisation.
        let mut input = if training_points.is_empty() {
            (vec![0.0; self.n_in], vec![1.0; self.n_in])
        } else {
            normalisation(&self.raw_inputs, &training_points)
        };
        super::constant_components(&mut input.1, vectors);
        let (n_t, n_out) = (self.n_target, self.n_out);
        let mut target_square = vec![0.0; n_t];
        for &r in training {
            for (t, s) in target_square.iter_mut().enumerate() {
                *s += self.targets[r * n_t + t].powi(2);
            }
        }
        let rows = training.len().max(1) as f64;
        self.target_scale = target_square
            .iter()
            .map(|s| positive_or_one((s / rows).sqrt()))
            .collect();
        // In units of each target column's RMS: Σ over rows and columns of the
        // normalised targets², against Σ over points and columns of each output's
        // normalised lever².
        let carried: f64 = (target_square.iter().zip(&self.target_scale))
            .map(|(t, s)| t / (s * s))
            .sum();
        let mut lever_square = vec![0.0; n_out];
        for &p in &training_points {
            let lever = &self.levers[p * n_t * n_out..(p + 1) * n_t * n_out];
            for (k, sum) in lever_square.iter_mut().enumerate() {
                *sum += (0..n_t)
                    .map(|t| (lever[t * n_out + k] / self.target_scale[t]).powi(2))
                    .sum::<f64>();
            }
        }
        self.output_scale = lever_square
            .iter()
            .map(|l| positive_or_one((carried / l).sqrt()))
            .collect();
        self.x = (self.raw_inputs.iter())
            .flat_map(|row| {
                let input = &input;
                row.iter()
                    .zip(input.0.iter().zip(&input.1))
                    .map(|(v, (m, s))| (v - m) / s)
            })
            .collect();
        self.input = input;
        self
    }

    /// Row `r`'s prediction Σ_p L_p·y(x_p) (raw target units), evaluating each point
    /// into `scratch`.
    fn predict(
        &self,
        layout: &Layout,
        parameters: &[f64],
        r: usize,
        scratch: &mut super::network::Scratch,
    ) -> Vec<f64> {
        self.predict_scaled(layout, parameters, r, scratch, &self.output_scale)
    }

    /// [`Self::predict`] with the outputs de-normalised by `scale` (0 fixes one at 0).
    fn predict_scaled(
        &self,
        layout: &Layout,
        parameters: &[f64],
        r: usize,
        scratch: &mut super::network::Scratch,
        scale: &[f64],
    ) -> Vec<f64> {
        let (n_t, n_out) = (self.n_target, self.n_out);
        let mut prediction = vec![0.0; n_t];
        for p in self.points[r].clone() {
            let y_hat = layout.forward(parameters, self.input_of(p), scratch);
            let lever = self.lever(p);
            for (t, value) in prediction.iter_mut().enumerate() {
                for k in 0..n_out {
                    *value += lever[t * n_out + k] * y_hat[k] * scale[k];
                }
            }
        }
        prediction
    }

    fn input_of(&self, p: usize) -> &[f64] {
        &self.x[p * self.n_in..(p + 1) * self.n_in]
    }

    fn lever(&self, p: usize) -> &[f64] {
        let size = self.n_target * self.n_out;
        &self.levers[p * size..(p + 1) * size]
    }

    fn target(&self, r: usize) -> &[f64] {
        &self.targets[r * self.n_target..(r + 1) * self.n_target]
    }

    /// Squared error of row `r`'s `prediction` in units of each target column's RMS,
    /// summed over the columns.
    fn squared_error(&self, prediction: &[f64], r: usize) -> f64 {
        // In units of each target column's RMS, as the gradient descends it: a raw sum
        // let a wall's hundreds of newtons hide a friction component's or a torque's
        // error, and a silenced friction scale made those ten times PM2's (R² −12 on
        // two moving bodies, tests/identify/two_bodies.rs).
        (prediction
            .iter()
            .zip(self.target(r))
            .zip(&self.target_scale))
        .map(|((y, t), s)| ((y - t) / s).powi(2))
        .sum()
    }

    /// Adds row `r`'s ∂L/∂θ to `gradient` and returns its raw squared error.
    fn row_gradient(
        &self,
        layout: &Layout,
        parameters: &[f64],
        r: usize,
        scratch: &mut super::network::Scratch,
        gradient: &mut [f64],
    ) -> f64 {
        let prediction = self.predict(layout, parameters, r, scratch);
        // ∂/∂prediction_t of Σ_t ((prediction_t − target_t)/s_t)².
        let slope: Vec<f64> = (prediction.iter().zip(self.target(r)))
            .zip(&self.target_scale)
            .map(|((y, t), s)| 2.0 * (y - t) / (s * s))
            .collect();
        let n_out = self.n_out;
        for p in self.points[r].clone() {
            layout.forward(parameters, self.input_of(p), scratch);
            let lever = self.lever(p);
            scratch.set_output_gradient((0..n_out).map(|k| {
                let through: f64 = (slope.iter().enumerate())
                    .map(|(t, g)| g * lever[t * n_out + k])
                    .sum();
                through * self.output_scale[k]
            }));
            layout.backpropagate(parameters, self.input_of(p), scratch, gradient);
        }
        self.squared_error(&prediction, r)
    }
}

impl Summed {
    /// Σ over `rows` of the squared error with the outputs scaled by `scale`.
    fn squared_error_scaled(
        &self,
        layout: &Layout,
        parameters: &[f64],
        rows: &[usize],
        scale: &[f64],
    ) -> f64 {
        chunked_sum(layout, rows, |r, scratch| {
            let y = self.predict_scaled(layout, parameters, r, scratch, scale);
            self.squared_error(&y, r)
        })
    }

    /// The outputs the fit on `rows` does not need (see [`train_summed`]).
    fn unneeded(&self, layout: &Layout, parameters: &[f64], rows: &[usize]) -> Vec<usize> {
        let full = self.squared_error_scaled(layout, parameters, rows, &self.output_scale);
        let zero = self.squared_error_scaled(layout, parameters, rows, &vec![0.0; self.n_out]);
        let gain = zero - full;
        (0..self.n_out)
            .filter(|&k| {
                let mut scale = self.output_scale.clone();
                scale[k] = 0.0;
                let without = self.squared_error_scaled(layout, parameters, rows, &scale);
                !(without - full >= UNNEEDED * gain && gain > 0.0)
            })
            .collect()
    }
}

impl Objective for Summed {
    fn columns(&self) -> usize {
        self.n_target
    }

    fn gradient(&self, layout: &Layout, parameters: &[f64], rows: &[usize]) -> (Vec<f64>, f64) {
        chunked_gradient(layout, parameters.len(), rows, |r, scratch, gradient| {
            self.row_gradient(layout, parameters, r, scratch, gradient)
        })
    }

    fn loss(&self, layout: &Layout, parameters: &[f64], rows: &[usize]) -> f64 {
        let sum = self.squared_error_scaled(layout, parameters, rows, &self.output_scale);
        sum / (rows.len().max(1) * self.n_target) as f64
    }
}

/// `value` rounded to `f32` (the blob stores it so), or 1 where it is not a positive
/// finite number.
fn positive_or_one(value: f64) -> f64 {
    if value.is_finite() && value > 0.0 {
        f64::from(value as f32)
    } else {
        1.0
    }
}

/// `values` of row `row` are `expected` long and finite.
fn check(
    which: &'static str,
    row: usize,
    values: &[f64],
    expected: usize,
) -> Result<(), TrainError> {
    if values.len() != expected {
        return Err(TrainError::RaggedRow {
            which,
            row,
            expected,
            found: values.len(),
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
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ragged_or_non_finite_rows_are_refused_by_row() {
        let good = SummedRow {
            points: vec![(vec![0.0], vec![1.0])],
            target: vec![1.0],
        };
        let mut bad = good.clone();
        bad.points[0].1 = vec![1.0, 2.0];
        let error = train_summed(
            &[good.clone(), bad],
            1,
            &TrainSettings::default(),
            |_, _, _| {},
        );
        assert!(
            matches!(
                error,
                Err(TrainError::RaggedRow {
                    which: "lever",
                    row: 1,
                    ..
                })
            ),
            "{error:?}"
        );
        let mut nan = good.clone();
        nan.target[0] = f64::NAN;
        let error = train_summed(&[good, nan], 1, &TrainSettings::default(), |_, _, _| {});
        assert!(matches!(error, Err(TrainError::NonFinite { row: 1, .. })));
        let error = train_summed(&[], 1, &TrainSettings::default(), |_, _, _| {});
        assert!(matches!(error, Err(TrainError::NoData)));
    }
}

#[cfg(test)]
mod gradient_check {
    use super::*;

    #[test]
    fn the_gradient_is_the_loss_slope() {
        let rows: Vec<SummedRow> = (0..5)
            .map(|i| SummedRow {
                points: (0..=i % 3)
                    .map(|j| {
                        (
                            vec![i as f64 * 0.3 - j as f64 * 0.2, 0.1 * j as f64],
                            vec![1.0 + j as f64, -0.5, 0.3, 2.0],
                        )
                    })
                    .collect(),
                target: vec![0.3 * i as f64, -1.0 + i as f64],
            })
            .collect();
        let data = Summed::new(&rows, 2).unwrap();
        let all: Vec<usize> = (0..5).collect();
        let data = data.normalised(&all, &[]);
        let layout = Layout::new(2, 4, 2, 2, super::super::Activation::Tanh);
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let parameters = layout.initial_parameters(&mut rng);
        let (gradient, _) = data.gradient(&layout, &parameters, &all);
        // Normalised loss: Σ_rows Σ_t ((pred − t)/s_t)².
        let loss = |p: &[f64]| -> f64 {
            let mut scratch = layout.scratch();
            all.iter()
                .map(|&r| {
                    let pred = data.predict(&layout, p, r, &mut scratch);
                    pred.iter()
                        .zip(data.target(r))
                        .zip(&data.target_scale)
                        .map(|((y, t), s)| ((y - t) / s).powi(2))
                        .sum::<f64>()
                })
                .sum()
        };
        for k in 0..parameters.len() {
            let mut up = parameters.clone();
            let mut down = parameters.clone();
            up[k] += 1e-6;
            down[k] -= 1e-6;
            let numeric = (loss(&up) - loss(&down)) / 2e-6;
            // The rational tanh's slope differs from 1 − a² by up to 1.3e-5 (tanh.rs).
            assert!(
                (numeric - gradient[k]).abs() < 2e-4 * (1.0 + numeric.abs()),
                "{k}: {numeric} vs {}",
                gradient[k]
            );
        }
    }
}
