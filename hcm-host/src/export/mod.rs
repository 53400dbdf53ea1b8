//! Export stage: a trained residual network → the weights blob a controller embeds.
//!
//! The blob format is defined once, in the core (`hcm_core::residual::blob`); this
//! module fills the core's [`BlobContents`] from the trainer's f64 network and seals it
//! with the CRC. [`ExportModel::evaluate`] is the f64 reference the core's `f32`
//! evaluation is tested against.

mod blob;
mod round_trip;

pub use blob::{blob, export_blobs, Blob, Blobs};
pub use round_trip::{round_trip_error, round_trip_error_over};

use crate::train::int8_row;
use hcm_core::residual::blob::{BlobContents, Shape, MAGIC, VERSION};
use hcm_core::residual::{crc32, Activation, Quantisation};

/// A trained residual network as the host holds it (f64, heap), in the layout the
/// blob stores: layers input → hidden 1 → … → output, each with its weights row-major
/// `[out][in]` and its bias `[out]`.
pub use crate::train::Network as ExportModel;

/// Why a network cannot be exported.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ExportError {
    /// A vector's length does not match the declared shape.
    #[error("{what} has {found} values; the network's shape needs {expected}")]
    WrongLength {
        /// Which vector, e.g. "layer 2 weights".
        what: String,
        /// Length the shape implies.
        expected: usize,
        /// Length found.
        found: usize,
    },
    /// The blob format holds 1 to 3 hidden layers.
    #[error("the network has {found} hidden layers; the blob format holds 1 to 3")]
    UnsupportedDepth {
        /// Declared number of hidden layers.
        found: usize,
    },
    /// A value is NaN, infinite, or too large for an `f32`.
    #[error("{what} is NaN, infinite or beyond the f32 range")]
    NonFinite {
        /// Which value, e.g. "layer 0 weight 5".
        what: String,
    },
    /// A normalisation scale is not > 0.
    #[error("{what} must be greater than zero")]
    NotPositive {
        /// Which scale, e.g. "input scale 1".
        what: String,
    },
    /// An envelope minimum exceeds its maximum, or its tolerance is negative.
    #[error(
        "the envelope of input {input} has its minimum above its maximum or a negative tolerance"
    )]
    BadEnvelope {
        /// Index of the input.
        input: usize,
    },
    /// An int8 blob of a network whose activation is not the quantised tanh.
    #[error(
        "an int8 blob runs the quantised tanh, and this network uses {found:?}: export its int8 \
         twin (`hcm train` makes one, trained with it) or export it as f32"
    )]
    Int8Activation {
        /// The network's activation.
        found: Activation,
    },
    /// A layer size does not fit the blob's 32-bit shape fields.
    #[error("a layer size does not fit in 32 bits")]
    TooLarge,
    /// postcard could not serialise the blob's contents.
    #[error("cannot serialise the weights blob: {0}")]
    Serialise(#[from] postcard::Error),
    /// The core rejects the blob just encoded.
    #[error(
        "the exported blob does not decode in the core: {0} (shape not the shipped 3-16-16-1?)"
    )]
    Decode(hcm_core::residual::BlobError),
}

impl ExportModel {
    /// (inputs, outputs) of each layer, input → output.
    pub fn layer_sizes(&self) -> Vec<(usize, usize)> {
        let mut sizes = vec![(self.inputs, self.width)];
        sizes.extend((1..self.hidden_layers).map(|_| (self.width, self.width)));
        sizes.push((self.width, self.outputs));
        sizes
    }

    /// `Ok` if every vector has the length the shape implies and the depth is 1 to 3.
    pub(crate) fn check_shape(&self) -> Result<(), ExportError> {
        if !(1..=3).contains(&self.hidden_layers) {
            return Err(ExportError::UnsupportedDepth {
                found: self.hidden_layers,
            });
        }
        let length = |what: String, expected: usize, found: usize| {
            if expected == found {
                Ok(())
            } else {
                Err(ExportError::WrongLength {
                    what,
                    expected,
                    found,
                })
            }
        };
        let sizes = self.layer_sizes();
        length("layers".into(), sizes.len(), self.layers.len())?;
        for (index, ((weights, bias), (inputs, outputs))) in
            self.layers.iter().zip(sizes).enumerate()
        {
            length(
                format!("layer {index} weights"),
                inputs.saturating_mul(outputs),
                weights.len(),
            )?;
            length(format!("layer {index} bias"), outputs, bias.len())?;
        }
        for (what, values, expected) in [
            ("input mean", &self.input_mean, self.inputs),
            ("input scale", &self.input_scale, self.inputs),
            ("output mean", &self.output_mean, self.outputs),
            ("output scale", &self.output_scale, self.outputs),
            ("envelope min", &self.envelope_min, self.inputs),
            ("envelope max", &self.envelope_max, self.inputs),
        ] {
            length(what.into(), expected, values.len())?;
        }
        if !self.envelope_tolerance.is_empty() {
            let found = self.envelope_tolerance.len();
            length("envelope tolerance".into(), self.inputs, found)?;
        }
        Ok(())
    }
}

