//! The export stage of a trained residual: its weights blobs, each decoded back by the
//! core and compared with the host network. `hcm export` writes one; `hcm reproduce`
//! both.

use super::{encode, round_trip_error, ExportError};
use crate::residual::ContactResidual;
use crate::scenario::Model;
use crate::train::TrainedResidual;
use hcm_core::residual::Quantisation;

/// One exported blob.
#[derive(Clone, Debug)]
pub struct Blob {
    /// Its weight storage: the f32 network or its int8 twin.
    pub(crate) quantisation: Quantisation,
    /// The blob (`residual.bin`, `residual.int8.bin`).
    pub bytes: Vec<u8>,
    /// Worst relative |core − host| over the envelope grid (–), see
    /// [`round_trip_error`].
    pub round_trip_error: f64,
    /// The blob as the core decoded it: the residual the HCM simulates.
    pub residual: ContactResidual,
}

/// Both blobs of a trained residual.
#[derive(Clone, Debug)]
pub struct Blobs {
    /// The f32 network's.
    pub f32: Blob,
    /// The int8 twin's.
    pub int8: Blob,
}

impl Blobs {
    /// The two HCMs: `pm2` with the f32 blob's residual on contact `c`, and with the
    /// int8 blob's — the models a controller running either blob simulates.
    pub fn hybrid_models(&self, pm2: &Model, c: usize) -> (Model, Model) {
        let with = |blob: &Blob| {
            let mut hcm = pm2.clone();
            hcm.contacts[c].model.residual = Some(blob.residual.clone());
            hcm
        };
        (with(&self.f32), with(&self.int8))
    }
}

/// The blob of `trained` in `quantisation` storage (the f32 network, or the int8
/// twin for [`Quantisation::Int8`]), checked by decoding it in the core.
pub fn blob(trained: &TrainedResidual, quantisation: Quantisation) -> Result<Blob, ExportError> {
    let network = match quantisation {
        Quantisation::F32 => &trained.network,
        Quantisation::Int8 => &trained.int8_network,
    };
    let bytes = encode(network, quantisation)?;
    let residual = ContactResidual::decode(&bytes).map_err(ExportError::Decode)?;
    Ok(Blob {
        quantisation,
        round_trip_error: round_trip_error(network, &residual),
        bytes,
        residual,
    })
}

/// Both blobs of `trained`.
pub fn export_blobs(trained: &TrainedResidual) -> Result<Blobs, ExportError> {
    Ok(Blobs {
        f32: blob(trained, Quantisation::F32)?,
        int8: blob(trained, Quantisation::Int8)?,
    })
}
