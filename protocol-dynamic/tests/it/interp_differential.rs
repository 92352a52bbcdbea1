//! The interpreter against the generated code, spec by spec: the same layouts (compared as
//! the runtime's `Debug` prints them), and for every golden vector and thousands of random
//! frames per spec the same decoded values (compared with the generated `Packet`'s `{:?}`,
//! field for field), the same errors, and the same bytes when the decoded message is encoded
//! again (the interpreter's message going through JSON text with the `serde` feature, as in
//! `decode | encode`).
//!
//! Besides the bundled specs, `tests/fixtures/features.toml` holds every feature of the spec
//! language that they do not use. A spec added to `specs/` joins by one `protocol!` line and one
//! `generated!` line below (`catalogue::` of the tests crate checks that every spec of the
//! registry `tests/catalogue.toml` has its `protocol!` line here, or skips `interp`); the golden
//! vector files come from the registry.

use crate::support;

/// The registry of bundled specs (`tests/catalogue.toml`).
#[path = "../../../tests/catalogue.rs"]
mod catalogue;

use protocol_dynamic::{Codec, DecodeIssue, Decoded, Interpreter, Item, Value, hex, word_field};
use protocol_kit::{CanFrame, DecodeError, EncodeError, Event, FrameLayout, Reject, StreamDecoder};
use protocol_spec::ir::{DirectionRule, Protocol, Transport};
use support::{Rng, interpreter, rust_debug, unhex, vectors};

protocol_kit::protocol!("../specs/hflink.toml");
protocol_kit::protocol!("../specs/referee.toml");
protocol_kit::protocol!("../specs/referee2018.toml");
protocol_kit::protocol!("../specs/crsf.toml");
protocol_kit::protocol!("../specs/scout.toml");
protocol_kit::protocol!("../specs/mavlink.toml");
protocol_kit::protocol!("../specs/dynamixel.toml");
protocol_kit::protocol!("../specs/dynamixel1.toml");
protocol_kit::protocol!("../specs/roborts.toml");
protocol_kit::protocol!("../specs/ibus.toml");
protocol_kit::protocol!("../specs/sbus.toml");
protocol_kit::protocol!("../specs/ubx.toml");
protocol_kit::protocol!("../specs/vesc.toml");
protocol_kit::protocol!("../specs/feetech.toml");
protocol_kit::protocol!("../specs/lx16a.toml");
protocol_kit::protocol!("../specs/msp.toml");
protocol_kit::protocol!("tests/fixtures/features.toml");

/// A decoded message as `{:?}` prints it, and its bytes encoded again.
type Generated<T> = Result<(String, T), DecodeError>;

/// A generated packet's `decode`, then `encode`.
type Decode = fn(&[u8]) -> Generated<Vec<u8>>;

/// What the test needs of a generated module.
struct Gen {
    spec: &'static str,
    /// `{:?}` of every frame format's `LAYOUT`, in spec order.
    layouts: fn() -> Vec<String>,
    /// Seals a frame of a format with the generated layout.
    seal: fn(usize, &mut [u8]) -> Result<(), EncodeError>,
    /// `Packet::decode`, then `Packet::encode`.
    decode: Decode,
    /// `<Frame>Packet::decode(can)`, then `encode`, for a spec with a CAN frame format.
    can: Option<fn(&CanFrame) -> Generated<CanFrame>>,
    /// A frame format that carries one struct, and its `<Frame>Packet::decode`, then `encode`.
    message: Option<(usize, Decode)>,
    /// The events of `decoder()` over a stream cut in chunks of `n` bytes.
    stream: fn(&[u8], usize) -> Vec<String>,
    /// For a spec whose directions are given to the decoder: the direction `decode` decodes,
    /// which the interpreter is given too.
    direction: Option<&'static str>,
    /// A command format of the link after the first, and its `<Frame>Packet::decode`, then
    /// `encode`.
    other: Option<(usize, Decode)>,
}

impl Gen {
    /// The interpreter's codec, given this entry's direction; a carrying field decodes as its
    /// bytes, as the generated struct holds them (`carried_codec` of the tests crate compares
    /// the packets they carry).
    fn codec<'i>(&self, interp: &'i Interpreter) -> Codec<'i> {
        let codec = interp.codec().with_carried_packets(false);
        let direction = self.direction.and_then(|d| codec.direction_index(d));
        codec.with_direction(direction)
    }
}

fn event_text(e: &Event<'_>) -> String {
    match e {
        Event::Frame(f) => format!("frame @{} {}", f.offset, hex(f.bytes)),
        other => format!("{other:?}"),
    }
}

