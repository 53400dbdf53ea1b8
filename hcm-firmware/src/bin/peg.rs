//! The peg-in-hole's HCM on a Cortex-M4F: the second firmware image (`cargo run
//! --release --bin peg` in `hcm-firmware`), beside the ball's (`src/main.rs`).
//!
//! It decodes the peg's embedded residual blobs (13-32-32-6, f32 and int8), evaluates
//! the table of [`peg`] and prints over semihosting, one line each, in the ball
//! image's format: `case GROUP.ITEM HEX…`, `cost GROUP.ITEM N` (instructions per
//! evaluation), `size flash|ram|stack N`, `end`; then it exits QEMU with status 0 (1
//! if a blob failed to decode).
#![no_std]
#![no_main]

#[path = "../cost.rs"]
mod cost;
#[path = "../harness.rs"]
mod harness;
#[path = "../memory.rs"]
mod memory;
#[path = "../out.rs"]
mod out;
#[path = "../peg/mod.rs"]
mod peg;
#[path = "../vectors.rs"]
mod vectors;

use core::hint::black_box;
use cortex_m_rt::entry;
use cortex_m_semihosting::debug;
use hcm_core::rigid::RigidState;
use peg::{peg_load, PegFixture, PEG_STATES};

#[entry]
fn main() -> ! {
    harness::run(PegFixture::decode, peg::evaluate_all, costs)
}

/// Instructions per evaluation of the peg's contact manifold, its residual and its
/// whole HCM (f32, int8) at the second wall contact's peak, and one decoding.
fn costs(counter: &cost::Counter, fixture: &PegFixture, report: &mut dyn FnMut(&str, &str, u32)) {
    let state = RigidState {
        components: PEG_STATES[3],
    };
    report(
        "peg",
        "manifold",
        counter.instructions(|| {
            black_box(peg::manifold(black_box(&state)));
        }),
    );
    report(
        "peg_residual",
        "f32",
        counter.instructions(|| {
            black_box(
                fixture
                    .hcm_f32
                    .residual
                    .evaluate(black_box(&state.components)),
            );
        }),
    );
    report(
        "peg_residual",
        "int8",
        counter.instructions(|| {
            black_box(
                fixture
                    .hcm_int8
                    .residual
                    .evaluate(black_box(&state.components)),
            );
        }),
    );
    report(
        "peg_hcm",
        "f32",
        counter.instructions(|| {
            black_box(peg_load(&fixture.hcm_f32, black_box(&state)));
        }),
    );
    report(
        "peg_hcm",
        "int8",
        counter.instructions(|| {
            black_box(peg_load(&fixture.hcm_int8, black_box(&state)));
        }),
    );
    report(
        "peg_decode",
        "f32",
        counter.instructions_once(|| {
            let decoded: Result<peg::PegResidual, _> =
                hcm_core::residual::decode(black_box(peg::PEG_F32_BLOB));
            black_box(decoded.is_ok());
        }),
    );
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    // hcm-core never panics; should anything else, fail the run.
    harness::exit(debug::EXIT_FAILURE)
}
