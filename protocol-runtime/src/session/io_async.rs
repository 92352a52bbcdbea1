//! The requester over `embedded-io-async` (the `embedded-io-async` feature), for firmware:
//! [`Link::request`] sends a request on a writer and reads the reader until the request
//! resolves to its one [`Reply`] (its answer, the spec's NACK, or a timeout after its
//! retries), resending as the requester says. `no_std`, no heap: the answer is copied into
//! the caller's buffer, frames that answer nothing go to the caller's closure, and time comes
//! from a [`Clock`] the firmware implements over its timer (embassy's `Instant` and `Timer`,
//! a HAL's monotonic counter).
//!
//! This module owns the loop between a read, a deadline and the machine; matching, numbering,
//! retries and the handshake are the [`Requester`]'s, finding frames is the engine's. One
//! request is open at a time (a firmware's request waits for its answer); the machine's slots
//! and window still bound the numbers of requests that expect no answer.

use core::future::{Future, poll_fn};
use core::pin::pin;
use core::task::Poll;

use embedded_io_async::{Read, Write};

use super::{
    Due, IdSet, Received, Requester, Resolution, SendError, SessionLayout, SessionRef, Ticket,
};
use crate::decoder::StreamDecoder;

/// A monotonic clock in milliseconds, and a wait until an instant of it.
pub trait Clock {
    /// Milliseconds since an arbitrary start; never decreases.
    fn now_ms(&self) -> u64;

    /// Completes once [`now_ms`](Self::now_ms) reaches `at`.
    fn wait_until(&mut self, at: u64) -> impl Future<Output = ()>;
}

/// How a request ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Reply {
    /// Its answer arrived: its frame is the first `len` bytes of the caller's buffer.
    Answered {
        /// Bytes of the answer's frame.
        len: usize,
    },
    /// The spec's NACK, or an error reply of its command (a frame of an empty direction),
    /// refused it: that frame is the first `len` bytes of the caller's buffer.
    Refused {
        /// Bytes of the refusing frame.
        len: usize,
    },
    /// Its answer arrived with a result value that is not a success (the command's
    /// `result`): its frame is the first `len` bytes of the caller's buffer.
    Rejected {
        /// The answer's result value.
        value: u64,
        /// Bytes of the answer's frame.
        len: usize,
    },
    /// No answer came within its timeout and retries.
    TimedOut,
    /// A request answered once by each id it lists timed out with some of its answers (each
    /// went to the caller's closure as it came): the ids that did not answer.
    Incomplete {
        /// The ids that did not answer.
        missing: IdSet,
    },
    /// The request expects no answer: it was sent once.
    Sent,
}

/// Why a request has no [`Reply`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum LinkError<R, W> {
    /// The requester refuses the request; nothing was sent.
    Send(SendError),
    /// The answer is longer than the caller's buffer.
    AnswerTooLong,
    /// The reader failed, or ended.
    Read(Option<R>),
    /// The writer failed.
    Write(W),
}

/// A requester on a reader and a writer: a read buffer of `B` bytes, an engine of `N`, a
/// requester of `SLOTS` slots of `FRAME` bytes, over the rules `S` finds ([`SessionRef`]: a
/// generated module's `Session`, or a `&SessionRules`).
///
/// The reader's `read` is cancelled when a deadline comes first: it must lose no bytes when
/// dropped (the buffered UART readers of embassy's HALs do not).
pub struct Link<
    S: SessionRef,
    R,
    W,
    C,
    const SLOTS: usize,
    const FRAME: usize,
    const N: usize,
    const B: usize,
> {
    reader: R,
    writer: W,
    clock: C,
    requester: Requester<S, SLOTS, FRAME>,
    decoder: StreamDecoder<SessionLayout<S>, N>,
    buf: [u8; B],
    start: usize,
    end: usize,
}

impl<
    S: SessionRef,
    R: Read,
    W: Write,
    C: Clock,
    const SLOTS: usize,
    const FRAME: usize,
    const N: usize,
    const B: usize,
