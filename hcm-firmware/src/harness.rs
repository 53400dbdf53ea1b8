//! What both images do around their own table: boot, print every case, the
//! calibration and the costs, the sizes, then leave QEMU with the run's status.

use crate::out::{Out, Radix};
use crate::{cost, memory};
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
    let mut out = Out::new();
    let counter = cortex_m::Peripherals::take().map(|p| cost::Counter::start(p.SYST));
    let Ok(fixture) = decode() else {
        out.line(&["error blob"], &[], Radix::Decimal);
        exit(EXIT_FAILURE)
    };
    evaluate(&fixture, &mut |group, item, bits| {
        out.case(group, item, bits)
    });
    if let Some(counter) = &counter {
        let calibration = [counter.calibration_ticks, counter.calibration_instructions];
        out.line(&["calibration"], &calibration, Radix::Decimal);
        costs(counter, &fixture, &mut |group, item, n| {
            out.cost(group, item, n)
        });
    }
    // usize is 32 bits on this target: the casts are lossless.
    let sizes = [
        ("size flash", memory::flash_bytes()),
        ("size ram", memory::static_ram_bytes()),
        ("size stack", memory::peak_stack_bytes()),
    ];
    for (name, bytes) in sizes {
        out.line(&[name], &[bytes as u32], Radix::Decimal);
    }
    out.line(&["end"], &[], Radix::Decimal);
    exit(EXIT_SUCCESS)
}

/// Leaves QEMU with `status` (semihosting), or halts on hardware without a debugger.
pub fn exit(status: debug::ExitStatus) -> ! {
    debug::exit(status);
    loop {
        cortex_m::asm::bkpt();
    }
}