/// Encodes `model` as a weights blob with its weights stored as `quantisation`.
///
/// Int8 stores each weight row of the hidden → hidden layers as q = round(w / s) with
/// s = max|w_row| / 127 (s = 1 for an all-zero row), so the largest weight of each row
/// is exact to f32 rounding and the others are off by at most s/2; the input and
/// output layers stay f32. An int8 blob needs a network with the quantised tanh
/// ([`ExportError::Int8Activation`] otherwise).
pub fn encode(model: &ExportModel, quantisation: Quantisation) -> Result<Vec<u8>, ExportError> {
    model.check_shape()?;
    let size = |n: usize| u32::try_from(n).map_err(|_| ExportError::TooLarge);
    let shape = Shape {
        inputs: size(model.inputs)?,
        width: size(model.width)?,
        outputs: size(model.outputs)?,
        hidden_layers: size(model.hidden_layers)?,
    };

    let mut normalisation = Vec::new();
    push_f32s(&mut normalisation, "input mean", &model.input_mean)?;
    push_positive(&mut normalisation, "input scale", &model.input_scale)?;
    push_f32s(&mut normalisation, "output mean", &model.output_mean)?;
    push_positive(&mut normalisation, "output scale", &model.output_scale)?;

    let mut envelope = Vec::new();
    push_f32s(&mut envelope, "envelope min", &model.envelope_min)?;
    push_f32s(&mut envelope, "envelope max", &model.envelope_max)?;
    if let Some(input) = (0..model.inputs).find(|&i| model.envelope_min[i] > model.envelope_max[i])
    {
        return Err(ExportError::BadEnvelope { input });
    }
    // A network written before the tolerance existed has none: 0 for every input.
    let tolerance = match model.envelope_tolerance.as_slice() {
        [] => vec![0.0; model.inputs],
        given => given.to_vec(),
    };
    if let Some(input) = tolerance.iter().position(|&t| t < 0.0) {
        return Err(ExportError::BadEnvelope { input });
    }
    push_f32s(&mut envelope, "envelope tolerance", &tolerance)?;

    let mut layers = Vec::new();
    for (index, ((weights, bias), (inputs, _))) in
        model.layers.iter().zip(model.layer_sizes()).enumerate()
    {
        let what = format!("layer {index} weights");
        // Only hidden → hidden layers are int8 (blob format version 2).
        let hidden_to_hidden = index > 0 && index + 1 < model.layers.len();
        match quantisation {
            Quantisation::Int8 if hidden_to_hidden => {
                push_int8(&mut layers, &what, weights, inputs)?
            }
            _ => push_f32s(&mut layers, &what, weights)?,
        }
        push_f32s(&mut layers, &format!("layer {index} bias"), bias)?;
    }

    // The core's int8 kernel runs the quantised tanh only (hcm_core::residual::int8).
    if quantisation == Quantisation::Int8 && model.activation != Activation::QuantisedTanh {
        return Err(ExportError::Int8Activation {
            found: model.activation,
        });
    }

    seal(&BlobContents {
        magic: MAGIC,
        version: VERSION,
        shape,
        activation: model.activation.tag(),
        quantisation: quantisation.tag(),
        normalisation: &normalisation,
        envelope: &envelope,
        layers: &layers,
    })
}

/// Serialises `contents` with postcard and appends its CRC-32 (little-endian): a blob.
///
/// [`encode`] is the normal way in; this is public so that tests can build blobs the
/// encoder refuses to write (another version, a NaN weight).
pub fn seal(contents: &BlobContents<'_>) -> Result<Vec<u8>, ExportError> {
    let mut blob = postcard::to_allocvec(contents)?;
    let crc = crc32(&blob);
    blob.extend_from_slice(&crc.to_le_bytes());
    Ok(blob)
}

/// Appends `value` as a little-endian `f32`, refusing what does not fit.
fn push_f32(out: &mut Vec<u8>, what: &str, index: usize, value: f64) -> Result<(), ExportError> {
    let single = value as f32;
    if !single.is_finite() {
        return Err(ExportError::NonFinite {
            what: format!("{what} {index}"),
        });
    }
    out.extend_from_slice(&single.to_le_bytes());
    Ok(())
}

fn push_f32s(out: &mut Vec<u8>, what: &str, values: &[f64]) -> Result<(), ExportError> {
    values
        .iter()
        .enumerate()
        .try_for_each(|(index, &value)| push_f32(out, what, index, value))
}

fn push_positive(out: &mut Vec<u8>, what: &str, values: &[f64]) -> Result<(), ExportError> {
    if let Some(index) = values
        .iter()
        .position(|&scale| scale.is_finite() && scale <= 0.0)
    {
        return Err(ExportError::NotPositive {
            what: format!("{what} {index}"),
        });
    }
    push_f32s(out, what, values)
}

/// Appends the rows of `weights` as int8 (one byte each), then one `f32` scale per row.
fn push_int8(
    out: &mut Vec<u8>,
    what: &str,
    weights: &[f64],
    columns: usize,
) -> Result<(), ExportError> {
    if let Some(index) = weights.iter().position(|w| !w.is_finite()) {
        return Err(ExportError::NonFinite {
            what: format!("{what} {index}"),
        });
    }
    let mut scales = Vec::new();
    for row in weights.chunks(columns.max(1)) {
        let (levels, scale) = int8_row(row);
        out.extend(levels.iter().map(|q| q.to_le_bytes()[0]));
        scales.push(f64::from(scale));
    }
    push_f32s(out, &format!("{what} row scale"), &scales)
}
