//! The session client over tokio (the `tokio` feature): a task that holds a [`Requester`] on
//! any `AsyncRead + AsyncWrite` byte stream (a serial port, a pseudo-terminal, a socket), so
//! that [`Client::request`] resolves to exactly one [`Reply`]: the answer, the spec's NACK, or a
//! timeout after the spec's retries. Frames that answer no request flow to a channel; what a
//! request hears before it resolves (an answer that says it is in progress, each answer of a
//! request of several) flows to the request's own channel ([`Client::request_watched`]).
//!
//! This module owns the I/O and the clock around the sans-IO machine: it reads the stream
//! through the engine ([`StreamDecoder`]), gives each frame and the passing of time (tokio's
//! clock, in milliseconds since the client started) to the requester, writes what it asks to
//! send, and queues requests the requester cannot take yet (its slots are full, its window is
//! wide, or an answer could not be told from an open request's) until an outcome frees room.
//! Matching, numbering, retries and the handshake are the requester's.
//!
//! ```no_run
//! # async fn run(port: tokio::io::DuplexStream) -> Result<(), Box<dyn std::error::Error>> {
//! protocol_kit::protocol!("../specs/hflink.toml");
//! use hflink::{ChassisCoord, Header, Message, Packet, Request, Response};
//! use protocol_kit::session::client::{Client, Reply};
//!
//! // `port`: a serial port (`tokio_serial::SerialStream`), a socket, a pipe.
//! // 4 requests open at once, frames of at most MAX_FRAME_LEN bytes.
//! let (client, mut unsolicited) =
//!     Client::spawn::<_, 4, { hflink::MAX_FRAME_LEN }>(port, hflink::Session);
//! let to_slave = Header { sender: 0x01, receiver: 0x11 };
//! let request = |r| Packet { header: to_slave, message: Message::Request(r) };
//!
//! let here = ChassisCoord { x: 0.0, y: 0.0, z: 0.0 };
//! client.request(&request(Request::ShakingHands(here))).await?;
//! match client.request(&request(Request::ReadRobotSpeed)).await? {
//!     Reply::Answered(frame) => match Packet::from_frame(&frame)?.message {
//!         Message::Response(Response::ReadRobotSpeed(speed)) => println!("{speed:?}"),
//!         other => println!("another answer: {other:?}"),
//!     },
//!     Reply::Refused(_) => println!("not handshaken"),
//!     Reply::Rejected { value, .. } => println!("refused with result {value}"),
//!     Reply::TimedOut => println!("no answer after the retries"),
//!     Reply::AnsweredAll(_) | Reply::Incomplete { .. } => unreachable!("one answer"),
//!     Reply::Sent => unreachable!("a READ expects its reply"),
//! }
//! while let Ok(frame) = unsolicited.try_recv() {
//!     println!("unsolicited: {:?}", Packet::from_frame(&frame));
//! }
//! # Ok(())
//! # }
//! ```

use std::collections::VecDeque;
use std::fmt;
use std::future::Future;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::vec::Vec;

use tokio::io::{AsyncRead, AsyncReadExt, AsyncWrite, AsyncWriteExt};
use tokio::sync::{mpsc, oneshot};
use tokio::time::Instant;

use super::{
    Due, Outcome, Received, Requester, Resolution, SendError, SessionLayout, SessionRef, Ticket,
};
use crate::decoder::{HOST_BUFFER_LEN, StreamDecoder};
use crate::error::EncodeError;
use crate::packet::EncodePacket;

/// How a request ended: its one outcome.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum Reply {
    /// Its answer arrived: the answer's frame (an acknowledgement, the reply, or the command
    /// the spec says answers it).
    Answered(Vec<u8>),
    /// The spec's NACK command, or an error reply of its command (a frame of an empty
    /// direction: MSP's `!`), refused it: that frame.
    Refused(Vec<u8>),
    /// Its answer arrived with a result value that is not a success (the command's
    /// `result`): the value and the answer's frame.
    Rejected {
        /// The answer's result value.
        value: u64,
        /// The answer's frame.
        frame: Vec<u8>,
    },
    /// No answer came within its timeout and retries.
    TimedOut,
    /// A request answered once by each id it lists: every answer's frame, in arrival order.
    AnsweredAll(Vec<Vec<u8>>),
    /// A request answered once by each id it lists timed out after its retries with some of
    /// its answers.
    Incomplete {
        /// The frames of the answers that came, in arrival order.
        frames: Vec<Vec<u8>>,
        /// The ids that did not answer, in increasing order.
        missing: Vec<u8>,
    },
    /// The request expects no answer: it was sent once.
    Sent,
}

