//! Every exported blob, damaged every way one bit or one cut can damage it, through
//! the C API (`hcm_residual_decode`, the very function C links): each damaged blob is
//! refused with an error code, nothing crashes, and the output is left marked "not
//! decoded", so a controller cannot evaluate a half-written or stale network.
//!
//! No flip is harmless: the blob's CRC-32 covers every byte before it, a CRC detects
//! every single-bit error, and a flip inside the stored CRC itself no longer matches.

use hcm_ffi::{
    hcm_hybrid_force, hcm_residual_decode, hcm_residual_info, hcm_status_name, HcmContact,
    HcmExtendedLaw, HcmHybridForce, HcmLaw, HcmResidual, HcmResidualInfo, HcmStatus, HCM_LAW_HERTZ,
};
use std::collections::BTreeMap;
use std::ffi::CStr;
use std::path::PathBuf;

/// The exported blobs (examples/blobs), read at test time, and the weight storage
/// each declares (0: f32, 1: int8).
fn blobs() -> Vec<(String, Vec<u8>, u32)> {
    let folder = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../examples/blobs");
    [("bouncing_ball.f32.hcm", 0), ("bouncing_ball.int8.hcm", 1)]
        .into_iter()
        .map(|(name, quantisation)| {
            let path = folder.join(name);
            let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            (name.to_owned(), bytes, quantisation)
        })
        .collect()
}

fn zeroed() -> Box<HcmResidual> {
    Box::new(HcmResidual {
        storage: [0; hcm_ffi::HCM_RESIDUAL_SIZE],
    })
}

fn decode(blob: &[u8], out: &mut HcmResidual) -> HcmStatus {
    // SAFETY: `blob` is `blob.len()` readable bytes, `out` an exclusive `HcmResidual`.
    unsafe { hcm_residual_decode(blob.as_ptr(), blob.len(), out) }
}

/// The status of evaluating the hybrid model with `residual` (a Hertz law, in contact).
fn evaluate(residual: &HcmResidual) -> HcmStatus {
    let physics = HcmExtendedLaw {
        base: HcmLaw {
            kind: HCM_LAW_HERTZ,
            parameters: [1e9, 1.5, 0.0, 0.0, 0.0],
        },
        effect_count: 0,
        effects: [hcm_ffi::HcmEffect {
            kind: 0,
            parameters: [0.0; 5],
        }; 4],
    };
    let contact = HcmContact {
        depth: 1e-5,
        rate: 0.1,
        approach_speed: 1.0,
        max_depth: 1e-5,
    };
    let mut out = HcmHybridForce {
        force: 0.0,
        physics: 0.0,
        residual_used: false,
        outside_envelope: 0,
    };
    // SAFETY: every pointer is to a live, aligned value of its type.
    unsafe { hcm_hybrid_force(&physics, residual, contact, &mut out) }
}

fn name(status: HcmStatus) -> String {
    // SAFETY: `hcm_status_name` returns a static NUL-terminated string.
    unsafe { CStr::from_ptr(hcm_status_name(status as i32)) }
        .to_string_lossy()
        .into_owned()
}

#[test]
fn intact_blobs_decode_into_their_weight_storage() {
    for (file, blob, quantisation) in blobs() {
        let mut residual = zeroed();
        assert_eq!(evaluate(&residual), HcmStatus::NotDecoded, "{file}");
        assert_eq!(decode(&blob, &mut residual), HcmStatus::Ok, "{file}");
        let mut info = HcmResidualInfo {
            quantisation: 9,
            inputs: 0,
            width: 0,
            hidden_layers: 0,
            outputs: 0,
            envelope_min: [0.0; 3],
            envelope_max: [0.0; 3],
        };
        // SAFETY: both pointers are to live, aligned values.
        assert_eq!(
            unsafe { hcm_residual_info(&*residual, &mut info) },
            HcmStatus::Ok
        );
        assert_eq!(info.quantisation, quantisation, "{file}");
        let shape = (info.inputs, info.width, info.hidden_layers, info.outputs);
        assert_eq!(shape, (3, 16, 2, 1), "{file}");
        assert!(info
            .envelope_min
            .iter()
            .zip(&info.envelope_max)
            .all(|(lo, hi)| lo <= hi));
        assert_eq!(evaluate(&residual), HcmStatus::Ok, "{file}");
    }
}

