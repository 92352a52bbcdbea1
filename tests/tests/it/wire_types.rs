//! The payload types beyond the fixed-width primitives, decoded and encoded by generated code
//! and by the run-time codec (`protocol-dynamic`) from the same spec: golden payloads whose
//! layout comes from a public protocol description (named at each), the errors of values the
//! wire cannot hold, and round trips of arbitrary values.

use proptest::prelude::*;
use protocol_dynamic::{Interpreter, Value};
use protocol_kit::{EncodeError, Payload};

protocol_kit::protocol!("../protocol-codegen/tests/features/int24.toml");
protocol_kit::protocol!("../protocol-codegen/tests/features/reserved_bits.toml");
protocol_kit::protocol!("../protocol-codegen/tests/features/packed.toml");

/// The spec behind the `packed` module.
const PACKED_SPEC: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../protocol-codegen/tests/features/packed.toml"
);

/// A CRSF RC_CHANNELS_PACKED frame, as the README of kielerrr/CRSFv2-elrs shows it (address
/// 0xEE, length 24, type 0x16, 22 bytes of channels, CRC-8/DVB-S2 0x36); its channels are the
/// 11-bit LSB-first values of those bytes.
const CRSF_RC_FRAME: [u8; 26] = [
    0xEE, 0x18, 0x16, 0xE1, 0xE3, 0xDE, 0x09, 0xC7, 0xD7, 0x8A, 0x56, 0x80, 0x0F, 0x7C, 0xE0, 0x03,
    0x1F, 0xF8, 0xC0, 0x07, 0x3E, 0xF0, 0x81, 0x0F, 0x7C, 0x36,
];
const CRSF_RC_CHANNELS: [u16; 16] = [
    993, 988, 1063, 995, 173, 173, 992, 992, 992, 992, 992, 992, 992, 992, 992, 992,
];

/// SBUS frames with the channels their sources assert: zklapow/sbus `tests/parse_tester.rs`
/// (flags 0x03: both digital channels on) and LapochnihIvan/SBUSParser
/// `tests/src/parsing_test.c` (flags 0x4D: ch17, frame lost, failsafe, and the reserved bit 6).
const SBUS_FRAMES: [([u8; 25], [u16; 16], u8); 2] = [
    (
        [
            0x0F, 0xE0, 0x03, 0x1F, 0x58, 0xC0, 0x07, 0x16, 0xB0, 0x80, 0x05, 0x2C, 0x60, 0x01,
            0x0B, 0xF8, 0xC0, 0x07, 0x00, 0x00, 0x00, 0x00, 0x00, 0x03, 0x00,
        ],
        [
            992, 992, 352, 992, 352, 352, 352, 352, 352, 352, 992, 992, 0, 0, 0, 0,
        ],
        0x03,
    ),
    (
        [
            15, 41, 107, 214, 235, 44, 169, 3, 33, 187, 239, 95, 95, 76, 252, 16, 236, 190, 212,
            237, 81, 6, 69, 77, 0,
        ],
        [
            809, 717, 943, 1174, 58, 1602, 1006, 767, 1119, 1929, 67, 1910, 1355, 987, 404, 552,
        ],
        0x4D,
    ),
];

/// The spec behind the `int24` module, for the run-time codec.
const INT24_SPEC: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../protocol-codegen/tests/features/int24.toml"
);

/// The spec behind the `reserved_bits` module.
const RESERVED_BITS_SPEC: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../protocol-codegen/tests/features/reserved_bits.toml"
);

/// A CRSF `BATTERY_SENSOR` frame (type 0x08) laid out as the CRSF working group's packet
/// reference (crsf-wg/crsf wiki, `CRSF_FRAMETYPE_BATTERY_SENSOR`) describes it: big-endian
/// voltage and current in 0.1 V and 0.1 A, the capacity drawn as a 24-bit mAh count, the
/// remaining percentage; CRC-8/DVB-S2 over type and payload. 16.8 V, 12.3 A, 1500 mAh, 75 %.
const BATTERY_FRAME: [u8; 12] = [
    0xC8, 0x0A, 0x08, 0x00, 0xA8, 0x00, 0x7B, 0x00, 0x05, 0xDC, 0x4B, 0x29,
];

/// A `Samples` payload: -2 (i24le), 101325 Pa (u24le, 0.25 Pa), 123.45 m (i24be, 0.01 m from
/// -100 m), the extremes of i24, and the rate 0x0E1000.
const SAMPLES_PAYLOAD: [u8; 18] = [
    0xFE, 0xFF, 0xFF, 0x34, 0x2F, 0x06, 0x00, 0x57, 0x49, 0x80, 0x00, 0x00, 0x7F, 0xFF, 0xFF, 0x0E,
    0x10, 0x00,
];