macro_rules! generated {
    ($m:ident, [$($layout:ident),*], $can:expr) => {
        generated!($m, [$($layout),*], $can, None)
    };
    ($m:ident, [$($layout:ident),*], $can:expr, $message:expr) => {
        generated!($m, [$($layout),*], $can, $message, decode, None)
    };
    ($m:ident, [$($layout:ident),*], $can:expr, $message:expr, $decode:ident, $direction:expr) => {
        Gen {
            direction: $direction,
            other: None,
            spec: stringify!($m),
            layouts: || vec![$(format!("{:?}", $m::$layout)),*],
            seal: |fi, frame| {
                let layouts: &[&FrameLayout<'static>] = &[$(&$m::$layout),*];
                layouts[fi].seal(frame)
            },
            decode: |bytes| {
                let packet = $m::Packet::$decode(bytes)?;
                let mut buf = vec![0u8; $m::MAX_FRAME_LEN];
                let n = packet.encode(&mut buf).expect("generated code encodes what it decoded");
                Ok((format!("{packet:?}"), buf[..n].to_vec()))
            },
            can: $can,
            message: $message,
            stream: |bytes, n| {
                let mut decoder = $m::decoder();
                let mut events = Vec::new();
                for mut chunk in bytes.chunks(n) {
                    while let Some(e) = decoder.next_event(&mut chunk) {
                        events.push(event_text(&e));
                    }
                }
                while let Some(e) = decoder.flush_event() {
                    events.push(event_text(&e));
                }
                events
            },
        }
    };
}

fn scout_can(can: &CanFrame) -> Generated<CanFrame> {
    let packet = scout::CanPacket::decode(can)?;
    let again = packet
        .encode()
        .expect("generated code encodes what it decoded");
    Ok((format!("{packet:?}"), again))
}

fn dynamixel_feedback(bytes: &[u8]) -> Generated<Vec<u8>> {
    let packet = dynamixel::FeedbackPacket::decode(bytes)?;
    let mut buf = vec![0u8; dynamixel::FEEDBACK_MAX_FRAME_LEN];
    let n = packet
        .encode(&mut buf)
        .expect("generated code encodes what it decoded");
    Ok((format!("{packet:?}"), buf[..n].to_vec()))
}

fn sbus_packet(bytes: &[u8]) -> Generated<Vec<u8>> {
    let packet = sbus::Packet::decode(bytes)?;
    let mut buf = vec![0u8; sbus::MAX_FRAME_LEN];
    let n = packet
        .encode(&mut buf)
        .expect("generated code encodes what it decoded");
    Ok((format!("{packet:?}"), buf[..n].to_vec()))
}

fn mavlink_v1(bytes: &[u8]) -> Generated<Vec<u8>> {
    let packet = mavlink::V1Packet::decode(bytes)?;
    let mut buf = vec![0u8; mavlink::V1_MAX_FRAME_LEN];
    let n = packet
        .encode(&mut buf)
        .expect("generated code encodes what it decoded");
    Ok((format!("{packet:?}"), buf[..n].to_vec()))
}

fn msp_v2(bytes: &[u8]) -> Generated<Vec<u8>> {
    let packet = msp::V2Packet::decode(bytes)?;
    let mut buf = vec![0u8; msp::V2_MAX_FRAME_LEN];
    let n = packet
        .encode(&mut buf)
        .expect("generated code encodes what it decoded");
    Ok((format!("{packet:?}"), buf[..n].to_vec()))
}

fn specs() -> Vec<Gen> {
    vec![
        generated!(crsf, [LAYOUT], None),
        generated!(hflink, [LAYOUT], None),
        generated!(referee, [LAYOUT], None),
        generated!(referee2018, [LAYOUT], None),
        generated!(scout, [LAYOUT, CAN_LAYOUT], Some(scout_can)),
        generated!(
            dynamixel,
            [LAYOUT, FEEDBACK_LAYOUT],
            None,
            Some((1, dynamixel_feedback))
        ),
        generated!(
            dynamixel1,
            [LAYOUT],
            None,
            None,
            decode_request,
            Some("request")
        ),
        generated!(
            dynamixel1,
            [LAYOUT],
            None,
            None,
            decode_response,
            Some("response")
        ),
        generated!(roborts, [LAYOUT], None),
        Gen {
            other: Some((1, mavlink_v1)),
            ..generated!(mavlink, [LAYOUT, V1_LAYOUT], None)
        },
        Gen {
            other: Some((1, msp_v2)),
            ..generated!(msp, [LAYOUT, V2_LAYOUT], None)
        },
        generated!(ibus, [LAYOUT], None),
        generated!(sbus, [LAYOUT], None, Some((0, sbus_packet))),
        generated!(ubx, [LAYOUT], None),
        generated!(vesc, [LAYOUT], None, None, decode_request, Some("request")),
        generated!(
            vesc,
            [LAYOUT],
            None,
            None,
            decode_response,
            Some("response")
        ),
        generated!(
            feetech,
            [LAYOUT],
            None,
            None,
            decode_request,
            Some("request")
        ),
        generated!(
            feetech,
            [LAYOUT],
            None,
            None,
            decode_response,
            Some("response")
        ),
        generated!(lx16a, [LAYOUT], None, None, decode_request, Some("request")),
        generated!(
            lx16a,
            [LAYOUT],
            None,
            None,
            decode_response,
            Some("response")
        ),
        generated!(features, [LAYOUT, RAW_LAYOUT], None),
    ]
}

/// Outcomes of the comparisons of one spec.
#[derive(Debug, Default)]
struct Tally {
    same_message: usize,
    same_error: Vec<(String, usize)>,
}

impl Tally {
    fn error(&mut self, e: &DecodeError) {
        let kind = format!("{e:?}")
            .split([' ', '('])
            .next()
            .unwrap_or("")
            .to_string();
        match self.same_error.iter_mut().find(|(k, _)| *k == kind) {
            Some((_, n)) => *n += 1,
            None => self.same_error.push((kind, 1)),
        }
    }
}

/// The interpreter's message, through JSON text as `decode | encode` carries it, encoded.
fn reencode(codec: &Codec<'_>, d: &Decoded, label: &str) -> protocol_dynamic::Encoded {
    let text = serde_json::to_string(&codec.frame_value(d, 0, &[])).expect("a value serializes");
    let back: Value = serde_json::from_str(&text).expect("JSON text reads back");
    codec
        .encode(&back)
        .unwrap_or_else(|e| panic!("{label}: the interpreter cannot encode {text}: {e}"))
}

fn compare(
    codec: &Codec<'_>,
    label: &str,
    generated: Generated<Vec<u8>>,
    interpreted: Result<Decoded, DecodeIssue>,
    tally: &mut Tally,
) {
    match (generated, interpreted) {
        (Ok((debug, bytes)), Ok(d)) => {
            assert_eq!(
                rust_debug(codec.protocol(), &d),
                debug,
                "{label}: decoded values"
            );
            let again = reencode(codec, &d, label);
            assert_eq!(hex(&again.bytes), hex(&bytes), "{label}: encoded again");
            tally.same_message += 1;
        }
        (Err(g), Err(i)) => {
            assert_eq!(i.to_runtime(), g.without_place(), "{label}: errors ({i})");
            same_place(&g, &i, label);
            tally.error(&g);
        }
        (g, i) => panic!("{label}: generated code gives {g:?}, the interpreter {i:?}"),
    }
}

/// Generated code names the command and field of an enum value without variant (`Struct.field`)
/// as the run-time codec does (the path in the payload, whose last step is the field).
fn same_place(g: &DecodeError, i: &DecodeIssue, label: &str) {
    if let (Some(place), DecodeIssue::InvalidEnum { command, field, .. }) = (g.place(), i) {
        assert_eq!(place.command(), command, "{label}: the command of {g}");
        // The last step of a path, without an element's index (`modes[2]`).
        let last = |path: &str| {
            let step = path.rsplit('.').next().unwrap_or("");
            step.split('[').next().unwrap_or("").to_string()
        };
        assert_eq!(
            last(place.field()),
            last(field),
            "{label}: the field of {g} ({i})"
        );
    }
}

fn compare_can(
    codec: &Codec<'_>,
    fi: usize,
    label: &str,
    g: &Gen,
    can: &CanFrame,
    tally: &mut Tally,
) {
    let generated = (g.can.expect("a CAN packet"))(can);
    let interpreted = codec.decode_can(fi, can);
    match (generated, interpreted) {
        (Ok((debug, again)), Ok(d)) => {
            assert_eq!(
                rust_debug(codec.protocol(), &d),
                debug,
                "{label}: decoded values"
            );
            assert_eq!(
                reencode(codec, &d, label).can,
                Some(again),
                "{label}: encoded again"
            );
            tally.same_message += 1;
        }
        (Err(g), Err(i)) => {
            assert_eq!(i.to_runtime(), g.without_place(), "{label}: errors ({i})");
            same_place(&g, &i, label);
            tally.error(&g);
        }
        (g, i) => panic!("{label}: generated code gives {g:?}, the interpreter {i:?}"),
    }
}

#[test]
fn every_layout_is_the_generated_one() {
    for g in specs() {
        let interp = interpreter(g.spec);
        let codec = g.codec(&interp);
        let generated = (g.layouts)();
        assert_eq!(
            generated.len(),
            interp.protocol().frames.len(),
            "{}",
            g.spec
        );
        for (i, expected) in generated.iter().enumerate() {
            let built = format!("{:?}", codec.layout(i).expect("a layout"));
            // The codec computes every CRC with sixteen tables, whatever the spec's `table`
            // (a microcontroller's choice; see `protocol_dynamic`'s layout module): the same
            // layout, but for the tables' name.
            let expected = expected
                .replace("NoTable(", "Table16(")
                .replace("Table1(", "Table16(");
            assert_eq!(built, expected, "{}: frame format {i}", g.spec);
        }
    }
}

/// Every frame of the golden vector files, decoded by both codecs with every spec that could
/// read it (the 2018 referee frame is also read by the 2019 spec, and the other way round).
#[test]
fn golden_vectors_decode_and_encode_alike() {
    // The registry's `interp` suite (`tests/catalogue.toml`).
    let catalogue = catalogue::load();
    let files: Vec<(&str, &str)> = catalogue
        .vectors("interp")
        .map(|(e, v)| (e.name.as_str(), v.file.as_str()))
        .collect();
    let gens = specs();
    for (spec, _) in &files {
        assert!(
            gens.iter().any(|g| g.spec == *spec),
            "{spec}: the registry (tests/catalogue.toml) has it read its vectors here, but \
             protocol-dynamic/tests/it/interp_differential.rs has no `generated!` entry of it"
        );
    }
    // A spec whose directions are given has an entry per direction: each reads every frame.
    for (g, file) in files.iter().flat_map(|(spec, file)| {
        gens.iter()
            .filter(move |g| g.spec == *spec)
            .map(move |g| (g, *file))
    }) {
        let spec = g.spec;
        let interp = interpreter(spec);
        let codec = g.codec(&interp);
        let v = vectors(file);
        let mut tally = Tally::default();
        let mut reproduced = 0;
        for frame in v["frames"].as_array().expect("frames") {
            let name = frame["name"].as_str().unwrap_or("?");
            let serial = frame["hex"].as_str().or(frame["uart"]["hex"].as_str());
            if let Some(text) = serial {
                let bytes = unhex(text);
                let label = format!("{spec}: {name}");
                // A frame of the link's other command format goes through its packet.
                let (fi, decode) = match g.other {
                    Some((fi, d)) if codec.layout(fi).is_some_and(|l| l.parse(&bytes).is_ok()) => {
                        (fi, d)
                    }
                    _ => (0, g.decode),
                };
                let generated = decode(&bytes);
                if matches!(&generated, Ok((_, again)) if *again == bytes) {
                    reproduced += 1;
                }
                compare(
                    &codec,
                    &label,
                    generated,
                    codec.parse(fi, &bytes),
                    &mut tally,
                );
            }
            if let (Some(id), Some(data)) = (
                frame["can"]["can_id"].as_u64(),
                frame["can"]["data_hex"].as_str(),
            ) {
                let can = CanFrame::new(id as u32, &unhex(data)).expect("a CAN frame");
                let fi = can_format(interp.protocol());
                compare_can(
                    &codec,
                    fi,
                    &format!("{spec}: {name} (CAN)"),
                    g,
                    &can,
                    &mut tally,
                );
            }
        }
        for list in [&v["can_frames_captured"], &v["streams"][1]["frames"]] {
            for (k, frame) in list.as_array().into_iter().flatten().enumerate() {
                let id = frame["can_id"].as_u64().expect("can_id") as u32;
                let can = CanFrame::new(id, &unhex(frame["data_hex"].as_str().expect("data")))
                    .expect("CAN");
                let fi = can_format(interp.protocol());
                compare_can(
                    &codec,
                    fi,
                    &format!("{spec}: CAN frame {k}"),
                    g,
                    &can,
                    &mut tally,
                );
            }
        }
        println!(
            "{spec} on {file}: {tally:?}, {reproduced} reproduced byte for byte by generated code"
        );
        assert!(
            tally.same_message > 0,
            "{spec}: no vector decoded: the test compares nothing"
        );
    }
}

/// A constant bit member of the header (the features spec's `version = 2` in `flags`): both
/// backends write it on encode, and refuse a frame that holds any other value in its bits as a
/// bad header (the constants are verified before the checks, so the stale CRCs are not what is
/// reported; sealing would write the constant back).
#[test]
fn a_header_constant_bit_is_written_and_verified_alike() {
    let packet = features::Packet {
        header: features::Header {
            reply: false,
            priority: 5,
            node: 1,
        },
        message: features::Message::Request(features::Request::Ping),
    };
    let mut buf = [0u8; features::MAX_FRAME_LEN];
    let n = packet.encode(&mut buf).expect("generated code encodes");
    let frame = buf[..n].to_vec();
    // `flags` follows the sync and the length: reply, priority, then version in bits 4..8.
    assert_eq!(frame[4] >> 4, 2, "version written: {}", hex(&frame));
    let interp = interpreter("features");
    let codec = interp.codec();
    let d = codec.parse(0, &frame).expect("the interpreter decodes it");
    let again = reencode(&codec, &d, "features: PING");
    assert_eq!(
        hex(&again.bytes),
        hex(&frame),
        "the interpreter writes it alike"
    );
    for version in (0u8..16).filter(|&v| v != 2) {
        let mut bad = frame.clone();
        bad[4] = (bad[4] & 0x0F) | (version << 4);
        let refused = Err(DecodeError::Frame(Reject::BadHeader));
        assert_eq!(
            features::Packet::decode(&bad).map(|_| ()),
            refused,
            "generated code, version {version}"
        );
        assert_eq!(
            codec.parse(0, &bad).map(|_| ()).map_err(|e| e.to_runtime()),
            refused,
            "interpreter, version {version}"
        );
    }
}

fn can_format(p: &Protocol) -> usize {
    p.frames
        .iter()
        .position(|f| matches!(f.transport, Transport::Can { .. }))
        .expect("a CAN frame format")
}

/// Payload sizes to try for a struct of `min..=max` bytes in a format of `lo..=hi`: the
/// smallest and largest, one in between, and one byte off either end (each size error is also
/// compared).
fn sizes(
    rng: &mut Rng,
    min: usize,
    max: usize,
    lo: usize,
    hi: usize,
    round: usize,
) -> Option<usize> {
    let n = match round % 10 {
        0..=3 => max,
        4 | 5 => min,
        6 | 7 => rng.range(min as u64, max as u64) as usize,
        8 => max + 1,
        _ => min.checked_sub(1)?,
    };
    (lo..=hi).contains(&n).then_some(n)
}

/// Random frames of every command format `fi` carries in every direction, decoded by
/// `decode` (the format's generated packet) and by the interpreter; the number of frames.
fn random_command_frames(
    g: &Gen,
    codec: &Codec<'_>,
    fi: usize,
    decode: Decode,
    rng: &mut Rng,
    tally: &mut Tally,
) -> usize {
    const ROUNDS: usize = 60;
    let p = codec.protocol();
    let f = &p.frames[fi];
    let own = g
        .direction
        .and_then(|d| p.directions.iter().position(|x| x.name == d));
    let mut attempts = 0;
    for c in f.commands.iter().map(|&ci| &p.commands[ci]) {
        for (slot, payload) in c.payloads.iter().enumerate() {
            let (min, max) =
                payload.map_or((0, 0), |si| (p.structs[si].min_size, p.structs[si].size));
            for round in 0..ROUNDS {
                let Some(len) = sizes(
                    rng,
                    min,
                    max.min(f.payload_max),
                    f.payload_min,
                    f.payload_max,
                    round,
                ) else {
                    continue;
                };
                let mut frame = vec![0u8; f.header_len + len + f.trailer_len];
                rng.fill(&mut frame);
                if let Some((after, insert)) = f
                    .stuffing
                    .as_ref()
                    .filter(|(a, _)| round % 3 == 0 && len > a.len())
                {
                    // A stuffed pattern, as a sender writes it.
                    let at = f.header_len + rng.range(0, (len - after.len() - 1) as u64) as usize;
                    frame[at..at + after.len()].copy_from_slice(after);
                    frame[at + after.len()] = *insert;
                }
                for (&vi, id) in f.dispatch.iter().zip(&c.id) {
                    word_field(&f.values[vi])
                        .write(&mut frame, *id)
                        .expect("id fits");
                }
                if let Some((flag, _)) = f.ack {
                    // Mostly a command; sometimes an acknowledgement.
                    let equals = codec
                        .with_rules(fi, |r| r.ack.map(|a| a.equals))
                        .flatten()
                        .expect("the format has acknowledgements");
                    let value = if round % 4 == 0 { equals } else { 1 - equals };
                    word_field(&f.values[flag])
                        .write(&mut frame, value)
                        .expect("fits");
                }
                // Mostly a header of the slot's direction; sometimes whatever came.
                if let (Some(d), true) = (p.directions.get(slot), round % 7 != 0) {
                    let set = match d.rule.in_frame(f) {
                        DirectionRule::InSet { value, set } => {
                            let a = &p.addresses[set];
                            Some((value, rng.range(a.first, a.last)))
                        }
                        DirectionRule::Equals { value, equals } => Some((value, equals)),
                        // The decoder is given it: no header value tells it.
                        DirectionRule::Given => None,
                    };
                    if let Some((vi, value)) = set {
                        word_field(&f.values[vi])
                            .write(&mut frame, value)
                            .expect("fits");
                    }
                }
                // A sync from a set: a value of the set (the layout refuses any other).
                if !f.sync_set.is_empty() {
                    frame[0] = f.sync_set[rng.range(0, f.sync_set.len() as u64 - 1) as usize];
                }
                // A flag trailer (a MAVLink 2 signature): present in some rounds, its flag
                // set and its bytes appended; else its flag clear.
                if let Some(t) = &f.flag_trailer {
                    let on = round % 5 == 0;
                    word_field(&f.values[t.flag])
                        .write(&mut frame, u64::from(on))
                        .expect("a one-bit flag");
                    if on {
                        let mut extra = vec![0u8; t.len];
                        rng.fill(&mut extra);
                        frame.extend_from_slice(&extra);
                    }
                }
                // A payload from the marker value up to the extension's width (MSP v1: 255 or
                // 256 bytes) in a frame without the extension's bytes has no encoding: the
                // frame's length reads as a shorter jumbo payload, which a sender writes in the
                // short form. No frame to compare.
                let sealed = (g.seal)(fi, &mut frame);
                let unsealable = f.length_extension.as_ref().is_some_and(|e| {
                    let marker = usize::try_from(e.marker).expect("a byte count");
                    (marker..marker + e.len).contains(&len)
                });
                if sealed.is_err() && unsealable {
                    continue;
                }
                sealed.expect("the generated layout seals");
                // A frame of the other direction, given to a decoder of this one, is compared
                // as well, but not counted among the frames that should mostly decode: where
                // most commands carry data one way only (VESC, LX-16A), it is mostly an error.
                if own.is_none_or(|o| o == slot) {
                    attempts += 1;
                }
                let label = format!(
                    "{}: {} {} slot {slot} round {round}: {}",
                    g.spec,
                    f.name,
                    c.name,
                    hex(&frame)
                );
                compare(
                    codec,
                    &label,
                    decode(&frame),
                    codec.parse(fi, &frame),
                    tally,
                );
            }
        }
    }
    attempts
}

/// Random frames of every command in every direction, of every struct-carrying format, of
/// acknowledgements and bare headers: random header values and payload bytes (NaNs,
/// out-of-range enums and bools, non-zero padding, stuffing patterns included), of the sizes
/// `sizes` picks, sealed by the generated layout.
#[test]
fn random_messages_decode_and_encode_alike() {
    const ROUNDS: usize = 60;
    for g in specs() {
        let interp = interpreter(g.spec);
        let codec = g.codec(&interp);
        let p = interp.protocol();
        let mut rng = Rng(0x9E37_79B9_7F4A_7C15 ^ g.spec.len() as u64);
        let mut tally = Tally::default();
        let f = &p.frames[0];
        let mut attempts = random_command_frames(&g, &codec, 0, g.decode, &mut rng, &mut tally);
        if let Some((fi, decode)) = g.other {
            attempts += random_command_frames(&g, &codec, fi, decode, &mut rng, &mut tally);
        }
        if let Some(bare) = f.bare_len {
            for round in 0..ROUNDS {
                let mut frame = vec![0u8; bare];
                rng.fill(&mut frame);
                (g.seal)(0, &mut frame).expect("the generated layout seals a bare header");
                attempts += 1;
                let label = format!("{}: bare header round {round}: {}", g.spec, hex(&frame));
                compare(
                    &codec,
                    &label,
                    (g.decode)(&frame),
                    codec.parse(0, &frame),
                    &mut tally,
                );
            }
        }
        if let Some((fi, decode)) = g.message {
            let mf = &p.frames[fi];
            let si = mf.message.expect("a struct");
            let (min, max) = (p.structs[si].min_size, p.structs[si].size);
            for round in 0..ROUNDS {
                let Some(len) = sizes(&mut rng, min, max, mf.payload_min, mf.payload_max, round)
                else {
                    continue;
                };
                let mut frame = vec![0u8; mf.header_len + len + mf.trailer_len];
                rng.fill(&mut frame);
                (g.seal)(fi, &mut frame).expect("the generated layout seals");
                attempts += 1;
                let label = format!("{}: {} round {round}: {}", g.spec, mf.name, hex(&frame));
                compare(
                    &codec,
                    &label,
                    decode(&frame),
                    codec.parse(fi, &frame),
                    &mut tally,
                );
            }
        }
        if g.can.is_some() {
            let fi = can_format(p);
            let cf = &p.frames[fi];
            let can_id = cf
                .values
                .iter()
                .find(|v| v.name == "can_id")
                .expect("can_id");
            for c in p.commands.iter().filter(|c| c.can_id.is_some()) {
                let size = c.payloads[0].map_or(0, |si| p.structs[si].size);
                for round in 0..ROUNDS {
                    let mut frame = vec![0u8; cf.header_len + size + cf.trailer_len];
                    rng.fill(&mut frame);
                    // Mostly a real bus's frame; sometimes bits above the id's width.
                    let mut word = word_field(can_id);
                    if round % 10 != 9 {
                        word.shift = 0;
                        word.width = 32;
                    }
                    word.write(&mut frame, c.can_id.unwrap_or(0)).expect("fits");
                    (g.seal)(fi, &mut frame).expect("the generated layout seals");
                    let can = CanFrame::from_virtual(&frame).expect("a CAN frame");
                    attempts += 1;
                    let label = format!("{}: {} on CAN round {round}", g.spec, c.name);
                    compare_can(&codec, fi, &label, &g, &can, &mut tally);
                }
            }
        }
        println!("{}: {attempts} frames: {tally:?}", g.spec);
        // Most random frames are messages: the values of both codecs are compared, not only
        // their errors.
        assert!(
            tally.same_message * 2 > attempts,
            "{}: too few frames decoded: {tally:?}",
            g.spec
        );
    }
}

/// The items of the codec's own stream decoder over `bytes` in chunks of `n`, as event texts;
/// every frame's decoded message is compared with the generated `Packet::decode` of it.
fn stream_items(codec: &Codec<'_>, g: &Gen, bytes: &[u8], n: usize) -> Vec<String> {
    let mut stream = codec.stream(0).expect("a stream");
    let mut texts = Vec::new();
    let mut tally = Tally::default();
    let mut take = |item: Item<'_>, texts: &mut Vec<String>| match item {
        Item::Frame {
            offset,
            bytes,
            decoded,
        } => {
            let label = format!("{}: stream frame @{offset}", g.spec);
            compare(codec, &label, (g.decode)(bytes), decoded, &mut tally);
            texts.push(format!("frame @{offset} {}", hex(bytes)));
        }
        Item::Rejected { offset, reason } => {
            texts.push(event_text(&Event::Rejected { offset, reason }));
        }
        Item::Skipped { offset, len } => texts.push(event_text(&Event::Skipped { offset, len })),
    };
    for mut chunk in bytes.chunks(n) {
        while let Some(item) = stream.next_item(&mut chunk) {
            take(item, &mut texts);
        }
    }
    while let Some(item) = stream.flush_item() {
        take(item, &mut texts);
    }
    texts
}

