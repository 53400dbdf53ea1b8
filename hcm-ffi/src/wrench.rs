//! The wrench residual from C: the body-state network of a rigid body's contact (the
//! peg-in-hole's 13-32-32-6, `examples/blobs/peg_in_hole.*.hcm`), decoded into a
//! caller-provided, fixed-size `HcmWrenchResidual` as `HcmResidual` holds the 1D
//! contact's network (same marker scheme, its own marker).
//!
//! Its 13 inputs are the body's state as the network was trained on it — for the
//! peg: position (m), orientation quaternion w, x, y, z (–), velocity (m/s),
//! body-frame angular velocity (rad/s) — and its six outputs the force (N) and torque
//! (N·m) correction on body 1 about its reference point, world frame
//! (`hcm_core::model::Correction::Wrench`), which `hcm_pair_load` adds to the physics.

use crate::boundary::{checked_mut, guard};
use crate::residual::{decode_either, decode_into, stored, Storage};
use crate::HcmStatus;
use core::mem::{align_of, size_of};
use hcm_core::residual::{BlobError, F32Weights, Int8Weights, Mlp, Quantisation};

/// Inputs of the wrench residual: the body's state (for the peg: position (m),
/// quaternion w, x, y, z (–), velocity (m/s), body-frame angular velocity (rad/s)).
pub const HCM_WRENCH_RESIDUAL_INPUTS: usize = 13;
/// Neurons per hidden layer of the wrench residual.
pub const HCM_WRENCH_RESIDUAL_WIDTH: usize = 32;
/// Hidden layers of the wrench residual.
pub const HCM_WRENCH_RESIDUAL_HIDDEN_LAYERS: usize = 2;
/// Outputs of the wrench residual: force x, y, z (N), then torque x, y, z (N·m).
pub const HCM_WRENCH_RESIDUAL_OUTPUTS: usize = 6;
/// Bytes of an `HcmWrenchResidual`: room for the network in either weight format
/// (7,136 bytes today), with margin for a change of the core's layout (a
/// compile-time check guards it).
pub const HCM_WRENCH_RESIDUAL_SIZE: usize = 12288;
/// Alignment (bytes) of an `HcmWrenchResidual`; a pointer that is not a multiple of it
/// is answered with `HCM_STATUS_MISALIGNED`.
pub const HCM_WRENCH_RESIDUAL_ALIGN: usize = 16;

/// The wrench residual with f32 weights.
pub type F32WrenchNetwork = Mlp<
    HCM_WRENCH_RESIDUAL_INPUTS,
    HCM_WRENCH_RESIDUAL_WIDTH,
    HCM_WRENCH_RESIDUAL_OUTPUTS,
    HCM_WRENCH_RESIDUAL_HIDDEN_LAYERS,
    F32Weights,
>;
/// The same with int8 hidden → hidden weights.
pub type Int8WrenchNetwork = Mlp<
    HCM_WRENCH_RESIDUAL_INPUTS,
    HCM_WRENCH_RESIDUAL_WIDTH,
    HCM_WRENCH_RESIDUAL_OUTPUTS,
    HCM_WRENCH_RESIDUAL_HIDDEN_LAYERS,
    Int8Weights,
>;

/// Storage for one decoded wrench residual (13-32-32-6, f32 or int8 weights).
///
/// Declare it anywhere (stack, static, inside a struct): the compiler aligns it.
/// Fill it with `hcm_wrench_residual_decode`; it holds no pointers, so a decoded one
/// may be copied with `memcpy` or by assignment. Its bytes mean nothing to C.
#[repr(C, align(16))]
pub struct HcmWrenchResidual {
    /// Opaque.
    pub storage: [u8; HCM_WRENCH_RESIDUAL_SIZE],
}

const _: () = assert!(align_of::<HcmWrenchResidual>() == HCM_WRENCH_RESIDUAL_ALIGN);
const _: () = assert!(size_of::<HcmWrenchResidual>() == HCM_WRENCH_RESIDUAL_SIZE);

/// A wrench residual of either weight format.
// Not boxed: no allocation, and the C storage is sized for the largest variant anyway.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum WrenchNetwork {
    /// f32 weights.
    F32(F32WrenchNetwork),
    /// int8 hidden → hidden weights.
    Int8(Int8WrenchNetwork),
}

impl WrenchNetwork {
    /// The network `blob` holds, in whichever weight format it declares.
    pub fn decode(blob: &[u8]) -> Result<WrenchNetwork, BlobError> {
        decode_either(blob, WrenchNetwork::F32, WrenchNetwork::Int8)
    }
}

