//! A `tokio_util::codec` codec for a spec's packets (the `tokio` feature): [`PacketCodec`]
//! decodes a byte stream into [`PacketEvent`]s and encodes packets into frames, so that
//! `FramedRead`, `FramedWrite` and `Framed` carry typed packets over a serial port, a socket or
//! a pipe.
//!
//! Bad bytes are items, not errors: a rejected candidate or an undecodable frame is a
//! [`PacketEvent::Invalid`] and the stream goes on; only the transport's I/O errors end it.
//! This module owns the mapping between the codec traits and the [`PacketDecoder`]; finding
//! and decoding frames is the decoder's business.

use std::io;

use tokio_util::bytes::{Buf, BytesMut};
use tokio_util::codec::{Decoder, Encoder};

use crate::packet::{EncodePacket, PacketDecoder, PacketEvent, PacketLayout};

/// Decodes a spec's packets from bytes and encodes packets into frames, for
/// `tokio_util::codec` (`FramedRead::new(port, PacketCodec::<_, 512>::new(hflink::Layout))`).
///
/// The decoder's engine has a buffer of `N` bytes (a generated format's `DECODER_BUFFER_LEN`
/// fits its frames): bytes of the read buffer are moved into it as they are scanned, so the
/// read buffer never holds more than one read.
pub struct PacketCodec<L: PacketLayout, const N: usize> {
    decoder: PacketDecoder<L, N>,
}

impl<L: PacketLayout, const N: usize> PacketCodec<L, N> {
    /// A codec of `layout`'s packets.
    pub const fn new(layout: L) -> Self {
        PacketCodec {
            decoder: PacketDecoder::new(layout),
        }
    }

    /// The packet decoder (its stats, its engine).
    pub fn decoder(&mut self) -> &mut PacketDecoder<L, N> {
        &mut self.decoder
    }
}

impl<L: PacketLayout, const N: usize> core::fmt::Debug for PacketCodec<L, N> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("PacketCodec")
            .field("decoder", &self.decoder)
            .finish()
    }
}

impl<L: PacketLayout, const N: usize> Decoder for PacketCodec<L, N> {
    type Item = PacketEvent<L::Packet, L::Error>;
    type Error = io::Error;

    /// The next event of the bytes read so far. Every byte of `src` the engine scanned is
    /// consumed (a partial frame is kept in the engine's buffer), so `None` leaves `src` empty.
    fn decode(&mut self, src: &mut BytesMut) -> io::Result<Option<Self::Item>> {
        let mut input: &[u8] = src;
        let event = self.decoder.next_packet(&mut input);
        let used = src.len().saturating_sub(input.len());
        src.advance(used);
        Ok(event)
    }

    /// At the end of the input: the events of the last bytes, then those of the pending bytes
    /// (a frame cut short is rejected as truncated, [`PacketDecoder::flush_packet`]).
    fn decode_eof(&mut self, src: &mut BytesMut) -> io::Result<Option<Self::Item>> {
        match self.decode(src)? {
            Some(event) => Ok(Some(event)),
            None => Ok(self.decoder.flush_packet()),
        }
    }
}

impl<P: EncodePacket, L: PacketLayout, const N: usize> Encoder<P> for PacketCodec<L, N> {
    type Error = io::Error;

    /// Appends the packet's frame to `dst`.
    ///
    /// # Errors
    /// `InvalidInput` with the [`EncodeError`](crate::EncodeError) when the packet does not
    /// encode (a value out of its field's range); `dst` is left as it was.
    fn encode(&mut self, packet: P, dst: &mut BytesMut) -> io::Result<()> {
        let start = dst.len();
        dst.resize(start.saturating_add(packet.encoded_len()), 0);
        let written = dst
            .get_mut(start..)
            .map(|buf| packet.encode_into(buf))
            .unwrap_or(Ok(0));
        match written {
            Ok(n) => {
                dst.truncate(start.saturating_add(n));
                Ok(())
            }
            Err(e) => {
                dst.truncate(start);
                Err(io::Error::new(io::ErrorKind::InvalidInput, e))
            }
        }
    }
}
