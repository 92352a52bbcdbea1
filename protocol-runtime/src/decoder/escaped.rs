//! The stream engine's path for a format whose frames are escaped between flags
//! ([`FrameLayout::escape`](crate::FrameLayout::escape): HDLC, SLIP, Sensirion SHDLC).
//!
//! This module owns how such a stream is cut into candidates: bytes before a flag are skipped;
//! a flag opens a candidate; the bytes after it are unescaped into the buffer as they come
//! ([`Escape::original`]); the next flag closes the candidate, which the ordinary rules then
//! decide ([`probe`](super::probe): length, constants, checks, markers, all over the
//! unescaped bytes), and opens the next one. So a flag is always a frame boundary: a damaged
//! or cut frame ends at the next flag and never costs the frame that follows, and two frames
//! may share a flag (`7E frame 7E frame 7E`). An escape byte followed by a byte that is no
//! substitute rejects the candidate as [`Reject::BadEscape`]. A candidate longer than the
//! format's `max_len` (or the buffer) is rejected as soon as it is, without waiting for its
//! flag. Every byte is looked at once; nothing is allocated.
//!
//! The frames yielded are the unescaped bytes, flags included: what
//! [`FrameLayout::parse`](crate::FrameLayout::parse) and the packet rules read. Offsets and
//! [`Stats`](super::Stats) count bytes on the wire; a flag shared by two frames counts with the
//! first. The bytes [`pending_bytes`](StreamDecoder::pending_bytes) are the candidate's, unescaped;
//! [`pending`](StreamDecoder::pending) counts its bytes on the wire not counted yet.
//!
//! The state lives in the fields the other path uses for its search inside a pending
//! candidate, which this path never runs: `inner_owner` holds the stream offset of the
//! candidate's opening flag, `inner_dead` two flags ([`ESCAPED`], [`COUNTED`]).

use super::event::Reject;
use super::stream::{Step, StreamDecoder};
use super::{Probe, probe};
use crate::escape::Escape;
use crate::layout::LayoutRef;

/// `inner_dead` bit: the last byte of the candidate was the escape byte.
const ESCAPED: usize = 2;
/// `inner_dead` bit: the candidate's opening flag closed the frame before it, and is counted.
const COUNTED: usize = 4;

impl<L: LayoutRef, const N: usize> StreamDecoder<L, N> {
    /// One step of the escaped path: a skipped run, a frame (in the buffer), a rejected
    /// candidate, or `Idle` when the input is used up.
    pub(super) fn escaped_step(&mut self, input: &mut &[u8], at_end: bool) -> Step {
        let link = self.layout;
        let Some(esc) = link.layout().escape else {
            return Step::Idle;
        };
        loop {
            if self.start >= self.end {
                if let Some(step) = self.hunt(esc, input) {
                    return step;
                }
                continue;
            }
            let Some(&byte) = input.first() else {
                return self.input_ended(at_end);
            };
            self.consume(input, 1);
            if byte == esc.flag {
                match self.close(esc) {
                    Some(step) => return step,
                    None => continue,
                }
            }
            let state = self.inner_dead;
            let unescaped = if state & ESCAPED != 0 {
                self.inner_dead = state & !ESCAPED;
                match esc.original(byte) {
                    Some(original) => original,
                    None => return self.reject(Reject::BadEscape, 0),
                }
            } else if byte == esc.escape {
                self.inner_dead = state | ESCAPED;
                continue;
            } else {
                byte
            };
            if !self.push(unescaped) {
                return self.reject(Reject::BadLength, 0);
            }
        }
    }

    /// With no candidate: skips the bytes before the next flag (a `Skipped` step), or opens a
    /// candidate at it (`None`: go on).
    fn hunt(&mut self, esc: Escape<'_>, input: &mut &[u8]) -> Option<Step> {
        self.start = 0;
        self.end = 0;
        if input.is_empty() {
            return Some(Step::Idle);
        }
        let skip = input
            .iter()
            .position(|b| *b == esc.flag)
            .unwrap_or(input.len());
        let offset = self.position;
        if skip > 0 {
            self.consume(input, skip);
            self.stats.skipped_bytes = self.stats.skipped_bytes.wrapping_add(skip as u64);
            return Some(Step::Skipped { offset, len: skip });
        }
        self.consume(input, 1);
        self.open(esc.flag, offset, 0);
        None
    }

    /// Starts a candidate at a flag at stream offset `offset`.
    fn open(&mut self, flag: u8, offset: u64, state: usize) {
        self.start = 0;
        self.end = 0;
        self.inner_owner = offset;
        self.inner_dead = state;
        // (A buffer of no bytes holds no candidate: every one is then too long.)
        let _ = self.push(flag);
    }

    /// Appends an unescaped byte to the candidate; `false` if the candidate would be longer
    /// than a frame may be.
    fn push(&mut self, byte: u8) -> bool {
        if self.end.saturating_sub(self.start) >= self.limit() {
            return false;
        }
        if self.end >= N {
            self.buf.copy_within(self.start..self.end, 0);
            self.end = self.end.saturating_sub(self.start);
            self.start = 0;
        }
        match self.buf.get_mut(self.end) {
            Some(slot) => {
                *slot = byte;
                self.end = self.end.wrapping_add(1);
                true
            }
            None => false,
        }
    }