> Link<S, R, W, C, SLOTS, FRAME, N, B>
{
    /// A link of `rules` on `reader` and `writer`, timed by `clock`.
    pub fn new(rules: S, reader: R, writer: W, clock: C) -> Self {
        Link {
            reader,
            writer,
            clock,
            requester: Requester::new(rules),
            decoder: StreamDecoder::new(SessionLayout(rules)),
            buf: [0; B],
            start: 0,
            end: 0,
        }
    }

    /// The requester (its handshake, its open requests).
    pub fn requester(&self) -> &Requester<S, SLOTS, FRAME> {
        &self.requester
    }

    /// Sends the request `frame` (encoded; numbered and sealed here) and waits for its one
    /// [`Reply`]; an answer or a NACK is copied into `answer`. Every other frame read
    /// meanwhile goes to `other` (an answer that says the request is in progress too: the
    /// request waits on; and, for a request answered once by each id it lists, every answer
    /// but the last, which resolves it).
    ///
    /// # Errors
    /// [`LinkError`]; a read or write error leaves the request open in the requester, to
    /// time out on a later call.
    pub async fn request(
        &mut self,
        frame: &mut [u8],
        answer: &mut [u8],
        mut other: impl FnMut(&[u8]),
    ) -> Result<Reply, LinkError<R::Error, W::Error>> {
        let now = self.clock.now_ms();
        let sent = self.requester.send(now, frame).map_err(LinkError::Send)?;
        self.writer
            .write_all(frame)
            .await
            .map_err(LinkError::Write)?;
        self.writer.flush().await.map_err(LinkError::Write)?;
        let Some(ticket) = sent else {
            return Ok(Reply::Sent);
        };
        loop {
            if let Some(reply) = self.scan(ticket, answer, &mut other)? {
                return Ok(reply);
            }
            if let Some(reply) = self.due(ticket).await? {
                return Ok(reply);
            }
            self.read_until_deadline().await?;
        }
    }

    /// The frames in the bytes read so far: `ticket`'s reply when one resolves it.
    fn scan(
        &mut self,
        ticket: Ticket,
        answer: &mut [u8],
        other: &mut impl FnMut(&[u8]),
    ) -> Result<Option<Reply>, LinkError<R::Error, W::Error>> {
        loop {
            let mut input = self.buf.get(self.start..self.end).unwrap_or_default();
            let before = input.len();
            let frame = self.decoder.decode(&mut input);
            self.start = self
                .start
                .saturating_add(before.saturating_sub(input.len()));
            let Some(frame) = frame else {
                return Ok(None);
            };
            let now = self.clock.now_ms();
            let outcome = match self.requester.on_frame(now, frame.bytes) {
                Received::Outcome(o) if o.ticket == ticket => o,
                _ => {
                    other(frame.bytes);
                    continue;
                }
            };
            let len = frame.bytes.len();
            answer
                .get_mut(..len)
                .ok_or(LinkError::AnswerTooLong)?
                .copy_from_slice(frame.bytes);
            return Ok(Some(match outcome.resolution {
                Resolution::Answered => Reply::Answered { len },
                Resolution::Refused => Reply::Refused { len },
                Resolution::Rejected(value) => Reply::Rejected { value, len },
                Resolution::TimedOut => Reply::TimedOut,
                Resolution::Incomplete(missing) => Reply::Incomplete { missing },
            }));
        }
    }

    /// What time asks for: retries written; `ticket`'s timeout when it comes.
    async fn due(
        &mut self,
        ticket: Ticket,
    ) -> Result<Option<Reply>, LinkError<R::Error, W::Error>> {
        loop {
            match self.requester.poll(self.clock.now_ms()) {
                None => return Ok(None),
                Some(Due::Resend { frame, .. }) => {
                    self.writer
                        .write_all(frame)
                        .await
                        .map_err(LinkError::Write)?;
                    self.writer.flush().await.map_err(LinkError::Write)?;
                }
                Some(Due::Outcome(o)) if o.ticket == ticket => {
                    return Ok(Some(match o.resolution {
                        Resolution::Incomplete(missing) => Reply::Incomplete { missing },
                        _ => Reply::TimedOut,
                    }));
                }
                Some(Due::Outcome(_)) => {}
            }
        }
    }

    /// Reads into the buffer, or returns when the requester's next deadline comes first.
    async fn read_until_deadline(&mut self) -> Result<(), LinkError<R::Error, W::Error>> {
        let at = self.requester.next_deadline();
        let mut read = pin!(self.reader.read(&mut self.buf));
        let mut wait = pin!(async {
            match at {
                Some(at) => self.clock.wait_until(at).await,
                None => core::future::pending().await,
            }
        });
        let n = poll_fn(|cx| {
            if let Poll::Ready(r) = read.as_mut().poll(cx) {
                return Poll::Ready(Some(r));
            }
            if wait.as_mut().poll(cx).is_ready() {
                return Poll::Ready(None);
            }
            Poll::Pending
        })
        .await;
        match n {
            None => Ok(()),
            Some(Ok(0)) => Err(LinkError::Read(None)),
            Some(Ok(n)) => {
                self.start = 0;
                self.end = n.min(B);
                Ok(())
            }
            Some(Err(e)) => Err(LinkError::Read(Some(e))),
        }
    }
}

impl<S, R, W, C, const SLOTS: usize, const FRAME: usize, const N: usize, const B: usize>
    core::fmt::Debug for Link<S, R, W, C, SLOTS, FRAME, N, B>
where
    S: SessionRef + core::fmt::Debug,
{
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Link")
            .field("requester", &self.requester)
            .field("unscanned", &self.end.saturating_sub(self.start))
            .finish_non_exhaustive()
    }
}
