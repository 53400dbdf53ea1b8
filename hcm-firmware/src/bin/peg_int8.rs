//! The peg-in-hole's HCM with int8 weights on a Cortex-M4F (`cargo run --release --bin
//! peg-int8` in `hcm-firmware`): the body is `src/peg/image.rs`.
#![no_std]
#![no_main]

/// The weight format this image's blob holds.
type Weights = hcm_core::residual::Int8Weights;

include!("../peg/image.rs");
