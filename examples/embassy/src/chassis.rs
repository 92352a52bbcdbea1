//! A RoboRTS chassis (`specs/roborts.toml`) over a UART: the firmware side of a session with
//! acknowledgements, sequence numbers and retries. Frames are found with the runtime's stream
//! decoder and answered in one of two ways, so that the cost of the session machinery is the
//! difference between two builds of the same firmware:
//!
//! - [`serve_session`] passes each frame through the runtime's session
//!   [`Responder`](roborts::Responder) for the spec's `[session]`: a new request is delivered
//!   to the [`Chassis`] and acknowledged, a request received again (a retry whose
//!   acknowledgement was lost, a duplicate of the link) is acknowledged again without being
//!   delivered twice.
//! - [`serve_by_hand`] delivers every frame and acknowledges it by copying its header: what a
//!   firmware without the session machinery does, duplicates delivered twice.
//!
//! RoboRTS rather than HFLink: its sequence number lets the responder suppress duplicates,
//! which HFLink (no sequence number) cannot. Each step is reported to the binary through
//! [`Step`], with the ticks of a counter the binary passes in (its SysTick), so the binary
//! prints what was delivered and what each request cost.

use protocol_kit::embedded_io_async::{Read, Write};
use protocol_kit::session::Incoming;
use protocol_kit::{Bytes, StreamDecoder};

use crate::roborts::{self, ChassisSpeed, Header, Message, Packet};

/// The chassis's address.
pub const CHASSIS: u8 = 0x01;

/// Sequence numbers the responder remembers: at least the requester's open requests.
pub const SLOTS: usize = 8;

/// Bytes of an answer the responder keeps: an acknowledgement without data is the 12-byte
/// header alone.
pub const ANSWER_LEN: usize = 12;

/// Bytes of one read of the UART.
pub const READ_BUFFER: usize = 32;

/// The session machine of this firmware. The generated machine (over the `Session` type rather
/// than the `SESSION` static) lets the compiler fold the conversation and the frame rules into
/// it.
pub type ChassisResponder = roborts::Responder<SLOTS, ANSWER_LEN>;

/// The frame finder of this firmware. The generated layout type (rather than the `LAYOUT`
/// static) lets the compiler fold the frame rules into the decoder.
pub type Decoder = StreamDecoder<roborts::Layout, DECODER_LEN>;

/// Bytes of the decoder's buffer, as the spec sizes it.
pub const DECODER_LEN: usize = roborts::DECODER_BUFFER_LEN;

/// A decoder of RoboRTS frames.
pub const fn decoder() -> Decoder {
    StreamDecoder::new(roborts::Layout)
}

/// A responder for the spec's `[session]`.
pub fn responder() -> ChassisResponder {
    ChassisResponder::new(roborts::Session)
}

/// What the chassis was asked to do.
#[derive(Debug, Clone, Copy, Default)]
pub struct Chassis {
    /// The last speed command delivered.
    pub speed: ChassisSpeed,
    /// Commands delivered.
    pub delivered: u32,
}

impl Chassis {
    /// Carries out a delivered command.
    pub fn deliver(&mut self, packet: &Packet) {
        self.delivered = self.delivered.wrapping_add(1);
        if let Message::SetChassisSpeed(speed) = packet.message {
            self.speed = speed;
        }
    }
}

/// What became of one frame the firmware found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Step {
    /// A command delivered to the chassis; `ticks` from the frame found to its answer ready
    /// (or to its delivery, when it expects no answer).
    Delivered {
        /// Its sequence number.
        seq: u16,
        /// Its session id (its mode).
        session: u8,
        /// Counter ticks spent on it.
        ticks: u32,
    },
    /// A command received again: not delivered; its answer, if one was sent, sent again.
    Duplicate {
        /// Its sequence number.
        seq: u16,
        /// Counter ticks spent on it.
        ticks: u32,
    },
    /// A command older than the responder's window: neither delivered nor answered.
    Stale {
        /// Its sequence number.
        seq: u16,
    },
    /// A checked frame that is no command of the spec (or an acknowledgement).
    Ignored,
}

/// A frame-level I/O failure of the serving loop.
#[derive(Debug)]
pub enum ServeError<R, W> {
    /// The UART's read failed.
    Read(R),
    /// An answer was not written.
    Write(W),
}

