//! The RoboRTS chassis of `embassy_hflink::chassis` on QEMU's `mps2-an386`, answering by
//! hand (every command delivered, its header copied into the acknowledgement): the same
//! firmware as the `mps2-session` binary without the session machinery, the baseline of its
//! cost.

#![no_std]
#![no_main]
#![deny(unsafe_code)]

#[path = "board.rs"]
mod board;
#[path = "../mps2/uart.rs"]
mod uart;

use core::mem::size_of_val;

use cortex_m_semihosting::hprintln;
use embassy_executor::Spawner;
use embassy_hflink::chassis::{self, Chassis};

#[embassy_executor::main]
async fn main(_spawner: Spawner) {
    board::start_counter();
    let (mut rx, mut tx) = uart::take(board::PCLK_HZ, board::BAUD);
    let mut decoder = chassis::decoder();
    let mut robot = Chassis::default();
    hprintln!("size decoder {}", size_of_val(&decoder));
    hprintln!("ready");
    let outcome = chassis::serve_by_hand(
        &mut rx,
        &mut tx,
        &mut decoder,
        &mut robot,
        board::counter,
        board::report,
    )
    .await;
    panic!("serving stopped: {outcome:?}");
}
