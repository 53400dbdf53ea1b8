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
use cortex_m_semihosting::debug::{self, EXIT_FAILURE, EXIT_SUCCESS};
use hcm_core::rigid::RigidState;
use out::Line;
use peg::{peg_load, PegFixture, PEG_STATES};

#[entry]
fn main() -> ! {
    memory::paint_stack();
    let mut line = Line::new();
    let counter = cortex_m::Peripherals::take().map(|p| cost::Counter::start(p.SYST));
    let Ok(fixture) = PegFixture::decode() else {
        line.word("error blob").end();
        exit(EXIT_FAILURE)
    };
    peg::evaluate_all(&fixture, &mut |group, item, bits| {
        line.word("case ").word(group).word(".").word(item);
        for &word in bits {
            line.hex(word);
        }
        line.end();
    });
    if let Some(counter) = &counter {
        line.word("calibration")
            .decimal(counter.calibration_ticks)
            .decimal(counter.calibration_instructions)
            .end();
        costs(counter, &fixture, &mut |group, item, n| {
            line.word("cost ")
                .word(group)
                .word(".")
                .word(item)
                .decimal(n)
                .end();
        });
    }
    // usize is 32 bits on this target: the casts are lossless.
    line.word("size flash")
        .decimal(memory::flash_bytes() as u32)
        .end();
    line.word("size ram")
        .decimal(memory::static_ram_bytes() as u32)
        .end();
    line.word("size stack")
        .decimal(memory::peak_stack_bytes() as u32)
        .end();
    line.word("end").end();
    exit(EXIT_SUCCESS)
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

fn exit(status: debug::ExitStatus) -> ! {
    debug::exit(status);
    loop {
        cortex_m::asm::bkpt();
    }
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    // hcm-core never panics; should anything else, fail the run.
    exit(EXIT_FAILURE)
}
