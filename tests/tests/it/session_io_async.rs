//! The requester over `embedded-io-async` (`session::io_async::Link`), as firmware runs it: an
//! in-memory UART whose other end is a device holding the runtime's `Responder`, a simulated
//! clock whose waits complete at once (time jumps to the deadline), and a minimal executor
//! (`embassy_futures::block_on`). The device drops the frames it is told to; the link must
//! retry at exactly the spec's deadlines, resolve each request to exactly one reply, and the
//! device must deliver no request twice.

use core::cell::{Cell, RefCell};
use core::convert::Infallible;
use core::future::{Future, pending};
use std::rc::Rc;

use embassy_futures::block_on;
use protocol_kit::embedded_io_async::{ErrorType, Read, Write};
use protocol_kit::session::io_async::{Clock, Link, LinkError, Reply};
use protocol_kit::session::{Incoming, Responder, SendError, SessionRules};
use protocol_kit::{FrameLayout, StreamDecoder};

protocol_kit::protocol!("../specs/roborts.toml");
protocol_kit::protocol!("../specs/hflink.toml");

/// The device at the other end of the UART, and what it saw.
struct Device {
    responder: Responder<&'static SessionRules<'static>, 8, 64>,
    decoder: StreamDecoder<&'static FrameLayout<'static>, 256>,
    /// Bytes for the host to read.
    out: Vec<u8>,
    /// Frames received (each copy of each request), and which of them to drop (by count).
    received: usize,
    drop: fn(usize) -> bool,
    delivered: usize,
    duplicates: usize,
    /// Builds the answer to a delivered request.
    answer: fn(&[u8]) -> Vec<u8>,
}

type Shared = Rc<RefCell<Device>>;

impl Device {
    fn new(
        rules: &'static SessionRules<'static>,
        drop: fn(usize) -> bool,
        answer: fn(&[u8]) -> Vec<u8>,
    ) -> Shared {
        Rc::new(RefCell::new(Device {
            responder: Responder::new(rules),
            decoder: StreamDecoder::new(rules.packet.layout),
            out: Vec::new(),
            received: 0,
            drop,
            delivered: 0,
            duplicates: 0,
            answer,
        }))
    }

    /// Bytes the host wrote: every whole request is handled.
    fn hear(&mut self, mut bytes: &[u8]) {
        let mut frames = Vec::new();
        while let Some(frame) = self.decoder.decode(&mut bytes) {
            frames.push(frame.bytes.to_vec());
        }
        for frame in frames {
            self.received += 1;
            if (self.drop)(self.received) {
                continue;
            }
            let answer = match self.responder.on_frame(0, &frame) {
                Incoming::Deliver { answer: true } => {
                    self.delivered += 1;
                    let mut answer = (self.answer)(&frame);
                    self.responder.answer(&frame, &mut answer).expect("answers");
                    Some(answer)
                }
                Incoming::Deliver { answer: false } => {
                    self.delivered += 1;
                    None
                }
                Incoming::Duplicate(sent) => {
                    self.duplicates += 1;
                    sent.map(<[u8]>::to_vec)
                }
                other => panic!("the device got {other:?}"),
            };
            self.out.extend(answer.unwrap_or_default());
        }
    }
}

/// The host's end of the UART: reads what the device wrote (pending while there is
/// nothing), writes to the device.
struct Uart(Shared);

impl ErrorType for Uart {
    type Error = Infallible;
}

impl Read for Uart {
    async fn read(&mut self, buf: &mut [u8]) -> Result<usize, Infallible> {
        let n = {
            let mut d = self.0.borrow_mut();
            let n = d.out.len().min(buf.len());
            buf[..n].copy_from_slice(&d.out[..n]);
            d.out.drain(..n);
            n
        };
        if n == 0 {
            // Nothing on the line: the deadline's wait completes first.
            pending::<()>().await;
        }
        Ok(n)
    }
}

impl Write for Uart {
    async fn write(&mut self, buf: &[u8]) -> Result<usize, Infallible> {
        self.0.borrow_mut().hear(buf);
        Ok(buf.len())
    }

    async fn flush(&mut self) -> Result<(), Infallible> {
        Ok(())
    }
}

/// A clock whose waits end at once, at their deadline.
#[derive(Clone, Default)]
struct SimClock(Rc<Cell<u64>>);

impl Clock for SimClock {
    fn now_ms(&self) -> u64 {
        self.0.get()
    }

    fn wait_until(&mut self, at: u64) -> impl Future<Output = ()> {
        self.0.set(self.0.get().max(at));
        core::future::ready(())
    }
}

fn encoded(packet: &impl protocol_kit::EncodePacket) -> Vec<u8> {
    let mut buf = vec![0u8; packet.encoded_len()];
    let n = packet.encode_into(&mut buf).expect("encodes");
    buf.truncate(n);
    buf
}

