//! Flash and RAM from the linker's symbols, and the stack's high-water mark from a
//! pattern painted at boot.

/// What an untouched stack word holds.
const PAINT: u32 = 0xC0FF_EE55;
/// How far below the stack top the stack is painted (B): far more than the firmware
/// needs; a high-water mark at this depth means it may have been exceeded.
pub const PAINTED: usize = 64 * 1024;
/// Left unpainted below the painter's own stack pointer (B).
const MARGIN: usize = 64;

extern "C" {
    // cortex-m-rt's link.x: the .data image and its RAM copy, the end of the statics,
    // the top of the stack.
    static __sidata: u32;
    static __sdata: u32;
    static __edata: u32;
    static __euninit: u32;
    static _stack_start: u32;
}

fn address(symbol: &u32) -> usize {
    symbol as *const u32 as usize
}

/// Flash used (B): code, read-only data and the initial image of `.data`, which
/// cortex-m-rt places from address 0 on.
pub fn flash_bytes() -> usize {
    // SAFETY: only the symbols' addresses are taken, never their contents.
    unsafe { address(&__sidata) + (address(&__edata) - address(&__sdata)) }
}

/// Static RAM (B): `.data`, `.bss` and `.uninit`.
pub fn static_ram_bytes() -> usize {
    // SAFETY: as above.
    unsafe { address(&__euninit) - address(&__sdata) }
}

/// The lowest address painted and the stack top.
fn painted_range() -> (usize, usize) {
    // SAFETY: as above.
    let (statics_end, top) = unsafe { (address(&__euninit), address(&_stack_start)) };
    (top.saturating_sub(PAINTED).max(statics_end), top)
}

/// Fills the unused stack below the current stack pointer with [`PAINT`].
#[inline(never)]
pub fn paint_stack() {
    let (bottom, _) = painted_range();
    let below_sp = cortex_m::register::msp::read() as usize - MARGIN;
    let mut at = bottom;
    while at < below_sp {
        // SAFETY: [bottom, below_sp) is RAM between the statics and the live stack,
        // which nothing else uses; word-aligned (both ends are multiples of 4).
        unsafe { core::ptr::write_volatile(at as *mut u32, PAINT) };
        at += 4;
    }
}

/// Deepest stack use since [`paint_stack`] (B): from the stack top down to the
/// lowest word no longer holding the paint.
pub fn peak_stack_bytes() -> usize {
    let (bottom, top) = painted_range();
    let mut at = bottom;
    // SAFETY: reads of the painted RAM, word-aligned.
    while at < top && unsafe { core::ptr::read_volatile(at as *const u32) } == PAINT {
        at += 4;
    }
    top - at
}
