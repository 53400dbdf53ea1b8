//! The weights blob: how a trained residual travels from the host to the controller.
//!
//! ```text
//! postcard(BlobContents) ‖ CRC-32 (4 bytes, little-endian) of everything before it
//! ```
//!
//! [`BlobContents`] opens with the magic `HCM1` (four raw bytes, so `head -c4` shows
//! it), the format [`VERSION`], the [`Shape`], the activation and quantisation tags,
//! then three byte sections whose numbers are little-endian:
//!
//! - `normalisation`: μ_x, σ_x (INPUTS `f32` each), μ_y, σ_y (OUTPUTS `f32` each);
//! - `envelope`: min, max, tolerance (INPUTS `f32` each), raw units; the tolerance
//!   (finite, ≥ 0) widens each input's [min, max] (version 3; version 2 had none);
//! - `layers`: for each layer, input → hidden → … → output: the weights row-major
//!   `[out][in]` (`f32`, or for the hidden → hidden layers of an int8 blob `i8` in
//!   \[−127, 127\] followed by one `f32` scale per output row), then the bias `[out]`
//!   (`f32`). The input and output layers are `f32` in both kinds (since version 2;
//!   version 1 stored every layer of an int8 blob as int8). The decoder transposes
//!   the `f32` weights into the core's column-by-column [`super::Layer`] and keeps
//!   int8 levels in [`super::Int8Layer`]'s kernel order.
//!
//! The arrays are raw bytes in a borrowed postcard byte field, not serde sequences:
//! decoding then borrows from the blob (nothing allocated) and works for any size
//! (serde derives arrays only up to 32 elements). [`decode`] checks, in order: the
//! magic, the version, the length the header announces (a blob cut short, or with
//! bytes after its end), the CRC, the postcard structure, the tags and the shape,
//! then that every number is finite and every scale positive. A header that names
//! an unknown depth or tag is believed only when the CRC is intact (an intact blob
//! written for another firmware); otherwise the blob is reported as corrupted.

mod error;
mod length;

pub use error::BlobError;

use super::mlp::{Hidden, HiddenDepth, Mlp, WeightFormat};
use super::{crc32, Activation, Quantisation};
use core::fmt;
use length::Header;
use serde::{Deserialize, Serialize, Serializer};

/// The first four bytes of every blob.
pub const MAGIC: [u8; 4] = *b"HCM1";

/// The blob format this crate writes and reads.
pub const VERSION: u16 = 3;

/// The layer sizes of a network.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shape {
    /// Number of inputs.
    pub inputs: u32,
    /// Neurons in each hidden layer.
    pub width: u32,
    /// Number of outputs.
    pub outputs: u32,
    /// Number of hidden layers, 1 to 3.
    pub hidden_layers: u32,
}

impl Shape {
    /// The shape of an [`Mlp`] with these const generics.
    pub fn of<
        const INPUTS: usize,
        const WIDTH: usize,
        const OUTPUTS: usize,
        const HIDDEN: usize,
    >() -> Self {
        let count = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
        Shape {
            inputs: count(INPUTS),
            width: count(WIDTH),
            outputs: count(OUTPUTS),
            hidden_layers: count(HIDDEN),
        }
    }
}

impl fmt::Display for Shape {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} inputs, {} hidden layer(s) of {}, {} outputs",
            self.inputs, self.hidden_layers, self.width, self.outputs
        )
    }
}

/// Everything in a blob but the trailing CRC, as postcard (de)serialises it.
///
/// Public so that the host encoder writes exactly what [`decode`] reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct BlobContents<'a> {
    /// [`MAGIC`].
    pub magic: [u8; 4],
    /// [`VERSION`].
    pub version: u16,
    /// Layer sizes.
    pub shape: Shape,
    /// [`Activation::tag`].
    pub activation: u8,
    /// [`Quantisation::tag`].
    pub quantisation: u8,
    /// μ_x, σ_x, μ_y, σ_y, `f32` little-endian.
    #[serde(serialize_with = "as_bytes")]
    pub normalisation: &'a [u8],
    /// Envelope min, max, `f32` little-endian.
    #[serde(serialize_with = "as_bytes")]
    pub envelope: &'a [u8],
    /// Weights, row scales (int8) and biases of every layer.
    #[serde(serialize_with = "as_bytes")]
    pub layers: &'a [u8],
}