#[test]
fn a_crsf_battery_frame_decodes_and_encodes_with_its_24_bit_capacity() {
    let packet = int24::Packet::decode(&BATTERY_FRAME).expect("the frame decodes");
    let int24::Message::Battery(battery) = &packet.message else {
        panic!("not a battery frame: {packet:?}");
    };
    assert_eq!(battery.capacity, 1500);
    assert_eq!(battery.remaining, 75);
    assert!((battery.voltage - 16.8).abs() < 1e-4, "{battery:?}");
    assert!((battery.current - 12.3).abs() < 1e-4, "{battery:?}");
    let mut buf = [0u8; int24::MAX_FRAME_LEN];
    let n = packet.encode(&mut buf).expect("it encodes");
    assert_eq!(buf[..n], BATTERY_FRAME);

    let interp = Interpreter::load(INT24_SPEC).expect("the spec loads");
    let codec = interp.codec();
    let d = codec
        .parse(0, &BATTERY_FRAME)
        .expect("the codec decodes it");
    assert_eq!(d.payload["capacity"], Value::UInt(1500));
    assert_eq!(d.payload["remaining"], Value::UInt(75));
    let v = codec.frame_value(&d, 0, &BATTERY_FRAME);
    assert_eq!(codec.encode(&v).expect("encodes").bytes, BATTERY_FRAME);
}

#[test]
fn signed_24_bit_values_extend_their_sign_and_scale() {
    let s = int24::Samples::from_bytes(&SAMPLES_PAYLOAD).expect("it decodes");
    assert_eq!(s.offset, -2);
    assert_eq!(s.pressure, 101_325.0);
    assert!((s.altitude - 123.45).abs() < 1e-9, "{s:?}");
    assert_eq!(s.history, [-0x80_0000, 0x7F_FFFF]);
    assert_eq!(s.rate, int24::Rate::Fast);
    assert_eq!(int24::Samples::SIZE, 18);
    let mut buf = [0u8; 18];
    assert_eq!(s.to_bytes(&mut buf), Ok(18));
    assert_eq!(buf, SAMPLES_PAYLOAD);
}

#[test]
fn a_value_beyond_24_bits_is_an_encode_error_not_a_truncation() {
    let mut battery = int24::Battery {
        voltage: 16.8,
        current: 12.3,
        capacity: 0x100_0000,
        remaining: 75,
    };
    let mut buf = [0u8; 18];
    assert_eq!(
        battery.to_bytes(&mut buf),
        Err(EncodeError::ValueOutOfRange {
            place: protocol_kit::error::Place::new("", "Battery.capacity")
        })
    );
    battery.capacity = 0xFF_FFFF;
    assert_eq!(battery.to_bytes(&mut buf), Ok(8));

    let mut s = int24::Samples::from_bytes(&SAMPLES_PAYLOAD).expect("it decodes");
    s.history[1] = 0x80_0000;
    assert_eq!(
        s.to_bytes(&mut buf),
        Err(EncodeError::ValueOutOfRange {
            place: protocol_kit::error::Place::new("", "Samples.history")
        })
    );
    s.history[1] = 0;
    // 0x80_0000 * 0.25 Pa: one step past the largest raw value.
    s.pressure = 4_194_304.0;
    assert_eq!(
        s.to_bytes(&mut buf),
        Err(EncodeError::ValueOutOfRange {
            place: protocol_kit::error::Place::new("", "Samples.pressure")
        })
    );

    let interp = Interpreter::load(INT24_SPEC).expect("the spec loads");
    let codec = interp.codec();
    let d = codec
        .parse(0, &BATTERY_FRAME)
        .expect("the codec decodes it");
    let mut v = codec.frame_value(&d, 0, &BATTERY_FRAME);
    let Value::Struct(frame) = &mut v else {
        panic!("a frame is an object")
    };
    let Some(Value::Struct(mut payload)) = frame.get("payload").cloned() else {
        panic!("the frame has a payload object: {frame:?}")
    };
    payload.insert("capacity", Value::UInt(0x100_0000));
    frame.insert("payload", Value::Struct(payload));
    let e = codec.encode(&v).expect_err("the codec refuses it");
    assert!(e.to_string().contains("u24"), "{e}");
}

