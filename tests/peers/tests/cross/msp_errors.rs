//! The MSP error replies (`tests/vectors/msp_errors.json`) against `cu-msp-lib` 1.3, the
//! implementation that wrote them: each frame is what its serializer writes for an
//! `Unsupported` packet (`!`) of the frame's command without data (`serialize` for v1,
//! `serialize_v2` for v2), and its parser reads it back as that packet.

use cu_msp_lib::{MspPacket, MspPacketData, MspPacketDirection, MspParser};
use protocol_peers::{frame_bytes, frames, load_vectors, name, uint};

#[test]
fn every_error_frame_is_what_cu_msp_lib_writes_and_reads_for_its_command() {
    let v = load_vectors("msp_errors.json");
    for frame in frames(&v) {
        let at = name(frame);
        let bytes = frame_bytes(frame);
        let cmd = u16::try_from(uint(frame, "id")).expect("a 16-bit id");
        let packet = MspPacket {
            cmd,
            direction: MspPacketDirection::Unsupported,
            data: MspPacketData::from(&[][..]),
        };
        let v2 = frame["version"] == "v2";
        let mut written = vec![
            0u8;
            if v2 {
                packet.packet_size_bytes_v2()
            } else {
                packet.packet_size_bytes()
            }
        ];
        if v2 {
            packet.serialize_v2(&mut written).expect("serialize_v2");
        } else {
            packet.serialize(&mut written).expect("serialize");
        }
        assert_eq!(written, bytes, "{at}: cu-msp-lib's bytes");
        let mut parser = MspParser::new();
        let read: Vec<MspPacket> = bytes
            .iter()
            .filter_map(|&b| parser.parse(b).expect("parse"))
            .collect();
        assert_eq!(read.len(), 1, "{at}");
        assert_eq!(read[0].cmd, cmd, "{at}");
        assert_eq!(read[0].direction, MspPacketDirection::Unsupported, "{at}");
        assert!(read[0].data.as_slice().is_empty(), "{at}");
    }
    assert_eq!(frames(&v).len(), 60);
}
