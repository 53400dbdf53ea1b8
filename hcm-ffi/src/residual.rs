//! The residual network from C: a caller-provided, fixed-size `HcmResidual` that
//! `hcm_residual_decode` fills from a weights blob, with no allocation.
//!
//! C cannot name the core's `Mlp<3, 16, 1, 2, Q>`, so `HcmResidual` is opaque storage
//! of a size and alignment fixed here and checked at compile time against the Rust
//! type it holds ([`Decoded`]: a marker, then the network in f32 or int8 weights). The
//! marker tells a decoded `HcmResidual` from one that never was (zeroed, or left
//! behind by a failed decode): only a decoded one is read as a network.

use crate::boundary::{checked, checked_mut, guard};
use crate::HcmStatus;
use core::mem::{align_of, size_of};
use core::ptr::addr_of_mut;
use hcm_core::residual::{decode, BlobError, F32Weights, Int8Weights, Mlp, Quantisation};

/// Inputs of the residual: [δ (m), δ̇ (m/s), δ̇0 (m/s)].
pub const HCM_RESIDUAL_INPUTS: usize = 3;
/// Neurons per hidden layer.
pub const HCM_RESIDUAL_WIDTH: usize = 16;
/// Hidden layers.
pub const HCM_RESIDUAL_HIDDEN_LAYERS: usize = 2;
/// Bytes of an `HcmResidual`: room for the network in either weight format, with
/// margin for a change of the core's layout (a compile-time check guards it).
pub const HCM_RESIDUAL_SIZE: usize = 4096;
/// Alignment (bytes) of an `HcmResidual`; a pointer that is not a multiple of it is
/// answered with `HCM_STATUS_MISALIGNED`.
pub const HCM_RESIDUAL_ALIGN: usize = 16;

/// The 1D contact residual with f32 weights.
pub type F32Network = Mlp<HCM_RESIDUAL_INPUTS, HCM_RESIDUAL_WIDTH, 1, 2, F32Weights>;
/// The same with int8 hidden → hidden weights.
pub type Int8Network = Mlp<HCM_RESIDUAL_INPUTS, HCM_RESIDUAL_WIDTH, 1, 2, Int8Weights>;

/// Storage for one decoded residual network (3-16-16-1, f32 or int8 weights).
///
/// Declare it anywhere (stack, static, inside a struct): the compiler aligns it.
/// Fill it with `hcm_residual_decode`; it holds no pointers, so a decoded one may be
/// copied with `memcpy` or by assignment. Its bytes mean nothing to C.
#[repr(C, align(16))]
pub struct HcmResidual {
    /// Opaque.
    pub storage: [u8; HCM_RESIDUAL_SIZE],
}

/// A network of either weight format.
// Boxing is not an option (no allocation, and the C storage is sized for the largest
// variant anyway).
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Network {
    /// f32 weights.
    F32(F32Network),
    /// int8 hidden → hidden weights.
    Int8(Int8Network),
}

/// What an `HcmResidual`'s storage holds: `marker` first, so that it can be read
/// (as plain bytes) before anything else is.
#[repr(C)]
struct Decoded {
    marker: u64,
    network: Network,
}

/// Written after a successful decode: the bytes `hcm-rdl1` (any other value,
/// zero included, means "not decoded").
const DECODED: u64 = u64::from_le_bytes(*b"hcm-rdl1");

// The Rust type fits the C storage, and the storage's alignment serves it.
const _: () = assert!(size_of::<Decoded>() <= HCM_RESIDUAL_SIZE);
const _: () = assert!(align_of::<Decoded>() <= align_of::<HcmResidual>());
const _: () = assert!(align_of::<HcmResidual>() == HCM_RESIDUAL_ALIGN);
const _: () = assert!(size_of::<HcmResidual>() == HCM_RESIDUAL_SIZE);

impl Network {
    /// The network `blob` holds, in whichever weight format it declares.
    pub fn decode(blob: &[u8]) -> Result<Network, BlobError> {
        match decode::<
            HCM_RESIDUAL_INPUTS,
            HCM_RESIDUAL_WIDTH,
            1,
            HCM_RESIDUAL_HIDDEN_LAYERS,
            F32Weights,
        >(blob)
        {
            Err(BlobError::WrongQuantisation {
                found: Quantisation::Int8,
                ..
            }) => decode(blob).map(Network::Int8),
            other => other.map(Network::F32),
        }
    }
}

