//! The rover of the tutorial: the module `protocol!` generates from `specs/rover.toml`, and
//! the rover's side of the link. `no_std` and heap-free, so the same code runs on the rover's
//! microcontroller and in tests on a host.
#![no_std]
#![forbid(unsafe_code)]

protocol_kit::protocol!("specs/rover.toml");

use protocol_kit::EncodeError;
use rover::{Drive, Header, Lights, Message, Packet, Status};

/// What the rover knows: the last commands it received and what it reports.
pub struct Rover {
    /// The last `DRIVE`.
    pub drive: Drive,
    /// The last `LIGHTS`.
    pub lights: Lights,
    /// What `STATUS` reports.
    pub status: Status,
    decoder: rover::Decoder,
}

impl Rover {
    /// A rover that has received nothing yet and reports `status`.
    pub const fn new(status: Status) -> Self {
        Rover {
            drive: Drive {
                speed: 0.0,
                turn: 0.0,
            },
            lights: Lights {
                on: false,
                level: 0,
            },
            status,
            decoder: rover::decoder(),
        }
    }

    /// Decodes the bytes that arrived (a chunk of any size: a frame may straddle two calls)
    /// and answers each `PING` with a `STATUS` frame, passed to `send`. Bad bytes cost only
    /// themselves; `self.link()` counts them.
    ///
    /// # Errors
    ///
    /// An `EncodeError` if a reply does not fit its frame (it always fits: the buffer is
    /// `MAX_FRAME_LEN` bytes).
    pub fn receive(
        &mut self,
        mut input: &[u8],
        send: &mut impl FnMut(&[u8]),
    ) -> Result<(), EncodeError> {
        while let Some(frame) = self.decoder.decode(&mut input) {
            // A frame whose framing and CRC are right can still carry an unknown command.
            let Ok(packet) = Packet::from_frame(frame.bytes) else {
                continue;
            };
            match packet.message {
                Message::Ping => {
                    let reply = Packet {
                        header: Header {},
                        message: Message::Status(self.status),
                    };
                    let mut buf = [0u8; rover::MAX_FRAME_LEN];
                    let n = reply.encode(&mut buf)?;
                    send(&buf[..n]);
                }
                Message::Drive(drive) => self.drive = drive,
                Message::Lights(lights) => self.lights = lights,
                Message::Status(_) => {}
            }
        }
        Ok(())
    }

    /// What the decoder dropped so far: bad CRCs, impossible lengths, skipped bytes.
    pub fn link(&self) -> &protocol_kit::Stats {
        self.decoder.stats()
    }
}
