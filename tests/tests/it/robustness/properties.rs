//! Properties of every spec's generated code, on values generated from the spec itself:
//!
//! - any message encodes and decodes back to itself, and the frame the encoder wrote is exactly
//!   the canonical frame it came from (so every valid canonical frame re-encodes byte for byte);
//! - any frame that passes the checks, whatever its header values, payload length and bytes,
//!   decodes to a packet or an error, never a panic, and a packet re-encodes to a frame that
//!   decodes to the same packet;
//! - frames back to back yield the same frames fed whole or in any chunk sizes;
//! - arbitrary bytes (biased towards sync bytes and pieces of frames) never panic, never make
//!   the decoder hold more than its buffer, always make progress, and account for every byte.
//!
//! Case counts follow `PROPTEST_CASES` (256 by default). The specs come from
//! `support::for_each_spec!`: adding a spec there adds it here.

use proptest::prelude::*;
use proptest::test_runner::Config;
use protocol_kit::{DecodeError, EncodeError, Event, Reject};

use crate::support::model::{Model, model, sync_word};
use crate::support::stream::{assert_chunking_invariant, assert_same_packet, check_packet, run};
use crate::support::{Entropy, Source, Spec, hex, unescaped};

/// CI-sized: proptest's default case count (or `PROPTEST_CASES`), no regression files written
/// into the source tree (regressions become named tests instead).
fn config() -> Config {
    Config {
        failure_persistence: None,
        ..Config::default()
    }
}

/// Bytes that drive the generators.
fn entropy() -> impl Strategy<Value = Vec<u8>> {
    proptest::collection::vec(any::<u8>(), 0..512)
}

/// Chunk sizes, empty chunks included.
fn chunk_sizes() -> impl Strategy<Value = Vec<usize>> {
    proptest::collection::vec(0usize..160, 1..24)
}

/// A canonical frame decodes to a packet that encodes back to the same bytes and decodes to the
/// same packet; a buffer one byte short is an error. The frames are as they go on the wire;
/// `from_frame` reads a frame as the decoder yields it (unescaped, on a format that escapes its
/// frames), `decode` the wire's bytes.
fn message_round_trip<S: Spec>(entropy: &[u8]) {
    let m = model::<S>();
    let frame = m.try_canonical(&mut Entropy(entropy)).unwrap_or_else(|r| {
        panic!(
            "{}: the packet rules refuse a {}-byte frame the spec allows ({:?}): {}",
            S::NAME,
            r.len,
            r.choice,
            r.error
        )
    });
    let yielded = unescaped(m.format_for(&frame).layout, &frame);
    let packet = S::from_frame(&yielded).unwrap_or_else(|e| {
        panic!(
            "{}: canonical frame {} does not decode: {e}",
            S::NAME,
            hex(&frame)
        )
    });
    let bytes = packet.to_vec().expect("a decoded packet encodes");
    assert_eq!(
        packet.encoded_len(),
        bytes.len(),
        "{}: encoded_len() is not the length encode() wrote for {}",
        S::NAME,
        hex(&bytes)
    );
    assert!(
        bytes == frame,
        "{}: {packet:?} re-encodes to {} instead of {}",
        S::NAME,
        hex(&bytes),
        hex(&frame)
    );
    let again = S::decode(&bytes).expect("encoded packet decodes");
    assert_same_packet(&packet, &again, &bytes);
    let mut short = vec![0u8; bytes.len() - 1];
    assert!(matches!(
        packet.encode(&mut short),
        Err(EncodeError::BufferTooSmall { .. })
    ));
}

/// Any frame that passes the checks decodes or errs; every prefix of it is `Truncated`. `decode`
/// reads the wire's bytes, `from_frame` and `check_packet` the frame the decoder yields of them.
fn raw_frames<S: Spec>(entropy: &[u8]) {
    let m = model::<S>();
    let mut src = Entropy(entropy);
    let frame = m.raw(&mut src);
    let yielded = unescaped(m.format_for(&frame).layout, &frame);
    check_packet::<S>(&yielded);
    match (S::decode(&frame), S::from_frame(&yielded)) {
        (Ok(a), Ok(b)) => assert_same_packet(&a, &b, &frame),
        (a, b) => assert_eq!(
            a.err(),
            b.err(),
            "{}: decode and from_frame differ",
            S::NAME
        ),
    }
    let cut = src.below(frame.len() as u64) as usize;
    assert!(matches!(
        S::decode(&frame[..cut]),
        Err(DecodeError::Truncated { .. })
    ));
}

