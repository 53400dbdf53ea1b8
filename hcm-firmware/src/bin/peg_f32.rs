//! The peg-in-hole's HCM with f32 weights on a Cortex-M4F (`cargo run --release --bin
//! peg-f32` in `hcm-firmware`): the body is `src/peg/image.rs`.
#![no_std]
#![no_main]

/// The weight format this image's blob holds.
type Weights = hcm_core::residual::F32Weights;

/// The network of the peg's f32 blob, decoded when the image is built (`build.rs`):
/// in flash, read in place.
static NETWORK: peg::PegResidual<Weights> = include!(concat!(env!("OUT_DIR"), "/peg_f32.rs"));

include!("../peg/image.rs");