proptest! {
    #[test]
    fn any_samples_round_trip_in_generated_code(
        offset in -0x80_0000i32..=0x7F_FFFF,
        raw_pressure in 0u32..=0xFF_FFFF,
        raw_altitude in -0x80_0000i32..=0x7F_FFFF,
        history in proptest::array::uniform2(-0x80_0000i32..=0x7F_FFFF),
        fast in any::<bool>(),
    ) {
        let mut bytes = Vec::new();
        bytes.extend_from_slice(&offset.to_le_bytes()[..3]);
        bytes.extend_from_slice(&raw_pressure.to_le_bytes()[..3]);
        bytes.extend_from_slice(&raw_altitude.to_be_bytes()[1..]);
        for h in history {
            bytes.extend_from_slice(&h.to_be_bytes()[1..]);
        }
        bytes.extend_from_slice(if fast { &[0x0E, 0x10, 0x00] } else { &[0x00, 0x25, 0x80] });
        let s = int24::Samples::from_bytes(&bytes).expect("every 24-bit value decodes");
        prop_assert_eq!(s.offset, offset);
        prop_assert_eq!(s.history, history);
        let mut buf = [0u8; 18];
        prop_assert_eq!(s.to_bytes(&mut buf), Ok(18));
        prop_assert_eq!(&buf[..], &bytes[..]);
        prop_assert_eq!(int24::Samples::from_bytes(&buf), Ok(s));
    }
}

/// A `Validity` payload: the NAV-PVT-style `valid` flags 0x37 (date, time, fully resolved, and
/// the reserved bits 4 and 5 set), a status word 0xF2A5 (mode 5, level 84, reserved bits
/// 12..16 all set) and a reserved-zero byte 0x81 (ready, bit 7 set).
const VALIDITY_PAYLOAD: [u8; 4] = [0x37, 0xA5, 0xF2, 0x81];

#[test]
fn undeclared_bits_are_kept_unless_the_spec_declares_them_reserved_zero() {
    let v = reserved_bits::Validity::from_bytes(&VALIDITY_PAYLOAD).expect("it decodes");
    assert!(v.valid_date && v.valid_time && v.fully_resolved && !v.valid_mag);
    assert_eq!(v.valid_reserved, 0b11);
    assert_eq!((v.mode, v.level, v.status_reserved), (5, 84, 0xF));
    assert!(v.ready);
    let mut buf = [0u8; 4];
    assert_eq!(v.to_bytes(&mut buf), Ok(4));
    // The kept bits come back; the reserved-zero bit 7 of the last byte is written as 0.
    assert_eq!(buf, [0x37, 0xA5, 0xF2, 0x01]);
    let too_wide = reserved_bits::Validity {
        valid_reserved: 0x10,
        ..v
    };
    assert_eq!(
        too_wide.to_bytes(&mut buf),
        Err(EncodeError::ValueOutOfRange {
            place: protocol_kit::error::Place::new("", "Validity.valid_reserved")
        })
    );

    // The same frame through the run-time codec: the same values, the same bytes.
    let mut frame = vec![0xB5, 0x62, 0x07, 0x04, 0x00];
    frame.extend_from_slice(&VALIDITY_PAYLOAD);
    frame.push(frame[2..].iter().fold(0u8, |a, b| a.wrapping_add(*b)));
    let packet = reserved_bits::Packet::decode(&frame).expect("the frame decodes");
    let interp = Interpreter::load(RESERVED_BITS_SPEC).expect("the spec loads");
    let codec = interp.codec();
    let d = codec.parse(0, &frame).expect("the codec decodes it");
    assert_eq!(d.payload["valid_reserved"], Value::UInt(0b11));
    assert_eq!(d.payload["status_reserved"], Value::UInt(0xF));
    assert_eq!(d.payload["ready"], Value::Bool(true));
    let mut generated = [0u8; reserved_bits::MAX_FRAME_LEN];
    let n = packet.encode(&mut generated).expect("it encodes");
    let value = codec.frame_value(&d, 0, &frame);
    assert_eq!(codec.encode(&value).expect("encodes").bytes, generated[..n]);
    assert_eq!(generated[5..9], [0x37, 0xA5, 0xF2, 0x01]);
}

proptest! {
    #[test]
    fn any_word_with_kept_bits_round_trips(valid in any::<u8>(), status in any::<u16>(), ready in 0u8..2) {
        let mut bytes = vec![valid];
        bytes.extend_from_slice(&status.to_le_bytes());
        bytes.push(ready);
        let v = reserved_bits::Validity::from_bytes(&bytes).expect("every word decodes");
        let mut buf = [0u8; 4];
        prop_assert_eq!(v.to_bytes(&mut buf), Ok(4));
        prop_assert_eq!(&buf[..], &bytes[..]);
    }
}

