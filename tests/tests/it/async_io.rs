//! The `embedded-io-async` integration: `PacketReader` over an in-memory async reader that
//! hands out a few bytes per read (and is pending every other poll, as a UART driver waiting
//! for bytes is), and `write_packet` into an in-memory async writer, run by a minimal
//! executor (`embassy_futures::block_on`).

use core::convert::Infallible;
use core::future::poll_fn;
use core::task::Poll;

use embassy_futures::block_on;
use protocol_kit::embedded_io_async::{ErrorType, Read, Write};
use protocol_kit::io_async::{PacketReader, WriteError, write_packet};
use protocol_kit::{DecodeError, EncodeError, PacketEvent, Reject};
use protocol_tests::{load_vectors, stream_vector};

protocol_kit::protocol!("../specs/hflink.toml");
protocol_kit::protocol!("../specs/referee.toml");

/// A reader of `bytes`, at most `chunk` bytes per read, pending on every other poll.
struct Uart<'a> {
    bytes: &'a [u8],
    chunk: usize,
    wait: bool,
}

impl ErrorType for Uart<'_> {
    type Error = Infallible;
}

impl Read for Uart<'_> {
    async fn read(&mut self, buf: &mut [u8]) -> Result<usize, Infallible> {
        poll_fn(|cx| {
            self.wait = !self.wait;
            if self.wait {
                cx.waker().wake_by_ref();
                Poll::Pending
            } else {
                Poll::Ready(())
            }
        })
        .await;
        let n = self.bytes.len().min(self.chunk).min(buf.len());
        buf[..n].copy_from_slice(&self.bytes[..n]);
        self.bytes = &self.bytes[n..];
        Ok(n)
    }
}

/// A writer that keeps what it is given, in writes of at most 5 bytes.
#[derive(Default)]
struct Sink(Vec<u8>);

impl ErrorType for Sink {
    type Error = Infallible;
}

impl Write for Sink {
    async fn write(&mut self, buf: &[u8]) -> Result<usize, Infallible> {
        let n = buf.len().min(5);
        self.0.extend_from_slice(&buf[..n]);
        Ok(n)
    }

    async fn flush(&mut self) -> Result<(), Infallible> {
        Ok(())
    }
}

/// Every event of a reader of `bytes` with reads of `chunk` bytes and a read buffer of `B`.
fn read_all<L: protocol_kit::PacketLayout, const N: usize, const B: usize>(
    layout: L,
    bytes: &[u8],
    chunk: usize,
) -> Vec<PacketEvent<L::Packet, L::Error>> {
    let uart = Uart {
        bytes,
        chunk,
        wait: false,
    };
    let mut reader = PacketReader::<_, L, N, B>::new(uart, layout);
    block_on(async {
        let mut events = Vec::new();
        while let Some(event) = reader.next_packet().await.expect("infallible") {
            events.push(event);
        }
        events
    })
}

fn packets<P: Copy, E>(events: &[PacketEvent<P, E>]) -> Vec<(u64, P)> {
    events
        .iter()
        .filter_map(|e| match e {
            PacketEvent::Packet { offset, packet, .. } => Some((*offset, *packet)),
            _ => None,
        })
        .collect()
}

#[test]
fn hflink_stream_from_an_async_reader() {
    let v = load_vectors("hflink.json");
    let (bytes, expected) = stream_vector(&v["streams"][0]);
    let want: Vec<_> = expected
        .iter()
        .map(|(o, f)| (*o, hflink::Packet::decode(f).expect("decodes")))
        .collect();
    for chunk in [1, 2, 3, 7, 16, 64, bytes.len()] {
        let events =
            read_all::<_, { hflink::DECODER_BUFFER_LEN }, 16>(hflink::Layout, &bytes, chunk);
        assert_eq!(packets(&events), want, "reads of {chunk}");
        assert!(events.iter().any(|e| matches!(
            e,
            PacketEvent::Invalid {
                error: DecodeError::Frame(Reject::BadChecksum),
                ..
            }
        )));
        // The truncated frame at the end is rejected when the reader ends.
        assert!(events.iter().any(|e| matches!(
            e,
            PacketEvent::Invalid {
                error: DecodeError::Frame(Reject::Truncated),
                ..
            }
        )));
    }
}

#[test]
fn referee_stream_from_an_async_reader() {
    let v = load_vectors("robomaster_referee.json");
    let (bytes, expected) = stream_vector(&v["streams"][0]);
    let want: Vec<_> = expected
        .iter()
        .map(|(o, f)| (*o, referee::Packet::decode(f).expect("decodes")))
        .collect();
    for chunk in [1, 5, 64] {
        let events =
            read_all::<_, { referee::DECODER_BUFFER_LEN }, 32>(referee::Layout, &bytes, chunk);
        assert_eq!(packets(&events), want, "reads of {chunk}");
    }
}

/// Packets written with `write_packet` read back with `PacketReader`, and a packet that does
/// not fit the buffer is an encode error with nothing written.
#[test]
fn write_then_read() {
    use hflink::{ChassisCoord, Header, Message, Packet, Request, Response};
    let sent = [
        Packet {
            header: Header {
                sender: 0x01,
                receiver: 0x11,
            },
            message: Message::Request(Request::SetRobotSpeed(ChassisCoord {
                x: 1.0,
                y: 2.0,
                z: 3.0,
            })),
        },
        Packet {
            header: Header {
                sender: 0x11,
                receiver: 0x01,
            },
            message: Message::Response(Response::SetRobotSpeed),
        },
    ];
    let mut sink = Sink::default();
    let mut buf = [0u8; hflink::MAX_FRAME_LEN];
    block_on(async {
        for p in &sent {
            let n = write_packet(&mut sink, p, &mut buf).await.expect("writes");
            assert_eq!(n, p.encoded_len());
        }
        let mut short = [0u8; 4];
        let err = write_packet(&mut sink, &sent[0], &mut short)
            .await
            .expect_err("too small");
        assert!(matches!(
            err,
            WriteError::Encode(EncodeError::BufferTooSmall { .. })
        ));
    });
    let events = read_all::<_, { hflink::DECODER_BUFFER_LEN }, 8>(hflink::Layout, &sink.0, 3);
    let got: Vec<_> = events
        .into_iter()
        .map(|e| e.packet().expect("only packets"))
        .collect();
    assert_eq!(got, sent);
}
