//! What the two chassis binaries share on QEMU's `mps2-an386`: the panic handler, the UART's
//! interrupt, SysTick as the counter the serving loop times itself with, and the semihosting
//! lines the host harness reads.
//!
//! Counting: QEMU models no DWT cycle counter, but under `-icount shift=0` its virtual clock
//! runs one nanosecond per instruction and SysTick counts it at the board's 25 MHz: one tick
//! per 40 instructions.
//!
//! Lines (space-separated): `size NAME BYTES` at start, then one per frame:
//! `delivered SEQ SESSION TICKS`, `duplicate SEQ TICKS`, `stale SEQ`, `ignored`.

use cortex_m::peripheral::SYST;
use cortex_m::peripheral::syst::SystClkSource;
use cortex_m_rt::exception;
use cortex_m_semihosting::{debug, hprintln};
use embassy_hflink::chassis::Step;

use crate::uart;

/// The mps2-an386's peripheral clock.
pub const PCLK_HZ: u32 = 25_000_000;
/// The UART's rate (QEMU's pseudo-terminal ignores it; a board would not).
pub const BAUD: u32 = 115_200;

#[panic_handler]
fn panic(info: &core::panic::PanicInfo<'_>) -> ! {
    hprintln!("panic {}", info);
    debug::exit(debug::EXIT_FAILURE);
    loop {
        core::hint::spin_loop();
    }
}

// Without a device crate, cortex-m-rt sends every interrupt here, with its number.
#[allow(unsafe_code)]
#[exception]
unsafe fn DefaultHandler(irqn: i16) {
    uart::on_interrupt(irqn);
}

/// Starts SysTick as a free-running 24-bit down-counter of the core clock.
pub fn start_counter() {
    let Some(mut p) = cortex_m::Peripherals::take() else {
        panic!("the core peripherals are taken once");
    };
    p.SYST.set_clock_source(SystClkSource::Core);
    p.SYST.set_reload(0x00FF_FFFF);
    p.SYST.clear_current();
    p.SYST.enable_counter();
}

/// The counter's value (it counts down).
pub fn counter() -> u32 {
    SYST::get_current()
}

/// Prints one line per step.
pub fn report(step: Step) {
    match step {
        Step::Delivered {
            seq,
            session,
            ticks,
        } => hprintln!("delivered {} {} {}", seq, session, ticks),
        Step::Duplicate { seq, ticks } => hprintln!("duplicate {} {}", seq, ticks),
        Step::Stale { seq } => hprintln!("stale {}", seq),
        Step::Ignored => hprintln!("ignored"),
    }
}