/// Frames back to back: fed whole they are exactly the frames sent (as the decoder yields them:
/// unescaped, on a format that escapes its frames); in chunks, the same.
fn back_to_back<S: Spec>(entropy: &[u8], sizes: &[usize]) {
    let m = model::<S>();
    let mut src = Entropy(entropy);
    let mut stream = Vec::new();
    let mut sent = Vec::new();
    for _ in 0..=src.below(8) {
        let frame = if src.one_in(2) {
            m.canonical(&mut src)
        } else {
            m.raw(&mut src)
        };
        let yielded = unescaped(m.format_for(&frame).layout, &frame);
        sent.push((stream.len() as u64, yielded));
        stream.extend(frame);
    }
    let whole = run::<S>(&stream, &[stream.len()]);
    assert_eq!(
        whole.frames,
        sent,
        "{}: frames back to back, fed whole",
        S::NAME
    );
    assert_eq!(whole.stats.skipped_bytes, 0);
    assert_chunking_invariant::<S>(&stream, sizes);
}

/// Bytes that reach deep into the decoder: garbage, sync bytes, whole and cut frames, frames
/// with a flipped bit (on a link, of its formats).
fn hostile(link: &Model, src: &mut impl Source) -> Vec<u8> {
    let m = link.pick(src);
    let sync = sync_word(m.layout, src.below(256) as usize);
    let mut out = Vec::new();
    for _ in 0..src.below(12) {
        match src.below(6) {
            0 => {
                let n = src.below(8) as usize;
                out.extend(src.bytes(n));
            }
            1 => out.extend_from_slice(&sync),
            2 => out.extend(link.canonical(src)),
            3 => {
                let frame = link.raw(src);
                let cut = src.below(frame.len() as u64) as usize;
                out.extend_from_slice(&frame[..cut]);
            }
            4 => {
                let mut frame = link.raw(src);
                let bit = src.below(8 * frame.len() as u64) as usize;
                frame[bit / 8] ^= 1 << (bit % 8);
                out.extend(frame);
            }
            _ => out.extend(std::iter::repeat_n(sync[0], src.below(4) as usize + 1)),
        }
    }
    out
}

/// Arbitrary and hostile bytes: every invariant of the checked driver, whole and in chunks.
fn arbitrary_bytes<S: Spec>(bytes: &[u8], entropy: &[u8], sizes: &[usize]) {
    assert_chunking_invariant::<S>(bytes, sizes);
    let stream = hostile(model::<S>(), &mut Entropy(entropy));
    assert_chunking_invariant::<S>(&stream, sizes);
}

/// The interpreter and generated code agree on canonical and raw frames, whole and cut.
fn interpreter_agrees<S: Spec>(entropy: &[u8]) {
    let m = model::<S>();
    let mut src = Entropy(entropy);
    let frame = if src.one_in(2) {
        m.canonical(&mut src)
    } else {
        m.raw(&mut src)
    };
    crate::support::fuzz::interp::<S>(&frame);
    let cut = src.below(frame.len() as u64) as usize;
    crate::support::fuzz::interp::<S>(&frame[..cut]);
}

macro_rules! properties {
    ($name:ident, $path:literal $(, $given:tt)*) => {
        mod $name {
            use super::*;

            type P = crate::support::packet!($name $(, $given)*);

            proptest! {
                #![proptest_config(config())]

                #[test]
                fn message_round_trip(e in entropy()) {
                    super::message_round_trip::<P>(&e);
                }

                #[test]
                fn raw_frames_decode_or_err(e in entropy()) {
                    super::raw_frames::<P>(&e);
                }

                #[test]
                fn back_to_back_frames_in_any_chunks(e in entropy(), sizes in chunk_sizes()) {
                    super::back_to_back::<P>(&e, &sizes);
                }

                #[test]
                fn arbitrary_bytes_keep_every_invariant(
                    bytes in proptest::collection::vec(any::<u8>(), 0..600),
                    e in entropy(),
                    sizes in chunk_sizes(),
                ) {
                    super::arbitrary_bytes::<P>(&bytes, &e, &sizes);
                }
            }

            proptest! {
                #![proptest_config(config())]

                #[test]
                fn interpreter_agrees_with_generated_code(e in entropy()) {
                    super::interpreter_agrees::<P>(&e);
                }
            }

            #[test]
            fn documented_nested_frame_rule() {
                super::nested_frame_rule::<P>();
            }
        }
    };
}

crate::support::for_each_spec!(properties);