/// The streams of the vector files, in chunks of several sizes: the interpreter's layout in
/// the engine yields the events of the generated decoder, and so does the codec's stream
/// decoder, whose frames decode as generated code decodes them.
#[test]
fn vector_streams_yield_the_same_events() {
    let files: &[(&str, &str)] = &[
        ("hflink", "hflink.json"),
        ("referee", "robomaster_referee.json"),
        ("scout", "agilex_scout.json"),
        ("dynamixel", "dynamixel_protocol2.json"),
        ("dynamixel1", "dynamixel_protocol1.json"),
        ("roborts", "roborts_sdk.json"),
        ("mavlink", "mavlink.json"),
        ("msp", "msp.json"),
        ("ibus", "ibus.json"),
        ("sbus", "sbus.json"),
        ("ubx", "ubx.json"),
    ];
    let gens = specs();
    for (g, file) in files.iter().flat_map(|(spec, file)| {
        gens.iter()
            .filter(move |g| g.spec == *spec)
            .map(move |g| (g, *file))
    }) {
        let spec = g.spec;
        let interp: Interpreter = interpreter(spec);
        let codec = g.codec(&interp);
        let layout = codec.layout(0).expect("layout");
        for stream in vectors(file)["streams"].as_array().expect("streams") {
            let Some(text) = stream["hex"].as_str() else {
                continue;
            };
            let bytes = unhex(text);
            for n in [1, 3, 7, 64, bytes.len()] {
                let mut decoder = StreamDecoder::<_, 4096>::new(&layout);
                let mut events = Vec::new();
                for mut chunk in bytes.chunks(n) {
                    while let Some(e) = decoder.next_event(&mut chunk) {
                        events.push(event_text(&e));
                    }
                }
                while let Some(e) = decoder.flush_event() {
                    events.push(event_text(&e));
                }
                assert_eq!(events, (g.stream)(&bytes, n), "{spec}: chunks of {n}");
                assert!(
                    events.iter().any(|e| e.starts_with("frame")),
                    "{spec}: no frame"
                );
                assert_eq!(
                    stream_items(&codec, g, &bytes, n),
                    events,
                    "{spec}: the codec's stream in chunks of {n}"
                );
            }
        }
    }
}

