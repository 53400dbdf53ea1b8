//! The device part of the vector table: AN386's 32 external interrupts (UARTs,
//! timers, …), none of which the firmware enables, so every entry is empty.

/// IRQ0–IRQ31 of the MPS2 AN386 image.
#[link_section = ".vector_table.interrupts"]
#[no_mangle]
#[used]
static __INTERRUPTS: [Option<unsafe extern "C" fn()>; 32] = [None; 32];