fn rr_request(session_id: u8) -> Vec<u8> {
    use roborts::*;
    encoded(&Packet {
        header: Header {
            session_id,
            sender: 0,
            receiver: 1,
            seq_num: 0,
        },
        message: Message::Heartbeat(Heartbeat { heartbeat: 7 }),
    })
}

fn rr_ack(_request: &[u8]) -> Vec<u8> {
    use roborts::*;
    encoded(&Packet {
        header: Header {
            session_id: 0,
            sender: 1,
            receiver: 0,
            seq_num: 0,
        },
        message: Message::Ack(protocol_kit::Bytes::from_slice(&[]).expect("empty")),
    })
}

type RrLink = Link<roborts::Session, Uart, Uart, SimClock, 4, { roborts::MAX_FRAME_LEN }, 256, 32>;

fn rr_link(device: &Shared, clock: &SimClock) -> RrLink {
    Link::new(
        roborts::Session,
        Uart(Rc::clone(device)),
        Uart(Rc::clone(device)),
        clock.clone(),
    )
}

#[test]
fn roborts_retries_at_the_deadlines_and_resolves_once() {
    // The first copy of every second request is lost: the retry, 50 ms later, is answered.
    // Every copy of the last request is lost: it times out after 3 retries of 50 ms.
    let device = Device::new(&roborts::SESSION, |n| n % 3 == 2 || n >= 10, rr_ack);
    let clock = SimClock::default();
    let mut link = rr_link(&device, &clock);
    let mut answer = [0u8; 64];
    let mut others = 0;
    let mut replies = Vec::new();
    for i in 0..7u16 {
        let before = clock.now_ms();
        let mut frame = rr_request(2);
        let reply = block_on(link.request(&mut frame, &mut answer, |_| others += 1));
        let reply = reply.expect("no I/O error");
        replies.push((reply, clock.now_ms() - before));
        if let Reply::Answered { len } = reply {
            let ack = roborts::Packet::from_frame(&answer[..len]).expect("an ack");
            assert_eq!(ack.header.seq_num, i, "the ack of request {i}");
        }
    }
    // Copies received: 1, (2 lost, 3), 4, (5 lost, 6), 7, (8 lost, 9), (10 to 13 lost).
    assert_eq!(
        replies,
        [
            (Reply::Answered { len: 12 }, 0),
            (Reply::Answered { len: 12 }, 50),
            (Reply::Answered { len: 12 }, 0),
            (Reply::Answered { len: 12 }, 50),
            (Reply::Answered { len: 12 }, 0),
            (Reply::Answered { len: 12 }, 50),
            (Reply::TimedOut, 200),
        ]
    );
    let d = device.borrow();
    assert_eq!(
        (d.received, d.delivered, d.duplicates, others),
        (13, 6, 0, 0)
    );
    // Mode 0 expects nothing: sent once, numbered in turn.
    drop(d);
    let mut frame = rr_request(0);
    let reply = block_on(link.request(&mut frame, &mut answer, |_| others += 1));
    assert_eq!(reply, Ok(Reply::Sent));
}

#[test]
fn roborts_a_lost_answer_is_answered_again_not_delivered_again() {
    let device = Device::new(&roborts::SESSION, |_| false, rr_ack);
    let clock = SimClock::default();
    let mut link = rr_link(&device, &clock);
    let mut answer = [0u8; 64];
    let mut frame = rr_request(2);
    let reply = block_on(link.request(&mut frame, &mut answer, |_| {}));
    assert_eq!(reply, Ok(Reply::Answered { len: 12 }));
    // The same numbered request again (a copy the link duplicated): acknowledged again from
    // the responder's table, not delivered again.
    device.borrow_mut().hear(&frame);
    let d = device.borrow();
    assert_eq!((d.delivered, d.duplicates), (1, 1));
    assert_eq!(d.out, answer[..12]);
}

#[test]
fn hflink_refuses_a_request_before_the_handshake() {
    let device = Device::new(&hflink::SESSION, |_| false, |_| Vec::new());
    let clock = SimClock::default();
    let mut link: Link<
        hflink::Session,
        Uart,
        Uart,
        SimClock,
        4,
        { hflink::MAX_FRAME_LEN },
        256,
        32,
    > = Link::new(
        hflink::Session,
        Uart(Rc::clone(&device)),
        Uart(Rc::clone(&device)),
        clock,
    );
    let mut frame = encoded(&hflink::Packet {
        header: hflink::Header {
            sender: 0x01,
            receiver: 0x11,
        },
        message: hflink::Message::Request(hflink::Request::ReadRobotSpeed),
    });
    let mut answer = [0u8; 64];
    let reply = block_on(link.request(&mut frame, &mut answer, |_| {}));
    assert_eq!(reply, Err(LinkError::Send(SendError::Handshake)));
    assert_eq!(device.borrow().received, 0, "nothing was sent");
}
