//! Session-aware decoding of a capture: both ends of a half-duplex wire, frame by frame. A
//! frame that follows a request expecting an answer is read first as that answer (in the
//! response direction, for a spec whose frames do not tell their direction: Dynamixel 1.0's
//! status packets); otherwise it is read as a request. Each answer names the request it
//! answers and, when frames carry times, the round-trip time; requests never answered are
//! counted. The pairing is the runtime's [`Observer`], run on the spec's session rules. A
//! request that selects registers (a READ of a `[registers]` map) is remembered until its
//! answer, whose bytes are then typed by the registers it asked for ([`crate::registers`]); a
//! request answered once by each device it lists (a SYNC_READ, a BULK_READ) until its last
//! answer, each typed by the run its sender was asked for.

use std::collections::VecDeque;

use protocol_runtime::session::{Observer, Paired};

use crate::registers::{self, RegisterValues, Selected};
use crate::{Codec, DecodeIssue, Decoded};

/// Requests that wait for their answer at once; an older one is counted unanswered to make
/// room.
const OPEN: usize = 64;

/// A conversation followed through a capture.
#[derive(Debug, Clone, Default)]
pub struct Conversation {
    observer: Observer<OPEN>,
    frames: u64,
    /// The register runs of open requests that read registers, by frame number (at most
    /// `OPEN`, the oldest dropped first, as the observer drops its requests).
    selected: VecDeque<(u64, Selected)>,
}

/// One frame of the conversation.
#[derive(Debug)]
pub struct Heard {
    /// The frame's number in the conversation (from 0).
    pub index: u64,
    /// The frame, decoded.
    pub decoded: Result<Decoded, DecodeIssue>,
    /// The request it answers, when it is an answer.
    pub answers: Option<Paired>,
    /// The registers its bytes hold: a request's data it writes, or an answer's data its
    /// request read.
    pub registers: Option<RegisterValues>,
}

impl Conversation {
    /// A conversation that has heard nothing.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Answers paired so far.
    #[must_use]
    pub fn answered(&self) -> u64 {
        self.observer.answered()
    }

    /// The capture ended: how many requests went unanswered in all.
    pub fn finish(&mut self) -> u64 {
        self.observer.finish()
    }

    /// Reads `frame`, a frame of format `format` that the engine checked, heard at `at`
    /// (milliseconds, when known). `decoded` is the codec's own decoding of it, kept when the
    /// frame's header tells its direction (or the spec has none); a spec whose direction is
    /// given decodes it again in the direction the conversation picks. A frame of another
    /// format than the session's, or of a spec without `[session]`, is taken as decoded.
    pub fn hear(
        &mut self,
        codec: &Codec<'_>,
        format: usize,
        frame: &[u8],
        at: Option<u64>,
        decoded: Result<Decoded, DecodeIssue>,
    ) -> Heard {
        let index = self.frames;
        self.frames = self.frames.saturating_add(1);
        let p = codec.protocol();
        let session_frame = p.session.as_ref().map(|s| s.frame);
        if session_frame != Some(format) {
            let registers = decoded
                .as_ref()
                .ok()
                .and_then(|d| registers::of_request(p, d));
            return Heard {
                index,
                decoded,
                answers: None,
                registers,
            };
        }
        let observer = &mut self.observer;
        let answers = codec
            .with_session(|rules| observer.answer(rules, at, frame))
            .flatten();
        let given = p.directions_given();
        let decoded = match (given, answers.is_some()) {
            // The response direction answers; the request direction asks.
            (true, true) => codec.decode_frame_as(format, frame, Some(1)),
            (true, false) => codec.decode_frame_as(format, frame, Some(0)),
            (false, _) => decoded,
        };
        if answers.is_none() {
            codec.with_session(|rules| observer.request(rules, index, at, frame));
        }
        let registers = match (&decoded, answers) {
            (Ok(d), Some(a)) => self
                .runs_of(a)
                .and_then(|sel| registers::of_answer(p, &sel, d)),
            (Ok(d), None) => {
                if let Some(sel) = registers::selected(p, d) {
                    if self.selected.len() == OPEN {
                        self.selected.pop_front();
                    }
                    self.selected.push_back((index, sel));
                }
                registers::of_request(p, d)
            }
            (Err(_), _) => None,
        };
        Heard {
            index,
            decoded,
            answers,
            registers,
        }
    }

    /// The register runs the request that `answer` answers selected, forgotten once the
    /// request is answered whole (kept while it waits for the answers of other devices it
    /// lists, or for the final answer after one that says it is in progress).
    fn runs_of(&mut self, answer: Paired) -> Option<Selected> {
        let at = self
            .selected
            .iter()
            .position(|(i, _)| *i == answer.request)?;
        if answer.open {
            return self.selected.get(at).map(|(_, sel)| sel.clone());
        }
        self.selected.remove(at).map(|(_, sel)| sel)
    }
}
