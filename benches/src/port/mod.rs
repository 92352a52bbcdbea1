//! Ports of the C originals' receivers: byte-at-a-time state machines, written from the
//! originals' behaviour (no original code was copied; `tests/vectors/README.md` names the
//! functions and commits). They are the "as the robots do it today" baseline.
//!
//! Each keeps the original's behaviour, including its losses: no rescan after a failed
//! candidate, so a stray sync byte or a truncated frame costs the next valid frame too. Where
//! the original has undefined behaviour (writing past its buffer), the port stops the candidate
//! instead; the module of each protocol lists such differences.
//!
//! Each is driven two ways, which differ only in what the compiler may do across bytes:
//!
//! - as a [`ChunkDecoder`] itself: the state machine inlined into the loop over the chunk, so
//!   that its state can stay in registers from one byte to the next (the benchmark's "port"
//!   column, against which the 10x target of `BENCHMARKS.md` is computed);
//! - through [`OneCallPerByte`]: one call per byte into a receiver that keeps its state in
//!   memory, the shape of the originals' interfaces. HFLink's `StateMachine::receiveStates`
//!   takes one byte per call (`const unsigned char rx_data`), called in a loop over the bytes
//!   taken from the serial receive queue; the referee's `referee_unpack_fifo_data` takes each
//!   byte from its FIFO with a call to `fifo_s_get`, its state in a global struct. Slower than
//!   the fused loop on HFLink, and steadier from build to build (`BENCHMARKS.md`).

use crate::ChunkDecoder;

pub mod hflink;
pub mod referee;

/// A byte-at-a-time receiver: the state machine of one original.
pub trait Receiver: Default {
    /// Takes one byte; true when it completes a valid frame, then [`frame`](Self::frame).
    fn push(&mut self, byte: u8) -> bool;
    /// The frame the last `push` that returned true completed.
    fn frame(&self) -> &[u8];
    /// Forgets a partial frame (the end of the stream).
    fn reset(&mut self);
}

/// Feeds the chunk byte by byte with the state machine inlined into the loop.
impl<R: Receiver> ChunkDecoder for R {
    #[inline]
    fn feed<F: FnMut(&[u8])>(&mut self, chunk: &[u8], sink: &mut F) {
        for &byte in chunk {
            if self.push(byte) {
                sink(self.frame());
            }
        }
    }

    fn finish<F: FnMut(&[u8])>(&mut self, _: &mut F) {
        self.reset();
    }
}

/// A receiver called once per byte, not inlined into the caller's loop: its state goes through
/// memory between bytes, as in the originals.
#[derive(Default)]
pub struct OneCallPerByte<R>(pub R);

/// The one call per byte.
#[inline(never)]
fn receive<R: Receiver>(receiver: &mut R, byte: u8) -> bool {
    receiver.push(byte)
}

impl<R: Receiver> ChunkDecoder for OneCallPerByte<R> {
    #[inline]
    fn feed<F: FnMut(&[u8])>(&mut self, chunk: &[u8], sink: &mut F) {
        for &byte in chunk {
            if receive(&mut self.0, byte) {
                sink(self.0.frame());
            }
        }
    }

    fn finish<F: FnMut(&[u8])>(&mut self, _: &mut F) {
        self.0.reset();
    }
}
