//! The residual network from C: a caller-provided, fixed-size `HcmResidual` that
//! `hcm_residual_decode` fills from a weights blob, with no allocation.
//!
//! C cannot name the core's `Mlp<3, 16, 1, 2, Q>`, so `HcmResidual` is opaque storage
//! of a size and alignment fixed here and checked at compile time against the Rust
//! type it holds ([`Decoded`]: a marker, then the network in f32 or int8 weights). The
//! marker tells a decoded `HcmResidual` from one that never was (zeroed, or left
//! behind by a failed decode): only a decoded one is read as a network. The peg's
//! wrench residual (`crate::wrench`) is stored the same way ([`Storage`]).

use crate::boundary::{checked, checked_mut, guard};
use crate::HcmStatus;
use core::mem::{align_of, size_of};
use core::ptr::addr_of_mut;
use hcm_core::residual::{
    decode, BlobError, F32Weights, Hidden, HiddenDepth, Int8Weights, Mlp, Quantisation,
};

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

/// Caller-provided opaque storage for one network type: what it holds once decoded,
/// how to decode it, and the marker that says it was.
pub(crate) trait Storage {
    /// The network the storage holds after a successful decode.
    type Network;
    /// Written after a successful decode (any other value, zero included, means "not
    /// decoded"); one per storage type, so that the bytes of one kind of storage
    /// copied into another are not taken for a network.
    const MARKER: u64;
    /// The network `blob` holds, in whichever weight format it declares.
    fn decode(blob: &[u8]) -> Result<Self::Network, BlobError>;
}

/// What a [`Storage`] holds: `marker` first, so that it can be read (as plain bytes)
/// before anything else is.
#[repr(C)]
struct Decoded<N> {
    marker: u64,
    network: N,
}

/// Decodes `len` bytes at `blob` into the storage `out`, which is marked not decoded
/// first (if `out` itself is usable), so that a refused blob leaves no stale network.
///
/// # Safety
/// `blob` must be null or point to `len` readable bytes; `out` must be null or point
/// to writable memory for one `S` not accessed elsewhere during the call.
pub(crate) unsafe fn decode_into<S: Storage>(
    blob: *const u8,
    len: usize,
    out: *mut S,
) -> Result<(), HcmStatus> {
    // The Rust type fits the C storage, and the storage's alignment serves it.
    const {
        assert!(size_of::<Decoded<S::Network>>() <= size_of::<S>());
        assert!(align_of::<Decoded<S::Network>>() <= align_of::<S>());
    }
    let decoded = checked_mut(out)?.cast::<Decoded<S::Network>>();
    // SAFETY: `out` is non-null and aligned for `S`, hence (compile-time checks above)
    // for `Decoded`, and writable (contract); `addr_of_mut` creates no reference to the
    // possibly uninitialised `network`.
    unsafe { addr_of_mut!((*decoded).marker).write(0) };
    let blob = checked(blob)?;
    if len > isize::MAX as usize {
        return Err(HcmStatus::BadLength);
    }
    // SAFETY: non-null, `u8` needs no alignment, `len` ≤ isize::MAX, and `len`
    // readable bytes by the caller's contract.
    let bytes = unsafe { core::slice::from_raw_parts(blob, len) };
    let network = S::decode(bytes)?;
    // SAFETY: as for the marker above; the whole `Decoded` fits the storage.
    unsafe {
        decoded.write(Decoded {
            marker: S::MARKER,
            network,
        })
    };
    Ok(())
}

/// The network inside the storage `*storage`, if it was decoded.
///
/// # Safety
/// `storage` must be null or point to an initialised `S` (any bytes: a zeroed one is
/// fine) that is not written during `'a`. Its marker is read first; only storage that
/// [`decode_into`] wrote (or a byte copy of it) carries `S`'s marker, and only then is
/// the rest read as an `S::Network`.
pub(crate) unsafe fn stored<'a, S: Storage>(
    storage: *const S,
) -> Result<&'a S::Network, HcmStatus> {
    const {
        assert!(size_of::<Decoded<S::Network>>() <= size_of::<S>());
        assert!(align_of::<Decoded<S::Network>>() <= align_of::<S>());
    }
    let decoded = checked(storage)?.cast::<Decoded<S::Network>>();
    // SAFETY: non-null, aligned (checked; `Decoded` needs no more than `S`) and
    // initialised (contract); a `u64` is valid for any bytes.
    let marker = unsafe { core::ptr::addr_of!((*decoded).marker).read() };
    if marker != S::MARKER {
        return Err(HcmStatus::NotDecoded);
    }
    // SAFETY: the marker is written only together with a valid `S::Network`
    // (`decode_into`), so the storage holds one.
    Ok(unsafe { &(*decoded).network })
}

/// The network of shape `INPUTS`-`WIDTH`×`HIDDEN`-`OUTPUTS` that `blob` holds, as
/// `f32` (f32 weights) or `int8` (int8 weights) makes it.
pub(crate) fn decode_either<
    const INPUTS: usize,
    const WIDTH: usize,
    const OUTPUTS: usize,
    const HIDDEN: usize,
    N,
>(
    blob: &[u8],
    f32: fn(Mlp<INPUTS, WIDTH, OUTPUTS, HIDDEN, F32Weights>) -> N,
    int8: fn(Mlp<INPUTS, WIDTH, OUTPUTS, HIDDEN, Int8Weights>) -> N,
) -> Result<N, BlobError>
where
    Hidden<HIDDEN>: HiddenDepth<WIDTH, F32Weights> + HiddenDepth<WIDTH, Int8Weights>,
{
    match decode(blob) {
        Err(BlobError::WrongQuantisation {
            found: Quantisation::Int8,
            ..
        }) => decode(blob).map(int8),
        other => other.map(f32),
    }
}

impl Storage for HcmResidual {
    type Network = Network;
    /// The bytes `hcm-rdl1`.
    const MARKER: u64 = u64::from_le_bytes(*b"hcm-rdl1");

    fn decode(blob: &[u8]) -> Result<Network, BlobError> {
        Network::decode(blob)
    }
}

const _: () = assert!(align_of::<HcmResidual>() == HCM_RESIDUAL_ALIGN);
const _: () = assert!(size_of::<HcmResidual>() == HCM_RESIDUAL_SIZE);

impl Network {
    /// The network `blob` holds, in whichever weight format it declares.
    pub fn decode(blob: &[u8]) -> Result<Network, BlobError> {
        decode_either(blob, Network::F32, Network::Int8)
    }
}

/// Decodes the weights blob `blob` (`len` bytes, e.g. `bouncing_ball.f32.hcm`) into
/// `*out`, whichever of f32 or int8 weights it holds.
///
/// On any error `*out` is marked not decoded (if `out` itself is usable), so a later
/// evaluation answers `HCM_STATUS_NOT_DECODED` rather than use a stale network.
/// Every damaged blob is refused with its `HCM_STATUS_BLOB_*` code; a blob of another
/// shape than 3-16-16-1 (the peg's 13-32-32-6: `hcm_wrench_residual_decode`) with
/// `HCM_STATUS_BLOB_WRONG_SHAPE`.
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
    // SAFETY: the caller's contract above is `decode_into`'s.
    guard(|| unsafe { decode_into(blob, len, out) })
}

/// The network inside `*residual`, if it was decoded.
///
/// # Safety
/// As [`stored`]: `residual` null or an initialised `HcmResidual` not written during
/// `'a`.
pub(crate) unsafe fn network<'a>(residual: *const HcmResidual) -> Result<&'a Network, HcmStatus> {
    // SAFETY: the caller's contract above.
    unsafe { stored(residual) }
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
