//! How the peg's wrench residual (13 inputs, 6 outputs) is trained: one six-output
//! network or the paper's six single-output networks, and their sizes.
//!
//! The core evaluates either as one network of a shipped shape
//! (`crate::residual::ContactResidual`): the joint network is 13-32-32-6, the six
//! networks 13-8-8-1 merged block-diagonally into 13-48-48-6.
//!
//! Measured (`cargo test --test train peg_hcm::six_single -- --nocapture`: 20 runs, PM2 =
//! IMPACT with exponent 2, 16 runs' 8215 rows trained, 4 runs' 2053 rows held out;
//! PM2's own error 180 N, 0.45 N·m RMS, on the wall contacts 6.9 N, 0.18 N·m):
//!
//! | networks | held-out RMS | walls | parameters (stored) | f32 blob | time |
//! |---|---|---|---|---|---|
//! | one 13-32-32-6 | 9.0 N, 0.054 N·m | 3.5 N, 0.038 N·m | 1702 (1702) | 7.1 kB | 6 s |
//! | six 13-8-8-1 | 8.5 N, 0.053 N·m | 3.4 N, 0.035 N·m | 1158 (3318) | 13.6 kB | 9 s |
//!
//! Comparable errors; the default is one network ([`OutputNets::Joint`]): half the
//! stored weights and multiply–adds in the controller (the merged network stores its
//! zero off-diagonal blocks), one training run instead of six.

use super::{OutputNets, TrainSettings};
use crate::residual::{HIDDEN, PER_OUTPUT_WIDTH, WRENCH_WIDTH};

/// Largest number of epochs: the six-output network stops early at 130–170 epochs on
/// 8 000 rows, the single-output ones run longer (up to 360).
const MAX_EPOCHS: usize = 400;
/// Epochs without improvement before stopping.
const PATIENCE: usize = 40;

/// The training settings of a wrench residual split as `nets`, seeded with `seed`:
/// width `WRENCH_WIDTH` for one network, `PER_OUTPUT_WIDTH` per network for six;
/// the state's position, quaternion, velocity and angular velocity as input vectors.
pub fn wrench_settings(nets: OutputNets, seed: u64) -> TrainSettings {
    TrainSettings {
        hidden_layers: HIDDEN,
        width: match nets {
            OutputNets::Joint => WRENCH_WIDTH,
            OutputNets::PerOutput => PER_OUTPUT_WIDTH,
        },
        max_epochs: MAX_EPOCHS,
        patience: PATIENCE,
        output_nets: nets,
        seed,
        input_vectors: vec![0..3, 3..7, 7..10, 10..13],
        ..TrainSettings::default()
    }
}
