//! A generator of valid frames driven by a spec's checked IR: it knows every command, which
//! payload each direction carries, where the header values are and how a payload struct is laid
//! out, so it builds frames for any spec without naming its types.
//!
//! *Canonical* frames are the ones the encoder itself produces (padding zero, booleans 0 or 1,
//! unused bits zero, enum values that exist): those must survive decode → encode byte for byte.
//! *Raw* frames only pass the frame checks (any header values, any payload length and bytes):
//! those must decode to a value or an error, never a panic.

use protocol_codegen::ir;
use protocol_codegen::source::SpecSource;
use protocol_runtime::decoder::Probe;
use protocol_runtime::layout::{ByteOrder, Pos, WordField};
use protocol_runtime::{FrameLayout, LengthRule};

use super::{Source, Spec};

/// One way a frame can be sent: a command, in a direction, with that direction's payload.
#[derive(Debug, Clone, Copy)]
pub struct Choice {
    /// Index into the IR's commands.
    pub command: usize,
    /// Index into the IR's directions (`None` when the spec has none).
    pub direction: Option<usize>,
    /// The payload struct (`None`: empty payload).
    pub payload: Option<usize>,
}

/// A spec's IR and its generated layout.
pub struct Model {
    /// The checked protocol.
    pub ir: ir::Protocol,
    /// The generated layout (what the decoder runs on).
    pub layout: &'static FrameLayout<'static>,
    /// Every (command, direction) pair.
    pub choices: Vec<Choice>,
}

impl Model {
    /// Compiles the spec of `S`.
    ///
    /// # Panics
    /// If the spec does not compile (it compiled for `protocol!` already).
    pub fn of<S: Spec>() -> Model {
        let source = SpecSource::new(S::PATH, S::TEXT);
        let ir = protocol_codegen::compile(&source)
            .unwrap_or_else(|e| panic!("{} does not compile: {e:?}", S::PATH));
        let mut choices = Vec::new();
        for (command, c) in ir.commands.iter().enumerate() {
            if ir.directions.is_empty() {
                let payload = c.payloads.first().copied().flatten();
                choices.push(Choice { command, direction: None, payload });
            } else {
                for direction in 0..ir.directions.len() {
                    let payload = c.payloads.get(direction).copied().flatten();
                    choices.push(Choice { command, direction: Some(direction), payload });
                }
            }
        }
        Model { ir, layout: S::layout(), choices }
    }

    /// The frame format under test (the spec's first).
    pub fn frame(&self) -> &ir::Frame {
        &self.ir.frames[0]
    }

    /// Payload bytes of a choice.
    pub fn payload_len(&self, choice: Choice) -> usize {
        choice.payload.map_or(0, |s| self.ir.structs[s].size)
    }

    /// A random choice.
    pub fn choose(&self, src: &mut impl Source) -> Choice {
        self.choices[src.below(self.choices.len() as u64) as usize]
    }

    /// A canonical frame for a random choice.
    pub fn canonical(&self, src: &mut impl Source) -> Vec<u8> {
        let choice = self.choose(src);
        self.canonical_for(src, choice)
    }

    /// A canonical frame for `choice`.
    pub fn canonical_for(&self, src: &mut impl Source, choice: Choice) -> Vec<u8> {
        let mut payload = Vec::new();
        if let Some(s) = choice.payload {
            self.canonical_struct(src, s, &mut payload);
        }
        self.build(src, choice, &payload)
    }

    /// A frame of `choice` whose payload is `payload` (any bytes), sealed.
    ///
    /// # Panics
    /// If the layout refuses to seal it (a payload outside the format's bounds).
    pub fn build(&self, src: &mut impl Source, choice: Choice, payload: &[u8]) -> Vec<u8> {
        let f = self.frame();
        let mut frame = vec![0u8; f.header_len + payload.len() + f.trailer_len];
        for (i, v) in f.values.iter().enumerate() {
            let value = match &v.role {
                ir::Role::Const(c) => *c,
                ir::Role::Length => continue,
                ir::Role::Dispatch => {
                    let k = f.dispatch.iter().position(|&d| d == i).expect("dispatch value");
                    self.ir.commands[choice.command].id[k]
                }
                ir::Role::User { .. } => self.user_value(src, choice, i, v),
            };
            word_field(v).write(&mut frame, value).expect("header value fits");
        }
        let end = frame.len() - f.trailer_len;
        frame[f.header_len..end].copy_from_slice(payload);
        self.seal(frame)
    }

    /// A frame that passes every check but is otherwise random: any header values (an unknown
    /// command, an address in no direction's range), any payload length and bytes.
    pub fn raw(&self, src: &mut impl Source) -> Vec<u8> {
        let f = self.frame();
        let len = src.range(f.payload_min as u64, f.payload_max as u64) as usize;
        let mut frame = vec![0u8; f.header_len + len + f.trailer_len];
        for v in &f.values {
            let field = word_field(v);
            let value = match v.role {
                ir::Role::Length => continue,
                ir::Role::Const(c) if !src.one_in(8) => c,
                _ => src.next_u64() & field.max_value(),
            };
            field.write(&mut frame, value).expect("header value fits");
        }
        let end = frame.len() - f.trailer_len;
        let payload = src.bytes(len);
        frame[f.header_len..end].copy_from_slice(&payload);
        self.seal(frame)
    }