impl Storage for HcmWrenchResidual {
    type Network = WrenchNetwork;
    /// The bytes `hcm-rdw1`.
    const MARKER: u64 = u64::from_le_bytes(*b"hcm-rdw1");

    fn decode(blob: &[u8]) -> Result<WrenchNetwork, BlobError> {
        WrenchNetwork::decode(blob)
    }
}

/// Decodes the weights blob `blob` (`len` bytes, e.g. `peg_in_hole.f32.hcm`) into
/// `*out`, whichever of f32 or int8 weights it holds.
///
/// On any error `*out` is marked not decoded (if `out` itself is usable), so a later
/// evaluation answers `HCM_STATUS_NOT_DECODED` rather than use a stale network.
/// Every damaged blob is refused with its `HCM_STATUS_BLOB_*` code; a blob of another
/// shape than 13-32-32-6 (the ball's 3-16-16-1: `hcm_residual_decode`) with
/// `HCM_STATUS_BLOB_WRONG_SHAPE`.
///
/// # Safety
/// `blob` must be null or point to `len` readable bytes; `out` must be null or point
/// to writable memory for one `HcmWrenchResidual` not accessed elsewhere during the
/// call.
#[no_mangle]
pub unsafe extern "C" fn hcm_wrench_residual_decode(
    blob: *const u8,
    len: usize,
    out: *mut HcmWrenchResidual,
) -> HcmStatus {
    // SAFETY: the caller's contract above is `decode_into`'s.
    guard(|| unsafe { decode_into(blob, len, out) })
}

/// The network inside `*residual`, if it was decoded.
///
/// # Safety
/// `residual` must be null or point to an initialised `HcmWrenchResidual` (any bytes)
/// that is not written during `'a`.
pub(crate) unsafe fn wrench_network<'a>(
    residual: *const HcmWrenchResidual,
) -> Result<&'a WrenchNetwork, HcmStatus> {
    // SAFETY: the caller's contract above is `stored`'s.
    unsafe { stored(residual) }
}

/// What a decoded wrench residual is: its weight storage, shape and training envelope.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HcmWrenchResidualInfo {
    /// 0: f32 weights, 1: int8 hidden → hidden weights (the blob's tag).
    pub quantisation: u32,
    /// Inputs (13).
    pub inputs: u32,
    /// Neurons per hidden layer (32).
    pub width: u32,
    /// Hidden layers (2).
    pub hidden_layers: u32,
    /// Outputs (6).
    pub outputs: u32,
    /// Smallest value of each input in training, in the input's unit (for the peg:
    /// m, –, m/s, rad/s as `HCM_WRENCH_RESIDUAL_INPUTS` lists them).
    pub envelope_min: [f32; HCM_WRENCH_RESIDUAL_INPUTS],
    /// Largest value of each input in training, in the input's unit.
    pub envelope_max: [f32; HCM_WRENCH_RESIDUAL_INPUTS],
}

/// Describes the decoded `*residual` into `*info`: `HCM_STATUS_NOT_DECODED` if it was
/// never decoded.
///
/// # Safety
/// `residual` must be null or point to an initialised `HcmWrenchResidual` (zeroed, or
/// passed to `hcm_wrench_residual_decode`); `info` must be null or point to writable
/// memory for one `HcmWrenchResidualInfo`.
#[no_mangle]
pub unsafe extern "C" fn hcm_wrench_residual_info(
    residual: *const HcmWrenchResidual,
    info: *mut HcmWrenchResidualInfo,
) -> HcmStatus {
    guard(|| {
        // SAFETY: the caller's contract above.
        let network = unsafe { wrench_network(residual) }?;
        let info = checked_mut(info)?;
        let (quantisation, envelope) = match network {
            WrenchNetwork::F32(mlp) => (Quantisation::F32, mlp.envelope),
            WrenchNetwork::Int8(mlp) => (Quantisation::Int8, mlp.envelope),
        };
        let count = |n: usize| n as u32;
        let value = HcmWrenchResidualInfo {
            quantisation: quantisation.tag().into(),
            inputs: count(HCM_WRENCH_RESIDUAL_INPUTS),
            width: count(HCM_WRENCH_RESIDUAL_WIDTH),
            hidden_layers: count(HCM_WRENCH_RESIDUAL_HIDDEN_LAYERS),
            outputs: count(HCM_WRENCH_RESIDUAL_OUTPUTS),
            envelope_min: envelope.min,
            envelope_max: envelope.max,
        };
        // SAFETY: non-null and aligned (checked), writable (contract).
        unsafe { info.write(value) };
        Ok(())
    })
}
