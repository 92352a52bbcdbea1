//! The hand-written HFLink codec: packets (decoded by direction and command, encoded back),
//! the sum, and the receiver that scans a 256-byte buffer in place. Its own module, so that the
//! QEMU firmware (`examples/firmware-qemu`) runs the very same code beside the generated codec.

use crate::messages::{Request, Response};

/// Largest frame: 6 header bytes, 120 of command and payload, the sum.
pub const MAX_FRAME: usize = 127;

/// A decoded frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Message {
    Request(Request),
    Response(Response),
}

/// A frame's header values and message.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Packet {
    pub sender: u8,
    pub receiver: u8,
    pub message: Message,
}

fn sum(bytes: &[u8]) -> u8 {
    (bytes.iter().map(|&b| u32::from(b)).sum::<u32>() % 255) as u8
}

impl Packet {
    /// The packet of a valid frame; `None` for an unknown command, a sender in neither range,
    /// or a payload of the wrong size.
    pub fn from_frame(frame: &[u8]) -> Option<Self> {
        let (&[_, _, sender, receiver, _, _, command], rest) = frame.split_first_chunk::<7>()?;
        let payload = rest.get(..rest.len().checked_sub(1)?)?;
        let message = match sender {
            0x01..=0x10 => Message::Request(Request::decode(command, payload)?),
            0x11..=0x40 => Message::Response(Response::decode(command, payload)?),
            _ => return None,
        };
        Some(Packet {
            sender,
            receiver,
            message,
        })
    }

    /// Writes the frame at the start of `out`; its length.
    pub fn encode(&self, out: &mut [u8]) -> Option<usize> {
        let (command, n) = match (&self.message, self.sender) {
            (Message::Request(m), 0x01..=0x10) => m.encode(out.get_mut(7..MAX_FRAME - 1)?)?,
            (Message::Response(m), 0x11..=0x40) => m.encode(out.get_mut(7..MAX_FRAME - 1)?)?,
            _ => return None,
        };
        let len = (n + 1) as u16;
        let [hi, lo] = len.to_be_bytes();
        out.get_mut(..7)?.copy_from_slice(&[
            0xFF,
            0xFF,
            self.sender,
            self.receiver,
            hi,
            lo,
            command,
        ]);
        let total = n + 8;
        out[total - 1] = sum(out.get(..total - 1)?);
        Some(total)
    }
}

/// What the receiver dropped.
#[derive(Debug, Default, Clone, Copy)]
pub struct Stats {
    pub frames: u32,
    pub bad_length: u32,
    pub bad_checksum: u32,
    pub skipped: u32,
}

/// The receiver: bytes not decided yet, scanned in place.
pub struct Receiver {
    pub buf: [u8; 256],
    pub len: usize,
    pub stats: Stats,
}

impl Default for Receiver {
    fn default() -> Self {
        Receiver {
            buf: [0; 256],
            len: 0,
            stats: Stats::default(),
        }
    }
}

impl Receiver {
    /// Appends `chunk` and calls `sink` with every frame now complete.
    pub fn feed(&mut self, mut chunk: &[u8], mut sink: impl FnMut(&[u8])) {
        while !chunk.is_empty() {
            let take = chunk.len().min(self.buf.len() - self.len);
            self.buf[self.len..self.len + take].copy_from_slice(&chunk[..take]);
            self.len += take;
            chunk = &chunk[take..];
            let done = self.scan(&mut sink);
            self.buf.copy_within(done..self.len, 0);
            self.len -= done;
        }
    }

    /// Frames in `buf[..len]`; returns the bytes decided.
    fn scan(&mut self, sink: &mut impl FnMut(&[u8])) -> usize {
        let data = &self.buf[..self.len];
        let mut at = 0;
        while at < data.len() {
            let rest = &data[at..];
            if rest[0] != 0xFF || rest.get(1).is_some_and(|&b| b != 0xFF) {
                self.stats.skipped += 1;
                at += 1;
                continue;
            }
            let Some(header) = rest.get(..6) else { break };
            let length = usize::from(u16::from_be_bytes([header[4], header[5]]));
            if !(1..=120).contains(&length) {
                self.stats.bad_length += 1;
                self.stats.skipped += 1;
                at += 1;
                continue;
            }
            let Some(frame) = rest.get(..length + 7) else {
                break;
            };
            if sum(&frame[..length + 6]) == frame[length + 6] {
                self.stats.frames += 1;
                sink(frame);
                at += frame.len();
            } else {
                self.stats.bad_checksum += 1;
                self.stats.skipped += 1;
                at += 1;
            }
        }
        at
    }
}
