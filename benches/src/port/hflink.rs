//! The HFLink receiver of the originals (`hf_link_state_machine.cpp`), one byte at a time.
//!
//! States: first `FF`, second `FF`, sender, receiver, length high, length low, data, checksum.
//! The sum (of every byte, both `FF` included) is accumulated as bytes arrive and reduced
//! modulo 255 at the checksum byte. As in the original: after a failed checksum the search
//! starts again at the next byte; a byte other than `FF` in the second-sync state is not looked
//! at again; the data state stores a byte before comparing the count with the length (so a
//! length of 0 takes one data byte).
//!
//! Differences: a length above 120 ends the candidate (the original writes past its 120-byte
//! buffer); the original's filter on the sender and receiver ids (a node accepts only frames
//! from its peer) is left out, since it is dispatch, not framing, and the streams carry both
//! directions.

use super::Receiver;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum State {
    WaitingFf1,
    WaitingFf2,
    SenderId,
    ReceiverId,
    LengthHigh,
    LengthLow,
    ReceivePackage,
    CheckSum,
}

/// The byte-at-a-time HFLink receiver.
pub struct HfLinkPort {
    state: State,
    /// The frame as received so far (the original keeps the fields apart; the raw bytes are
    /// kept here so that the frame can be handed on and checked).
    frame: [u8; 127],
    length: usize,
    count: usize,
    sum: u32,
}

impl Default for HfLinkPort {
    fn default() -> Self {
        HfLinkPort {
            state: State::WaitingFf1,
            frame: [0; 127],
            length: 0,
            count: 0,
            sum: 0,
        }
    }
}

impl Receiver for HfLinkPort {
    #[inline]
    fn push(&mut self, byte: u8) -> bool {
        match self.state {
            State::WaitingFf1 => {
                if byte == 0xFF {
                    self.frame[0] = byte;
                    self.sum = u32::from(byte);
                    self.state = State::WaitingFf2;
                }
            }
            State::WaitingFf2 => {
                if byte == 0xFF {
                    self.frame[1] = byte;
                    self.sum += u32::from(byte);
                    self.state = State::SenderId;
                } else {
                    self.state = State::WaitingFf1;
                }
            }
            State::SenderId => {
                self.frame[2] = byte;
                self.sum += u32::from(byte);
                self.state = State::ReceiverId;
            }
            State::ReceiverId => {
                self.frame[3] = byte;
                self.sum += u32::from(byte);
                self.state = State::LengthHigh;
            }
            State::LengthHigh => {
                self.frame[4] = byte;
                self.sum += u32::from(byte);
                self.length = usize::from(byte) << 8;
                self.state = State::LengthLow;
            }
            State::LengthLow => {
                self.frame[5] = byte;
                self.sum += u32::from(byte);
                self.length |= usize::from(byte);
                self.count = 0;
                self.state = if self.length > 120 {
                    State::WaitingFf1
                } else {
                    State::ReceivePackage
                };
            }
            State::ReceivePackage => {
                self.frame[6 + self.count] = byte;
                self.sum += u32::from(byte);
                self.count += 1;
                if self.count >= self.length {
                    self.state = State::CheckSum;
                }
            }
            State::CheckSum => {
                self.state = State::WaitingFf1;
                if (self.sum % 255) as u8 == byte {
                    self.frame[6 + self.count] = byte;
                    return true;
                }
            }
        }
        false
    }

    #[inline]
    fn frame(&self) -> &[u8] {
        &self.frame[..self.count + 7]
    }

    fn reset(&mut self) {
        self.state = State::WaitingFf1;
    }
}
