//! The referee protocol by hand: the frame scan and an encoder.
//!
//! `A5 data_length(u16 LE) seq CRC8 | cmd_id(u16 LE) data CRC16(LE)`: the CRC-8 covers the first
//! four bytes and is checked before the length is trusted; `data_length` is at most 118; the
//! CRC-16/MCRF4XX covers everything before it.

use super::crc::{crc8_header, crc16};
use super::{Lead, Scan};

/// Referee frames.
pub struct Referee;

/// Largest frame a receiver accepts.
const MAX_FRAME: usize = 127;
/// Shortest frame: the header, the command id and the CRC-16.
const SHORTEST: usize = 9;
/// `A5`, and two bytes on the high byte of `data_length` (at most 118): zero.
const LEAD: Lead = Lead {
    first: 0xA5,
    reach: 2,
    mask: 0xFF,
    value: 0x00,
};
/// Largest `data_length`.
const MAX_DATA: usize = 118;

/// Where the next candidate (an `A5`) starts at or after `at`.
#[inline(always)]
fn find_sof(data: &[u8], at: usize) -> Option<usize> {
    // On a clean stream the next frame starts right here.
    if data.get(at) == Some(&0xA5) {
        return Some(at);
    }
    Some(at + memchr::memchr(0xA5, data.get(at..)?)?)
}

impl Scan for Referee {
    const MAX_FRAME: usize = MAX_FRAME;
    const SHORTEST: usize = SHORTEST;
    const LEAD: Lead = LEAD;

    #[inline(always)]
    fn scan<F: FnMut(&[u8])>(buf: &[u8], len: usize, at_end: bool, sink: &mut F) -> usize {
        scan_with(buf, len, at_end, sink, crc16)
    }
}

/// Referee frames, the CRC-16 folded with carry-less multiplication where the CPU has it
/// ([`clmul`](super::clmul)), by slicing-by-16 elsewhere.
pub struct RefereeClmul;

/// The scan with the carry-less CRC-16, compiled for CPUs with `pclmulqdq`.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "pclmulqdq")]
fn scan_clmul<F: FnMut(&[u8])>(buf: &[u8], len: usize, at_end: bool, sink: &mut F) -> usize {
    scan_with(buf, len, at_end, sink, |data: &[u8], n| {
        super::clmul::crc16(data, n)
    })
}

impl Scan for RefereeClmul {
    const MAX_FRAME: usize = MAX_FRAME;
    const SHORTEST: usize = SHORTEST;
    const LEAD: Lead = LEAD;

    #[inline(always)]
    #[allow(unsafe_code)]
    fn scan<F: FnMut(&[u8])>(buf: &[u8], len: usize, at_end: bool, sink: &mut F) -> usize {
        #[cfg(target_arch = "x86_64")]
        if super::clmul::available() {
            // SAFETY: the CPU has `pclmulqdq`, the one feature `scan_clmul` is compiled for.
            return unsafe { scan_clmul(buf, len, at_end, sink) };
        }
        scan_with(buf, len, at_end, sink, crc16)
    }
}

/// Referee frames, the CRC-16 computed by the `crc-fast` crate (SIMD folding behind its own
/// run-time dispatch): what a maintained crate, called once per frame, costs in the scan.
pub struct RefereeCrcFast;

impl Scan for RefereeCrcFast {
    const MAX_FRAME: usize = MAX_FRAME;
    const SHORTEST: usize = SHORTEST;
    const LEAD: Lead = LEAD;

    #[inline(always)]
    fn scan<F: FnMut(&[u8])>(buf: &[u8], len: usize, at_end: bool, sink: &mut F) -> usize {
        scan_with(buf, len, at_end, sink, |data: &[u8], n| {
            let covered = data.get(..n).unwrap_or(data);
            crc_fast::checksum(crc_fast::CrcAlgorithm::Crc16Mcrf4xx, covered) as u16
        })
    }
}

/// The scan of [`Scan::scan`], with `crc` the CRC-16 of `data[..n]`.
#[inline(always)]
fn scan_with<F: FnMut(&[u8]), C: Fn(&[u8], usize) -> u16>(
    buf: &[u8],
    len: usize,
    at_end: bool,
    sink: &mut F,
    crc: C,
) -> usize {
    let data = &buf[..len];
    let mut at = 0;
    while let Some(p) = find_sof(data, at) {
        let rest = &data[p..];
        let Some(&[h0, h1, h2, h3, h4]) = rest.first_chunk::<5>() else {
            if at_end {
                at = p + 1;
                continue;
            }
            return p;
        };
        let data_len = usize::from(u16::from_le_bytes([h1, h2]));
        if crc8_header([h0, h1, h2, h3]) != h4 || data_len > MAX_DATA {
            at = p + 1;
            continue;
        }
        let total = data_len + 9;
        let Some(frame) = rest.get(..total) else {
            if at_end {
                at = p + 1;
                continue;
            }
            return p;
        };
        let stored = u16::from_le_bytes([frame[total - 2], frame[total - 1]]);
        if crc(&buf[p..], total - 2) == stored {
            sink(frame);
            at = p + total;
        } else {
            at = p + 1;
        }
    }
    data.len()
}

/// Bytes of a `GAME_ROBOT_POS` frame: 7 header bytes, 16 data bytes, the CRC-16.
pub const ROBOT_POS_FRAME: usize = 25;

/// Writes a `GAME_ROBOT_POS` frame (`x`, `y`, `z`, `yaw` as `f32`) with sequence number `seq` at
/// the start of `buf`; returns its length, or `None` if `buf` is too short.
#[inline]
pub fn encode_robot_pos(buf: &mut [u8], seq: u8, pos: [f32; 4]) -> Option<usize> {
    let frame = buf.first_chunk_mut::<ROBOT_POS_FRAME>()?;
    let header = [0xA5, 16, 0, seq];
    frame[..4].copy_from_slice(&header);
    frame[4] = crc8_header(header);
    frame[5..7].copy_from_slice(&0x0203u16.to_le_bytes());
    for (dst, v) in frame[7..23].chunks_exact_mut(4).zip(pos) {
        dst.copy_from_slice(&v.to_le_bytes());
    }
    let crc = crc16(frame, 23);
    frame[23..].copy_from_slice(&crc.to_le_bytes());
    Some(ROBOT_POS_FRAME)
}
