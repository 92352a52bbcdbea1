//! The `embedded-can` integration with generated CAN packets: a spec with extended identifiers
//! encodes extended frames (a small number included), a standard spec standard ones, and both
//! cross a driver's frame type (`embedded_can::Frame`) and decode back; a received frame whose
//! identifier is of the other kind than the spec's is rejected, by generated code and by
//! `protocol-dynamic` alike.

use protocol_dynamic::{DecodeIssue, Interpreter};
use protocol_kit::embedded_can::{ExtendedId, Frame, Id, StandardId};
use protocol_kit::{CanFrame, DecodeError, Reject};

protocol_kit::protocol!(
    inline = r#"
[protocol]
name = "j1939ish"
byte_order = "big"

[frames.uart]
layout = [
  { sync = [0x5A, 0xA5] },
  { field = "frame_id", type = "u8" },
  { payload = { min = 2, max = 2 } },
  { check = "sum8", over = "frame" },
]
dispatch = ["frame_id"]

[frames.can]
transport = "can"
can_id = "extended"
layout = [
  { payload = { min = 2, max = 2 } },
]
dispatch = ["can_id"]

[commands]
SPEED = { id = 1, can_id = 0x18FF_50E5, payload = "Speed" }
SMALL = { id = 2, can_id = 0x42, payload = "Speed" }

[structs.Speed]
fields = [{ name = "mm_s", type = "i16" }]
"#
);

protocol_kit::protocol!("../specs/scout.toml");

#[test]
fn extended_spec_encodes_extended_frames() {
    use j1939ish::{CanHeader, CanPacket, Message, Speed};
    for (message, raw) in [
        (Message::Speed(Speed { mm_s: -300 }), 0x18FF_50E5),
        (Message::Small(Speed { mm_s: 7 }), 0x42),
    ] {
        let packet = CanPacket {
            header: CanHeader {},
            message,
        };
        let frame = packet.encode().expect("encodes");
        assert!(frame.extended, "{raw:#x}: extended, as the spec says");
        assert_eq!(
            Frame::id(&frame),
            Id::Extended(ExtendedId::new(raw).expect("29 bits"))
        );
        let received: CanFrame = CanFrame::from_frame(&frame).expect("a data frame");
        assert_eq!(received, frame);
        assert_eq!(CanPacket::decode(&received), Ok(packet));
    }
}

#[test]
fn standard_spec_encodes_standard_frames() {
    use scout::{CanHeader, CanPacket, Message, SystemStatus};
    let status = CanPacket {
        header: CanHeader { count: 3 },
        message: Message::SystemStatus(SystemStatus::default()),
    };
    let frame = status.encode().expect("encodes");
    assert!(!frame.is_extended());
    assert_eq!(
        Frame::id(&frame),
        Id::Standard(StandardId::new(0x151).expect("11 bits"))
    );
    let again = CanFrame::from_frame(&frame.to_frame::<CanFrame>().expect("converts"));
    assert_eq!(again.map(|f| CanPacket::decode(&f)), Some(Ok(status)));
}

/// A frame of the other identifier kind is another protocol's frame, even with the number
/// and the data of a valid one.
const WRONG_KIND: DecodeError = DecodeError::Frame(Reject::BadHeader);

#[test]
fn extended_spec_rejects_standard_frames() {
    use j1939ish::{CanHeader, CanPacket, Message, Speed};
    let packet = CanPacket {
        header: CanHeader {},
        message: Message::Small(Speed { mm_s: 7 }),
    };
    let frame = packet.encode().expect("encodes");
    let standard = CanFrame {
        extended: false,
        ..frame
    };
    assert_eq!(CanPacket::decode(&frame), Ok(packet));
    assert_eq!(CanPacket::decode(&standard), Err(WRONG_KIND));
}

#[test]
fn standard_spec_rejects_extended_frames_generated_and_dynamic() {
    use scout::{CanHeader, CanPacket, Message, SystemStatus};
    let status = CanPacket {
        header: CanHeader { count: 3 },
        message: Message::SystemStatus(SystemStatus::default()),
    };
    let frame = status.encode().expect("encodes");
    let extended = frame.into_extended();
    assert_eq!(CanPacket::decode(&frame), Ok(status));
    assert_eq!(CanPacket::decode(&extended), Err(WRONG_KIND));

    let interp = Interpreter::load(concat!(env!("CARGO_MANIFEST_DIR"), "/../specs/scout.toml"))
        .expect("loads");
    let codec = interp.codec();
    let can = codec.format_index("can").expect("the CAN format");
    let decoded = codec
        .decode_can(can, &frame)
        .expect("the standard frame decodes");
    assert_eq!(decoded.can_id, Some(0x151));
    assert!(matches!(
        codec.decode_can(can, &extended),
        Err(DecodeIssue::Frame(e)) if e == WRONG_KIND
    ));
}