    /// Seals `frame` with the generated layout and checks that it is then a valid frame.
    fn seal(&self, mut frame: Vec<u8>) -> Vec<u8> {
        self.layout.seal(&mut frame).expect("seal");
        assert_eq!(self.layout.probe(&frame), Probe::Frame(frame.len()), "sealed frame is valid");
        frame
    }

    /// A header value set by the user: the direction's range or value for the field that
    /// tells the direction, anything that fits otherwise.
    fn user_value(&self, src: &mut impl Source, choice: Choice, index: usize, v: &ir::HeaderValue) -> u64 {
        if let Some(d) = choice.direction {
            match self.ir.directions[d].rule {
                ir::DirectionRule::InSet { value, set } if value == index => {
                    let set = &self.ir.addresses[set];
                    return src.range(set.first, set.last);
                }
                ir::DirectionRule::Equals { value, equals } if value == index => return equals,
                _ => {}
            }
        }
        src.next_u64() & word_field(v).max_value()
    }

    /// Appends the canonical bytes of a random value of struct `s`.
    pub fn canonical_struct(&self, src: &mut impl Source, s: usize, out: &mut Vec<u8>) {
        for field in &self.ir.structs[s].fields {
            match &field.kind {
                ir::FieldKind::Padding => out.resize(out.len() + field.size, 0),
                ir::FieldKind::Value { ty, count } => {
                    for _ in 0..count.unwrap_or(1) {
                        self.canonical_value(src, ty, out);
                    }
                }
                ir::FieldKind::Bits { word, members } => {
                    let mut bits = 0u64;
                    for m in members {
                        let value = match (m.enum_index, m.prim) {
                            (Some(e), _) => self.enum_value(src, e, m.width),
                            (None, ir::Prim::Bool) => src.below(2),
                            (None, _) => src.next_u64() & mask(m.width),
                        };
                        bits |= (value & mask(m.width)) << m.shift;
                    }
                    put_uint(out, *word, bits);
                }
            }
        }
    }

    fn canonical_value(&self, src: &mut impl Source, ty: &ir::ValueType, out: &mut Vec<u8>) {
        match ty {
            ir::ValueType::Struct(s) => self.canonical_struct(src, *s, out),
            ir::ValueType::Enum(e, scalar) => {
                let value = self.enum_value(src, *e, 8 * scalar.prim.size() as u32);
                put_uint(out, *scalar, value);
            }
            ir::ValueType::Scalar { scalar, .. } => {
                let value = match scalar.prim {
                    ir::Prim::Bool => src.below(2),
                    _ => src.next_u64(),
                };
                put_uint(out, *scalar, value);
            }
        }
    }

    /// A value of enum `e`: one of its variants, or (when unknown values are kept) any value.
    fn enum_value(&self, src: &mut impl Source, e: usize, width: u32) -> u64 {
        let en = &self.ir.enums[e];
        if en.unknown == ir::UnknownPolicy::Keep && src.one_in(4) || en.variants.is_empty() {
            return src.next_u64() & mask(width);
        }
        en.variants[src.below(en.variants.len() as u64) as usize].value
    }
}

/// The low `width` bits.
fn mask(width: u32) -> u64 {
    if width >= 64 { u64::MAX } else { (1u64 << width) - 1 }
}

/// Appends the low bytes of `value` in the scalar's size and byte order.
fn put_uint(out: &mut Vec<u8>, scalar: ir::Scalar, value: u64) {
    let size = scalar.prim.size();
    let le = value.to_le_bytes();
    let bytes = &le[..size];
    match scalar.endian {
        ir::Endian::Little => out.extend_from_slice(bytes),
        ir::Endian::Big => out.extend(bytes.iter().rev()),
    }
}

/// The runtime position of an IR position.
pub fn pos(p: ir::Pos) -> Pos {
    match p {
        ir::Pos::Start(n) => Pos::Start(n),
        ir::Pos::End(n) => Pos::End(n),
    }
}

/// The runtime word field of a header value.
pub fn word_field(v: &ir::HeaderValue) -> WordField {
    WordField {
        at: pos(v.at),
        size: v.word.prim.size() as u8,
        order: match v.word.endian {
            ir::Endian::Little => ByteOrder::Little,
            ir::Endian::Big => ByteOrder::Big,
        },
        shift: v.shift as u8,
        width: v.width as u8,
    }
}

/// The length field of the layout, with the adjustment (`None` for fixed-length frames).
pub fn length_field(layout: &FrameLayout<'_>) -> Option<(WordField, i64)> {
    match layout.length {
        LengthRule::Field { field, adjust } => Some((field, adjust)),
        LengthRule::Fixed(_) => None,
    }
}
