//! The `tokio` integration: `PacketCodec` under `FramedRead`, `FramedWrite` and `Framed` over
//! `tokio::io::duplex` pipes whose small buffers cut the stream into chunks, with noise
//! between the frames. Bad frames are items; the stream ends only with the pipe.

use futures_util::{SinkExt, StreamExt};
use protocol_kit::codec::PacketCodec;
use protocol_kit::{DecodeError, PacketEvent, Reject};
use protocol_tests::{load_vectors, stream_vector};
use tokio::io::AsyncWriteExt;
use tokio_util::codec::{Encoder, Framed, FramedRead, FramedWrite};

protocol_kit::protocol!("../specs/hflink.toml");

use hflink::{DECODER_BUFFER_LEN, Header, Layout, Message, Packet, Request, Response};

type Codec = PacketCodec<Layout, DECODER_BUFFER_LEN>;

fn codec() -> Codec {
    PacketCodec::new(Layout)
}

/// Packets of both directions, with and without payloads.
fn packets() -> Vec<Packet> {
    let request = Header {
        sender: 0x01,
        receiver: 0x11,
    };
    let response = Header {
        sender: 0x11,
        receiver: 0x01,
    };
    vec![
        Packet {
            header: request,
            message: Message::Request(Request::ReadRobotSpeed),
        },
        Packet {
            header: request,
            message: Message::Request(Request::SetRobotSpeed(hflink::ChassisCoord {
                x: 0.25,
                y: -1.5,
                z: 3.0,
            })),
        },
        Packet {
            header: response,
            message: Message::Response(Response::SetRobotSpeed),
        },
        Packet {
            header: response,
            message: Message::Response(Response::ReadRobotSpeed(hflink::ChassisCoord {
                x: 1.0,
                y: 2.0,
                z: -0.5,
            })),
        },
    ]
}

/// Writes `bytes` into a duplex pipe of `pipe` bytes, `chunk` bytes per write, and collects the
/// events a `FramedRead` yields until the pipe closes.
async fn read_events(bytes: Vec<u8>, pipe: usize, chunk: usize) -> Vec<PacketEvent<Packet>> {
    let (mut tx, rx) = tokio::io::duplex(pipe);
    let writer = tokio::spawn(async move {
        for part in bytes.chunks(chunk) {
            tx.write_all(part).await.expect("pipe write");
        }
        // Dropping `tx` closes the pipe: the reader sees the end of the input.
    });
    let events: Vec<_> = FramedRead::new(rx, codec())
        .map(|item| item.expect("no I/O error on a pipe"))
        .collect()
        .await;
    writer.await.expect("writer task");
    events
}

fn only_packets(events: &[PacketEvent<Packet>]) -> Vec<(u64, Packet)> {
    events
        .iter()
        .filter_map(|e| match e {
            PacketEvent::Packet { offset, packet, .. } => Some((*offset, *packet)),
            _ => None,
        })
        .collect()
}

/// The golden stream (garbage, a corrupt frame, a truncated one) through a pipe at several
/// buffer and write sizes: the expected frames come out decoded, the rejections as items.
#[tokio::test(flavor = "current_thread")]
async fn golden_stream_through_a_pipe() {
    let v = load_vectors("hflink.json");
    let (bytes, expected) = stream_vector(&v["streams"][0]);
    let want: Vec<(u64, Packet)> = expected
        .iter()
        .map(|(o, f)| (*o, Packet::decode(f).expect("expected frames decode")))
        .collect();
    for (pipe, chunk) in [(1, 1), (3, 2), (7, 5), (16, 13), (64, 64), (4096, 4096)] {
        let events = read_events(bytes.clone(), pipe, chunk).await;
        assert_eq!(
            only_packets(&events),
            want,
            "pipe {pipe}, writes of {chunk}"
        );
        assert!(
            events.iter().any(|e| matches!(
                e,
                PacketEvent::Invalid {
                    error: DecodeError::Frame(Reject::BadChecksum),
                    ..
                }
            )),
            "pipe {pipe}: the corrupt frame is an item"
        );
    }
}

/// Frames encoded by the codec, with noise between them (bytes that start no frame, a lone
/// sync byte, a frame with a bad sum): every packet comes out, each noise byte is accounted
/// for as skipped or as a rejected candidate's first byte.
#[tokio::test(flavor = "current_thread")]
async fn encoded_frames_with_noise() {
    let mut wire = tokio_util::bytes::BytesMut::new();
    let mut offsets = Vec::new();
    let noise: [&[u8]; 4] = [
        &[0x00, 0x13],
        &[0xFF],
        &[0xFF, 0xFF, 0x11, 0x01, 0x00, 0x01, 0x0C, 0x1E],
        &[],
    ];
    let mut codec = codec();
    for (i, p) in packets().iter().cycle().take(40).enumerate() {
        wire.extend_from_slice(noise[i % noise.len()]);
        offsets.push(wire.len() as u64);
        codec.encode(p, &mut wire).expect("encodes");
    }
    let want: Vec<(u64, Packet)> = offsets
        .iter()
        .copied()
        .zip(packets().into_iter().cycle())
        .collect();
    for (pipe, chunk) in [(1, 3), (5, 5), (9, 31), (256, 100)] {
        let events = read_events(wire.to_vec(), pipe, chunk).await;
        assert_eq!(
            only_packets(&events),
            want,
            "pipe {pipe}, writes of {chunk}"
        );
        let covered: usize = events
            .iter()
            .map(|e| match e {
                PacketEvent::Packet { len, .. } | PacketEvent::Skipped { len, .. } => *len,
                PacketEvent::Invalid { .. } => 1,
            })
            .sum();
        assert_eq!(covered, wire.len(), "pipe {pipe}: every byte is an item's");
    }
}

