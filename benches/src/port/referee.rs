//! The referee receiver of the originals (RoboRTS-Firmware `referee_unpack_fifo_data`), one
//! byte at a time.
//!
//! Steps: start byte `A5`, length low, length high (a length of 119 or more ends the candidate),
//! sequence, header CRC-8 (checked over the five header bytes once the fifth arrives), then data
//! and CRC-16 until `length + 9` bytes are stored, when the CRC-16 is checked over the whole
//! frame. Both CRCs use byte-wise 256-entry tables, as the originals do. Any failure restarts
//! the search for `A5` at the next unread byte: bytes already consumed are never looked at
//! again.

use super::Receiver;

const fn crc8_table() -> [u8; 256] {
    let mut t = [0u8; 256];
    let mut x = 0;
    while x < 256 {
        let mut r = x as u8;
        let mut bit = 0;
        while bit < 8 {
            r = if r & 1 != 0 { (r >> 1) ^ 0x8C } else { r >> 1 };
            bit += 1;
        }
        t[x] = r;
        x += 1;
    }
    t
}

const fn crc16_table() -> [u16; 256] {
    let mut t = [0u16; 256];
    let mut x = 0;
    while x < 256 {
        let mut r = x as u16;
        let mut bit = 0;
        while bit < 8 {
            r = if r & 1 != 0 {
                (r >> 1) ^ 0x8408
            } else {
                r >> 1
            };
            bit += 1;
        }
        t[x] = r;
        x += 1;
    }
    t
}

static CRC8_TABLE: [u8; 256] = crc8_table();
static CRC16_TABLE: [u16; 256] = crc16_table();

/// The originals' `Verify_CRC8_Check_Sum`: CRC-8 (register from 0xFF) of all bytes but the
/// last, compared with the last.
fn verify_crc8(bytes: &[u8]) -> bool {
    let Some((&stored, covered)) = bytes.split_last() else {
        return false;
    };
    let mut crc = 0xFFu8;
    for &b in covered {
        crc = CRC8_TABLE[usize::from(crc ^ b)];
    }
    crc == stored
}

/// The originals' `Verify_CRC16_Check_Sum`: CRC-16 (register from 0xFFFF) of all bytes but the
/// last two, compared with them (low byte first).
fn verify_crc16(bytes: &[u8]) -> bool {
    let Some((covered, stored)) = bytes.split_last_chunk::<2>() else {
        return false;
    };
    let mut crc = 0xFFFFu16;
    for &b in covered {
        crc = (crc >> 8) ^ CRC16_TABLE[usize::from((crc ^ u16::from(b)) & 0xFF)];
    }
    crc == u16::from_le_bytes(*stored)
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Step {
    Sof,
    LenLow,
    LenHigh,
    FrameSeq,
    HeaderCrc8,
    DataCrc16,
}

/// The byte-at-a-time referee receiver.
pub struct RefereePort {
    step: Step,
    buf: [u8; 128],
    index: usize,
    data_len: usize,
}

impl Default for RefereePort {
    fn default() -> Self {
        RefereePort {
            step: Step::Sof,
            buf: [0; 128],
            index: 0,
            data_len: 0,
        }
    }
}

impl Receiver for RefereePort {
    #[inline]
    fn push(&mut self, byte: u8) -> bool {
        match self.step {
            Step::Sof => {
                if byte == 0xA5 {
                    self.buf[0] = byte;
                    self.index = 1;
                    self.step = Step::LenLow;
                }
            }
            Step::LenLow => {
                self.buf[self.index] = byte;
                self.index += 1;
                self.data_len = usize::from(byte);
                self.step = Step::LenHigh;
            }
            Step::LenHigh => {
                self.buf[self.index] = byte;
                self.index += 1;
                self.data_len |= usize::from(byte) << 8;
                self.step = if self.data_len < 128 - 9 {
                    Step::FrameSeq
                } else {
                    Step::Sof
                };
            }
            Step::FrameSeq => {
                self.buf[self.index] = byte;
                self.index += 1;
                self.step = Step::HeaderCrc8;
            }
            Step::HeaderCrc8 => {
                self.buf[self.index] = byte;
                self.index += 1;
                self.step = if verify_crc8(&self.buf[..5]) {
                    Step::DataCrc16
                } else {
                    Step::Sof
                };
            }
            Step::DataCrc16 => {
                let total = self.data_len + 9;
                if self.index < total {
                    self.buf[self.index] = byte;
                    self.index += 1;
                }
                if self.index == total {
                    self.step = Step::Sof;
                    return verify_crc16(&self.buf[..total]);
                }
            }
        }
        false
    }

    #[inline]
    fn frame(&self) -> &[u8] {
        &self.buf[..self.index]
    }

    fn reset(&mut self) {
        self.step = Step::Sof;
    }
}
