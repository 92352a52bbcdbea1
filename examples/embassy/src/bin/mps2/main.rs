//! The HFLink slave of `embassy_hflink` on QEMU's `mps2-an386` (a Cortex-M4), with UART0 as
//! its serial link: `run.sh` feeds golden requests into the UART and checks the answers that
//! come out. The protocol part is the library's, the same code the STM32F4 binary runs; this
//! file and `uart.rs` are the machine's: the UART driver, its interrupt, and semihosting for
//! the one line this binary prints (the protocol part's RAM) and for a panic.

#![no_std]
#![no_main]
#![deny(unsafe_code)]

mod uart;

use core::mem::size_of_val;

use cortex_m_rt::exception;
use cortex_m_semihosting::{debug, hprintln};
use embassy_executor::Spawner;
use embassy_hflink::hflink::{self, SystemInfo};
use embassy_hflink::{Noise, Robot, serve};

/// The mps2-an386's peripheral clock.
const PCLK_HZ: u32 = 25_000_000;
const BAUD: u32 = 115_200;

/// The address of the MCU on an HFLink link.
const SLAVE: u8 = 0x11;

/// What READ_SYSTEM_INFO reports: the values of the golden vector `read_system_info_response`
/// (a capture of the original slave), so that `run.sh` compares this answer with its bytes.
const SYSTEM_INFO: SystemInfo = SystemInfo {
    system_time: 123.5,
    cpu_temperature: 45.25,
    cpu_usage: 0.375,
    battery_voltage: 12.6,
    power_remain: 87.5,
};

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

#[embassy_executor::main]
async fn main(_spawner: Spawner) {
    let (rx, mut tx) = uart::take(PCLK_HZ, BAUD);
    let mut reader = embassy_hflink::reader(rx);
    let mut robot = Robot::new(SLAVE, SYSTEM_INFO);
    let mut noise = Noise::default();
    hprintln!(
        "ram reader {} (decoder buffer {}) robot {} answer-buffer {}",
        size_of_val(&reader),
        hflink::DECODER_BUFFER_LEN,
        size_of_val(&robot),
        hflink::MAX_FRAME_LEN,
    );
    // A UART never ends and this one never fails: `serve` returns only on a bug.
    let outcome = serve(&mut reader, &mut tx, &mut robot, &mut noise).await;
    panic!("serve returned {outcome:?}");
}