/// The events of a link's generated `any_decoder` over a stream cut in chunks of `n` bytes,
/// and each frame's format and its `AnyPacket` decoded (as `{:?}` prints the packet of its
/// format) and encoded again in that format.
type LinkEvents = fn(&[u8], usize) -> (Vec<String>, Vec<(usize, Generated<Vec<u8>>)>);

macro_rules! link_events {
    ($m:ident) => {
        |bytes: &[u8], n: usize| {
            let any = |frame: &protocol_kit::Frame<'_>| -> Generated<Vec<u8>> {
                let packet = $m::AnyPacket::from_frame(frame)?;
                let mut buf = vec![0u8; $m::ANY_DECODER_BUFFER_LEN];
                let n = packet
                    .encode(&mut buf)
                    .expect("generated code encodes what it decoded");
                let debug = match packet {
                    $m::AnyPacket::V1(p) => format!("{p:?}"),
                    $m::AnyPacket::V2(p) => format!("{p:?}"),
                };
                Ok((debug, buf[..n].to_vec()))
            };
            let mut decoder = $m::any_decoder();
            let mut events = Vec::new();
            let mut generated = Vec::new();
            for mut chunk in bytes.chunks(n) {
                while let Some(e) = decoder.next_event(&mut chunk) {
                    if let Event::Frame(f) = &e {
                        generated.push((f.format, any(f)));
                    }
                    events.push(event_text(&e));
                }
            }
            while let Some(e) = decoder.flush_event() {
                if let Event::Frame(f) = &e {
                    generated.push((f.format, any(f)));
                }
                events.push(event_text(&e));
            }
            (events, generated)
        }
    };
}

