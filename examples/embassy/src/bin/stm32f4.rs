//! The HFLink slave of `embassy_hflink` on an STM32F405 board, on USART2 (TX on PA2, RX on
//! PA3, 115200 baud): `embassy-stm32`'s buffered UART (interrupt-driven, the bytes in two ring
//! buffers) is the `embedded-io-async` reader and writer the library's `serve` takes. This
//! file is the board-specific part: the chip, the pins, the clocks (`embassy-stm32`'s default:
//! the 16 MHz internal oscillator) and what a failure does.

#![no_std]
#![no_main]
#![deny(unsafe_code)]

use embassy_executor::Spawner;
use embassy_hflink::hflink::SystemInfo;
use embassy_hflink::{Noise, Robot, serve};
use embassy_stm32::usart::{BufferedInterruptHandler, BufferedUart, Config};
use embassy_stm32::{bind_interrupts, peripherals};

// `bind_interrupts!` defines the USART2 interrupt handler (an `unsafe extern "C" fn`).
#[allow(unsafe_code)]
mod irqs {
    use super::{BufferedInterruptHandler, bind_interrupts, peripherals};

    bind_interrupts!(pub struct Irqs {
        USART2 => BufferedInterruptHandler<peripherals::USART2>;
    });
}

/// The address of the MCU on an HFLink link.
const SLAVE: u8 = 0x11;

#[panic_handler]
fn panic(_info: &core::panic::PanicInfo<'_>) -> ! {
    // A board without a debugger has nowhere to print: stop here, where a debugger finds it.
    loop {
        cortex_m::asm::bkpt();
    }
}

#[embassy_executor::main]
async fn main(_spawner: Spawner) {
    let p = embassy_stm32::init(embassy_stm32::Config::default());
    let mut config = Config::default();
    config.baudrate = 115_200;
    let mut tx_ring = [0u8; 128];
    let mut rx_ring = [0u8; 128];
    let Ok(uart) = BufferedUart::new(
        p.USART2,
        p.PA3,
        p.PA2,
        &mut tx_ring,
        &mut rx_ring,
        irqs::Irqs,
        config,
    ) else {
        panic!("USART2 refused its configuration");
    };
    let (mut tx, rx) = uart.split();
    let mut reader = embassy_hflink::reader(rx);
    // The board's own readings go into `robot` (battery, IMU, ...); this example keeps zeros.
    let mut robot = Robot::new(SLAVE, SystemInfo::default());
    let mut noise = Noise::default();
    // A UART error (overrun, framing, parity) drops the bytes of that read: serving goes on.
    loop {
        let _ = serve(&mut reader, &mut tx, &mut robot, &mut noise).await;
    }
}
