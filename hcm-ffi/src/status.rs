//! What every entry point returns: one status code, `HCM_STATUS_OK` or the reason
//! the call did nothing.

use core::ffi::c_char;
use hcm_core::residual::BlobError;

/// The outcome of an `hcm_*` call. On anything but `HCM_STATUS_OK` the call wrote
/// nothing through its output pointers (except `hcm_residual_decode` and
/// `hcm_wrench_residual_decode`, which mark their output as not decoded).
///
/// Codes 1–15 are the caller's mistakes at the boundary, 16 and up why a weights
/// blob was refused (one per `hcm_core::residual::BlobError` variant).
#[repr(i32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum HcmStatus {
    /// Success: the outputs are written.
    Ok = 0,
    /// A pointer argument is null.
    NullPointer = 1,
    /// A pointer argument is not aligned for its type (see `HCM_RESIDUAL_ALIGN` for
    /// `HcmResidual`, `HCM_WRENCH_RESIDUAL_ALIGN` for `HcmWrenchResidual`; 4 bytes for
    /// `float` and the other structs).
    Misaligned = 2,
    /// A blob length larger than any object can be (more than `PTRDIFF_MAX` bytes).
    BadLength = 3,
    /// An unknown law, effect or friction kind, more effects than `HCM_MAX_EFFECTS`,
    /// or more contact points than `HCM_MAX_POINTS`.
    BadParameter = 4,
    /// A law, effect or friction parameter outside its physical domain
    /// (`hcm_law_validate`, `hcm_extended_law_validate`, `hcm_pair_physics_validate`),
    /// or one kind of effect listed twice.
    OutOfDomain = 5,
    /// The `HcmResidual` (`HcmWrenchResidual`) was never filled by a successful
    /// `hcm_residual_decode` (`hcm_wrench_residual_decode`).
    NotDecoded = 6,
    /// A bug inside hcm: a Rust panic, caught at the boundary.
    Panic = 7,
    /// The blob ends before its contents or its CRC do.
    BlobTruncated = 16,
    /// The blob goes on after the end its header announces.
    BlobTrailingBytes = 17,
    /// The blob does not start with `HCM1`.
    BlobBadMagic = 18,
    /// The blob's format version is not the one this library reads.
    BlobUnsupportedVersion = 19,
    /// The blob's CRC-32 does not match its contents: it was corrupted.
    BlobBadCrc = 20,
    /// The blob's network is not the shape the call decodes: 3 inputs, 2 hidden
    /// layers of 16, 1 output for `hcm_residual_decode`; 13 inputs, 2 hidden layers of
    /// 32, 6 outputs for `hcm_wrench_residual_decode`.
    BlobWrongShape = 21,
    /// The blob's network has 0 or more than 3 hidden layers.
    BlobUnsupportedDepth = 22,
    /// The blob names an unknown activation.
    BlobBadActivation = 23,
    /// The blob names an unknown weight storage.
    BlobBadQuantisation = 24,
    /// The blob stores its weights in a format this entry point does not take.
    BlobWrongQuantisation = 25,
    /// A weight, bias or row scale in the blob is NaN or infinite.
    BlobNonFiniteWeight = 26,
    /// The blob's normalisation has a non-finite mean or a scale that is not > 0.
    BlobBadNormalisation = 27,
    /// The blob's envelope has a NaN bound or a minimum above its maximum.
    BlobBadEnvelope = 28,
    /// The blob's CRC is intact but its sections do not fit its header.
    BlobMalformed = 29,
    /// The blob was refused for a reason newer than this list.
    BlobInvalid = 30,
}

impl From<BlobError> for HcmStatus {
    fn from(error: BlobError) -> Self {
        match error {
            BlobError::Truncated { .. } => HcmStatus::BlobTruncated,
            BlobError::TrailingBytes { .. } => HcmStatus::BlobTrailingBytes,
            BlobError::BadMagic => HcmStatus::BlobBadMagic,
            BlobError::UnsupportedVersion { .. } => HcmStatus::BlobUnsupportedVersion,
            BlobError::BadCrc { .. } => HcmStatus::BlobBadCrc,
            BlobError::WrongShape { .. } => HcmStatus::BlobWrongShape,
            BlobError::UnsupportedDepth { .. } => HcmStatus::BlobUnsupportedDepth,
            BlobError::BadActivation { .. } => HcmStatus::BlobBadActivation,
            BlobError::BadQuantisation { .. } => HcmStatus::BlobBadQuantisation,
            BlobError::WrongQuantisation { .. } => HcmStatus::BlobWrongQuantisation,
            BlobError::NonFiniteWeight => HcmStatus::BlobNonFiniteWeight,
            BlobError::BadNormalisation => HcmStatus::BlobBadNormalisation,
            BlobError::BadEnvelope => HcmStatus::BlobBadEnvelope,
            BlobError::Malformed => HcmStatus::BlobMalformed,
            // `BlobError` is non-exhaustive: a variant added to the core later still
            // maps to an error, never to OK.
            _ => HcmStatus::BlobInvalid,
        }
    }
}

/// Every status, in code order (a free constant: cbindgen would export an associated
/// one into the header).
const ALL: [HcmStatus; 23] = [
    HcmStatus::Ok,
    HcmStatus::NullPointer,
    HcmStatus::Misaligned,
    HcmStatus::BadLength,
    HcmStatus::BadParameter,
    HcmStatus::OutOfDomain,
    HcmStatus::NotDecoded,
    HcmStatus::Panic,
    HcmStatus::BlobTruncated,
    HcmStatus::BlobTrailingBytes,
    HcmStatus::BlobBadMagic,
    HcmStatus::BlobUnsupportedVersion,
    HcmStatus::BlobBadCrc,
    HcmStatus::BlobWrongShape,
    HcmStatus::BlobUnsupportedDepth,
    HcmStatus::BlobBadActivation,
    HcmStatus::BlobBadQuantisation,
    HcmStatus::BlobWrongQuantisation,
    HcmStatus::BlobNonFiniteWeight,
    HcmStatus::BlobBadNormalisation,
    HcmStatus::BlobBadEnvelope,
    HcmStatus::BlobMalformed,
    HcmStatus::BlobInvalid,
];

