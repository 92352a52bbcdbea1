//! Packets over `embedded-io-async` byte streams (the `embedded-io-async` feature): a UART
//! driver of embassy or another async HAL in, typed packets out ([`PacketReader`]), and
//! packets written as frames ([`write_packet`]).
//!
//! Both are `no_std` and heap-free: the reader owns a read buffer of `B` bytes beside the
//! engine's buffer of `N`; the writer encodes into a caller's buffer. This module owns the
//! loop between reads and the engine; finding and decoding frames is [`PacketDecoder`]'s.

use core::fmt;

use embedded_io_async::{Read, Write};

use crate::error::EncodeError;
use crate::packet::{EncodePacket, PacketDecoder, PacketEvent, PacketLayout};

/// Reads packets from an async reader: each call to [`next_packet`](Self::next_packet) returns
/// the next event, reading when the bytes read so far hold none.
pub struct PacketReader<R, L: PacketLayout, const N: usize, const B: usize> {
    reader: R,
    decoder: PacketDecoder<L, N>,
    buf: [u8; B],
    start: usize,
    end: usize,
    ended: bool,
}

impl<R: Read, L: PacketLayout, const N: usize, const B: usize> PacketReader<R, L, N, B> {
    /// A reader of `layout`'s packets from `reader`, with a read buffer of `B` bytes and an
    /// engine buffer of `N`.
    pub const fn new(reader: R, layout: L) -> Self {
        PacketReader {
            reader,
            decoder: PacketDecoder::new(layout),
            buf: [0; B],
            start: 0,
            end: 0,
            ended: false,
        }
    }

    /// The next event: a packet, a rejected candidate or undecodable frame, or skipped bytes.
    /// `Ok(None)` once the reader has ended (a read returned 0 bytes) and the pending bytes are
    /// flushed.
    ///
    /// # Errors
    /// The reader's error; the bytes read before it stay pending, and the next call reads
    /// again.
    pub async fn next_packet(
        &mut self,
    ) -> Result<Option<PacketEvent<L::Packet, L::Error>>, R::Error> {
        loop {
            let mut input = self.buf.get(self.start..self.end).unwrap_or_default();
            let before = input.len();
            let event = self.decoder.next_packet(&mut input);
            self.start = self
                .start
                .saturating_add(before.saturating_sub(input.len()));
            if let Some(event) = event {
                return Ok(Some(event));
            }
            if self.ended {
                return Ok(self.decoder.flush_packet());
            }
            let n = self.reader.read(&mut self.buf).await?;
            self.start = 0;
            self.end = n.min(B);
            self.ended = n == 0;
        }
    }

    /// The packet decoder (its stats, its engine).
    pub fn decoder(&mut self) -> &mut PacketDecoder<L, N> {
        &mut self.decoder
    }

    /// The reader back; bytes read and not yet scanned are dropped.
    pub fn into_inner(self) -> R {
        self.reader
    }
}

impl<R, L: PacketLayout, const N: usize, const B: usize> fmt::Debug for PacketReader<R, L, N, B> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("PacketReader")
            .field("decoder", &self.decoder)
            .field("unscanned", &self.end.saturating_sub(self.start))
            .finish_non_exhaustive()
    }
}

/// Why a packet was not written.
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WriteError<E> {
    /// The packet does not encode into the buffer (too small, or a value out of range).
    Encode(EncodeError),
    /// The writer failed.
    Io(E),
}

impl<E: fmt::Debug> fmt::Display for WriteError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            WriteError::Encode(e) => write!(f, "packet not encoded: {e}"),
            WriteError::Io(e) => write!(f, "write failed: {e:?}"),
        }
    }
}

impl<E: fmt::Debug> core::error::Error for WriteError<E> {}

/// Encodes `packet` into `buf` and writes the frame to `writer` whole; returns its length.
///
/// # Errors
/// [`WriteError::Encode`] when the packet does not encode into `buf` (nothing is written),
/// [`WriteError::Io`] with the writer's error.
pub async fn write_packet<W: Write, P: EncodePacket>(
    writer: &mut W,
    packet: &P,
    buf: &mut [u8],
) -> Result<usize, WriteError<W::Error>> {
    let n = packet.encode_into(buf).map_err(WriteError::Encode)?;
    let frame = buf.get(..n).unwrap_or_default();
    writer.write_all(frame).await.map_err(WriteError::Io)?;
    Ok(n)
}
