//! Instructions per evaluation, counted by SysTick under QEMU's `-icount shift=0`.
//!
//! With `-icount shift=0` QEMU's virtual clock advances 1 ns per executed
//! instruction, and SysTick (clocked by the core clock, 25 MHz on mps2-an386) counts
//! down one tick per 40 ns: one tick per 40 instructions. The ratio is not assumed
//! but calibrated on a loop of known length; each evaluation is repeated [`REPEATS`]
//! times so that the 40-instruction resolution becomes a fraction of one, and the
//! cost of the measuring loop itself (an empty body) is subtracted.

use core::hint::black_box;
use cortex_m::peripheral::{syst::SystClkSource, SYST};

/// Evaluations per measurement.
pub const REPEATS: u32 = 256;
/// Iterations of the calibration loop (two instructions each).
const CALIBRATION_LOOPS: u32 = 100_000;
/// SysTick is a 24-bit down-counter.
const COUNTER_MASK: u32 = 0x00FF_FFFF;

/// A running SysTick and its calibration.
pub struct Counter {
    /// Ticks the calibration loop took.
    pub calibration_ticks: u32,
    /// Instructions the calibration loop executed.
    pub calibration_instructions: u32,
    /// Ticks of the measuring loop with an empty body.
    empty_ticks: u32,
}

impl Counter {
    /// Starts SysTick free-running from the core clock and calibrates it.
    pub fn start(mut syst: SYST) -> Self {
        syst.set_clock_source(SystClkSource::Core);
        syst.set_reload(COUNTER_MASK);
        syst.clear_current();
        syst.enable_counter();
        let start = SYST::get_current();
        spin(CALIBRATION_LOOPS);
        let calibration_ticks = elapsed(start);
        let mut counter = Counter {
            calibration_ticks,
            calibration_instructions: 2 * CALIBRATION_LOOPS,
            empty_ticks: 0,
        };
        counter.empty_ticks = repeated_ticks(|| {
            black_box(());
        });
        counter
    }

    /// Instructions one call of `evaluate` executes, measurement overhead removed.
    pub fn instructions(&self, evaluate: impl FnMut()) -> u32 {
        let ticks = repeated_ticks(evaluate).saturating_sub(self.empty_ticks);
        self.to_instructions(ticks, REPEATS)
    }

    /// Instructions a single call of `run` executes (for long runs: no repetition).
    #[allow(dead_code)] // the ball's image only (the peg images decode nothing)
    pub fn instructions_once(&self, run: impl FnOnce()) -> u32 {
        let start = SYST::get_current();
        run();
        self.to_instructions(elapsed(start), 1)
    }

    /// `ticks` over `calls` calls in instructions per call, to the nearest. In f32
    /// (exact below 2^24; the FPU makes it cheaper in flash than u64 division). Never
    /// inlined: one copy serves every measurement (measured: −124 B of flash in the
    /// ball image, −24 B in a peg image).
    #[inline(never)]
    fn to_instructions(&self, ticks: u32, calls: u32) -> u32 {
        let per_tick = self.calibration_instructions as f32 / self.calibration_ticks.max(1) as f32;
        (ticks as f32 * per_tick / calls as f32 + 0.5) as u32
    }
}

/// Ticks for [`REPEATS`] calls of `evaluate`.
#[inline(never)]
fn repeated_ticks(mut evaluate: impl FnMut()) -> u32 {
    let start = SYST::get_current();
    for _ in 0..REPEATS {
        evaluate();
    }
    elapsed(start)
}

fn elapsed(start: u32) -> u32 {
    start.wrapping_sub(SYST::get_current()) & COUNTER_MASK
}

/// Exactly `2·loops` instructions (`subs`, `bne`), plus a constant few.
#[inline(never)]
fn spin(loops: u32) {
    // SAFETY: touches only the register it is given and the flags.
    unsafe {
        core::arch::asm!(
            "1:",
            "subs {n}, #1",
            "bne 1b",
            n = inout(reg) loops => _,
            options(nomem, nostack),
        );
    }
}

/// Marks where a profiled stretch starts (`--features profile`: `tools/qprof.py` counts
/// the instructions executed between the two markers' calls in a QEMU trace).
#[cfg(feature = "profile")]
#[inline(never)]
#[no_mangle]
pub fn marker_start() {
    core::hint::black_box(1);
}

/// Marks where a profiled stretch ends (see [`marker_start`]).
#[cfg(feature = "profile")]
#[inline(never)]
#[no_mangle]
pub fn marker_end() {
    core::hint::black_box(2);
}