impl HcmStatus {
    /// The status's name as the C header spells it, NUL-terminated.
    pub const fn name(self) -> &'static core::ffi::CStr {
        match self {
            HcmStatus::Ok => c"HCM_STATUS_OK",
            HcmStatus::NullPointer => c"HCM_STATUS_NULL_POINTER",
            HcmStatus::Misaligned => c"HCM_STATUS_MISALIGNED",
            HcmStatus::BadLength => c"HCM_STATUS_BAD_LENGTH",
            HcmStatus::BadParameter => c"HCM_STATUS_BAD_PARAMETER",
            HcmStatus::OutOfDomain => c"HCM_STATUS_OUT_OF_DOMAIN",
            HcmStatus::NotDecoded => c"HCM_STATUS_NOT_DECODED",
            HcmStatus::Panic => c"HCM_STATUS_PANIC",
            HcmStatus::BlobTruncated => c"HCM_STATUS_BLOB_TRUNCATED",
            HcmStatus::BlobTrailingBytes => c"HCM_STATUS_BLOB_TRAILING_BYTES",
            HcmStatus::BlobBadMagic => c"HCM_STATUS_BLOB_BAD_MAGIC",
            HcmStatus::BlobUnsupportedVersion => c"HCM_STATUS_BLOB_UNSUPPORTED_VERSION",
            HcmStatus::BlobBadCrc => c"HCM_STATUS_BLOB_BAD_CRC",
            HcmStatus::BlobWrongShape => c"HCM_STATUS_BLOB_WRONG_SHAPE",
            HcmStatus::BlobUnsupportedDepth => c"HCM_STATUS_BLOB_UNSUPPORTED_DEPTH",
            HcmStatus::BlobBadActivation => c"HCM_STATUS_BLOB_BAD_ACTIVATION",
            HcmStatus::BlobBadQuantisation => c"HCM_STATUS_BLOB_BAD_QUANTISATION",
            HcmStatus::BlobWrongQuantisation => c"HCM_STATUS_BLOB_WRONG_QUANTISATION",
            HcmStatus::BlobNonFiniteWeight => c"HCM_STATUS_BLOB_NON_FINITE_WEIGHT",
            HcmStatus::BlobBadNormalisation => c"HCM_STATUS_BLOB_BAD_NORMALISATION",
            HcmStatus::BlobBadEnvelope => c"HCM_STATUS_BLOB_BAD_ENVELOPE",
            HcmStatus::BlobMalformed => c"HCM_STATUS_BLOB_MALFORMED",
            HcmStatus::BlobInvalid => c"HCM_STATUS_BLOB_INVALID",
        }
    }

    /// The status whose code is `code`, if any.
    pub fn from_code(code: i32) -> Option<HcmStatus> {
        ALL.into_iter().find(|status| *status as i32 == code)
    }
}

/// The name of status `code` (`"HCM_STATUS_BLOB_BAD_CRC"`), a static NUL-terminated
/// string the caller must not free; `"HCM_STATUS_UNKNOWN"` for a code no status has.
///
/// Takes the code as a plain integer: a C caller may pass any `int32_t`.
#[no_mangle]
pub extern "C" fn hcm_status_name(code: i32) -> *const c_char {
    HcmStatus::from_code(code)
        .map_or(c"HCM_STATUS_UNKNOWN", HcmStatus::name)
        .as_ptr()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_code_is_distinct_and_named_as_in_the_header() {
        for (i, status) in ALL.into_iter().enumerate() {
            assert_eq!(HcmStatus::from_code(status as i32), Some(status));
            let name = status.name().to_str().unwrap();
            assert!(name.starts_with("HCM_STATUS_"), "{name}");
            // The Rust variant name in SCREAMING_SNAKE_CASE is what cbindgen writes.
            let mut screaming = String::new();
            for (at, c) in format!("{status:?}").char_indices() {
                if c.is_uppercase() && at > 0 {
                    screaming.push('_');
                }
                screaming.push(c.to_ascii_uppercase());
            }
            assert_eq!(name, format!("HCM_STATUS_{screaming}"));
            assert!(ALL[..i].iter().all(|s| s.name() != status.name()));
        }
        assert_eq!(HcmStatus::from_code(8), None);
    }

    #[test]
    fn an_unknown_code_has_a_name_too() {
        // SAFETY: `hcm_status_name` returns a pointer into a static `CStr`.
        let name = |code| unsafe { core::ffi::CStr::from_ptr(hcm_status_name(code)) };
        assert_eq!(name(20).to_str(), Ok("HCM_STATUS_BLOB_BAD_CRC"));
        assert_eq!(name(-1).to_str(), Ok("HCM_STATUS_UNKNOWN"));
        assert_eq!(name(i32::MAX).to_str(), Ok("HCM_STATUS_UNKNOWN"));
    }

    #[test]
    fn no_blob_error_maps_to_success() {
        let errors = [
            BlobError::BadMagic,
            BlobError::Malformed,
            BlobError::NonFiniteWeight,
            BlobError::BadCrc {
                expected: 1,
                found: 2,
            },
        ];
        for error in errors {
            assert!(HcmStatus::from(error) as i32 >= 16, "{error:?}");
        }
    }
}
