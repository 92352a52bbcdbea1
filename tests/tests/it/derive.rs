//! `#[derive(Payload)]` on hand-written structs: the same generator as spec structs, driven by
//! attributes. Each case checks the exact wire bytes in both directions.

use protocol_kit::{DecodeError, Payload};

#[derive(Debug, Clone, Copy, PartialEq, Default, Payload)]
struct Pose {
    x: f32,
    #[payload(byte_order = "big")]
    heading: i16,
}

#[derive(Debug, Clone, Copy, PartialEq, Payload)]
#[payload(byte_order = "big")]
struct Report {
    id: u8,
    #[payload(pad_after = 1)]
    flags: bool,
    counts: [u16; 3],
    #[payload(scale = 0.001, raw = "i16")]
    speed: f32,
    pose: Pose,
    poses: [Pose; 2],
}

#[test]
fn derived_payloads_have_the_declared_layout() {
    let report = Report {
        id: 7,
        flags: true,
        counts: [1, 0x0203, 0xFFFF],
        speed: -1.5,
        pose: Pose {
            x: 1.0,
            heading: -2,
        },
        poses: [
            Pose { x: 0.0, heading: 1 },
            Pose {
                x: -2.0,
                heading: 0x0102,
            },
        ],
    };
    assert_eq!(Pose::SIZE, 6);
    assert_eq!(Report::SIZE, 1 + 1 + 1 + 6 + 2 + 6 + 12);
    let mut buf = [0u8; 64];
    let n = report.to_bytes(&mut buf).expect("fits");
    let expected: Vec<u8> = [
        &[7u8, 1, 0][..],                      // id, flags, pad
        &[0x00, 0x01, 0x02, 0x03, 0xFF, 0xFF], // counts, big-endian
        &(-1500i16).to_be_bytes(),             // speed in mm/s
        &1.0f32.to_le_bytes(),
        &(-2i16).to_be_bytes(), // pose: x little-endian, heading big
        &0.0f32.to_le_bytes(),
        &1i16.to_be_bytes(),
        &(-2.0f32).to_le_bytes(),
        &0x0102i16.to_be_bytes(),
    ]
    .concat();
    assert_eq!(&buf[..n], &expected[..]);
    assert_eq!(Report::from_bytes(&buf[..n]), Ok(report));
    assert_eq!(
        Report::from_bytes(&buf[..n - 1]),
        Err(DecodeError::PayloadLength {
            expected: Report::SIZE,
            actual: n - 1
        })
    );
    assert!(report.to_bytes(&mut buf[..n - 1]).is_err());
}

/// `raw` alone gives an integer field a narrower wire form of its Rust type: a `u32` as the
/// three bytes of a `u24`, an `i32` as an `i24`.
#[derive(Debug, Clone, Copy, PartialEq, Payload)]
#[payload(byte_order = "big")]
struct Wide {
    #[payload(raw = "u24")]
    total: u32,
    #[payload(raw = "i24", byte_order = "little")]
    delta: i32,
}

#[test]
fn derived_24_bit_fields_take_three_bytes() {
    assert_eq!(Wide::SIZE, 6);
    let w = Wide {
        total: 0x12_3456,
        delta: -2,
    };
    let mut buf = [0u8; 6];
    assert_eq!(w.to_bytes(&mut buf), Ok(6));
    assert_eq!(buf, [0x12, 0x34, 0x56, 0xFE, 0xFF, 0xFF]);
    assert_eq!(Wide::from_bytes(&buf), Ok(w));
    let too_big = Wide {
        total: 0x100_0000,
        ..w
    };
    assert_eq!(
        too_big.to_bytes(&mut buf),
        Err(protocol_kit::EncodeError::ValueOutOfRange {
            place: protocol_kit::error::Place::new("", "Wide.total")
        })
    );
}