#[test]
fn a_crsf_rc_channels_frame_decodes_and_encodes_as_16_packed_channels() {
    let packet = packed::Packet::decode(&CRSF_RC_FRAME).expect("the frame decodes");
    let packed::Message::RcChannelsPacked(rc) = &packet.message else {
        panic!("not RC channels: {packet:?}");
    };
    assert_eq!(rc.channels, CRSF_RC_CHANNELS);
    let mut buf = [0u8; packed::MAX_FRAME_LEN];
    let n = packet.encode(&mut buf).expect("it encodes");
    assert_eq!(buf[..n], CRSF_RC_FRAME);

    let interp = Interpreter::load(PACKED_SPEC).expect("the spec loads");
    let codec = interp.codec();
    let d = codec
        .parse(0, &CRSF_RC_FRAME)
        .expect("the codec decodes it");
    let expected: Vec<Value> = CRSF_RC_CHANNELS
        .iter()
        .map(|&c| Value::UInt(u64::from(c)))
        .collect();
    assert_eq!(d.payload["channels"], Value::Array(expected));
    let v = codec.frame_value(&d, 0, &CRSF_RC_FRAME);
    assert_eq!(codec.encode(&v).expect("encodes").bytes, CRSF_RC_FRAME);
}

#[test]
fn sbus_frames_decode_to_the_channels_their_sources_assert() {
    let interp = Interpreter::load(PACKED_SPEC).expect("the spec loads");
    let codec = interp.codec();
    let sbus = codec.format_index("sbus").expect("the sbus format");
    for (frame, channels, flags) in SBUS_FRAMES {
        let packet = packed::SbusPacket::decode(&frame).expect("the frame decodes");
        let data = &packet.payload;
        assert_eq!(data.channels, channels);
        assert_eq!(data.ch17, flags & 1 != 0);
        assert_eq!(data.ch18, flags & 2 != 0);
        assert_eq!(data.frame_lost, flags & 4 != 0);
        assert_eq!(data.failsafe, flags & 8 != 0);
        assert_eq!(data.flags_reserved, flags >> 4);
        let mut buf = [0u8; 25];
        let n = packet.encode(&mut buf).expect("it encodes");
        assert_eq!(buf[..n], frame);

        let d = codec.parse(sbus, &frame).expect("the codec decodes it");
        assert_eq!(
            d.payload["flags_reserved"],
            Value::UInt(u64::from(flags >> 4))
        );
        let v = codec.frame_value(&d, 0, &frame);
        assert_eq!(codec.encode(&v).expect("encodes").bytes, frame);
    }
}

#[test]
fn msb_first_elements_scale_and_refuse_what_does_not_fit() {
    // Six 5-bit elements MSB-first: raw 0, 1, 10, 20, 30, 31 in 30 bits, then 2 zero bits.
    let raw = [0u64, 1, 10, 20, 30, 31];
    let word = raw.iter().fold(0u64, |w, r| (w << 5) | r) << 2;
    let mut payload = (word as u32).to_be_bytes().to_vec();
    payload.push(0xAB);
    let l = packed::Levels::from_bytes(&payload).expect("it decodes");
    for (level, r) in l.levels.iter().zip(raw) {
        assert!(
            (f64::from(*level) - (r as f64 * 0.1 - 1.0)).abs() < 1e-6,
            "{l:?}"
        );
    }
    assert_eq!(l.tail, 0xAB);
    let mut buf = [0u8; 5];
    assert_eq!(l.to_bytes(&mut buf), Ok(5));
    assert_eq!(buf[..], payload[..]);
    let mut too_high = l;
    // Raw 32 does not fit 5 bits.
    too_high.levels[2] = 2.2;
    assert_eq!(
        too_high.to_bytes(&mut buf),
        Err(EncodeError::ValueOutOfRange {
            place: protocol_kit::error::Place::new("", "Levels.levels")
        })
    );
    let mut crsf = packed::RcChannels {
        channels: CRSF_RC_CHANNELS,
    };
    crsf.channels[3] = 0x800;
    let mut buf = [0u8; 22];
    assert_eq!(
        crsf.to_bytes(&mut buf),
        Err(EncodeError::ValueOutOfRange {
            place: protocol_kit::error::Place::new("", "RcChannels.channels")
        })
    );
}

proptest! {
    #[test]
    fn any_packed_channels_round_trip(channels in proptest::array::uniform16(0u16..0x800)) {
        let rc = packed::RcChannels { channels };
        let mut buf = [0u8; 22];
        prop_assert_eq!(rc.to_bytes(&mut buf), Ok(22));
        prop_assert_eq!(packed::RcChannels::from_bytes(&buf), Ok(rc));
        // LSB-first: channel i is bits 11 i .. 11 i + 11 of the bytes read as one little-endian
        // number.
        for (i, c) in channels.iter().enumerate() {
            let bit = 11 * i;
            let mut v = 0u16;
            for j in 0..11 {
                let k = bit + j;
                v |= u16::from((buf[k / 8] >> (k % 8)) & 1) << j;
            }
            prop_assert_eq!(v, *c);
        }
    }
}
