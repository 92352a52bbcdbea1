//! What the engine reports: [`Frame`]s, [`Event`]s, the [`Reject`] reasons and the [`Stats`]
//! counters, with the counting rules (every byte fed is counted once).
//!
//! This module owns the public types a caller of [`StreamDecoder`] handles and how the counters
//! add up. It does not decide anything: when a candidate is rejected is the parent module's
//! rule ([`FrameLayout::probe`](crate::FrameLayout::probe)), when bytes are skipped the
//! search's and the scan's.

use core::fmt;

#[cfg(doc)]
use super::StreamDecoder;
#[cfg(doc)]
use crate::layout::{Constant, Marker};

/// Why a candidate frame was rejected.
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Reject {
    /// The sync bytes or a [`Constant`] of the header do not match.
    BadHeader,
    /// A header check does not match.
    BadHeaderCheck,
    /// The length is outside the format's bounds or the decoder's buffer.
    BadLength,
    /// A frame check does not match.
    BadChecksum,
    /// A trailing [`Marker`] does not match.
    BadTrailer,
    /// On a link that escapes bytes ([`FrameLayout::escape`](crate::FrameLayout::escape)):
    /// an escape byte not followed by a substitute, or a flag right after an escape byte.
    /// Counted with [`Stats::bad_header`]: the frame's bytes break a rule of the format itself.
    BadEscape,
    /// The frame's bytes never came: a complete valid frame started inside its claimed length,
    /// or the input was declared ended ([`StreamDecoder::flush`]).
    Truncated,
}

impl fmt::Display for Reject {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Reject::BadHeader => "bad header",
            Reject::BadHeaderCheck => "bad header check",
            Reject::BadLength => "bad length",
            Reject::BadChecksum => "bad checksum",
            Reject::BadTrailer => "bad trailer",
            Reject::BadEscape => "bad escape",
            Reject::Truncated => "truncated frame",
        })
    }
}

impl core::error::Error for Reject {}

/// What a [`StreamDecoder`] counted, for link-quality reports.
///
/// Every byte fed is accounted for once: `frame_bytes + skipped_bytes` plus the bytes still
/// pending equals the bytes fed ([`StreamDecoder::position`]). A rejected candidate's first
/// byte counts as skipped (the search resumes right after it).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Stats {
    /// Valid frames yielded.
    pub frames: u64,
    /// Bytes of the valid frames.
    pub frame_bytes: u64,
    /// Bytes that belong to no valid frame.
    pub skipped_bytes: u64,
    /// Candidates rejected as [`Reject::BadHeader`] or [`Reject::BadEscape`].
    pub bad_header: u64,
    /// Candidates rejected as [`Reject::BadHeaderCheck`].
    pub bad_header_check: u64,
    /// Candidates rejected as [`Reject::BadLength`].
    pub bad_length: u64,
    /// Candidates rejected as [`Reject::BadChecksum`].
    pub bad_checksum: u64,
    /// Candidates rejected as [`Reject::BadTrailer`].
    pub bad_trailer: u64,
    /// Candidates rejected as [`Reject::Truncated`].
    pub truncated: u64,
}

impl Stats {
    pub(super) const ZERO: Stats = Stats {
        frames: 0,
        frame_bytes: 0,
        skipped_bytes: 0,
        bad_header: 0,
        bad_header_check: 0,
        bad_length: 0,
        bad_checksum: 0,
        bad_trailer: 0,
        truncated: 0,
    };

    /// Candidates rejected, for any reason.
    pub const fn rejected(&self) -> u64 {
        self.bad_header
            .wrapping_add(self.bad_header_check)
            .wrapping_add(self.bad_length)
            .wrapping_add(self.bad_checksum)
            .wrapping_add(self.bad_trailer)
            .wrapping_add(self.truncated)
    }

    /// Counts a rejected candidate, whose first byte is skipped.
    pub(super) fn count_reject(&mut self, reason: Reject) {
        self.skipped_bytes = self.skipped_bytes.wrapping_add(1);
        let counter = match reason {
            Reject::BadHeader | Reject::BadEscape => &mut self.bad_header,
            Reject::BadHeaderCheck => &mut self.bad_header_check,
            Reject::BadLength => &mut self.bad_length,
            Reject::BadChecksum => &mut self.bad_checksum,
            Reject::BadTrailer => &mut self.bad_trailer,
            Reject::Truncated => &mut self.truncated,
        };
        *counter = counter.wrapping_add(1);
    }

    /// Counts a frame of `len` bytes.
    pub(super) fn count_frame(&mut self, len: usize) {
        self.frames = self.frames.wrapping_add(1);
        self.frame_bytes = self.frame_bytes.wrapping_add(len as u64);
    }

    /// Adds what a scan counted: `frames` frames in `scanned` bytes; the bytes that belong to
    /// no frame (skipped runs and the first bytes of rejected candidates) were added to the
    /// skipped bytes since they were `skipped_before`.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub(super) fn count_scan(&mut self, frames: u64, scanned: usize, skipped_before: u64) {
        self.frames = self.frames.wrapping_add(frames);
        let gaps = self.skipped_bytes.wrapping_sub(skipped_before);
        let frame_bytes = (scanned as u64).wrapping_sub(gaps);
        self.frame_bytes = self.frame_bytes.wrapping_add(frame_bytes);
    }
}

/// A valid frame found in a stream.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Frame<'a> {
    /// The whole frame, sync to trailer.
    pub bytes: &'a [u8],
    /// Offset of its first byte in the whole stream.
    pub offset: u64,
    /// The frame format it came in, on a link of several
    /// ([`LayoutRef::others`](crate::layout::LayoutRef::others)): 0 for the first, 1 for the
    /// next, ... Always 0 on a link of one format.
    pub format: usize,
}

/// What a [`StreamDecoder`] reports with [`StreamDecoder::next_event`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Event<'a> {
    /// A valid frame.
    Frame(Frame<'a>),
    /// A candidate starting at `offset` was rejected; the search resumes at `offset + 1`.
    Rejected {
        /// Offset of the candidate's first byte in the stream.
        offset: u64,
        /// Why it was rejected.
        reason: Reject,
    },
    /// A run of `len` bytes where no candidate starts. A long run of garbage may be reported
    /// in several pieces (one per chunk of input, for example).
    Skipped {
        /// Offset of the run's first byte in the stream.
        offset: u64,
        /// Bytes in the run.
        len: usize,
    },
}