/// What a request hears before it resolves ([`Client::request_watched`]).
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum Update {
    /// An answer whose result value says the request is being carried out (the command's
    /// `result` `progress`): the request waits on for the answer that ends it.
    Progress {
        /// The answer's result value.
        value: u64,
        /// The answer's frame.
        frame: Vec<u8>,
    },
    /// One answer of a request answered once by each id it lists, others still to come.
    Partial {
        /// The id of the device that answered.
        id: u8,
        /// The answer's frame.
        frame: Vec<u8>,
    },
}

/// What a request hears before it resolves, in arrival order; the channel closes when the
/// request resolves.
pub type Updates = mpsc::UnboundedReceiver<Update>;

/// Why a request has no [`Reply`].
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum ClientError {
    /// The requester refuses the request (the handshake must come first, the frame is not a
    /// request of the format or does not fit a slot); nothing was sent.
    Send(SendError),
    /// The packet does not encode.
    Encode(EncodeError),
    /// The stream failed or closed; the client's task has ended.
    Closed(std::io::ErrorKind),
}

impl fmt::Display for ClientError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ClientError::Send(e) => write!(f, "request refused by the requester: {e:?}"),
            ClientError::Encode(e) => write!(f, "request not encoded: {e}"),
            ClientError::Closed(kind) => write!(f, "the link closed: {kind}"),
        }
    }
}

impl std::error::Error for ClientError {}

/// What the task tallies, for the application to read at any time.
#[derive(Debug, Default)]
struct Tally {
    retries: AtomicU64,
}

/// Where a request's reply and updates go.
struct Answer {
    reply: oneshot::Sender<Result<Reply, ClientError>>,
    updates: Option<mpsc::UnboundedSender<Update>>,
}

impl Answer {
    fn send(self, reply: Result<Reply, ClientError>) {
        let _ = self.reply.send(reply);
    }
}

/// A request the requester holds open: where its reply goes, and the answers heard so far of
/// a request of several answers.
struct Waiting {
    ticket: Ticket,
    answer: Answer,
    several: bool,
    parts: Vec<Vec<u8>>,
}

/// What a [`Client`] asks of its task.
enum Order {
    /// A request, through the requester.
    Request { frame: Vec<u8>, reply: Answer },
    /// Bytes written as they are, past the requester.
    Raw {
        bytes: Vec<u8>,
        done: oneshot::Sender<Result<(), ClientError>>,
    },
}

/// The frames that answer no open request (unsolicited messages, answers that came after
/// their request resolved), in arrival order.
pub type Unsolicited = mpsc::UnboundedReceiver<Vec<u8>>;

/// A handle on the session's task: cheap to clone, usable from several tasks at once (their
/// requests are open together, up to the requester's slots and window).
#[derive(Debug, Clone)]
pub struct Client {
    orders: mpsc::UnboundedSender<Order>,
    tally: Arc<Tally>,
}

impl Client {
    /// Starts the session's task on the current tokio runtime over `io`, with a requester of
    /// `SLOTS` open requests of frames of at most `FRAME` bytes (a generated module's
    /// `MAX_FRAME_LEN` fits its frames). Returns the client and the channel of unsolicited
    /// frames. The task ends when every client is dropped or the stream fails. `rules` is a
    /// generated module's `Session` or a `&'static SessionRules` ([`SessionRef`]).
    pub fn spawn<T, const SLOTS: usize, const FRAME: usize>(
        io: T,
        rules: impl SessionRef + Send + Sync + 'static,
    ) -> (Client, Unsolicited)
    where
        T: AsyncRead + AsyncWrite + Send + 'static,
    {
        let (orders, inbox) = mpsc::unbounded_channel();
        let (unsolicited, frames) = mpsc::unbounded_channel();
        let tally = Arc::new(Tally::default());
        let task = Task::<_, SLOTS, FRAME> {
            requester: Requester::new(rules),
            decoder: StreamDecoder::new(SessionLayout(rules)),
            start: Instant::now(),
            waiting: Vec::new(),
            queued: VecDeque::new(),
            unsolicited,
            tally: Arc::clone(&tally),
        };
        tokio::spawn(task.run(io, inbox));
        (Client { orders, tally }, frames)
    }