/// On `streams` in chunks of several sizes, the generated `any_decoder` and the codec's link
/// stream yield the same events, and every frame decodes alike by the format it came in.
fn link_streams_agree(spec: &str, streams: &[Vec<u8>], generated_events: LinkEvents) -> Tally {
    let interp = interpreter(spec);
    // A carrying field as its bytes, as the generated struct holds them.
    let codec = interp.codec().with_carried_packets(false);
    let link = interp.protocol().link.clone();
    assert_eq!(link.len(), 2, "{spec}: two command formats");
    let mut tally = Tally::default();
    for bytes in streams {
        for n in [1, 3, 7, 64, bytes.len()] {
            let (events, generated) = generated_events(bytes, n);
            let mut texts = Vec::new();
            let mut interpreted = Vec::new();
            let mut s = codec.link_stream().expect("a link stream");
            let mut take = |item: Item<'_>, texts: &mut Vec<String>| match item {
                Item::Frame {
                    offset,
                    bytes,
                    decoded,
                } => {
                    texts.push(format!("frame @{offset} {}", hex(bytes)));
                    interpreted.push(decoded);
                }
                Item::Rejected { offset, reason } => {
                    texts.push(event_text(&Event::Rejected { offset, reason }));
                }
                Item::Skipped { offset, len } => {
                    texts.push(event_text(&Event::Skipped { offset, len }));
                }
            };
            for mut chunk in bytes.chunks(n) {
                while let Some(item) = s.next_item(&mut chunk) {
                    take(item, &mut texts);
                }
            }
            while let Some(item) = s.flush_item() {
                take(item, &mut texts);
            }
            assert_eq!(texts, events, "{spec} link: chunks of {n}");
            assert_eq!(generated.len(), interpreted.len());
            for ((format, g), i) in generated.into_iter().zip(interpreted) {
                if let Ok(d) = &i {
                    assert_eq!(d.format, link[format], "the format it came in");
                }
                compare(&codec, &format!("{spec} link frame"), g, i, &mut tally);
            }
        }
    }
    tally
}

