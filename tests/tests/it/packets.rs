//! Typed packets from a stream (`PacketDecoder`): on every HFLink and referee stream vector, at
//! every chunk size, the generated codec's packets are the expected frames decoded, every
//! rejection and skipped byte is an event, and the run-time codec (`protocol-dynamic`) reports
//! the same events with the same errors.

use protocol_dynamic::Interpreter;
use protocol_kit::{DecodeError, PacketDecoder, PacketEvent, PacketLayout};
use protocol_tests::{load_vectors, stream_vector};

protocol_kit::protocol!("../specs/hflink.toml");
protocol_kit::protocol!("../specs/referee.toml");

/// An event with the packet left out: where it starts, how long it is, and the error.
#[derive(Debug, PartialEq)]
enum Seen {
    Packet(u64, usize),
    Invalid(u64, DecodeError),
    Skipped(u64, usize),
}

fn seen<P, E>(e: &PacketEvent<P, E>, to_runtime: impl Fn(&E) -> DecodeError) -> Seen {
    match e {
        PacketEvent::Packet { offset, len, .. } => Seen::Packet(*offset, *len),
        PacketEvent::Invalid { offset, error } => Seen::Invalid(*offset, to_runtime(error)),
        PacketEvent::Skipped { offset, len } => Seen::Skipped(*offset, *len),
    }
}

/// The events of a format's packets.
type Events<L> = Vec<PacketEvent<<L as PacketLayout>::Packet, <L as PacketLayout>::Error>>;

/// Every event of `bytes` fed in chunks of `chunk` bytes, then flushed.
fn events<L: PacketLayout, const N: usize>(
    layout: L,
    bytes: &[u8],
    chunk: usize,
) -> (Events<L>, protocol_kit::Stats) {
    let mut decoder = PacketDecoder::<L, N>::new(layout);
    let mut out = Vec::new();
    for part in bytes.chunks(chunk) {
        out.extend(decoder.packets(part));
    }
    while let Some(e) = decoder.flush_packet() {
        out.push(e);
    }
    (out, *decoder.stats())
}

fn check_stream<L, P>(vectors: &str, spec: &str, layout: L, decode: impl Fn(&[u8]) -> P)
where
    L: PacketLayout<Packet = P, Error = DecodeError>,
    P: PartialEq + Clone + std::fmt::Debug,
{
    let v = load_vectors(vectors);
    let interp = Interpreter::load(format!("{}/../specs/{spec}", env!("CARGO_MANIFEST_DIR")))
        .expect("spec loads");
    let codec = interp.codec();
    for stream in v["streams"].as_array().expect("streams") {
        let (bytes, expected) = stream_vector(stream);
        for chunk in 1..=bytes.len() {
            let (got, stats) = events::<L, 512>(layout, &bytes, chunk);
            let packets: Vec<(u64, P)> = got
                .iter()
                .filter_map(|e| match e {
                    PacketEvent::Packet { offset, packet, .. } => Some((*offset, packet.clone())),
                    _ => None,
                })
                .collect();
            let want: Vec<(u64, P)> = expected.iter().map(|(o, f)| (*o, decode(f))).collect();
            assert_eq!(packets, want, "chunk size {chunk}");
            // Every rejected candidate is an event; every byte is a packet's, a skipped run's or
            // a rejected candidate's first byte.
            let invalid = got
                .iter()
                .filter(|e| {
                    matches!(
                        e,
                        PacketEvent::Invalid {
                            error: DecodeError::Frame(_),
                            ..
                        }
                    )
                })
                .count() as u64;
            assert_eq!(invalid, stats.rejected(), "chunk size {chunk}");
            let covered: u64 = got
                .iter()
                .map(|e| match e {
                    PacketEvent::Packet { len, .. } | PacketEvent::Skipped { len, .. } => {
                        *len as u64
                    }
                    PacketEvent::Invalid {
                        error: DecodeError::Frame(_),
                        ..
                    } => 1,
                    PacketEvent::Invalid { .. } => 0,
                })
                .sum();
            assert_eq!(covered, bytes.len() as u64, "chunk size {chunk}");
            // The run-time codec sees the same events, with the same errors.
            let layout = codec.packet_layout(0).expect("a frame format");
            let (dynamic, _) = events::<_, 512>(layout, &bytes, chunk);
            let a: Vec<Seen> = got.iter().map(|e| seen(e, |e| e.without_place())).collect();
            let b: Vec<Seen> = dynamic
                .iter()
                .map(|e| seen(e, |e| e.to_runtime()))
                .collect();
            assert_eq!(a, b, "chunk size {chunk}");
        }
    }
}

#[test]
fn hflink_stream_yields_packets_and_rejections() {
    check_stream("hflink.json", "hflink.toml", hflink::Layout, |b| {
        hflink::Packet::decode(b).expect("an expected frame decodes")
    });
}

#[test]
fn referee_stream_yields_packets_and_rejections() {
    check_stream(
        "robomaster_referee.json",
        "referee.toml",
        referee::Layout,
        |b| referee::Packet::decode(b).expect("an expected frame decodes"),
    );
}

/// A frame the engine accepts whose command the spec lacks is an `Invalid` event with the
/// decode error, and the stream goes on.
#[test]
fn unknown_command_is_an_event() {
    let mut frame = [0u8; hflink::MAX_FRAME_LEN];
    let packet = hflink::Packet {
        header: hflink::Header {
            sender: 0x01,
            receiver: 0x11,
        },
        message: hflink::Message::Request(hflink::Request::ReadRobotSpeed),
    };
    let n = packet.encode(&mut frame).expect("encodes");
    let mut unknown = frame[..n].to_vec();
    unknown[6] = 0xEE;
    let sum = unknown[..n - 1].iter().map(|&b| u32::from(b)).sum::<u32>() % 255;
    unknown[n - 1] = sum as u8;
    let stream = [&unknown[..], &frame[..n]].concat();
    let (got, _) = events::<_, 512>(hflink::Layout, &stream, 3);
    assert_eq!(
        got,
        [
            PacketEvent::Invalid {
                offset: 0,
                error: DecodeError::UnknownCommand { key: 0xEE }
            },
            PacketEvent::Packet {
                offset: n as u64,
                len: n,
                packet
            },
        ]
    );
}
