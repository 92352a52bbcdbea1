//! UART0 of QEMU's `mps2-an386`, an Arm CMSDK APB UART, as an `embedded-io-async` reader and
//! writer: a read waits for the RX interrupt, a write for room in the transmit register. The
//! UART holds one byte each way; its interrupt handler ([`on_interrupt`]) clears the
//! interrupt and wakes the half that waits.
//!
//! This module owns every register access of the binary, the one place that needs `unsafe`
//! (volatile reads and writes of the UART's registers, and unmasking its interrupts).

#![allow(unsafe_code)]

use core::convert::Infallible;
use core::future::poll_fn;
use core::task::Poll;

use cortex_m::interrupt::InterruptNumber;
use cortex_m::peripheral::NVIC;
use embassy_hflink::protocol_kit::embedded_io_async::{ErrorType, Read, Write};
use embassy_sync::waitqueue::AtomicWaker;

/// UART0's registers (CMSDK APB UART: DATA, STATE, CTRL, INTSTATUS/INTCLEAR, BAUDDIV).
const BASE: usize = 0x4000_4000;
const DATA: usize = 0x00;
const STATE: usize = 0x04;
const CTRL: usize = 0x08;
const INTCLEAR: usize = 0x0C;
const BAUDDIV: usize = 0x10;

const STATE_TX_FULL: u32 = 1 << 0;
const STATE_RX_FULL: u32 = 1 << 1;
const CTRL_TX_EN: u32 = 1 << 0;
const CTRL_RX_EN: u32 = 1 << 1;
const CTRL_TX_INT_EN: u32 = 1 << 2;
const CTRL_RX_INT_EN: u32 = 1 << 3;
const INT_TX: u32 = 1 << 0;
const INT_RX: u32 = 1 << 1;

static RX_WAKER: AtomicWaker = AtomicWaker::new();
static TX_WAKER: AtomicWaker = AtomicWaker::new();

/// UART0's interrupt lines on the AN386 image: RX is IRQ 0, TX is IRQ 1.
#[derive(Clone, Copy)]
enum Irq {
    Rx = 0,
    Tx = 1,
}

// SAFETY: the numbers are UART0's interrupt lines on the mps2-an386, within its 32 IRQs.
unsafe impl InterruptNumber for Irq {
    fn number(self) -> u16 {
        self as u16
    }
}

fn read_reg(offset: usize) -> u32 {
    // SAFETY: BASE + offset is one of UART0's word-aligned registers, readable at any time.
    unsafe { core::ptr::read_volatile((BASE + offset) as *const u32) }
}

fn write_reg(offset: usize, value: u32) {
    // SAFETY: as in `read_reg`; a write changes only UART0's state.
    unsafe { core::ptr::write_volatile((BASE + offset) as *mut u32, value) }
}

/// The receiving half.
pub struct Rx(());

/// The transmitting half.
pub struct Tx(());

/// Sets UART0 to `baud` from the peripheral clock `pclk`, enables it with its interrupts and
/// unmasks them. Call it once.
pub fn take(pclk: u32, baud: u32) -> (Rx, Tx) {
    write_reg(BAUDDIV, pclk / baud);
    write_reg(
        CTRL,
        CTRL_TX_EN | CTRL_RX_EN | CTRL_TX_INT_EN | CTRL_RX_INT_EN,
    );
    // SAFETY: the handlers of these lines (`on_interrupt`) touch only UART0 and the wakers,
    // which are made for sharing with interrupts; no critical section relies on them masked.
    unsafe {
        NVIC::unmask(Irq::Rx);
        NVIC::unmask(Irq::Tx);
    }
    (Rx(()), Tx(()))
}

/// UART0's interrupt: clears what is pending and wakes the halves that wait for it.
pub fn on_interrupt(irqn: i16) {
    let (line, pending) = match irqn {
        n if n == Irq::Rx as i16 => (&RX_WAKER, INT_RX),
        n if n == Irq::Tx as i16 => (&TX_WAKER, INT_TX),
        _ => return,
    };
    write_reg(INTCLEAR, pending);
    line.wake();
}

/// Waits until `ready` holds, woken by `waker`'s interrupt.
async fn until(waker: &AtomicWaker, ready: impl Fn() -> bool) {
    poll_fn(|cx| {
        // Registered before the check: an interrupt between the two still wakes this task.
        waker.register(cx.waker());
        if ready() {
            Poll::Ready(())
        } else {
            Poll::Pending
        }
    })
    .await;
}

fn rx_full() -> bool {
    read_reg(STATE) & STATE_RX_FULL != 0
}

fn tx_free() -> bool {
    read_reg(STATE) & STATE_TX_FULL == 0
}

impl ErrorType for Rx {
    type Error = Infallible;
}

impl Read for Rx {
    /// Waits for a byte, then takes every byte the UART holds, up to `buf`'s length.
    async fn read(&mut self, buf: &mut [u8]) -> Result<usize, Infallible> {
        if buf.is_empty() {
            return Ok(0);
        }
        until(&RX_WAKER, rx_full).await;
        let mut n = 0;
        for slot in buf.iter_mut() {
            if !rx_full() {
                break;
            }
            *slot = (read_reg(DATA) & 0xFF) as u8;
            n += 1;
        }
        Ok(n)
    }
}

impl ErrorType for Tx {
    type Error = Infallible;
}

impl Write for Tx {
    /// Waits for room, then hands over bytes while the UART takes them.
    async fn write(&mut self, buf: &[u8]) -> Result<usize, Infallible> {
        if buf.is_empty() {
            return Ok(0);
        }
        until(&TX_WAKER, tx_free).await;
        let mut n = 0;
        for &byte in buf {
            if !tx_free() {
                break;
            }
            write_reg(DATA, u32::from(byte));
            n += 1;
        }
        Ok(n)
    }

    async fn flush(&mut self) -> Result<(), Infallible> {
        until(&TX_WAKER, tx_free).await;
        Ok(())
    }
}
