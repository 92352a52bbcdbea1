//! A run-time codec for `protocol` specs: load a spec while the program runs, then decode
//! and encode its frames to and from a dynamic [`Value`], without generating or compiling
//! code. The `protocol` command's `decode` and `encode` run on it; so can any tool or host
//! program that learns its spec at run time.
//!
//! It reads the same checked IR as the `protocol!` macro ([`protocol_spec::ir`], loaded and
//! checked by [`protocol_spec::compile`], so a bad spec gives the macro's diagnostics) and
//! runs the runtime's own engine on it: every frame format becomes a runtime
//! [`FrameLayout`] value (what generated code holds as its `LAYOUT` static), so finding frames
//! in a stream ([`Codec::stream`], on [`protocol_runtime::StreamDecoder`]), verifying them
//! and sealing them use the very code generated codecs use, and the wire rules exist once; and
//! a runtime [`PacketRules`] value (its `RULES` static, [`Codec::with_rules`]), so the packet
//! rules between a checked frame and a message (the payload, acknowledgements, the dispatch
//! key, the direction the header tells, stuffing, zero-fill) exist once too. What this crate
//! adds is the dynamic half of generated code: header values, which command a key names,
//! which struct it carries in a direction, and payload values, to and from [`Value`] (see
//! [`model`] for how each IR type maps to a value). The wire compatibility of two versions of
//! a spec is [`compat`]. It depends on the front end (`protocol-spec`) and the runtime, and on
//! no printer, so it builds without `syn`, `quote` or `prettyplease`.
//!
//! ```
//! use protocol_dynamic::{Fields, Interpreter, Value};
//!
//! let interp = Interpreter::load(concat!(env!("CARGO_MANIFEST_DIR"), "/../specs/hflink.toml"))?;
//! let codec = interp.codec();
//!
//! let header: Fields = [("sender", Value::from(1u64)), ("receiver", Value::from(17u64))]
//!     .into_iter()
//!     .collect();
//! let payload: Fields = [("x", 0.5f32), ("y", 0.0), ("z", 0.1)]
//!     .into_iter()
//!     .map(|(k, v)| (k, Value::F32(v)))
//!     .collect();
//! let message: Fields = [
//!     ("command", Value::from("SET_ROBOT_SPEED")),
//!     ("header", Value::Struct(header)),
//!     ("payload", Value::Struct(payload)),
//! ]
//! .into_iter()
//! .collect();
//! let frame = codec.encode(&Value::Struct(message))?;
//!
//! let decoded = codec.parse(0, &frame.bytes)?;
//! assert_eq!(interp.protocol().commands[decoded.command.unwrap()].name, "SET_ROBOT_SPEED");
//! assert_eq!(decoded.payload["x"], Value::F32(0.5));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! A stream ([`Codec::stream`]) takes bytes in chunks of any size and yields [`Item`]s: frames
//! with their decoded message, rejected candidates and skipped bytes.
//!
//! ```
//! use protocol_dynamic::{Interpreter, Item};
//!
//! let interp = Interpreter::load(concat!(env!("CARGO_MANIFEST_DIR"), "/../specs/hflink.toml"))?;
//! let codec = interp.codec();
//! // A stray byte, then a READ_ROBOT_SPEED request (FF FF sender receiver length command sum).
//! let capture = [0x42, 0xFF, 0xFF, 0x01, 0x11, 0x00, 0x01, 0x0D, 0x20];
//! let mut stream = codec.stream(0).expect("hflink has a frame format");
//! let mut seen = Vec::new();
//! for mut chunk in capture.chunks(4) {
//!     while let Some(item) = stream.next_item(&mut chunk) {
//!         seen.push(match item {
//!             Item::Frame { offset, decoded: Ok(d), .. } => {
//!                 format!("{offset}: {}", interp.protocol().commands[d.command.unwrap()].name)
//!             }
//!             Item::Frame { offset, .. } => format!("{offset}: no message"),
//!             Item::Rejected { offset, .. } => format!("{offset}: rejected"),
//!             Item::Skipped { offset, len } => format!("{offset}: {len} skipped"),
//!         });
//!     }
//! }
//! assert_eq!(seen, ["0: 1 skipped", "1: READ_ROBOT_SPEED"]);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! With the `serde` feature, a [`Value`] is `Serialize` and `Deserialize`: a frame value
//! ([`Codec::frame_value`]) serialized with `serde_json` is one line of `protocol decode`'s JSON
//! Lines output, and such a line deserialized is what [`Codec::encode`] takes.
//!
//! ```
//! # #[cfg(feature = "serde")] {
//! # let interp = protocol_dynamic::Interpreter::load(concat!(env!("CARGO_MANIFEST_DIR"), "/../specs/hflink.toml"))?;
//! # let codec = interp.codec();
//! let line = r#"{"command":"SET_ROBOT_SPEED","header":{"sender":1,"receiver":17},"payload":{"x":0.5,"y":0.0,"z":0.1}}"#;
//! let object: protocol_dynamic::Value = serde_json::from_str(line)?;
//! let frame = codec.encode(&object)?;
//! let decoded = codec.parse(0, &frame.bytes)?;
//! let printed = serde_json::to_string(&codec.frame_value(&decoded, 0, &frame.bytes))?;
//! // The f32 0.1 prints as the shortest decimal that reads back as the same bits.
//! assert!(printed.contains(r#""payload":{"x":0.5,"y":0.0,"z":0.1}"#), "{printed}");
//! # }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Layouts borrow CRC objects, so they cannot live in the same struct as them: an
//! [`Interpreter`] owns the protocol and its CRC objects, and a [`Codec`] borrowed from it holds
//! the slices the layouts and packet rules borrow, and builds those values from them on use.
#![forbid(unsafe_code)]