/// The empty acknowledgement of the chassis, with what `header` says it repeats; encoded into
/// `buf`, its length returned.
fn encode_ack(header: Header, buf: &mut [u8]) -> Option<usize> {
    let ack = Packet {
        header,
        message: Message::Ack(Bytes::from_slice(&[])?),
    };
    ack.encode(buf).ok()
}

/// Serves the chassis through the spec's session [`Responder`](roborts::Responder) until a read
/// or write fails.
/// `clock` is a down-counter (SysTick); `report` hears every step.
///
/// # Errors
/// The reader's error, or the writer's.
pub async fn serve_session<R: Read, W: Write>(
    rx: &mut R,
    tx: &mut W,
    decoder: &mut Decoder,
    responder: &mut ChassisResponder,
    chassis: &mut Chassis,
    clock: impl Fn() -> u32,
    mut report: impl FnMut(Step),
) -> Result<(), ServeError<R::Error, W::Error>> {
    let mut buf = [0u8; READ_BUFFER];
    let mut ack = [0u8; ANSWER_LEN];
    loop {
        let n = rx.read(&mut buf).await.map_err(ServeError::Read)?;
        let mut input = buf.get(..n).unwrap_or_default();
        while let Some(frame) = decoder.decode(&mut input) {
            let start = clock();
            let Ok(packet) = Packet::from_frame(frame.bytes) else {
                report(Step::Ignored);
                continue;
            };
            let seq = packet.header.seq_num;
            let session = packet.header.session_id;
            // RoboRTS declares no watchdog: the responder reads no time.
            match responder.on_frame(0, frame.bytes) {
                Incoming::Deliver { answer } => {
                    chassis.deliver(&packet);
                    let len = if answer {
                        let header = Header {
                            sender: CHASSIS,
                            ..packet.header
                        };
                        let len = encode_ack(header, &mut ack).unwrap_or(0);
                        let sent = ack.get_mut(..len).unwrap_or_default();
                        responder.answer(frame.bytes, sent).map_or(0, |()| len)
                    } else {
                        0
                    };
                    let ticks = start.wrapping_sub(clock()) & 0x00FF_FFFF;
                    report(Step::Delivered {
                        seq,
                        session,
                        ticks,
                    });
                    let sent = ack.get(..len).unwrap_or_default();
                    tx.write_all(sent).await.map_err(ServeError::Write)?;
                }
                Incoming::Duplicate(again) => {
                    let again = again.unwrap_or_default();
                    let ticks = start.wrapping_sub(clock()) & 0x00FF_FFFF;
                    report(Step::Duplicate { seq, ticks });
                    tx.write_all(again).await.map_err(ServeError::Write)?;
                }
                Incoming::Stale => report(Step::Stale { seq }),
                _ => report(Step::Ignored),
            }
        }
    }
}

/// Serves the chassis without the session machinery: every command is delivered and, unless
/// its session id is 0, acknowledged with its header's values (addresses swapped). Duplicates
/// are delivered again. Until a read or write fails.
///
/// # Errors
/// The reader's error, or the writer's.
pub async fn serve_by_hand<R: Read, W: Write>(
    rx: &mut R,
    tx: &mut W,
    decoder: &mut Decoder,
    chassis: &mut Chassis,
    clock: impl Fn() -> u32,
    mut report: impl FnMut(Step),
) -> Result<(), ServeError<R::Error, W::Error>> {
    let mut buf = [0u8; READ_BUFFER];
    let mut ack = [0u8; ANSWER_LEN];
    loop {
        let n = rx.read(&mut buf).await.map_err(ServeError::Read)?;
        let mut input = buf.get(..n).unwrap_or_default();
        while let Some(frame) = decoder.decode(&mut input) {
            let start = clock();
            let Ok(packet) = Packet::from_frame(frame.bytes) else {
                report(Step::Ignored);
                continue;
            };
            if matches!(packet.message, Message::Ack(_)) {
                report(Step::Ignored);
                continue;
            }
            let h = packet.header;
            chassis.deliver(&packet);
            let len = if h.session_id == 0 {
                0
            } else {
                let header = Header {
                    sender: h.receiver,
                    receiver: h.sender,
                    ..h
                };
                encode_ack(header, &mut ack).unwrap_or(0)
            };
            let ticks = start.wrapping_sub(clock()) & 0x00FF_FFFF;
            report(Step::Delivered {
                seq: h.seq_num,
                session: h.session_id,
                ticks,
            });
            let sent = ack.get(..len).unwrap_or_default();
            tx.write_all(sent).await.map_err(ServeError::Write)?;
        }
    }
}
