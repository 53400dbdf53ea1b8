//! What both images do around their own table: boot, print every case, the
//! calibration and the costs, the sizes, then leave QEMU with the run's status.

use crate::{cost, memory, out::Line};
use cortex_m_semihosting::debug::{self, EXIT_FAILURE, EXIT_SUCCESS};

/// Where a table sends its results: group, item, raw bits.
pub type Cases<'a> = &'a mut dyn FnMut(&str, &str, &[u32]);
/// Where the costs go: group, item, instructions per evaluation.
pub type Costs<'a> = &'a mut dyn FnMut(&str, &str, u32);

/// Paints the stack, starts SysTick, decodes the fixture with `decode` (exiting with
/// status 1 if it fails), prints `case` lines from `evaluate`, `cost` lines from
/// `costs`, the sizes and `end`, and exits QEMU with status 0.
pub fn run<F, E>(
    decode: impl FnOnce() -> Result<F, E>,
    evaluate: impl FnOnce(&F, Cases<'_>),
    costs: impl FnOnce(&cost::Counter, &F, Costs<'_>),
) -> ! {
    memory::paint_stack();
    let mut line = Line::new();
    let counter = cortex_m::Peripherals::take().map(|p| cost::Counter::start(p.SYST));
    let Ok(fixture) = decode() else {
        line.word("error blob").end();
        exit(EXIT_FAILURE)
    };
    evaluate(&fixture, &mut |group, item, bits| {
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

/// Leaves QEMU with `status` (semihosting), or halts on hardware without a debugger.
pub fn exit(status: debug::ExitStatus) -> ! {
    debug::exit(status);
    loop {
        cortex_m::asm::bkpt();
    }
}