    /// The input ran out inside a candidate: it waits for more, unless the input is declared
    /// ended (then it is truncated, or, a lone flag, skipped).
    fn input_ended(&mut self, at_end: bool) -> Step {
        if !at_end {
            return Step::Idle;
        }
        if self.end.saturating_sub(self.start) == 1 && self.inner_dead & ESCAPED == 0 {
            return self.drop_lone_flag();
        }
        self.reject(Reject::Truncated, 0)
    }

    /// A lone flag (idle fill, or the flag after a frame that no frame follows): skipped
    /// unless it was counted with the frame it closed.
    fn drop_lone_flag(&mut self) -> Step {
        let offset = self.inner_owner;
        let counted = self.inner_dead & COUNTED != 0;
        self.start = 0;
        self.end = 0;
        if counted {
            return Step::Idle;
        }
        self.stats.skipped_bytes = self.stats.skipped_bytes.wrapping_add(1);
        Step::Skipped { offset, len: 1 }
    }

    /// A flag (just consumed) closes the candidate: a frame if the ordinary rules accept its
    /// unescaped bytes, else a rejection; the flag opens the next candidate either way. `None`
    /// when there is nothing to report (a lone flag counted with the frame it closed).
    fn close(&mut self, esc: Escape<'_>) -> Option<Step> {
        let flag_at = self.position.wrapping_sub(1);
        let lone = self.end.saturating_sub(self.start) == 1;
        if self.inner_dead & ESCAPED != 0 {
            return Some(self.reject_closed(esc, Reject::BadEscape, flag_at));
        }
        if lone {
            let step = self.drop_lone_flag();
            self.open(esc.flag, flag_at, 0);
            return match step {
                Step::Idle => None,
                step => Some(step),
            };
        }
        if !self.push(esc.flag) {
            return Some(self.reject_closed(esc, Reject::BadLength, flag_at));
        }
        let len = self.end.saturating_sub(self.start);
        let readable = self.buf.get(self.start..).unwrap_or_default();
        let verdict = probe(&self.layout, readable, len, self.limit());
        Some(match verdict {
            Probe::Frame(n) if n == len => self.frame(esc, flag_at),
            Probe::Reject(reason) => self.reject_closed(esc, reason, flag_at),
            Probe::Frame(_) | Probe::Need(_) => self.reject_closed(esc, Reject::BadLength, flag_at),
        })
    }

    /// The candidate is a frame: counted, yielded from the buffer, and its closing flag (its
    /// last byte, counted with it) opens the next candidate.
    fn frame(&mut self, esc: Escape<'_>, flag_at: u64) -> Step {
        let offset = self.inner_owner;
        let wire = self.uncounted(0);
        self.stats.frames = self.stats.frames.wrapping_add(1);
        self.stats.frame_bytes = self.stats.frame_bytes.wrapping_add(wire);
        let (start, end) = (self.start, self.end);
        // The next candidate is the frame's last byte, the flag; it stays in place while the
        // caller holds the frame (the next bytes go behind it).
        self.start = end.saturating_sub(1);
        self.inner_owner = flag_at;
        self.inner_dead = COUNTED;
        // `debug_assert!`, not `debug_assert_eq!`: the latter prints both sides with `Debug`,
        // which links the formatting machinery into every debug firmware, escaped or not.
        debug_assert!(
            self.buf.get(self.start) == Some(&esc.flag),
            "the flag stays in place"
        );
        Step::Buffered {
            start,
            end,
            offset,
            format: 0,
        }
    }

    /// A closed candidate is rejected; its closing flag opens the next one.
    fn reject_closed(&mut self, esc: Escape<'_>, reason: Reject, flag_at: u64) -> Step {
        let step = self.reject(reason, 1);
        self.open(esc.flag, flag_at, 0);
        step
    }

    /// Rejects the candidate for `reason`: its bytes on the wire up to the position, but for
    /// the last `keep` (a closing flag that opens the next candidate), are skipped.
    fn reject(&mut self, reason: Reject, keep: u64) -> Step {
        let offset = self.inner_owner;
        let skipped = self.uncounted(keep);
        self.start = 0;
        self.end = 0;
        self.inner_dead = 0;
        self.stats.count_reject(reason);
        // (`count_reject` counted one byte.)
        let rest = skipped.saturating_sub(1);
        self.stats.skipped_bytes = self.stats.skipped_bytes.wrapping_add(rest);
        Step::Rejected { offset, reason }
    }

    /// [`pending`](Self::pending) for an escaped format: the open candidate's bytes on the
    /// wire not counted yet.
    pub(super) fn escaped_pending(&self) -> usize {
        if self.start >= self.end {
            return 0;
        }
        usize::try_from(self.uncounted(0)).unwrap_or(usize::MAX)
    }

    /// Bytes of the candidate on the wire not counted yet, up to the position less `keep`.
    fn uncounted(&self, keep: u64) -> u64 {
        let counted = u64::from(self.inner_dead & COUNTED != 0);
        self.position
            .wrapping_sub(self.inner_owner)
            .saturating_sub(keep)
            .saturating_sub(counted)
    }
}