    /// Encodes `packet` and hands it to the session's task as a request, at once (requests
    /// go out in the order of these calls); the future resolves to its one [`Reply`]. The
    /// future borrows nothing: requests made one after the other can be awaited together.
    ///
    /// # Errors
    /// [`ClientError`]: the packet does not encode, the requester refuses it, or the link
    /// closed.
    pub fn request<P: EncodePacket>(
        &self,
        packet: &P,
    ) -> impl Future<Output = Result<Reply, ClientError>> + Send + 'static {
        let mut frame = std::vec![0u8; packet.encoded_len()];
        let encoded = packet.encode_into(&mut frame).map(|n| {
            frame.truncate(n);
            frame
        });
        let sent = encoded
            .map_err(ClientError::Encode)
            .map(|frame| self.request_frame(frame));
        async move { sent?.await }
    }

    /// Hands `frame` (a request of the format, encoded; the requester numbers and seals it)
    /// to the session's task as a request, at once; the future resolves to its one [`Reply`].
    ///
    /// # Errors
    /// As [`request`](Self::request).
    pub fn request_frame(
        &self,
        frame: Vec<u8>,
    ) -> impl Future<Output = Result<Reply, ClientError>> + Send + 'static {
        self.order_request(frame, None)
    }

    /// As [`request`](Self::request), and what the request hears before it resolves flows to
    /// the returned channel: an answer that says it is in progress (MAVLink's COMMAND_ACK
    /// `IN_PROGRESS`), each answer of a request answered once by each id it lists.
    ///
    /// # Errors
    /// As [`request`](Self::request), from the future.
    pub fn request_watched<P: EncodePacket>(
        &self,
        packet: &P,
    ) -> (
        impl Future<Output = Result<Reply, ClientError>> + Send + 'static,
        Updates,
    ) {
        let (updates, watched) = mpsc::unbounded_channel();
        let mut frame = std::vec![0u8; packet.encoded_len()];
        let encoded = packet.encode_into(&mut frame).map(|n| {
            frame.truncate(n);
            frame
        });
        let sent = encoded
            .map_err(ClientError::Encode)
            .map(|frame| self.order_request(frame, Some(updates)));
        (async move { sent?.await }, watched)
    }

    fn order_request(
        &self,
        frame: Vec<u8>,
        updates: Option<mpsc::UnboundedSender<Update>>,
    ) -> impl Future<Output = Result<Reply, ClientError>> + Send + 'static {
        let (reply, answer) = oneshot::channel();
        let ordered = self.order(Order::Request {
            frame,
            reply: Answer { reply, updates },
        });
        async move {
            ordered?;
            answer.await.unwrap_or(Err(CLOSED))
        }
    }

    /// Writes `bytes` as they are, past the requester: no number, no seal, no wait for an
    /// answer (whatever comes back is unsolicited). For what the session would refuse to send,
    /// such as a request before the handshake when testing a device.
    ///
    /// # Errors
    /// [`ClientError::Closed`] when the link closed.
    pub fn send_raw(
        &self,
        bytes: Vec<u8>,
    ) -> impl Future<Output = Result<(), ClientError>> + Send + 'static {
        let (done, written) = oneshot::channel();
        let ordered = self.order(Order::Raw { bytes, done });
        async move {
            ordered?;
            written.await.unwrap_or(Err(CLOSED))
        }
    }

    /// Requests sent again since the client started (each retry the requester asked for).
    #[must_use]
    pub fn retries(&self) -> u64 {
        self.tally.retries.load(Ordering::Relaxed)
    }

    fn order(&self, order: Order) -> Result<(), ClientError> {
        self.orders.send(order).map_err(|_| CLOSED)
    }
}

/// The error of a task that has ended.
const CLOSED: ClientError = ClientError::Closed(std::io::ErrorKind::BrokenPipe);

