//! `hcm export`: a trained residual network (`hcm train`'s JSON) → the weights blob the
//! core decodes (postcard: magic, version, shapes, quantisation, normalisation,
//! envelope, weights, CRC-32).

use hcm_core::residual::Quantisation;
use hcm_host::output::write_bytes;
use hcm_host::train::TrainedResidual;
use std::path::PathBuf;

/// Weight storage of the blob.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Weights {
    /// f32 weights: the trained network.
    F32,
    /// int8 weights with one f32 scale per row: the quantisation-aware twin.
    Int8,
}

/// Export a trained residual network as a blob for the core (f32 or int8 weights).
///
/// Example: `hcm export --residual residual.json --weights int8 --out residual.int8.bin`
///
/// Decodes the blob again in the core and prints its worst difference to the host's
/// network over the envelope. `hcm evaluate --residual` and firmware read the blob.
///
/// Terms:
///   residual  the network trained by `hcm train`: the force PM2 gets wrong
///   blob      the network in the core's binary format (shapes, weights, normalisation,
///             envelope, checksum), decoded without allocation
///   int8      8-bit integer weights with one scale per row: about half the bytes
///   envelope  the range of inputs seen in training; outside it the HCM is PM2 alone
///   PM2       the physics law the residual corrects (`hcm identify`)
///   HCM       hybrid contact model: PM2 plus the residual network
#[derive(clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    /// Trained residual file written by `hcm train`.
    #[arg(long)]
    residual: PathBuf,
    /// Weight storage.
    #[arg(long, value_enum, default_value_t = Weights::F32)]
    weights: Weights,
    /// Blob to write.
    #[arg(long)]
    out: PathBuf,
}

/// The blob of `trained` in `weights` storage, checked by decoding it in the core:
/// (bytes, worst relative |core − host| over the envelope grid).
fn blob(trained: &TrainedResidual, weights: Weights) -> anyhow::Result<(Vec<u8>, f64)> {
    let quantisation = match weights {
        Weights::F32 => Quantisation::F32,
        Weights::Int8 => Quantisation::Int8,
    };
    let blob = hcm_host::export::blob(trained, quantisation)?;
    Ok((blob.bytes, blob.round_trip_error))
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let trained = TrainedResidual::read(&args.residual)?;
    let (bytes, error) = blob(&trained, args.weights)?;
    write_bytes(&args.out, &bytes)?;
    println!(
        "{} blob: {} bytes → {} (core vs host over the envelope: worst relative error {error:.2e})",
        match args.weights {
            Weights::F32 => "f32",
            Weights::Int8 => "int8",
        },
        bytes.len(),
        args.out.display()
    );
    Ok(())
}