/// A host and a simulated robot on the two ends of one pipe, each with `Framed`: the host
/// sends requests, the robot answers each, the host reads the answers.
#[tokio::test(flavor = "current_thread")]
async fn framed_request_and_response() {
    let (host_end, robot_end) = tokio::io::duplex(8);
    let robot = tokio::spawn(async move {
        let mut robot = Framed::new(robot_end, codec());
        while let Some(item) = robot.next().await {
            let Some(Packet {
                header,
                message: Message::Request(request),
            }) = item.expect("pipe").packet()
            else {
                continue;
            };
            let answer = match request {
                Request::ReadRobotSpeed => Response::ReadRobotSpeed(hflink::ChassisCoord {
                    x: 0.5,
                    y: 0.0,
                    z: 0.125,
                }),
                _ => Response::SetRobotSpeed,
            };
            let reply = Packet {
                header: Header {
                    sender: header.receiver,
                    receiver: header.sender,
                },
                message: Message::Response(answer),
            };
            robot.send(reply).await.expect("robot sends");
        }
    });
    let (rx, tx) = tokio::io::split(host_end);
    let mut host_out = FramedWrite::new(tx, codec());
    let mut host_in = FramedRead::new(rx, codec());
    let mut answers = Vec::new();
    for p in packets()
        .into_iter()
        .filter(|p| matches!(p.message, Message::Request(_)))
    {
        host_out.send(p).await.expect("host sends");
        let event = host_in.next().await.expect("an answer").expect("pipe");
        answers.push(event.packet().expect("the answer is a packet").message);
    }
    drop(host_out);
    drop(host_in);
    robot.await.expect("robot task");
    assert_eq!(
        answers,
        [
            Message::Response(Response::ReadRobotSpeed(hflink::ChassisCoord {
                x: 0.5,
                y: 0.0,
                z: 0.125
            })),
            Message::Response(Response::SetRobotSpeed),
        ]
    );
}

/// A packet that does not encode is an error of the sink, and leaves nothing in the buffer.
#[test]
fn encode_error_leaves_the_buffer() {
    let mut wire = tokio_util::bytes::BytesMut::new();
    let bad = Packet {
        // A request from a slave's address: no direction matches.
        header: Header {
            sender: 0x20,
            receiver: 0x01,
        },
        message: Message::Request(Request::ReadRobotSpeed),
    };
    let err = codec().encode(bad, &mut wire).expect_err("does not encode");
    assert_eq!(err.kind(), std::io::ErrorKind::InvalidInput);
    assert!(wire.is_empty());
}

protocol_kit::protocol!("../specs/mavlink.toml");

/// A link of two command formats through one codec (`AnyLayout`, `AnyPacket`): every MAVLink 1
/// and 2 vector frame as its packet, sent through `FramedWrite` and read back through
/// `FramedRead` over a small pipe, each in the format it went out in.
#[tokio::test(flavor = "current_thread")]
async fn a_links_packets_of_both_formats_cross_one_codec() {
    type LinkCodec = PacketCodec<mavlink::AnyLayout, { mavlink::ANY_DECODER_BUFFER_LEN }>;
    let sent: Vec<mavlink::AnyPacket> = load_vectors("mavlink.json")["frames"]
        .as_array()
        .expect("frames")
        .iter()
        .map(|f| {
            let bytes = protocol_tests::hex(f["hex"].as_str().expect("hex"));
            match bytes[0] {
                0xFE => mavlink::AnyPacket::V1(mavlink::V1Packet::decode(&bytes).expect("v1")),
                _ => mavlink::AnyPacket::V2(mavlink::Packet::decode(&bytes).expect("v2")),
            }
        })
        .collect();
    assert!(sent.iter().any(|p| matches!(p, mavlink::AnyPacket::V1(_))));
    assert!(sent.iter().any(|p| matches!(p, mavlink::AnyPacket::V2(_))));
    let (tx, rx) = tokio::io::duplex(16);
    let to_send = sent.clone();
    let writer = tokio::spawn(async move {
        let mut out = FramedWrite::new(tx, LinkCodec::new(mavlink::AnyLayout));
        for p in to_send {
            out.send(p).await.expect("sends");
        }
    });
    let got: Vec<mavlink::AnyPacket> = FramedRead::new(rx, LinkCodec::new(mavlink::AnyLayout))
        .map(|item| item.expect("no I/O error on a pipe"))
        .filter_map(|e| async move { e.packet() })
        .collect()
        .await;
    writer.await.expect("writer task");
    assert_eq!(got.len(), sent.len());
    for (g, s) in got.iter().zip(&sent) {
        // Floats compared by their bytes: the frames as each packet encodes.
        let (mut a, mut b) = ([0u8; mavlink::MAX_FRAME_LEN], [0u8; mavlink::MAX_FRAME_LEN]);
        let n = g.encode(&mut a).expect("encodes");
        let m = s.encode(&mut b).expect("encodes");
        assert_eq!(a[..n], b[..m]);
        assert_eq!(
            matches!(g, mavlink::AnyPacket::V1(_)),
            matches!(s, mavlink::AnyPacket::V1(_))
        );
    }
}