/// The session's task: the requester, the engine, and the requests it holds.
struct Task<S: SessionRef, const SLOTS: usize, const FRAME: usize> {
    requester: Requester<S, SLOTS, FRAME>,
    decoder: StreamDecoder<SessionLayout<S>, HOST_BUFFER_LEN>,
    start: Instant,
    /// Requests the requester holds open.
    waiting: Vec<Waiting>,
    /// Requests the requester cannot take yet, in the order they came.
    queued: VecDeque<(Vec<u8>, Answer)>,
    unsolicited: mpsc::UnboundedSender<Vec<u8>>,
    tally: Arc<Tally>,
}

/// What woke the task.
enum Wake {
    Order(Option<Order>),
    Read(std::io::Result<usize>),
    Due,
}

impl<S: SessionRef, const SLOTS: usize, const FRAME: usize> Task<S, SLOTS, FRAME> {
    /// The loop: orders in, bytes in, deadlines; until the clients are gone or the stream
    /// fails (every request still waiting then resolves to [`ClientError::Closed`]).
    async fn run<T: AsyncRead + AsyncWrite>(
        mut self,
        io: T,
        mut inbox: mpsc::UnboundedReceiver<Order>,
    ) {
        let (mut rd, mut wr) = tokio::io::split(io);
        let mut buf = [0u8; 512];
        let ended = loop {
            let deadline = self.requester.next_deadline();
            let wait = std::time::Duration::from_millis(deadline.unwrap_or(0));
            let at = self.start.checked_add(wait).unwrap_or(self.start);
            let wake = tokio::select! {
                order = inbox.recv() => Wake::Order(order),
                read = rd.read(&mut buf) => Wake::Read(read),
                () = tokio::time::sleep_until(at), if deadline.is_some() => Wake::Due,
            };
            let step = match wake {
                Wake::Order(None) => break std::io::ErrorKind::BrokenPipe,
                Wake::Order(Some(order)) => self.take(order, &mut wr).await,
                Wake::Read(Ok(0)) => Err(std::io::ErrorKind::UnexpectedEof),
                Wake::Read(Ok(n)) => self.heard(buf.get(..n).unwrap_or_default()),
                Wake::Read(Err(e)) => Err(e.kind()),
                Wake::Due => Ok(()),
            };
            if let Err(kind) = self.settle(step, &mut wr).await {
                break kind;
            }
        };
        for w in self.waiting.drain(..) {
            w.answer.send(Err(ClientError::Closed(ended)));
        }
        for (_, reply) in self.queued.drain(..) {
            reply.send(Err(ClientError::Closed(ended)));
        }
    }

    /// After every event: what time asks for (retries, timeouts), then the queued requests
    /// the outcomes made room for.
    async fn settle<W: AsyncWrite + Unpin>(
        &mut self,
        step: Result<(), std::io::ErrorKind>,
        wr: &mut W,
    ) -> Result<(), std::io::ErrorKind> {
        step?;
        self.due(wr).await?;
        self.unqueue(wr).await
    }

    fn now(&self) -> u64 {
        u64::try_from(self.start.elapsed().as_millis()).unwrap_or(u64::MAX)
    }

    /// An order of a client.
    async fn take<W: AsyncWrite + Unpin>(
        &mut self,
        order: Order,
        wr: &mut W,
    ) -> Result<(), std::io::ErrorKind> {
        match order {
            Order::Raw { bytes, done } => {
                let written = write(wr, &bytes).await;
                let _ = done.send(written.map_err(ClientError::Closed));
                written
            }
            Order::Request { frame, reply } if self.queued.is_empty() => {
                self.send(frame, reply, wr).await
            }
            Order::Request { frame, reply } => {
                self.queued.push_back((frame, reply));
                Ok(())
            }
        }
    }

    /// Gives a request to the requester and writes it; queues it first in line when the
    /// requester has no room for it yet.
    async fn send<W: AsyncWrite + Unpin>(
        &mut self,
        mut frame: Vec<u8>,
        reply: Answer,
        wr: &mut W,
    ) -> Result<(), std::io::ErrorKind> {
        match self.requester.send(self.now(), &mut frame) {
            Err(SendError::Full | SendError::Window | SendError::Ambiguous) => {
                self.queued.push_front((frame, reply));
                return Ok(());
            }
            Err(e) => {
                reply.send(Err(ClientError::Send(e)));
                return Ok(());
            }
            Ok(Some(ticket)) => self.waiting.push(Waiting {
                ticket,
                answer: reply,
                several: self.requester.several(ticket),
                parts: Vec::new(),
            }),
            Ok(None) => reply.send(Ok(Reply::Sent)),
        }
        write(wr, &frame).await
    }