pub mod compat;
mod conversation;
mod defaults;
mod error;
mod frame;
mod layout;
mod load;
pub mod model;
mod names;
mod payload;
pub mod registers;
#[cfg(feature = "serde")]
mod serde_impl;
mod session;
mod stream;
mod value;

pub use conversation::{Conversation, Heard};
pub use error::{DecodeIssue, EncodeIssue};
pub use frame::{Decoded, HexError, hex, parse_hex, parse_hex_located};
pub use layout::word_field;
pub use load::LoadError;
pub use model::{Fields, Value};
pub use stream::{Format, Item, Stream};
pub use value::{NumError, value_f32, value_f64};

use protocol_runtime::rules::PacketRules;
use protocol_runtime::{CanFrame, DecodeError, FrameLayout};
use protocol_spec::ir::{Protocol, Transport};

use layout::{CrcStore, FrameParts};
use names::Names;

/// A checked protocol with the CRC objects its layouts borrow.
pub struct Interpreter {
    protocol: Protocol,
    crcs: CrcStore,
    names: Names,
}

impl Interpreter {
    /// An interpreter of a checked protocol.
    pub fn new(protocol: Protocol) -> Self {
        let crcs = CrcStore::new(&protocol);
        let names = Names::new(&protocol);
        Interpreter {
            protocol,
            crcs,
            names,
        }
    }

    /// The protocol.
    pub fn protocol(&self) -> &Protocol {
        &self.protocol
    }

    /// The codec: layouts of every frame format, decoding and encoding.
    pub fn codec(&self) -> Codec<'_> {
        let frames = self
            .protocol
            .frames
            .iter()
            .enumerate()
            .map(|(i, f)| FrameParts::new(&self.protocol, i, f, &self.crcs))
            .collect();
        // A direction's own layout of the first format has the format's checks, so it takes
        // the format's CRC objects.
        let own = self
            .protocol
            .directions
            .iter()
            .map(|d| {
                let f = d.frame.as_ref()?;
                Some(FrameParts::new(&self.protocol, 0, f, &self.crcs))
            })
            .collect();
        Codec {
            protocol: &self.protocol,
            names: &self.names,
            frames,
            own,
            direction: None,
            carried: true,
        }
    }
}

/// An encoded frame.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Encoded {
    /// Index of its frame format.
    pub format: usize,
    /// The frame's bytes (a CAN format's virtual frame: id, length, data).
    pub bytes: Vec<u8>,
    /// The CAN frame, for a CAN format.
    pub can: Option<CanFrame>,
}

