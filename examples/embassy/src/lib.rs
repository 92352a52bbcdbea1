//! HFLink's slave side over a UART, for any board: requests are read with the runtime's async
//! reader (`protocol_kit::io_async::PacketReader`), answered by [`Robot`], and the answers
//! written with `write_packet`. Everything here is generic over `embedded_io_async::{Read,
//! Write}`, so the STM32F4 binary (`embassy-stm32`'s buffered USART) and the QEMU binary (a
//! CMSDK UART driver) run the same code; the board-specific parts are the binaries alone.
//!
//! [`chassis`] is the second application: a RoboRTS chassis whose answers go through the
//! runtime's session `Responder` (or, for comparison, are built by hand).
//!
//! RAM: the reader holds the decoder (its buffer and state, in the generated module's docs)
//! and a read buffer of [`READ_BUFFER`] bytes; [`serve`] encodes each answer into a buffer of
//! `hflink::MAX_FRAME_LEN` bytes held in its future; [`Robot`] holds the robot's values. No heap.

#![no_std]
#![forbid(unsafe_code)]

pub mod chassis;
mod robot;

use protocol_kit::PacketEvent;
use protocol_kit::embedded_io_async::{Read, Write};
use protocol_kit::io_async::{PacketReader, WriteError, write_packet};

pub use robot::Robot;
// The facade, for the binaries (`embedded_io_async` at the version the reader takes).
pub use protocol_kit;

protocol_kit::protocol!("../../specs/hflink.toml");
protocol_kit::protocol!("../../specs/roborts.toml");

/// Bytes of the reader's read buffer: what one read of the UART driver may hand over.
pub const READ_BUFFER: usize = 32;

/// The async reader of HFLink packets this example runs.
pub type Reader<R> = PacketReader<R, hflink::Layout, { hflink::DECODER_BUFFER_LEN }, READ_BUFFER>;

/// A reader of HFLink packets from `uart`.
pub const fn reader<R: Read>(uart: R) -> Reader<R> {
    PacketReader::new(uart, hflink::Layout)
}

/// What the link saw that carried no request: frames the decoder rejected and bytes where no
/// frame starts.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Noise {
    /// Candidates rejected (bad checksum, bad length) and frames that hold no packet.
    pub rejected: u32,
    /// Bytes skipped between frames.
    pub skipped_bytes: u32,
}

/// Why [`serve`] stopped.
#[derive(Debug)]
pub enum ServeError<R, W> {
    /// The UART's read failed.
    Read(R),
    /// An answer was not written.
    Write(WriteError<W>),
}

/// Answers every request read from `reader` on `writer`, until the reader ends (a read of 0
/// bytes; a UART never ends) or fails. Frames that are not requests to `robot` get no answer;
/// rejected candidates and skipped bytes are counted in `noise`.
///
/// # Errors
/// The reader's error, or the writer's.
pub async fn serve<R: Read, W: Write>(
    reader: &mut Reader<R>,
    writer: &mut W,
    robot: &mut Robot,
    noise: &mut Noise,
) -> Result<(), ServeError<R::Error, W::Error>> {
    let mut frame = [0u8; hflink::MAX_FRAME_LEN];
    while let Some(event) = reader.next_packet().await.map_err(ServeError::Read)? {
        match event {
            PacketEvent::Packet { packet, .. } => {
                if let Some(answer) = robot.answer(&packet) {
                    write_packet(writer, &answer, &mut frame)
                        .await
                        .map_err(ServeError::Write)?;
                }
            }
            PacketEvent::Invalid { .. } => noise.rejected = noise.rejected.saturating_add(1),
            PacketEvent::Skipped { len, .. } => {
                let len = u32::try_from(len).unwrap_or(u32::MAX);
                noise.skipped_bytes = noise.skipped_bytes.saturating_add(len);
            }
        }
    }
    Ok(())
}
