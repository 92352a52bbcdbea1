//! The code under test: what `protocol_kit::protocol!` generates from the two specs, used
//! the way its documentation shows (a decoder from `decoder()`, `decode` in a loop per chunk,
//! `flush` at the end; `Packet::encode` into the caller's buffer).

use protocol_kit::StreamDecoder;
use protocol_kit::layout::LayoutRef;

use crate::ChunkDecoder;

protocol_kit::protocol!("../specs/hflink.toml");
protocol_kit::protocol!("../specs/referee.toml");

/// A generated decoder of either spec.
pub struct Generated<L: LayoutRef, const N: usize>(pub StreamDecoder<L, N>);

/// The generated HFLink decoder.
pub fn hflink_decoder() -> Generated<hflink::Layout, { hflink::DECODER_BUFFER_LEN }> {
    Generated(hflink::decoder())
}

/// The generated referee decoder.
pub fn referee_decoder() -> Generated<referee::Layout, { referee::DECODER_BUFFER_LEN }> {
    Generated(referee::decoder())
}

/// Bytes of the decoder buffer of the `*_decoder_small` variants: what generated decoders get
/// on microcontrollers for frames of up to 127 bytes (both specs' longest), where hosts get
/// 2 KiB.
pub const BUFFER_SMALL: usize = 384;

/// The generated HFLink decoder with the microcontrollers' buffer (`StreamDecoder`'s size is
/// the user's choice).
pub fn hflink_decoder_small() -> Generated<hflink::Layout, BUFFER_SMALL> {
    Generated(StreamDecoder::new(hflink::Layout))
}

/// The generated referee decoder with the microcontrollers' buffer.
pub fn referee_decoder_small() -> Generated<referee::Layout, BUFFER_SMALL> {
    Generated(StreamDecoder::new(referee::Layout))
}

/// The generated HFLink layout read through a reference, as the run-time codec reads its own.
pub fn hflink_decoder_by_ref()
-> Generated<&'static protocol_kit::FrameLayout<'static>, { hflink::DECODER_BUFFER_LEN }> {
    Generated(StreamDecoder::new(&hflink::LAYOUT))
}

/// The generated referee layout read through a reference, as the run-time codec reads its own.
pub fn referee_decoder_by_ref()
-> Generated<&'static protocol_kit::FrameLayout<'static>, { referee::DECODER_BUFFER_LEN }> {
    Generated(StreamDecoder::new(&referee::LAYOUT))
}

impl<L: LayoutRef, const N: usize> ChunkDecoder for Generated<L, N> {
    #[inline]
    fn feed<F: FnMut(&[u8])>(&mut self, chunk: &[u8], sink: &mut F) {
        self.0.feed(chunk, |frame| sink(frame.bytes));
    }

    fn finish<F: FnMut(&[u8])>(&mut self, sink: &mut F) {
        while let Some(frame) = self.0.flush() {
            sink(frame.bytes);
        }
    }
}

/// Writes a `READ_SYSTEM_INFO` response (a 20-byte `SystemInfo`) with the generated encoder at
/// the start of `buf`; returns its length.
///
/// # Errors
///
/// The encoder's, for a short buffer.
#[inline]
pub fn encode_system_info(
    buf: &mut [u8],
    sender: u8,
    receiver: u8,
    info: [f32; 5],
) -> Result<usize, protocol_kit::EncodeError> {
    use hflink::{Header, Message, Packet, Response, SystemInfo};
    let [
        system_time,
        cpu_temperature,
        cpu_usage,
        battery_voltage,
        power_remain,
    ] = info;
    Packet {
        header: Header { sender, receiver },
        message: Message::Response(Response::ReadSystemInfo(SystemInfo {
            system_time,
            cpu_temperature,
            cpu_usage,
            battery_voltage,
            power_remain,
        })),
    }
    .encode(buf)
}

/// Writes a `GAME_ROBOT_POS` frame (a 16-byte `GameRobotPos`) with the generated encoder at the
/// start of `buf`; returns its length.
///
/// # Errors
///
/// The encoder's, for a short buffer.
#[inline]
pub fn encode_robot_pos(
    buf: &mut [u8],
    seq: u8,
    pos: [f32; 4],
) -> Result<usize, protocol_kit::EncodeError> {
    use referee::{GameRobotPos, Header, Message, Packet};
    let [x, y, z, yaw] = pos;
    Packet {
        header: Header { seq },
        message: Message::GameRobotPos(GameRobotPos { x, y, z, yaw }),
    }
    .encode(buf)
}
