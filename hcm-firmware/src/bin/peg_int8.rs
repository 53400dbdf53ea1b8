//! The peg-in-hole's HCM with int8 weights on a Cortex-M4F (`cargo run --release --bin
//! peg-int8` in `hcm-firmware`): the body is `src/peg/image.rs`.
#![no_std]
#![no_main]

/// The weight format this image's blob holds.
type Weights = hcm_core::residual::Int8Weights;

/// The network of the peg's int8 blob, decoded when the image is built (`build.rs`):
/// in flash, read in place.
static NETWORK: peg::PegResidual<Weights> = include!(concat!(env!("OUT_DIR"), "/peg_int8.rs"));

include!("../peg/image.rs");