    /// Sends the queued requests, in order, while the requester takes them.
    async fn unqueue<W: AsyncWrite + Unpin>(
        &mut self,
        wr: &mut W,
    ) -> Result<(), std::io::ErrorKind> {
        while let Some((frame, reply)) = self.queued.pop_front() {
            let before = self.queued.len();
            self.send(frame, reply, wr).await?;
            if self.queued.len() > before {
                break;
            }
        }
        Ok(())
    }

    /// Bytes read: every frame the engine finds goes to the requester.
    fn heard(&mut self, mut input: &[u8]) -> Result<(), std::io::ErrorKind> {
        loop {
            let Some(frame) = self.decoder.decode(&mut input) else {
                return Ok(());
            };
            let frame = frame.bytes.to_vec();
            match self.requester.on_frame(self.now(), &frame) {
                Received::Outcome(outcome) => self.resolve(outcome, Some(frame)),
                // The request waits on for the answer that ends it.
                Received::Progress { ticket, value } => {
                    self.update(ticket, Update::Progress { value, frame });
                }
                Received::Partial { ticket, id, .. } => {
                    if let Some(w) = self.waiting.iter_mut().find(|w| w.ticket == ticket) {
                        w.parts.push(frame.clone());
                    }
                    self.update(ticket, Update::Partial { id, frame });
                }
                Received::Unsolicited | Received::Unreadable(_) => {
                    let _ = self.unsolicited.send(frame);
                }
            }
        }
    }

    /// What the passing of time asks for: retries written, timeouts resolved.
    async fn due<W: AsyncWrite + Unpin>(&mut self, wr: &mut W) -> Result<(), std::io::ErrorKind> {
        loop {
            let now = self.now();
            let resend = match self.requester.poll(now) {
                None => return Ok(()),
                Some(Due::Resend { frame, .. }) => frame.to_vec(),
                Some(Due::Outcome(outcome)) => {
                    self.resolve(outcome, None);
                    continue;
                }
            };
            self.tally.retries.fetch_add(1, Ordering::Relaxed);
            write(wr, &resend).await?;
        }
    }

    /// Hands a request's reply to its caller: its outcome, with the frame that resolved it
    /// (none for a timeout).
    fn resolve(&mut self, outcome: Outcome, frame: Option<Vec<u8>>) {
        let Some(i) = self.waiting.iter().position(|w| w.ticket == outcome.ticket) else {
            return;
        };
        let Waiting {
            answer,
            several,
            mut parts,
            ..
        } = self.waiting.swap_remove(i);
        let frame = frame.unwrap_or_default();
        let reply = match outcome.resolution {
            Resolution::Answered if !several => Reply::Answered(frame),
            Resolution::Answered => {
                parts.push(frame);
                Reply::AnsweredAll(parts)
            }
            Resolution::Refused => Reply::Refused(frame),
            Resolution::Rejected(value) => Reply::Rejected { value, frame },
            Resolution::TimedOut => Reply::TimedOut,
            Resolution::Incomplete(missing) => Reply::Incomplete {
                frames: parts,
                missing: missing.iter().collect(),
            },
        };
        answer.send(Ok(reply));
    }

    /// Hands what a request heard to its caller's channel, when it watches.
    fn update(&self, ticket: Ticket, update: Update) {
        let watcher = self.waiting.iter().find(|w| w.ticket == ticket);
        if let Some(tx) = watcher.and_then(|w| w.answer.updates.as_ref()) {
            let _ = tx.send(update);
        }
    }
}

/// Writes `bytes` whole and flushes.
async fn write<W: AsyncWrite + Unpin>(wr: &mut W, bytes: &[u8]) -> Result<(), std::io::ErrorKind> {
    wr.write_all(bytes).await.map_err(|e| e.kind())?;
    wr.flush().await.map_err(|e| e.kind())
}
