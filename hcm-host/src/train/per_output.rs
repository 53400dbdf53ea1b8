//! One network per output, the paper's choice (Section 4: a separate network for each
//! force and torque component), against one network for all outputs.
//!
//! With [`OutputNets::PerOutput`], output o gets its own network of the configured
//! width trained on column o alone with the same seed (so the same validation rows and
//! input normalisation), and the networks are merged into one
//! exportable network whose hidden layers are block-diagonal (width × outputs
//! neurons, no weights between blocks): output o of the merged network is exactly
//! network o's output, so the core evaluates either choice with the same code.
//!
//! Measured (`cargo test -p hcm-tests --test train training::output_nets -- --nocapture`, two
//! outputs: a force error and a moment error that shares its cause): see the README,
//! "One network or one per output". The default is [`OutputNets::Joint`]: the
//! outputs of a contact residual share their cause (the same missing physics seen as
//! force and as moment), which one network learns once, with fewer parameters and
//! one training run instead of one per output.

use super::{train, Network, TrainError, TrainReport, TrainSettings};
use std::time::Instant;

/// How the outputs are split among networks.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum OutputNets {
    /// One network with all outputs.
    #[default]
    Joint,
    /// One network per output, merged block-diagonally.
    PerOutput,
}

/// Trains one network per target column and merges them; the report's losses are
/// means over the outputs (as for a joint network), its epochs the longest run.
pub(super) fn train_each(
    inputs: &[Vec<f64>],
    targets: &[Vec<f64>],
    settings: &TrainSettings,
    progress: &mut dyn FnMut(usize, f64, f64),
) -> Result<(Network, TrainReport), TrainError> {
    let started = Instant::now();
    let n_out = targets[0].len();
    let mut parts = Vec::with_capacity(n_out);
    for o in 0..n_out {
        let column: Vec<Vec<f64>> = targets.iter().map(|t| vec![t[o]]).collect();
        let single = TrainSettings {
            output_nets: OutputNets::Joint,
            ..settings.clone()
        };
        parts.push(train(inputs, &column, &single, |e, t, v| {
            progress(e, t, v)
        })?);
    }
    let mean =
        |f: fn(&TrainReport) -> f64| parts.iter().map(|(_, r)| f(r)).sum::<f64>() / n_out as f64;
    let epochs = parts.iter().map(|(_, r)| r.epochs).max().unwrap_or(0);
    let history = (0..epochs)
        .map(|e| {
            let ran: Vec<(f64, f64)> = parts
                .iter()
                .filter_map(|(_, r)| r.history.get(e).copied())
                .collect();
            let n = ran.len() as f64;
            (
                ran.iter().map(|h| h.0).sum::<f64>() / n,
                ran.iter().map(|h| h.1).sum::<f64>() / n,
            )
        })
        .collect();
    let report = TrainReport {
        epochs,
        best_epoch: parts.iter().map(|(_, r)| r.best_epoch).max().unwrap_or(0),
        train_loss: mean(|r| r.train_loss),
        validation_loss: mean(|r| r.validation_loss),
        seconds: started.elapsed().as_secs_f64(),
        history,
    };
    let networks: Vec<Network> = parts.into_iter().map(|(n, _)| n).collect();
    Ok((merge(&networks), report))
}

/// The block-diagonal network whose output o is `parts[o]`'s single output. All parts
/// share inputs, depth, width, activation and input normalisation (they were trained
/// on the same rows with the same split).
pub(crate) fn merge(parts: &[Network]) -> Network {
    let first = &parts[0];
    let (width, n_in, blocks) = (first.width, first.inputs, parts.len());
    let merged_width = width * blocks;
    let mut layers = Vec::with_capacity(first.layers.len());
    for l in 0..first.layers.len() {
        let columns = if l == 0 { n_in } else { merged_width };
        let rows = if l + 1 == first.layers.len() {
            blocks
        } else {
            merged_width
        };
        let (mut weights, mut biases) = (vec![0.0; rows * columns], vec![0.0; rows]);
        for (b, part) in parts.iter().enumerate() {
            let (w, bias) = &part.layers[l];
            let part_columns = if l == 0 { n_in } else { width };
            let column_offset = if l == 0 { 0 } else { b * width };
            let row_offset = if l + 1 == first.layers.len() {
                b
            } else {
                b * width
            };
            for (r, row) in w.chunks(part_columns).enumerate() {
                let start = (row_offset + r) * columns + column_offset;
                weights[start..start + part_columns].copy_from_slice(row);
                biases[row_offset + r] = bias[r];
            }
        }
        layers.push((weights, biases));
    }
    Network {
        width: merged_width,
        outputs: blocks,
        layers,
        output_mean: parts.iter().map(|p| p.output_mean[0]).collect(),
        output_scale: parts.iter().map(|p| p.output_scale[0]).collect(),
        ..first.clone()
    }
}
