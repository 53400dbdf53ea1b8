//! Why a weights blob was refused, in words a controller engineer can act on.

use super::{Shape, VERSION};
use crate::residual::{Activation, Quantisation};
use core::fmt;

/// Why a weights blob was refused.
///
/// Each kind of damage has its own variant: a blob cut short (a failed download, a
/// flash write that stopped), one with bytes after its end (a padded flash page),
/// one whose bytes changed (its CRC-32 disagrees) and one that is intact but was
/// written for another firmware (version, shape, storage) are fixed differently.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum BlobError {
    /// The blob ends before its contents or its CRC do.
    Truncated {
        /// Bytes in the blob.
        length: usize,
        /// The length its header announces; `None` when the blob ends inside the
        /// header itself.
        announced: Option<usize>,
    },
    /// The blob goes on after the CRC that ends the length its header announces.
    TrailingBytes {
        /// Bytes after the end.
        count: usize,
        /// The length the header announces (where the CRC was found).
        announced: usize,
    },
    /// The blob does not start with `HCM1`: it is not a weights blob.
    BadMagic,
    /// The blob was written in a format version this firmware cannot read.
    UnsupportedVersion {
        /// The version in the blob.
        found: u16,
    },
    /// The CRC-32 stored in the blob does not match its contents: it was corrupted.
    BadCrc {
        /// The CRC stored in the blob.
        expected: u32,
        /// The CRC computed over the blob's contents.
        found: u32,
    },
    /// The blob holds a network of another size than the one the firmware declares.
    WrongShape {
        /// The firmware's network.
        expected: Shape,
        /// The blob's network.
        found: Shape,
    },
    /// The blob's network has 0 or more than 3 hidden layers.
    UnsupportedDepth {
        /// Its number of hidden layers.
        found: u32,
    },
    /// The activation tag is not one this firmware knows, or not one its weight
    /// storage runs (an int8 network runs the quantised tanh, tag 2, only).
    BadActivation {
        /// The tag in the blob.
        found: u8,
    },
    /// The weight-storage tag is not one this firmware knows.
    BadQuantisation {
        /// The tag in the blob.
        found: u8,
    },
    /// The blob stores its weights in another format than the firmware declares.
    WrongQuantisation {
        /// The firmware's storage.
        expected: Quantisation,
        /// The blob's storage.
        found: Quantisation,
    },
    /// A weight, bias or row scale is NaN or infinite.
    NonFiniteWeight,
    /// A normalisation mean is not finite, or a scale is not finite and > 0.
    BadNormalisation,
    /// An envelope bound is NaN, a minimum exceeds its maximum, or a tolerance is
    /// negative or not finite.
    BadEnvelope,
    /// The blob's CRC is intact but its structure is not a weights blob's (a section
    /// of the wrong length for its shape, an int8 weight of −128, a header whose
    /// shape gives no representable length): it was written wrong, not damaged.
    Malformed,
}

impl fmt::Display for BlobError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BlobError::Truncated {
                length,
                announced: Some(announced),
            } => write!(
                f,
                "the weights blob is cut short: {length} bytes, but its header announces {announced}"
            ),
            BlobError::Truncated {
                length,
                announced: None,
            } => write!(
                f,
                "the weights blob is cut short: {length} bytes, it ends inside its header"
            ),
            BlobError::TrailingBytes { count, announced } => write!(
                f,
                "the weights blob has {count} unexpected byte(s) after the end of the network \
                 (its header announces {announced} bytes, which end with a valid CRC)"
            ),
            BlobError::BadMagic => f.write_str("this is not a weights blob (no HCM1 header)"),
            BlobError::UnsupportedVersion { found } => write!(
                f,
                "the weights blob has format version {found}; this firmware reads version {VERSION}"
            ),
            BlobError::BadCrc { expected, found } => write!(
                f,
                "the weights blob is corrupted: its checksum does not match its contents \
                 (stored CRC-32 {expected:#010x}, computed {found:#010x})"
            ),
            BlobError::WrongShape { expected, found } => write!(
                f,
                "the weights blob holds a network of {found}; this firmware expects {expected}"
            ),
            BlobError::UnsupportedDepth { found } => write!(
                f,
                "the weights blob's network has {found} hidden layers; 1 to 3 are supported"
            ),
            BlobError::BadActivation { found } => match Activation::from_tag(*found) {
                Some(activation) => write!(
                    f,
                    "the weights blob is int8 with the {activation:?} activation (tag {found}); \
                     int8 networks run the quantised tanh (tag 2): export it again with this \
                     version of hcm"
                ),
                None => write!(f, "the weights blob names an unknown activation (tag {found})"),
            },
            BlobError::BadQuantisation { found } => {
                write!(f, "the weights blob names an unknown weight storage (tag {found})")
            }
            BlobError::WrongQuantisation { expected, found } => write!(
                f,
                "the weights blob stores {found} weights; this firmware expects {expected}"
            ),
            BlobError::NonFiniteWeight => {
                f.write_str("the weights blob contains a NaN or infinite weight")
            }
            BlobError::BadNormalisation => f.write_str(
                "the weights blob's normalisation has a non-finite mean or a scale that is not positive",
            ),
            BlobError::BadEnvelope => f.write_str(
                "the weights blob's training envelope has a NaN bound, a minimum above its maximum, or a negative or non-finite tolerance",
            ),
            BlobError::Malformed => f.write_str(
                "the weights blob is malformed: its checksum is intact, but its sections do not \
                 fit the network its header declares (written by another encoder?)",
            ),
        }
    }
}

impl core::error::Error for BlobError {}