/// Writes a byte slice as one postcard byte string (length, then the bytes), which is
/// what `&[u8]`'s `Deserialize` borrows back, rather than as a sequence of `u8`.
fn as_bytes<S: Serializer>(bytes: &&[u8], serializer: S) -> Result<S::Ok, S::Error> {
    serializer.serialize_bytes(bytes)
}

/// Decodes a weights blob into a network of the caller's shape and weight storage,
/// without allocating.
///
/// Fails, never panics, on any byte string that is not a valid blob of exactly this
/// shape and storage.
pub fn decode<
    const INPUTS: usize,
    const WIDTH: usize,
    const OUTPUTS: usize,
    const HIDDEN: usize,
    Q,
>(
    bytes: &[u8],
) -> Result<Mlp<INPUTS, WIDTH, OUTPUTS, HIDDEN, Q>, BlobError>
where
    Q: WeightFormat,
    Hidden<HIDDEN>: HiddenDepth<WIDTH, Q>,
{
    let contents = open(bytes)?;
    let expected = Shape::of::<INPUTS, WIDTH, OUTPUTS, HIDDEN>();
    if contents.shape != expected {
        return Err(BlobError::WrongShape {
            expected,
            found: contents.shape,
        });
    }
    // `open` checked both tags.
    let activation = Activation::from_tag(contents.activation).ok_or(BlobError::BadActivation {
        found: contents.activation,
    })?;
    let quantisation =
        Quantisation::from_tag(contents.quantisation).ok_or(BlobError::BadQuantisation {
            found: contents.quantisation,
        })?;
    if quantisation != Q::KIND {
        return Err(BlobError::WrongQuantisation {
            expected: Q::KIND,
            found: quantisation,
        });
    }
    // The int8 kernel runs the quantised tanh and no other activation (int8.rs).
    if quantisation == Quantisation::Int8 && activation != Activation::QuantisedTanh {
        return Err(BlobError::BadActivation {
            found: contents.activation,
        });
    }

    let mut mlp = Mlp::zeroed(activation);
    let scaling = &mut mlp.normalisation;
    let mut section = Reader(contents.normalisation);
    let positive = |scale: f32| scale > 0.0 && scale.is_finite();
    let finite = |value: f32| value.is_finite();
    section.read_f32s(&mut scaling.input_mean, finite, BlobError::BadNormalisation)?;
    section.read_f32s(
        &mut scaling.input_scale,
        positive,
        BlobError::BadNormalisation,
    )?;
    section.read_f32s(
        &mut scaling.output_mean,
        finite,
        BlobError::BadNormalisation,
    )?;
    section.read_f32s(
        &mut scaling.output_scale,
        positive,
        BlobError::BadNormalisation,
    )?;
    section.finish()?;

    let mut section = Reader(contents.envelope);
    let envelope = &mut mlp.envelope;
    let not_nan = |bound: f32| !bound.is_nan();
    section.read_f32s(&mut envelope.min, not_nan, BlobError::BadEnvelope)?;
    section.read_f32s(&mut envelope.max, not_nan, BlobError::BadEnvelope)?;
    let tolerance = |value: f32| value >= 0.0 && value.is_finite();
    section.read_f32s(&mut envelope.tolerance, tolerance, BlobError::BadEnvelope)?;
    section.finish()?;
    if envelope
        .min
        .iter()
        .zip(&envelope.max)
        .any(|(min, max)| min > max)
    {
        return Err(BlobError::BadEnvelope);
    }

    let mut section = Reader(contents.layers);
    let used = mlp.input_layer.read(section.0)?;
    section.take(used)?;
    for layer in mlp.hidden_layers.as_mut() {
        let used = Q::read_square(layer, section.0)?;
        section.take(used)?;
    }
    let used = mlp.output_layer.read(section.0)?;
    section.take(used)?;
    section.finish()?;
    Ok(mlp)
}

