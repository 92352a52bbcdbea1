//! Generated code that names its runtime through a re-export: this crate depends on the
//! `protocol` crate under another name (`link_kit`) and re-exports it as `crate::kit::protocol`,
//! as a crate that wraps `protocol` for its users would. `::protocol_kit` does not resolve here, so
//! the expansion compiles only if every path it names comes from the `crate = ...` override.
//! The `sensors` spec derives serde and defmt through the same override, with neither crate a
//! dependency of this one.

#![no_std]
#![forbid(unsafe_code)]
#![deny(warnings, missing_docs)]

/// Where this crate's users find the `protocol-kit` crate.
pub mod kit {
    pub use link_kit as protocol;
}

link_kit::protocol!(crate = crate::kit::protocol, "../../specs/hflink.toml");

link_kit::protocol!(
    inline = r#"
[protocol]
name = "lamp"

[frames.main]
layout = [
  { sync = [0xAA] },
  { field = "len", type = "u8", length_of = "payload" },
  { field = "cmd", type = "u8" },
  { payload = { max = 8 } },
  { check = "crc-8-smbus", over = "frame" },
]
dispatch = ["cmd"]

[commands]
SET_LEVEL = { id = 1, payload = "Level" }

[structs.Level]
fields = [{ name = "brightness", type = "u8" }]
"#,
    crate = "crate::kit::protocol"
);

link_kit::protocol!(
    crate = crate::kit::protocol,
    derive(serde, defmt),
    inline = r#"
[protocol]
name = "sensors"

[frames.main]
layout = [
  { sync = [0x5A] },
  { field = "len", type = "u8", length_of = "payload" },
  { field = "cmd", type = "u8" },
  { payload = { max = 16 } },
  { check = "crc-8-smbus", over = "frame" },
]
dispatch = ["cmd"]

[commands]
RANGE = { id = 1, payload = "Range" }
RESET = { id = 2 }

[enums.Unit]
type = "u8"
unknown = "keep"
values = { MM = 0, CM = 1 }

[structs.Range]
fields = [
  { name = "distance", type = "u16", scale = 0.001 },
  { name = "unit", type = "Unit" },
  { name = "tag", type = "bytes", max = 4 },
]
"#
);

/// A hand-written payload whose generated impl names the runtime through the override.
#[derive(Debug, Clone, Copy, PartialEq, Eq, link_kit::Payload)]
#[payload(crate = "crate::kit::protocol", byte_order = "big")]
pub struct Level {
    /// Brightness, 0 to 255.
    pub brightness: u8,
    /// Fade time in milliseconds.
    pub fade_ms: u16,
}

#[cfg(test)]
mod tests {
    use super::kit::protocol::Payload;
    use super::{Level, hflink, lamp, sensors};

    #[test]
    fn a_spec_expanded_through_the_override_encodes_and_decodes() {
        let packet = hflink::Packet {
            header: hflink::Header {
                sender: 0x01,
                receiver: 0x11,
            },
            message: hflink::Message::Request(hflink::Request::ReadRobotSpeed),
        };
        let mut buf = [0u8; hflink::MAX_FRAME_LEN];
        let n = packet.encode(&mut buf).expect("fits");
        // FF FF sender receiver length(u16 BE: the command byte) command(13), sum mod 255.
        let head = [0xFF, 0xFF, 0x01, 0x11, 0x00, 0x01, 0x0D];
        let sum = head.iter().map(|&b| u32::from(b)).sum::<u32>() % 255;
        assert_eq!(buf[..n - 1], head);
        assert_eq!(u32::from(buf[n - 1]), sum);
        assert_eq!(hflink::Packet::decode(&buf[..n]), Ok(packet));
    }

    #[test]
    fn an_inline_spec_and_a_derive_use_the_string_form() {
        let level = Level {
            brightness: 200,
            fade_ms: 0x01F4,
        };
        let mut payload = [0u8; Level::SIZE];
        assert_eq!(level.to_bytes(&mut payload), Ok(3));
        assert_eq!(payload, [200, 0x01, 0xF4]);
        assert_eq!(Level::from_bytes(&payload), Ok(level));

        let packet = lamp::Packet {
            header: lamp::Header {},
            message: lamp::Message::SetLevel(lamp::Level { brightness: 7 }),
        };
        let mut frame = [0u8; lamp::MAX_FRAME_LEN];
        let n = packet.encode(&mut frame).expect("fits");
        assert_eq!(frame[..4], [0xAA, 1, 1, 7]);
        let mut decoder = lamp::decoder();
        let mut input = &frame[..n];
        let decoded = decoder.decode(&mut input).expect("one frame");
        assert_eq!(lamp::Packet::from_frame(decoded.bytes), Ok(packet));
    }

    #[test]
    fn derives_through_the_override_serialize_as_the_codec_does() {
        let packet = sensors::Packet {
            header: sensors::Header {},
            message: sensors::Message::Range(sensors::Range {
                distance: 1.5,
                unit: sensors::Unit::Unknown(9),
                tag: link_kit::Bytes::from_slice(&[0xAB, 0x01]).expect("fits"),
            }),
        };
        let json = serde_json::to_string(&packet).expect("serializes");
        assert_eq!(
            json,
            r#"{"command":"RANGE","header":{},"payload":{"distance":1.5,"unit":9,"tag":"ab01"}}"#
        );
        let back: sensors::Packet = serde_json::from_str(&json).expect("reads back");
        assert_eq!(back, packet);
        let reset: sensors::Packet =
            serde_json::from_str(r#"{"command":"RESET","header":{},"payload":{}}"#).expect("reads");
        assert_eq!(reset.message, sensors::Message::Reset);
    }
}