/// The vector streams of a spec's vector file, and one more of all its frames back to back.
fn link_test_streams(file: &str) -> Vec<Vec<u8>> {
    let v = vectors(file);
    let mut streams: Vec<Vec<u8>> = v["streams"]
        .as_array()
        .expect("streams")
        .iter()
        .filter_map(|s| s["hex"].as_str().map(unhex))
        .collect();
    let all = v["frames"]
        .as_array()
        .expect("frames")
        .iter()
        .filter_map(|f| f["hex"].as_str().map(unhex))
        .flatten()
        .collect();
    streams.push(all);
    streams
}

/// A link of several command formats (MAVLink 1 and 2; MSP v1 and v2, whose directions each
/// format's own field tells): the vector streams, and every vector frame back to back.
#[test]
fn link_streams_yield_the_same_events() {
    let tally = link_streams_agree(
        "mavlink",
        &link_test_streams("mavlink.json"),
        link_events!(mavlink),
    );
    println!("mavlink link streams: {tally:?}");
    assert!(tally.same_message >= 4, "{tally:?}");
    let tally = link_streams_agree("msp", &link_test_streams("msp.json"), link_events!(msp));
    println!("msp link streams: {tally:?}");
    // The 16 frames the spec expresses, in the stream of all frames at each chunk size, and
    // the 5 of the mixed stream.
    assert_eq!(tally.same_message, 5 * (16 + 5), "{tally:?}");
}