/// Checks magic, version, length, CRC and structure, and returns the blob's contents.
fn open(bytes: &[u8]) -> Result<BlobContents<'_>, BlobError> {
    let length = bytes.len();
    match bytes.get(..MAGIC.len()) {
        Some(magic) if magic != MAGIC => return Err(BlobError::BadMagic),
        None if !MAGIC.starts_with(bytes) => return Err(BlobError::BadMagic),
        None => {
            return Err(BlobError::Truncated {
                length,
                announced: None,
            })
        }
        Some(_) => {}
    }
    // The version first, on its own: another version may lay out the rest differently.
    let (_, version): ([u8; 4], u16) = postcard::take_from_bytes(bytes)
        .map(|(header, _)| header)
        .map_err(|error| header_error(bytes, error))?;
    if version != VERSION {
        return Err(BlobError::UnsupportedVersion { found: version });
    }
    let (header, rest) =
        postcard::take_from_bytes::<Header>(bytes).map_err(|error| header_error(bytes, error))?;
    let Some(announced) = header.announced_length(length - rest.len()) else {
        // Random bytes after a valid start give an unknown depth or tag: believe the
        // header only if the blob is intact.
        check_crc(bytes)?;
        return Err(header.implausible().unwrap_or(BlobError::Malformed));
    };
    if length < announced {
        return Err(BlobError::Truncated {
            length,
            announced: Some(announced),
        });
    }
    let (blob, after) = bytes.split_at_checked(announced).unwrap_or((bytes, &[]));
    match check_crc(blob) {
        Ok(()) if !after.is_empty() => Err(BlobError::TrailingBytes {
            count: after.len(),
            announced,
        }),
        Ok(()) => contents(blob),
        Err(error) if after.is_empty() => Err(error),
        // No CRC where the header puts it: the header or the body was changed, or the
        // blob is intact but longer than its header says (written wrong).
        Err(_) => check_crc(bytes).and(Err(BlobError::Malformed)),
    }
}

/// The contents of `blob`, whose length and CRC have been checked: exactly one
/// [`BlobContents`] and its CRC.
fn contents(blob: &[u8]) -> Result<BlobContents<'_>, BlobError> {
    let body = blob
        .get(..blob.len().saturating_sub(4))
        .ok_or(BlobError::Malformed)?;
    match postcard::take_from_bytes::<BlobContents<'_>>(body) {
        Ok((contents, [])) => Ok(contents),
        _ => Err(BlobError::Malformed),
    }
}

/// Why the header of `bytes` did not parse: cut short inside it, else corrupted or
/// (with an intact CRC) malformed.
fn header_error(bytes: &[u8], error: postcard::Error) -> BlobError {
    match error {
        postcard::Error::DeserializeUnexpectedEnd => BlobError::Truncated {
            length: bytes.len(),
            announced: None,
        },
        _ => check_crc(bytes).err().unwrap_or(BlobError::Malformed),
    }
}

/// `Ok` if the last 4 bytes of `blob` are the little-endian CRC-32 of the rest.
fn check_crc(blob: &[u8]) -> Result<(), BlobError> {
    let (body, trailer) = blob
        .split_at_checked(blob.len().saturating_sub(4))
        .unwrap_or((blob, &[]));
    let stored: [u8; 4] = trailer.try_into().map_err(|_| BlobError::Truncated {
        length: blob.len(),
        announced: None,
    })?;
    let expected = u32::from_le_bytes(stored);
    let found = crc32(body);
    if expected == found {
        Ok(())
    } else {
        Err(BlobError::BadCrc { expected, found })
    }
}

