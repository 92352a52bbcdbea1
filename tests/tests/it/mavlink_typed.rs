//! `Packet::from_frame_as` and `Packet::encode_as` on the MAVLink 2 golden vectors
//! (`tests/vectors/mavlink.json`, `specs/mavlink.toml`): a frame decoded as each of the spec's
//! structs gives its packet's header and payload for the struct of its command and `None` for
//! every other one, and the struct encoded alone gives the packet's bytes. Then the errors:
//! a payload longer than its struct is the error `from_frame` gives, for that struct alone.

use protocol_tests::{F, hex, load_vectors};

protocol_kit::protocol!("../specs/mavlink.toml");

use mavlink::*;

/// The frame at the start of `bytes`, its framing checked.
fn frame(bytes: &[u8]) -> &[u8] {
    LAYOUT.parse(bytes).expect("a MAVLink 2 frame")
}

/// Decodes `frame` as `M` and, where it holds `M`, checks the header and payload against
/// `packet` and encodes them back to `bytes`; returns whether it held `M`.
fn as_struct<M>(frame: &[u8], packet: &Packet, payload: Option<&M>, bytes: &[u8]) -> bool
where
    M: protocol_kit::CommandPayload<Command = Command> + PartialEq + core::fmt::Debug,
{
    let name = M::COMMAND.name();
    let decoded = Packet::from_frame_as::<M>(frame).unwrap_or_else(|e| panic!("{name}: {e:?}"));
    assert_eq!(decoded.is_some(), payload.is_some(), "{name}");
    let Some((header, value)) = decoded else {
        return false;
    };
    assert_eq!(header, packet.header, "{name}");
    assert_eq!(Some(&value), payload, "{name}");
    let mut buf = [0u8; MAX_FRAME_LEN];
    let n =
        Packet::encode_as(&header, &value, &mut buf).unwrap_or_else(|e| panic!("{name}: {e:?}"));
    assert_eq!(F(&buf[..n]), F(bytes), "{name}");
    true
}

/// `as_struct` for every struct of the spec: how many of them `frame` holds.
fn every_struct(frame: &[u8], packet: &Packet, bytes: &[u8]) -> usize {
    macro_rules! each {
        ($($s:ident),*) => {
            [$(as_struct::<$s>(
                frame,
                packet,
                match &packet.message { Message::$s(p) => Some(p), _ => None },
                bytes,
            )),*]
        };
    }
    let held = each!(
        Heartbeat,
        SysStatus,
        SystemTime,
        ParamValue,
        GpsRawInt,
        Attitude,
        GlobalPositionInt,
        RcChannels,
        CommandLong,
        CommandAck,
        BatteryStatus,
        Statustext
    );
    held.into_iter().filter(|&h| h).count()
}

#[test]
fn every_mavlink_2_frame_decodes_as_its_struct_alone_and_encodes_back() {
    let mut checked = 0;
    for v in load_vectors("mavlink.json")["frames"]
        .as_array()
        .expect("frames")
    {
        if v["mavlink_version"] != 2 {
            continue;
        }
        let bytes = hex(v["hex"].as_str().expect("hex"));
        let frame = frame(&bytes);
        let packet = Packet::from_frame(frame).expect("decodes");
        assert_eq!(every_struct(frame, &packet, &bytes), 1, "{}", v["name"]);
        checked += 1;
    }
    assert!(checked >= 12, "{checked} MAVLink 2 frames");
}

#[test]
fn a_payload_longer_than_its_struct_is_an_error_of_that_struct_alone() {
    // HEARTBEAT (9 bytes, the last not zero: nothing truncated) sent with 10: the check is
    // computed over the long payload, so the framing holds and the payload's length fails.
    let heartbeat = Heartbeat {
        mavlink_version: 3,
        ..Heartbeat::default()
    };
    let header = Header::default();
    let mut buf = [0u8; MAX_FRAME_LEN];
    let n = Packet::encode_as(&header, &heartbeat, &mut buf).expect("encodes");
    let long = lengthened(&buf[..n]);
    let frame = frame(&long);
    let whole = Packet::from_frame(frame).map(|_| ());
    assert!(whole.is_err(), "{whole:?}");
    assert_eq!(Packet::from_frame_as::<Heartbeat>(frame).map(|_| ()), whole);
    assert_eq!(Packet::from_frame_as::<Attitude>(frame), Ok(None));
}

/// A HEARTBEAT frame with one more payload byte (zero) and its check recomputed.
fn lengthened(frame: &[u8]) -> Vec<u8> {
    let payload_end = frame.len() - 2;
    let mut long = frame[..payload_end].to_vec();
    long.push(0);
    long[1] += 1;
    let crc = crc::Crc::<u16>::new(&crc::CRC_16_MCRF4XX);
    let mut digest = crc.digest();
    digest.update(&long[1..]);
    digest.update(&[50]); // HEARTBEAT's CRC_EXTRA
    long.extend_from_slice(&digest.finalize().to_le_bytes());
    long
}

#[test]
fn a_payload_cut_to_its_last_non_zero_byte_reads_zero_extended() {
    // MAVLink 2 sends a payload without its trailing zeros: this HEARTBEAT goes out with the
    // five bytes up to `type`, and its struct reads them followed by zeros.
    let heartbeat = Heartbeat {
        custom_mode: 0x0403_0201,
        r#type: 2,
        ..Heartbeat::default()
    };
    let header = Header::default();
    let mut buf = [0u8; MAX_FRAME_LEN];
    let n = Packet::encode_as(&header, &heartbeat, &mut buf).expect("encodes");
    assert_eq!(buf[1], 5, "payload length on the wire");
    let frame = frame(&buf[..n]);
    assert_eq!(
        Packet::from_frame_as::<Heartbeat>(frame),
        Ok(Some((header, heartbeat)))
    );
    let whole = Packet::from_frame(frame).expect("decodes");
    assert_eq!(whole.message, Message::Heartbeat(heartbeat));
}
