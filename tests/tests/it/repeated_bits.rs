//! A struct with bit members repeated by another (`repeated_bits.toml`, a spec the random spec
//! generator found generated code could not compile): its elements decode to their values and
//! encode back to their bytes, a bit member's enum value without variant is an error that
//! names the field, and the run-time codec agrees on every frame.

use protocol_dynamic::Interpreter;
use protocol_kit::error::Place;
use protocol_kit::{DecodeError, Group};

protocol_kit::protocol!("../protocol-codegen/tests/features/repeated_bits.toml");

use repeated_bits::*;

/// A frame: sync, length, command 1, payload, xor of the bytes before it.
fn frame(payload: &[u8]) -> Vec<u8> {
    let mut f = vec![0x7E, payload.len() as u8, 1];
    f.extend_from_slice(payload);
    let x = f.iter().fold(0u8, |a, &b| a ^ b);
    f.push(x);
    f
}

#[test]
fn repeated_bit_members_round_trip_and_agree_with_the_run_time_codec() {
    let flags = Flags {
        seq: 9,
        flags: Group::from_slice(&[
            Flag {
                id: 1,
                on: true,
                level: Level::High,
                count: 5,
                bits_reserved: 0,
            },
            Flag {
                id: 2,
                on: false,
                level: Level::Low,
                count: 15,
                bits_reserved: 0x1FF,
            },
        ])
        .expect("fits"),
    };
    // Bit 0 `on`, bits 1-2 `level`, bits 3-6 `count`, the rest kept; little-endian words.
    let bytes = frame(&[9, 1, 0x2D, 0x00, 2, 0xF8, 0xFF]);
    let packet = Packet::decode(&bytes).expect("a valid frame");
    assert_eq!(packet.message, Message::Flags(flags));
    let mut buf = [0u8; MAX_FRAME_LEN];
    let n = packet.encode(&mut buf).expect("it encodes");
    assert_eq!(&buf[..n], &bytes[..]);

    let path = format!(
        "{}/../protocol-codegen/tests/features/repeated_bits.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let interp = Interpreter::load(&path).expect("the spec loads");
    assert!(interp.codec().parse(0, &bytes).is_ok());

    // Level 1 is no variant.
    let bad = frame(&[9, 1, 0x02, 0x00]);
    assert_eq!(
        Packet::decode(&bad).map(|_| ()),
        Err(DecodeError::InvalidEnum {
            value: 1,
            place: Place::new("FLAGS", "Flag.level"),
        })
    );
    let issue = interp
        .codec()
        .parse(0, &bad)
        .expect_err("level 1 is no variant");
    assert_eq!(
        issue.to_runtime(),
        DecodeError::InvalidEnum {
            value: 1,
            place: Place::NONE
        }
    );
}