#[test]
fn every_single_bit_flip_is_refused_with_an_error_code() {
    for (file, blob, _) in blobs() {
        let mut counts: BTreeMap<String, usize> = BTreeMap::new();
        let mut residual = zeroed();
        let mut damaged = blob.clone();
        for at in 0..blob.len() {
            for bit in 0..8 {
                // Start from a decoded network: a failed decode must not leave it usable.
                assert_eq!(decode(&blob, &mut residual), HcmStatus::Ok);
                damaged[at] ^= 1 << bit;
                let status = decode(&damaged, &mut residual);
                damaged[at] ^= 1 << bit;
                assert_ne!(
                    status,
                    HcmStatus::Ok,
                    "{file}: byte {at} bit {bit} accepted"
                );
                assert!(
                    status as i32 >= 16,
                    "{file}: byte {at} bit {bit}: {status:?}"
                );
                assert_eq!(
                    evaluate(&residual),
                    HcmStatus::NotDecoded,
                    "{file}: {at}/{bit}"
                );
                *counts.entry(name(status)).or_default() += 1;
            }
        }
        let total: usize = counts.values().sum();
        assert_eq!(total, 8 * blob.len());
        println!(
            "{file}: {} bytes, {total} single-bit flips: {counts:?}",
            blob.len()
        );
    }
}

#[test]
fn every_truncation_is_refused_as_cut_short() {
    for (file, blob, _) in blobs() {
        let mut residual = zeroed();
        for length in 0..blob.len() {
            assert_eq!(decode(&blob, &mut residual), HcmStatus::Ok);
            // A fresh allocation of exactly `length` bytes: reading past it would be
            // caught by a sanitizer or Miri, not hidden inside the intact blob.
            let cut = blob[..length].to_vec();
            let status = decode(&cut, &mut residual);
            assert_eq!(status, HcmStatus::BlobTruncated, "{file}: length {length}");
            assert_eq!(
                evaluate(&residual),
                HcmStatus::NotDecoded,
                "{file}: {length}"
            );
        }
        println!(
            "{file}: all {} truncations (0..{}) refused as HCM_STATUS_BLOB_TRUNCATED",
            blob.len(),
            blob.len()
        );
        let mut longer = blob.clone();
        longer.push(0);
        assert_eq!(decode(&longer, &mut residual), HcmStatus::BlobTrailingBytes);
    }
}

/// The peg-in-hole's blobs (13-32-32-6 wrench networks): the C API's model holds the
/// ball's 3-16-16-1 shape, so an intact peg blob is answered "wrong shape", and every
/// single-bit flip and every cut with an error code as well — never a crash, never a
/// usable model.
#[test]
fn the_pegs_blobs_are_refused_with_an_error_code_however_damaged() {
    let folder = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../examples/blobs");
    for file in ["peg_in_hole.f32.hcm", "peg_in_hole.int8.hcm"] {
        let path = folder.join(file);
        let blob = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let mut residual = zeroed();
        assert_eq!(
            decode(&blob, &mut residual),
            HcmStatus::BlobWrongShape,
            "{file}"
        );
        let mut counts: BTreeMap<String, usize> = BTreeMap::new();
        let mut damaged = blob.clone();
        for at in 0..blob.len() {
            for bit in 0..8 {
                damaged[at] ^= 1 << bit;
                let status = decode(&damaged, &mut residual);
                damaged[at] ^= 1 << bit;
                assert!(
                    status as i32 >= 16,
                    "{file}: byte {at} bit {bit}: {status:?}"
                );
                *counts.entry(name(status)).or_default() += 1;
            }
        }
        for length in 0..blob.len() {
            let cut = blob[..length].to_vec();
            assert_eq!(
                decode(&cut, &mut residual),
                HcmStatus::BlobTruncated,
                "{file}: length {length}"
            );
        }
        assert_eq!(evaluate(&residual), HcmStatus::NotDecoded, "{file}");
        println!(
            "{file}: {} bytes, intact HCM_STATUS_BLOB_WRONG_SHAPE, {} flips: {counts:?}, every cut BLOB_TRUNCATED",
            blob.len(),
            8 * blob.len()
        );
    }
}