/// Reads little-endian numbers off the front of a section.
struct Reader<'a>(&'a [u8]);

impl<'a> Reader<'a> {
    fn take(&mut self, count: usize) -> Result<&'a [u8], BlobError> {
        let (head, tail) = self.0.split_at_checked(count).ok_or(BlobError::Malformed)?;
        self.0 = tail;
        Ok(head)
    }

    fn read_f32(&mut self) -> Result<f32, BlobError> {
        let bytes: [u8; 4] = self.take(4)?.try_into().map_err(|_| BlobError::Malformed)?;
        Ok(f32::from_le_bytes(bytes))
    }

    /// Fills `values`, refusing any value for which `valid` is false with `error`.
    /// `valid` is a function pointer, not a generic closure: one copy of this loop
    /// serves every check (flash on a controller).
    fn read_f32s(
        &mut self,
        values: &mut [f32],
        valid: fn(f32) -> bool,
        error: BlobError,
    ) -> Result<(), BlobError> {
        for value in values {
            *value = self.read_f32()?;
            if !valid(*value) {
                return Err(error);
            }
        }
        Ok(())
    }

    /// `Ok` if the whole section was read.
    fn finish(&self) -> Result<(), BlobError> {
        if self.0.is_empty() {
            Ok(())
        } else {
            Err(BlobError::Malformed)
        }
    }
}

#[cfg(test)]
mod tests {
    extern crate std;

    use super::*;
    use crate::residual::{F32Weights, Int8Weights};
    use proptest::collection::vec;
    use proptest::prelude::*;
    use std::vec::Vec;

    fn le_bytes(values: &[&[f32]]) -> Vec<u8> {
        values
            .iter()
            .flat_map(|part| part.iter().flat_map(|value| value.to_le_bytes()))
            .collect()
    }

    /// The mlp tests' hand-built 2-3-1 tanh network and its blob, written with `postcard::to_slice`.
    fn tiny() -> (Mlp<2, 3, 1, 1>, Vec<u8>) {
        let mlp = crate::residual::mlp::tests::hand_built(Activation::Tanh);

        let scaling = &mlp.normalisation;
        let normalisation = le_bytes(&[
            &scaling.input_mean,
            &scaling.input_scale,
            &scaling.output_mean,
            &scaling.output_scale,
        ]);
        let envelope = le_bytes(&[
            &mlp.envelope.min,
            &mlp.envelope.max,
            &mlp.envelope.tolerance,
        ]);
        let input = &mlp.input_layer;
        let output = &mlp.output_layer;
        // The blob is row-major: W row by row.
        let input_rows: Vec<[f32; 2]> = (0..3).filter_map(|i| input.row(i)).collect();
        let output_rows: Vec<[f32; 3]> = output.row(0).into_iter().collect();
        let layers = le_bytes(&[
            input_rows.as_flattened(),
            &input.bias,
            output_rows.as_flattened(),
            &output.bias,
        ]);
        let contents = BlobContents {
            magic: MAGIC,
            version: VERSION,
            shape: Shape::of::<2, 3, 1, 1>(),
            activation: Activation::Tanh.tag(),
            quantisation: Quantisation::F32.tag(),
            normalisation: &normalisation,
            envelope: &envelope,
            layers: &layers,
        };
        let mut buffer = [0_u8; 256];
        let mut blob = postcard::to_slice(&contents, &mut buffer).unwrap().to_vec();
        let crc = crc32(&blob);
        blob.extend_from_slice(&crc.to_le_bytes());
        (mlp, blob)
    }

    #[test]
    fn decodes_exactly_the_network_that_was_written() {
        let (mlp, blob) = tiny();
        assert_eq!(&blob[..4], b"HCM1");
        assert_eq!(decode::<2, 3, 1, 1, F32Weights>(&blob), Ok(mlp));
    }

