// The body of the peg's firmware images, `include!`d by `src/bin/peg_f32.rs` and
// `src/bin/peg_int8.rs`, which differ only in the weight format `Weights` they name:
// boot, decode the embedded blob, print the table of [`peg`], the costs and the sizes
// over semihosting in the ball image's format (`case GROUP.ITEM HEX…`, `cost
// GROUP.ITEM N`, `size flash|ram|stack N`, `end`), and exit QEMU with status 0 (1 if
// the blob failed to decode).

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
use peg::{peg_load, PegFixture, PegWeights, PEG_STATES};

#[entry]
fn main() -> ! {
    harness::run(PegFixture::<Weights>::decode, peg::evaluate_all, costs)
}

/// Instructions per evaluation of the peg's contact manifold, its residual and its
/// whole HCM at the second wall contact's peak, and one decoding of the blob into the
/// HCM.
fn costs(
    counter: &cost::Counter,
    fixture: &PegFixture<Weights>,
    report: &mut dyn FnMut(&str, &str, u32),
) {
    let state = RigidState {
        components: PEG_STATES[3],
    };
    let name = Weights::NAME;
    report(
        "peg",
        "manifold",
        counter.instructions(|| {
            black_box(peg::manifold(black_box(&state)));
        }),
    );
    report(
        "peg_residual",
        name,
        counter.instructions(|| {
            black_box(fixture.hcm.residual.evaluate(black_box(&state.components)));
        }),
    );
    report(
        "peg_hcm",
        name,
        counter.instructions(|| {
            black_box(peg_load(&fixture.hcm, black_box(&state)));
        }),
    );
    report(
        "peg_decode",
        name,
        counter.instructions_once(|| {
            black_box(PegFixture::<Weights>::decode().is_ok());
        }),
    );
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    // hcm-core never panics; should anything else, fail the run.
    harness::exit(debug::EXIT_FAILURE)
}
