//! The length a blob's header announces: what tells a blob cut short, or followed by
//! stray bytes, from one whose bytes were changed.
//!
//! The header (magic, version, shape, activation and storage tags) fixes the size of
//! every section, so it fixes where the CRC must be. Only a plausible header (1 to 3
//! hidden layers, known tags) is believed: random bytes after a valid magic and
//! version would otherwise announce a random length and read as "cut short".

use super::{BlobError, Shape};
use crate::residual::{Activation, Quantisation};
use serde::Deserialize;

/// The fixed start of every blob: the first five fields of
/// [`BlobContents`](super::BlobContents), which postcard lays out identically.
#[derive(Clone, Copy, Debug, Deserialize)]
pub(super) struct Header {
    /// Read past: `open` checks the magic and the version on their own first.
    _magic: [u8; 4],
    _version: u16,
    pub shape: Shape,
    pub activation: u8,
    pub quantisation: u8,
}

impl Header {
    /// The first reason this header cannot be a blob this firmware reads, if any.
    pub fn implausible(&self) -> Option<BlobError> {
        let depth = self.shape.hidden_layers;
        if !(1..=3).contains(&depth) {
            return Some(BlobError::UnsupportedDepth { found: depth });
        }
        if Activation::from_tag(self.activation).is_none() {
            return Some(BlobError::BadActivation {
                found: self.activation,
            });
        }
        if Quantisation::from_tag(self.quantisation).is_none() {
            return Some(BlobError::BadQuantisation {
                found: self.quantisation,
            });
        }
        None
    }

    /// The whole blob's length (bytes) for a header of `header_length` bytes, CRC
    /// included; `None` for an implausible header or one whose length overflows.
    pub fn announced_length(&self, header_length: usize) -> Option<usize> {
        if self.implausible().is_some() {
            return None;
        }
        let quantisation = Quantisation::from_tag(self.quantisation)?;
        let size = |n: u32| usize::try_from(n).ok();
        let (inputs, width) = (size(self.shape.inputs)?, size(self.shape.width)?);
        let outputs = size(self.shape.outputs)?;
        let hidden_to_hidden = size(self.shape.hidden_layers)?.checked_sub(1)?;
        // μ_x, σ_x, μ_y, σ_y; envelope min, max, tolerance: f32 each.
        let normalisation = inputs.checked_add(outputs)?.checked_mul(8)?;
        let envelope = inputs.checked_mul(12)?;
        let hidden = layer_bytes(width, width, quantisation)?.checked_mul(hidden_to_hidden)?;
        let layers = layer_bytes(inputs, width, Quantisation::F32)?
            .checked_add(hidden)?
            .checked_add(layer_bytes(width, outputs, Quantisation::F32)?)?;
        [normalisation, envelope, layers].into_iter().try_fold(
            header_length.checked_add(4)?,
            |total, section| {
                total
                    .checked_add(varint_length(section))?
                    .checked_add(section)
            },
        )
    }
}

/// Bytes of one layer `inputs` → `outputs`: its weights (4 bytes each in f32, 1 in
/// int8 plus one f32 scale per output row), then its f32 bias.
fn layer_bytes(inputs: usize, outputs: usize, storage: Quantisation) -> Option<usize> {
    let weights = inputs.checked_mul(outputs)?;
    let (weight_bytes, row_scales) = match storage {
        Quantisation::F32 => (weights.checked_mul(4)?, 0),
        Quantisation::Int8 => (weights, outputs),
    };
    weight_bytes.checked_add(row_scales.checked_add(outputs)?.checked_mul(4)?)
}

/// Bytes of postcard's varint (LEB128, 7 bits a byte) for a section length.
fn varint_length(value: usize) -> usize {
    let bits = usize::BITS - value.leading_zeros();
    bits.div_ceil(7).max(1) as usize
}

#[cfg(test)]
mod tests {
    use super::varint_length;

    #[test]
    fn varints_take_one_byte_per_seven_bits() {
        let cases = [(0, 1), (127, 1), (128, 2), (16_383, 2), (16_384, 3)];
        for (value, bytes) in cases {
            assert_eq!(varint_length(value), bytes, "{value}");
        }
    }
}