    #[test]
    fn messages_name_the_problem() {
        let shape = Shape::of::<3, 16, 1, 2>();
        let message = std::format!(
            "{}",
            BlobError::WrongShape {
                expected: Shape { inputs: 2, ..shape },
                found: shape
            }
        );
        assert_eq!(
            message,
            "the weights blob holds a network of 3 inputs, 2 hidden layer(s) of 16, 1 outputs; \
             this firmware expects 2 inputs, 2 hidden layer(s) of 16, 1 outputs"
        );
    }

    #[test]
    fn random_bytes_after_a_valid_start_are_corruption_not_truncation() {
        let (_, blob) = tiny();
        // Magic, then the version as one varint byte: the rest from a fixed LCG.
        let mut state = 0x2545_f491_u32;
        for length in [blob.len(), 40, 600] {
            let mut bytes = blob[..5].to_vec();
            while bytes.len() < length {
                state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                bytes.push((state >> 24) as u8);
            }
            let error = decode::<2, 3, 1, 1, F32Weights>(&bytes).unwrap_err();
            assert!(
                matches!(error, BlobError::BadCrc { .. }),
                "{length}: {error}"
            );
            assert!(std::format!("{error}").contains("checksum does not match"));
        }
    }

    #[test]
    fn each_damage_has_its_own_message() {
        let (_, blob) = tiny();
        let length = blob.len();
        let short = decode::<2, 3, 1, 1, F32Weights>(&blob[..length - 3]).unwrap_err();
        assert_eq!(
            std::format!("{short}"),
            std::format!(
                "the weights blob is cut short: {} bytes, but its header announces {length}",
                length - 3
            )
        );
        let mut long = blob.clone();
        long.extend_from_slice(&[0, 0]);
        let long = decode::<2, 3, 1, 1, F32Weights>(&long).unwrap_err();
        assert_eq!(
            long,
            BlobError::TrailingBytes {
                count: 2,
                announced: length
            }
        );
        assert!(std::format!("{long}").starts_with("the weights blob has 2 unexpected byte(s)"));
    }

    proptest! {
        #[test]
        fn any_prefix_is_cut_short_and_any_suffix_trailing(cut in 0_usize..200, tail in vec(any::<u8>(), 1..40)) {
            let (_, blob) = tiny();
            let cut = cut % blob.len();
            match decode::<2, 3, 1, 1, F32Weights>(&blob[..cut]) {
                Err(BlobError::Truncated { length, announced }) => {
                    prop_assert_eq!(length, cut);
                    prop_assert!(announced.is_none_or(|a| a == blob.len()));
                }
                other => prop_assert!(false, "{:?}", other),
            }
            let mut longer = blob.clone();
            longer.extend_from_slice(&tail);
            prop_assert_eq!(
                decode::<2, 3, 1, 1, F32Weights>(&longer),
                Err(BlobError::TrailingBytes { count: tail.len(), announced: blob.len() })
            );
        }

        #[test]
        fn arbitrary_bytes_never_panic(bytes in vec(any::<u8>(), 0..600)) {
            prop_assert!(decode::<2, 3, 1, 1, F32Weights>(&bytes).is_err());
            prop_assert!(decode::<3, 16, 1, 2, Int8Weights>(&bytes).is_err());
        }

        #[test]
        fn arbitrary_bytes_after_a_valid_header_never_panic(tail in vec(any::<u8>(), 0..600)) {
            let mut bytes = MAGIC.to_vec();
            bytes.push(1); // version 1, as a postcard varint
            bytes.extend_from_slice(&tail);
            let _ = decode::<2, 3, 1, 1, F32Weights>(&bytes);
            let _ = decode::<3, 16, 1, 2, Int8Weights>(&bytes);
        }

        #[test]
        fn a_changed_byte_is_always_refused(at in 0_usize..200, byte in any::<u8>()) {
            let (_, mut blob) = tiny();
            let at = at % blob.len();
            prop_assume!(blob[at] != byte);
            blob[at] = byte;
            prop_assert!(decode::<2, 3, 1, 1, F32Weights>(&blob).is_err());
        }
    }
}