/// The decoder's documented rule (module docs of `protocol_kit::decoder`): a valid frame
/// whose payload holds another complete valid frame is yielded whole when it arrives whole; cut
/// by a chunk boundary just after the inner frame, the inner frame is yielded and the outer one
/// is rejected as truncated. Checked here as documented, for every spec whose payloads can hold
/// a frame.
fn nested_frame_rule<S: Spec>() {
    let m = model::<S>();
    let f = m.frame();
    let inner_len = f.header_len + f.payload_min + f.trailer_len;
    // A payload long enough to hold a frame after its first byte. With byte stuffing no frame
    // can appear inside a payload (its sync bytes would be stuffed): nothing to check.
    let room = |c: &crate::support::model::Choice| {
        let st = &m.ir.structs[c.payload?];
        let len = (inner_len + 1).max(st.min_size);
        (len <= st.size).then_some((*c, len))
    };
    let Some((choice, len)) = m
        .choices
        .iter()
        .find_map(room)
        .filter(|_| f.stuffing.is_none())
    else {
        return;
    };
    let mut rng = crate::support::Rng(7);
    let inner = m.raw_with_payload_len(&mut rng, f.payload_min);
    assert_eq!(inner.len(), inner_len);
    let mut payload = vec![0u8; len];
    payload[1..1 + inner_len].copy_from_slice(&inner);
    let outer = m.build(&mut rng, choice, &payload);
    let at = f.header_len + 1;

    let whole = run::<S>(&outer, &[outer.len()]);
    assert_eq!(whole.frames, vec![(0, outer.clone())]);

    let cut = at + inner_len;
    let chunked = run::<S>(&outer, &[cut, outer.len()]);
    assert_eq!(
        chunked.frames,
        vec![(at as u64, inner.clone())],
        "{}",
        S::NAME
    );
    assert_eq!(chunked.rejected.first(), Some(&(0, Reject::Truncated)));

    // The same frame with a chunk boundary anywhere else is yielded whole (a cut inside the
    // inner frame leaves no complete frame inside the outer one).
    for cut in (1..outer.len()).filter(|&c| c < cut) {
        let r = run::<S>(&outer, &[cut, outer.len()]);
        assert_eq!(
            r.frames,
            vec![(0, outer.clone())],
            "{}: cut at {cut}",
            S::NAME
        );
    }
    let mut decoder = S::decoder();
    let mut input = &outer[..cut];
    let mut events = Vec::new();
    while let Some(e) = crate::support::Dec::next_event(&mut decoder, &mut input) {
        events.push(matches!(e, Event::Frame(_)));
    }
    assert_eq!(
        events.last(),
        Some(&true),
        "{}: the inner frame comes at once",
        S::NAME
    );
}

/// Every spec in `specs/` is under test, but those the registry of bundled specs
/// (`tests/catalogue.toml`) says the robustness suites skip (a CAN-only link, whose frames
/// arrive whole: no byte stream to cut, damage and resynchronise); a new spec joins
/// `for_each_spec!` by its entry there. Each line is as the registry describes the spec: a
/// link of several formats, or the direction its decoders are given.
#[test]
fn specs_dir_is_covered() {
    let mut listed: Vec<String> = Vec::new();
    macro_rules! list {
        ($name:ident, $path:literal $(, $given:tt)*) => {
            let given: &[&str] = &[$(stringify!($given)),*];
            listed.push(format!("{} {} {}", $path.trim_start_matches("../"), stringify!($name), given.join(" ")));
        };
    }
    crate::support::for_each_spec!(list);
    let catalogue = crate::registry::load();
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../specs");
    let mut found: Vec<String> = std::fs::read_dir(dir)
        .expect("specs dir")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".toml"))
        .filter_map(|n| {
            let Some(e) = catalogue.by_file(&n) else {
                return Some(format!("specs/{n}: no entry in tests/catalogue.toml"));
            };
            let given = match (e.link, e.directions.first()) {
                _ if !e.takes("robustness") => return None,
                (true, _) => "link".to_string(),
                (false, Some(d)) => format!("{d:?} from_{d}_frame decode_{d}"),
                (false, None) => String::new(),
            };
            Some(format!("specs/{n} {} {given}", e.name))
        })
        .collect();
    found.sort();
    listed.sort();
    assert_eq!(
        found, listed,
        "for_each_spec! is written from tests/catalogue.toml: give every spec an entry there"
    );
}

/// Minimized cases found by the properties: each states what the spec allows and checks that
/// the generated code does it.
mod regressions {
    use protocol_kit::Bytes;

    use protocol_kit::EncodeError;

    use crate::support::{dynamixel, referee, roborts, scout};