/// Decodes the weights blob `blob` (`len` bytes, e.g. `bouncing_ball.f32.hcm`) into
/// `*out`, whichever of f32 or int8 weights it holds.
///
/// On any error `*out` is marked not decoded (if `out` itself is usable), so a later
/// evaluation answers `HCM_STATUS_NOT_DECODED` rather than use a stale network.
/// Every damaged blob is refused with its `HCM_STATUS_BLOB_*` code.
///
/// # Safety
/// `blob` must be null or point to `len` readable bytes; `out` must be null or point
/// to writable memory for one `HcmResidual` not accessed elsewhere during the call.
#[no_mangle]
pub unsafe extern "C" fn hcm_residual_decode(
    blob: *const u8,
    len: usize,
    out: *mut HcmResidual,
) -> HcmStatus {
    guard(|| {
        let decoded = checked_mut(out)?.cast::<Decoded>();
        // SAFETY: `out` is non-null and aligned for `HcmResidual`, hence (compile-time
        // checks above) for `Decoded`, and writable (contract); `addr_of_mut` creates
        // no reference to the possibly uninitialised `network`.
        unsafe { addr_of_mut!((*decoded).marker).write(0) };
        let blob = checked(blob)?;
        if len > isize::MAX as usize {
            return Err(HcmStatus::BadLength);
        }
        // SAFETY: non-null, `u8` needs no alignment, `len` ≤ isize::MAX, and `len`
        // readable bytes by the caller's contract.
        let bytes = unsafe { core::slice::from_raw_parts(blob, len) };
        let network = Network::decode(bytes)?;
        // SAFETY: as for the marker above; the whole `Decoded` fits the storage.
        unsafe {
            decoded.write(Decoded {
                marker: DECODED,
                network,
            })
        };
        Ok(())
    })
}

/// The network inside `*residual`, if it was decoded.
///
/// # Safety
/// `residual` must be null or point to an initialised `HcmResidual` (any bytes: a
/// zeroed one is fine) that is not written during `'a`. Its marker is read first; only
/// storage that `hcm_residual_decode` wrote (or a byte copy of it) carries the marker,
/// and only then is the rest read as a [`Network`].
pub(crate) unsafe fn network<'a>(residual: *const HcmResidual) -> Result<&'a Network, HcmStatus> {
    let decoded = checked(residual)?.cast::<Decoded>();
    // SAFETY: non-null, aligned (checked; `Decoded` needs no more than `HcmResidual`)
    // and initialised (contract); a `u64` is valid for any bytes.
    let marker = unsafe { core::ptr::addr_of!((*decoded).marker).read() };
    if marker != DECODED {
        return Err(HcmStatus::NotDecoded);
    }
    // SAFETY: the marker is written only together with a valid `Network`
    // (`hcm_residual_decode`), so the storage holds one.
    Ok(unsafe { &(*decoded).network })
}

/// What a decoded residual is: its weight storage, shape and training envelope.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HcmResidualInfo {
    /// 0: f32 weights, 1: int8 hidden → hidden weights (the blob's tag).
    pub quantisation: u32,
    /// Inputs (3), neurons per hidden layer (16), hidden layers (2), outputs (1).
    pub inputs: u32,
    /// Neurons per hidden layer.
    pub width: u32,
    /// Hidden layers.
    pub hidden_layers: u32,
    /// Outputs.
    pub outputs: u32,
    /// Smallest value of each input in training: δ (m), δ̇ (m/s), δ̇0 (m/s).
    pub envelope_min: [f32; HCM_RESIDUAL_INPUTS],
    /// Largest value of each input in training.
    pub envelope_max: [f32; HCM_RESIDUAL_INPUTS],
}

/// Describes the decoded `*residual` into `*info`: `HCM_STATUS_NOT_DECODED` if it was
/// never decoded.
///
/// # Safety
/// `residual` must be null or point to an initialised `HcmResidual` (zeroed, or
/// passed to `hcm_residual_decode`); `info` must be null or point to writable memory
/// for one `HcmResidualInfo`.
#[no_mangle]
pub unsafe extern "C" fn hcm_residual_info(
    residual: *const HcmResidual,
    info: *mut HcmResidualInfo,
) -> HcmStatus {
    guard(|| {
        // SAFETY: the caller's contract above.
        let network = unsafe { network(residual) }?;
        let info = checked_mut(info)?;
        let (quantisation, envelope) = match network {
            Network::F32(mlp) => (Quantisation::F32, mlp.envelope),
            Network::Int8(mlp) => (Quantisation::Int8, mlp.envelope),
        };
        let count = |n: usize| n as u32;
        let value = HcmResidualInfo {
            quantisation: quantisation.tag().into(),
            inputs: count(HCM_RESIDUAL_INPUTS),
            width: count(HCM_RESIDUAL_WIDTH),
            hidden_layers: count(HCM_RESIDUAL_HIDDEN_LAYERS),
            outputs: 1,
            envelope_min: envelope.min,
            envelope_max: envelope.max,
        };
        // SAFETY: non-null and aligned (checked), writable (contract).
        unsafe { info.write(value) };
        Ok(())
    })
}
