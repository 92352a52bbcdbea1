//! The RoboRTS chassis of `embassy_hflink::chassis` on QEMU's `mps2-an386`, answering through
//! the runtime's session `Responder`: duplicates are acknowledged again, never delivered
//! twice. The host harness (`cargo run -p protocol-tests --example qemu_session`) holds a
//! session with it over a pseudo-terminal through a fault-injecting relay.

#![no_std]
#![no_main]
#![deny(unsafe_code)]

#[path = "board.rs"]
mod board;
#[path = "../mps2/uart.rs"]
mod uart;

use core::mem::{size_of, size_of_val};

use cortex_m_semihosting::hprintln;
use embassy_executor::Spawner;
use embassy_hflink::chassis::{self, Chassis, SLOTS};
use embassy_hflink::roborts;

#[embassy_executor::main]
async fn main(_spawner: Spawner) {
    board::start_counter();
    let (mut rx, mut tx) = uart::take(board::PCLK_HZ, board::BAUD);
    let mut decoder = chassis::decoder();
    let mut responder = chassis::responder();
    let mut robot = Chassis::default();
    hprintln!("size decoder {}", size_of_val(&decoder));
    hprintln!("size responder {}", size_of_val(&responder));
    // The host's machine as this target sizes it: as many slots, its longest request.
    hprintln!("size requester {}", size_of::<roborts::Requester<SLOTS>>());
    hprintln!("ready");
    let outcome = chassis::serve_session(
        &mut rx,
        &mut tx,
        &mut decoder,
        &mut responder,
        &mut robot,
        board::counter,
        board::report,
    )
    .await;
    panic!("serving stopped: {outcome:?}");
}