    /// A message encodes to bytes that decode back to it, or encoding refuses it: never a
    /// silent change.
    fn round_trips_or_is_refused<P: super::Spec>(packet: P) {
        let mut buf = vec![0u8; P::MAX_FRAME_LEN];
        match packet.encode(&mut buf) {
            Err(EncodeError::ValueOutOfRange { .. }) => {}
            Ok(n) => assert_eq!(
                P::decode(&buf[..n]),
                Ok(packet),
                "{}",
                super::hex(&buf[..n])
            ),
            Err(e) => panic!("{e}"),
        }
    }

    /// Referee: `game_type` is a 4-bit member of a bitfield. The value 16 does not fit:
    /// `EncodeError::ValueOutOfRange` says so ("a value does not fit its field (for example a
    /// length or a bitfield)"); the encoder masked it and sent 0.
    #[test]
    fn referee_bitfield_member_out_of_range() {
        round_trips_or_is_refused(referee::Packet {
            header: referee::Header { seq: 1 },
            message: referee::Message::GameState(referee::GameState {
                game_type: 16,
                game_progress: 1,
                stage_remain_time: 5,
            }),
        });
    }

    /// Scout: `ControlMode::Unknown(1)` holds the value of `CmdCan`; it encodes as 1, which
    /// decodes as `CmdCan`.
    #[test]
    fn scout_unknown_enum_value_of_a_known_variant() {
        round_trips_or_is_refused(scout::Packet {
            header: scout::Header { count: 0 },
            message: scout::Message::SystemStatus(scout::SystemStatus {
                base_state: scout::BaseState::Normal,
                control_mode: scout::ControlMode::Unknown(1),
                ..Default::default()
            }),
        });
    }

    /// Scout (found by `cargo fuzz run stream_scout`): a MOTION_CONTROL frame whose angular
    /// velocity byte is 107 (0.560 rad/s, outside the spec's clamp range of +-0.5235) decodes
    /// to 0.560, which encodes clamped to 100 and decodes as 0.5235: decoding a valid frame,
    /// encoding and decoding again changes the packet. Decoding must reject (or clamp) what
    /// encoding cannot represent.
    #[test]
    fn scout_scaled_value_outside_its_clamp_range() {
        let mut frame = [
            0x5A, 0xA5, 0x0A, 0x55, 0x01, 0x00, 0x06, 0x00, 107, 0x00, 0x00, 0x00, 0x00,
        ];
        scout::LAYOUT.seal(&mut frame).expect("seal");
        let Ok(packet) = scout::Packet::from_frame(&frame) else {
            return; // Rejected on decode: consistent.
        };
        let mut buf = [0u8; scout::MAX_FRAME_LEN];
        let n = packet.encode(&mut buf).expect("a decoded packet encodes");
        assert_eq!(scout::Packet::decode(&buf[..n]), Ok(packet));
    }

    /// RoboRTS: an acknowledgement with one data byte is a 17-byte frame (12-byte header, the
    /// byte, CRC32). The layout's `min_len` (18, the smallest command frame) refused it: it
    /// could be neither sent nor received.
    #[test]
    fn roborts_ack_with_one_data_byte() {
        let packet = roborts::Packet {
            header: roborts::Header {
                session_id: 1,
                sender: 0x01,
                receiver: 0x00,
                seq_num: 7,
            },
            message: roborts::Message::Ack(Bytes::from_slice(&[0x00]).expect("fits")),
        };
        let mut buf = [0u8; roborts::MAX_FRAME_LEN];
        let n = packet.encode(&mut buf).expect("a one-byte ack encodes");
        assert_eq!(n, 17);
        assert_eq!(roborts::Packet::decode(&buf[..n]), Ok(packet));
    }

    /// Dynamixel: `encoded_len()` ("bytes of the encoded frame") must count the stuffing byte
    /// inserted after `FF FF FD` in the parameters, so that a buffer of that size is enough.
    #[test]
    fn dynamixel_encoded_len_counts_stuffing() {
        let packet = dynamixel::Packet {
            header: dynamixel::Header { id: 1 },
            message: dynamixel::Message::Write(dynamixel::Write {
                address: 116,
                data: Bytes::from_slice(&[0xFF, 0xFF, 0xFD, 0x00]).expect("fits"),
            }),
        };
        let mut buf = [0u8; dynamixel::MAX_FRAME_LEN];
        let n = packet.encode(&mut buf).expect("encodes");
        assert_eq!(n, 17, "8 header + 2 address + 4 data + 1 stuffing + 2 CRC");
        assert_eq!(packet.encoded_len(), n);
        let mut exact = vec![0u8; packet.encoded_len()];
        assert_eq!(packet.encode(&mut exact), Ok(n));
        assert_eq!(dynamixel::Packet::decode(&buf[..n]), Ok(packet));
    }
}