/// Decoding and encoding the frames of one protocol.
pub struct Codec<'a> {
    protocol: &'a Protocol,
    names: &'a Names,
    frames: Vec<FrameParts<'a>>,
    /// Per direction, its own layout of the first format (`None`: it has none).
    own: Vec<Option<FrameParts<'a>>>,
    direction: Option<usize>,
    carried: bool,
}

impl Codec<'_> {
    /// The protocol.
    pub fn protocol(&self) -> &Protocol {
        self.protocol
    }

    /// This codec decoding (and, for frame values that name none, encoding) frames of
    /// direction `direction` (an index into the protocol's directions): for a spec whose
    /// directions no header field tells (`given = true`), the decoding side's parameter, as
    /// generated code's `Packet::decode_<direction>`. Without one, such a spec's frames do not
    /// decode ([`DecodeIssue::DirectionNotGiven`]). A spec whose header tells its directions
    /// ignores it.
    #[must_use]
    pub fn with_direction(mut self, direction: Option<usize>) -> Self {
        self.direction = direction;
        self
    }

    /// This codec decoding a carrying field (`carries`) as the packet it carries (`true`, the
    /// default: as generated code's `<field>_<direction>()` reads it), or as its bytes
    /// (`false`: as the carrying struct holds them, and as the C peer reads them). Encoding
    /// takes either form.
    #[must_use]
    pub fn with_carried_packets(mut self, carried: bool) -> Self {
        self.carried = carried;
        self
    }

    /// The packets the payload of decoded frame `d` carries, read from the bytes of its
    /// carrying fields (`carries`, decoded [`with_carried_packets(false)`](Self::with_carried_packets))
    /// in the direction of the frame, as generated code's `<field>_<direction>()` reads them:
    /// per carrying field of the payload's struct, in field order, the command (an index into
    /// the protocol's commands) and its payload, or why the bytes are not one. Empty for a
    /// payload that carries none.
    pub fn carried_packets(&self, d: &Decoded) -> Vec<Result<(usize, Value), DecodeIssue>> {
        payload::carried_packets(self.protocol, self.names, d)
    }

    /// The direction this codec is given ([`with_direction`](Self::with_direction)).
    pub fn direction(&self) -> Option<usize> {
        self.direction
    }

    /// The index of the direction named `name`.
    pub fn direction_index(&self, name: &str) -> Option<usize> {
        self.protocol.directions.iter().position(|d| d.name == name)
    }

    /// The runtime layout of frame format `format` (an index into the protocol's frames), as
    /// generated code's `LAYOUT` holds it; for a direction this codec is given that has fields
    /// of its own, the first format as that direction lays it out (`RESPONSE_LAYOUT`). `None`
    /// for an index out of range.
    pub fn layout(&self, format: usize) -> Option<FrameLayout<'_>> {
        self.parts(format, self.direction).map(FrameParts::layout)
    }

    /// The parts of frame format `format` as the frames of `direction` lay it out.
    fn parts(&self, format: usize, direction: Option<usize>) -> Option<&FrameParts<'_>> {
        let own = direction
            .filter(|_| format == 0 && self.protocol.directions_given())
            .and_then(|d| self.own.get(d)?.as_ref());
        own.or_else(|| self.frames.get(format))
    }

    /// `f` run on the packet rules of frame format `format` (an index into the protocol's
    /// frames), as generated code's `RULES` holds them: what lies between a frame the engine
    /// checked and a message (the payload, acknowledgements, the dispatch key, the direction
    /// the header tells) and how a frame is assembled. `None` for an index out of range.
    ///
    /// A closure rather than a value: the rules borrow the format's layout, which the codec
    /// builds from its parts on each call.
    pub fn with_rules<R>(&self, format: usize, f: impl FnOnce(&PacketRules<'_>) -> R) -> Option<R> {
        self.with_rules_in(format, self.direction, f)
    }

    /// [`with_rules`](Self::with_rules) as the frames of `direction` lay the format out.
    fn with_rules_in<R>(
        &self,
        format: usize,
        direction: Option<usize>,
        f: impl FnOnce(&PacketRules<'_>) -> R,
    ) -> Option<R> {
        self.parts(format, direction)
            .map(|parts| parts.with_rules(f))
    }

    /// A stream decoder of frame format `format`: the runtime's engine on its layout, each
    /// frame it finds decoded ([`decode_frame`](Self::decode_frame)). `None` for an index out
    /// of range.
    pub fn stream(&self, format: usize) -> Option<Stream<'_>> {
        let layout = self.layout(format)?;
        Stream::new(self, vec![format], &[layout])
    }

    /// A stream decoder of the link: of every command format of the protocol (the first frame
    /// format and those that carry the commands too, `Protocol::link`), each frame decoded
    /// by the format it came in; of the first frame format when the link has one. `None` for
    /// a protocol without frame formats.
    pub fn link_stream(&self) -> Option<Stream<'_>> {
        let formats = if self.protocol.link.is_empty() {
            vec![0]
        } else {
            self.protocol.link.clone()
        };
        let layouts = formats
            .iter()
            .map(|&fi| self.layout(fi))
            .collect::<Option<Vec<_>>>()?;
        Stream::new(self, formats, &layouts)
    }

    /// Frame format `format` as the runtime's [`PacketLayout`](protocol_runtime::PacketLayout),
    /// for the runtime's `PacketDecoder` (a buffer size of the caller's choice) and the
    /// integrations built on it. `None` for an index out of range.
    pub fn packet_layout(&self, format: usize) -> Option<Format<'_>> {
        let layout = self.layout(format)?;
        Some(Format::new(self, format, layout))
    }

    /// The index of the frame format named `name`.
    pub fn format_index(&self, name: &str) -> Option<usize> {
        self.protocol.frames.iter().position(|f| f.name == name)
    }

    /// Decodes a frame the engine accepted (a CAN format's virtual frame), as generated
    /// `Packet::from_frame` does.
    ///
    /// # Errors
    /// [`DecodeIssue`], mirroring the runtime's [`DecodeError`] of generated code.
    pub fn decode_frame(&self, format: usize, frame: &[u8]) -> Result<Decoded, DecodeIssue> {
        self.decode_frame_as(format, frame, self.direction)
    }

    /// [`decode_frame`](Self::decode_frame) in direction `direction` (an index into the
    /// protocol's directions), whatever direction this codec is given: the choice of a
    /// decoder that knows each frame's direction from elsewhere ([`Conversation`]).
    ///
    /// # Errors
    /// As [`decode_frame`](Self::decode_frame).
    pub fn decode_frame_as(
        &self,
        format: usize,
        frame: &[u8],
        direction: Option<usize>,
    ) -> Result<Decoded, DecodeIssue> {
        self.with_rules_in(format, direction, |rules| {
            let read = (self.names, self.carried);
            frame::decode(self.protocol, read, format, rules, frame, direction)
        })
        .unwrap_or(Err(DecodeIssue::Frame(DecodeError::Frame(
            protocol_runtime::Reject::BadHeader,
        ))))
    }

    /// Verifies the framing of the frame at the start of `bytes`, then decodes it, as
    /// generated `Packet::decode` does.
    ///
    /// # Errors
    /// [`DecodeIssue::Frame`] when no valid frame starts there, then as
    /// [`decode_frame`](Self::decode_frame).
    pub fn parse(&self, format: usize, bytes: &[u8]) -> Result<Decoded, DecodeIssue> {
        let layout = self
            .layout(format)
            .ok_or(DecodeIssue::Frame(DecodeError::Frame(
                protocol_runtime::Reject::BadHeader,
            )))?;
        if layout.escape.is_some() {
            // The frame unescaped first, as generated code does on its stack.
            let mut unescaped = vec![0u8; layout.max_len];
            let frame = layout
                .parse_wire(bytes, &mut unescaped)
                .map_err(DecodeIssue::Frame)?;
            return self.decode_frame(format, frame);
        }
        let frame = layout.parse(bytes).map_err(DecodeIssue::Frame)?;
        self.decode_frame(format, frame)
    }

    /// Decodes a received CAN frame of a CAN format, verifying its checks on its virtual
    /// frame, as generated `<Name>Packet::decode` does.
    ///
    /// # Errors
    /// As [`parse`](Self::parse); [`DecodeIssue::Frame`] with `Reject::BadHeader` for an
    /// identifier of the other kind (standard or extended) than the format's.
    pub fn decode_can(&self, format: usize, can: &CanFrame) -> Result<Decoded, DecodeIssue> {
        let extended = self
            .protocol
            .frames
            .get(format)
            .is_some_and(|f| matches!(f.transport, Transport::Can { extended: true }));
        let can = can.of_kind(extended).map_err(DecodeIssue::Frame)?;
        let mut virt = [0u8; protocol_runtime::can::CAN_VIRTUAL_LEN];
        self.parse(format, can.to_virtual(&mut virt))
    }

    /// The value of a decoded frame, in the shape of a line of `protocol decode`'s JSON Lines
    /// output: offset, length, format, command, id, header, payload, hex (`can_id` for a CAN
    /// frame; `ack: true` instead of a command for an acknowledgement, whose payload is its
    /// data). `bytes` are the frame's bytes as received (a CAN frame's data bytes).
    pub fn frame_value(&self, d: &Decoded, offset: u64, bytes: &[u8]) -> Value {
        let p = self.protocol;
        let mut o = Fields::new();
        o.insert("offset", Value::UInt(offset));
        o.insert("length", Value::from(bytes.len()));
        let format = p.frames.get(d.format).map_or("", |f| f.name.as_str());
        o.insert("format", Value::from(format));
        // A direction no header field tells is part of the frame's value (encode reads it).
        if let Some(dir) = d
            .direction
            .filter(|_| p.directions_given())
            .and_then(|di| p.directions.get(di))
        {
            o.insert("direction", Value::from(dir.name.clone()));
        }
        if let Some(c) = d.command.and_then(|ci| p.commands.get(ci)) {
            o.insert("command", Value::from(c.name.clone()));
            let id = match d.id.as_slice() {
                [one] => Value::UInt(*one),
                many => Value::Array(many.iter().map(|x| Value::UInt(*x)).collect()),
            };
            o.insert("id", id);
        }
        if d.ack {
            o.insert("ack", Value::Bool(true));
        }
        if let Some(can_id) = d.can_id {
            o.insert("can_id", Value::UInt(can_id));
        }
        o.insert("header", Value::Struct(d.header.clone()));
        o.insert("payload", d.payload.clone());
        o.insert("hex", Value::Bytes(bytes.to_vec()));
        Value::Struct(o)
    }

    /// Encodes a frame value in the shape [`frame_value`](Self::frame_value) gives (`format`
    /// defaults to the first; `offset`, `length` and `hex` are ignored; values the spec
    /// computes, such as lengths and checks, are computed).
    ///
    /// # Errors
    /// [`EncodeIssue`] naming the first missing, ill-typed or out-of-range value.
    pub fn encode(&self, object: &Value) -> Result<Encoded, EncodeIssue> {
        let obj = object
            .as_struct()
            .ok_or_else(|| EncodeIssue::new("", "expected a frame object"))?;
        let format = match obj.get("format") {
            None | Some(Value::Null) => 0,
            Some(Value::String(name)) => self.format_index(name).ok_or_else(|| {
                EncodeIssue::new("format", format!("no frame format `{name}` in the spec"))
            })?,
            Some(_) => return Err(EncodeIssue::new("format", "expected a frame format name")),
        };
        let direction = frame::frame_direction(self.protocol, obj, self.direction);
        let bytes = self
            .with_rules_in(format, direction, |rules| {
                frame::encode(self.protocol, format, rules, obj, self.direction)
            })
            .ok_or_else(|| EncodeIssue::new("format", "no such frame format"))??;
        let can = match self.protocol.frames[format].transport {
            Transport::Can { .. } => {
                Some(CanFrame::from_virtual(&bytes).map_err(EncodeIssue::runtime)?)
            }
            Transport::Serial => None,
        };
        Ok(Encoded { format, bytes, can })
    }
}
