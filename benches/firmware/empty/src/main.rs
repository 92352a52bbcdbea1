//! The baseline: a firmware that does nothing. What it weighs (vector table, reset handler,
//! default exception handlers) is in every footprint binary; `footprint.sh` reports sizes net
//! of it too.

#![no_std]
#![no_main]
#![forbid(unsafe_code)]

use cortex_m_rt::entry;

#[panic_handler]
fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
    loop {
        core::hint::spin_loop();
    }
}

#[entry]
fn main() -> ! {
    let mut ticks = 0u32;
    loop {
        ticks = core::hint::black_box(ticks.wrapping_add(1));
    }
}
