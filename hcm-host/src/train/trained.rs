//! The output of `hcm train`: the trained residual network and its int8 twin, in one
//! JSON file that `hcm export` turns into weights blobs.
//!
//! ```json
//! { "format": "hcm-residual", "version": 1, "contact": 0,
//!   "network": { "inputs": 3, "width": 16, … },
//!   "int8_network": { … the same shape, weights on their int8 levels … } }
//! ```
//!
//! `network` is the f64 network as trained; `int8_network` its quantisation-aware twin
//! ([`super::quantise`]), whose weights the int8 blob stores exactly.

use super::{Network, QuantiseReport, TrainReport};
use crate::input;
use crate::output::write_atomically;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The `format` field's value.
pub(crate) const FORMAT: &str = "hcm-residual";
/// The version this build reads and writes.
pub(crate) const FILE_VERSION: u32 = 1;

/// A trained residual network file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrainedResidual {
    /// Always [`FORMAT`].
    pub(crate) format: String,
    /// [`FILE_VERSION`].
    pub(crate) version: u32,
    /// Index of the scenario contact whose force error the network models.
    pub(crate) contact: usize,
    /// The trained network (f64; exported as f32).
    pub(crate) network: Network,
    /// Its int8 twin (exported as int8).
    pub(crate) int8_network: Network,
}

/// Why a trained-residual file cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum TrainedError {
    /// The file cannot be read or parsed.
    #[error("{path}: {message}")]
    File {
        /// The file's path.
        path: String,
        /// Why it could not be read or parsed.
        message: String,
    },
    /// Not a file of this kind or version.
    #[error("{path}: expected format `{FORMAT}` version {FILE_VERSION}, found `{}` version {version}; write it with `hcm train`", input::excerpt(format))]
    WrongFormat {
        /// The file's path.
        path: String,
        /// The format the file names.
        format: String,
        /// The format version the file names.
        version: u32,
    },
}

impl TrainedResidual {
    /// A file holding `network`, its int8 twin, for scenario contact `contact`.
    pub fn new(contact: usize, network: Network, int8_network: Network) -> Self {
        Self {
            format: FORMAT.into(),
            version: FILE_VERSION,
            contact,
            network,
            int8_network,
        }
    }

    /// The trained network (f64; exported as f32).
    pub fn network(&self) -> &Network {
        &self.network
    }

    /// Reads and checks a file written by [`TrainedResidual::write`].
    pub fn read(path: &Path) -> Result<TrainedResidual, TrainedError> {
        let file = |message: String| TrainedError::File {
            path: path.display().to_string(),
            message,
        };
        let text = input::read_text(path, input::TEXT_LIMIT, "a trained residual").map_err(file)?;
        let remedy = "write it again with `hcm train` (or copy it again)";
        let trained: TrainedResidual =
            serde_json::from_str(&text).map_err(|e| file(input::json_error(&text, &e, remedy)))?;
        if trained.format != FORMAT || trained.version != FILE_VERSION {
            return Err(TrainedError::WrongFormat {
                path: path.display().to_string(),
                format: trained.format,
                version: trained.version,
            });
        }
        Ok(trained)
    }

    /// Writes it as pretty JSON, atomically.
    pub fn write(&self, path: &Path) -> anyhow::Result<()> {
        let text = serde_json::to_string_pretty(self)?;
        write_atomically(path, |w: &mut dyn std::io::Write| -> anyhow::Result<()> {
            w.write_all(text.as_bytes())?;
            Ok(w.write_all(b"\n")?)
        })
    }
}

/// A trained residual and how its training went, whichever the residual's kind (the
/// 1D normal force, the wrench from the body's state, the contact-frame points, from
/// motion).
#[derive(Clone, Debug)]
pub struct Trained {
    /// The f32 network and its int8 twin (`residual.json`).
    pub residual: TrainedResidual,
    /// Training rows: the force samples inside the contact (1D), the contact samples of
    /// the first events (3D).
    pub rows: usize,
    /// The f32 network's training.
    pub report: TrainReport,
    /// The int8 twin's fine-tuning.
    pub int8: QuantiseReport,
    /// R² of each output on the training rows (3D: force x y z, torque x y z); empty
    /// where it is not computed (the 1D network's one output).
    pub explained: Vec<f64>,
    /// Outputs fixed at zero: for the body-state network, wrench components whose R²
    /// is below [`super::EXPLAINED_MIN`]; for the contact-frame network, the point
    /// outputs the fit does not need ([`super::summed::train_summed`]).
    pub silenced: Vec<usize>,
}
