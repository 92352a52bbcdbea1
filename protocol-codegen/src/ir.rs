//! The checked, resolved protocol: what validation produces and every consumer (expansion,
//! docs, interpreter, diff) reads.
//!
//! Nothing here carries a span, a default still to apply or a string still to parse: every
//! size, offset, byte order and reference is resolved. Downstream code trusts it and never
//! reports a user error. Order is always the spec's order.
//!
//! The wire vocabulary is the runtime's own ([`ByteOrder`], [`Pos`], the check [`Algorithm`]):
//! what the IR says is what the engine runs, with nothing to translate in between.

/// What a check computes: the runtime's table-free description, decided in validation.
pub use protocol_runtime::checksum::{Algorithm, CrcSpec, CrcTable};
/// How a scaled value is rounded to its raw integer, and what an enum does with a value that
/// has no variant: the runtime's own field rules ([`protocol_runtime::field`]), which the
/// generated code and the run-time codec both apply.
pub use protocol_runtime::field::{Rounding, UnknownPolicy};
pub use protocol_runtime::layout::{ByteOrder, Pos, WordField};
/// How the bits of a packed array fill its bytes: the runtime's own.
pub use protocol_runtime::packed::BitOrder;

/// A whole protocol spec, checked.
#[derive(Debug, Clone, PartialEq)]
pub struct Protocol {
    /// Module name (`[protocol] name`), a valid snake_case Rust identifier.
    pub name: String,
    /// Free version string of the spec (`[protocol] version`), empty when absent.
    pub version: String,
    /// Documentation of the protocol.
    pub doc: String,
    /// Spec constants, in spec order.
    pub constants: Vec<Constant>,
    /// Named address sets, in spec order.
    pub addresses: Vec<AddressSet>,
    /// Enums, in spec order.
    pub enums: Vec<Enum>,
    /// Payload structs, in spec order. A struct only refers to structs before it in this list
    /// (validation sorts dependencies first, otherwise keeping spec order).
    pub structs: Vec<Struct>,
    /// Frame formats; at least one. The first is the default.
    pub frames: Vec<Frame>,
    /// Directions; empty when every command has one payload.
    pub directions: Vec<Direction>,
    /// Commands, in spec order.
    pub commands: Vec<Command>,
    /// The frame formats (indices into `frames`) of the link's one decoder, in the order of
    /// the runtime's `Frame::format`: the first format, then those with
    /// [`PacketKind::Commands`]. Empty when the link has one command format.
    pub link: Vec<usize>,
}

/// A named integer constant of the spec.
#[derive(Debug, Clone, PartialEq)]
pub struct Constant {
    /// Name as written (SCREAMING_SNAKE_CASE).
    pub name: String,
    /// Value.
    pub value: u64,
    /// Documentation.
    pub doc: String,
}

/// A named address, or inclusive range of addresses.
#[derive(Debug, Clone, PartialEq)]
pub struct AddressSet {
    /// Name as written (snake_case).
    pub name: String,
    /// Lowest address of the set.
    pub first: u64,
    /// Highest address of the set (== `first` for a single address).
    pub last: u64,
    /// Documentation.
    pub doc: String,
}

/// A primitive wire type.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Prim {
    /// `u8`
    U8,
    /// `i8`
    I8,
    /// `u16`
    U16,
    /// `i16`
    I16,
    /// `u24`: three bytes, a `u32` in Rust; a value above 24 bits is an encode error
    U24,
    /// `i24`: three bytes of two's complement, an `i32` in Rust (sign-extended on decode); a
    /// value outside the 24-bit range is an encode error
    I24,
    /// `u32`
    U32,
    /// `i32`
    I32,
    /// `u64`
    U64,
    /// `i64`
    I64,
    /// `f32`, IEEE 754 binary32
    F32,
    /// `f64`, IEEE 754 binary64
    F64,
    /// `bool`, one byte: 0 is false, anything else true (encoded as 1)
    Bool,
}

impl Prim {
    /// Size on the wire, in bytes.
    pub fn size(self) -> usize {
        match self {
            Prim::U8 | Prim::I8 | Prim::Bool => 1,
            Prim::U16 | Prim::I16 => 2,
            Prim::U24 | Prim::I24 => 3,
            Prim::U32 | Prim::I32 | Prim::F32 => 4,
            Prim::U64 | Prim::I64 | Prim::F64 => 8,
        }
    }

    /// The Rust type name (`u32` for `u24`, `i32` for `i24`).
    pub fn rust_name(self) -> &'static str {
        match self {
            Prim::U24 => "u32",
            Prim::I24 => "i32",
            Prim::U8 => "u8",
            Prim::I8 => "i8",
            Prim::U16 => "u16",
            Prim::I16 => "i16",
            Prim::U32 => "u32",
            Prim::I32 => "i32",
            Prim::U64 => "u64",
            Prim::I64 => "i64",
            Prim::F32 => "f32",
            Prim::F64 => "f64",
            Prim::Bool => "bool",
        }
    }

    /// The name a spec writes (before an optional `le`/`be` suffix): the Rust type name, but
    /// `u24` and `i24` for the 24-bit integers.
    pub fn spec_name(self) -> &'static str {
        match self {
            Prim::U24 => "u24",
            Prim::I24 => "i24",
            other => other.rust_name(),
        }
    }

    /// The primitive a Rust type name (`u8` ... `i64`, `f32`, `f64`, `bool`) stands for: the
    /// inverse of [`Prim::rust_name`].
    pub fn from_rust_name(name: &str) -> Option<Prim> {
        [
            Prim::U8,
            Prim::I8,
            Prim::U16,
            Prim::I16,
            Prim::U32,
            Prim::I32,
            Prim::U64,
            Prim::I64,
            Prim::F32,
            Prim::F64,
            Prim::Bool,
        ]
        .into_iter()
        .find(|p| p.rust_name() == name)
    }

    /// The primitive a spec name (`u8` ... `i64`, `u24`, `i24`, `f32`, `f64`, `bool`) stands
    /// for: the inverse of [`Prim::spec_name`].
    pub fn from_spec_name(name: &str) -> Option<Prim> {
        match name {
            "u24" => Some(Prim::U24),
            "i24" => Some(Prim::I24),
            other => Prim::from_rust_name(other),
        }
    }

    /// True for the unsigned integer types.
    pub fn is_unsigned(self) -> bool {
        matches!(
            self,
            Prim::U8 | Prim::U16 | Prim::U24 | Prim::U32 | Prim::U64
        )
    }

    /// True for the signed integer types.
    pub fn is_signed(self) -> bool {
        matches!(
            self,
            Prim::I8 | Prim::I16 | Prim::I24 | Prim::I32 | Prim::I64
        )
    }

    /// True for `f32` and `f64`.
    pub fn is_float(self) -> bool {
        matches!(self, Prim::F32 | Prim::F64)
    }
}

/// A primitive with its byte order (the byte order of a one-byte type is irrelevant but set).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Scalar {
    /// The type.
    pub prim: Prim,
    /// The byte order.
    pub endian: ByteOrder,
}

/// A payload struct.
#[derive(Debug, Clone, PartialEq)]
pub struct Struct {
    /// Rust name (PascalCase, as written).
    pub name: String,
    /// Documentation.
    pub doc: String,
    /// Fields in wire order, padding included.
    pub fields: Vec<Field>,
    /// Wire size in bytes (sum of the field sizes); the largest size when the struct ends with
    /// variable bytes.
    pub size: usize,
    /// Smallest wire size (`size` unless the struct ends with variable bytes).
    pub min_size: usize,
    /// Fields of the struct that repeats this one, which this struct's sized bytes take their
    /// size from (empty for a struct that stands alone).
    pub context: Vec<String>,
    /// A type of the user's crate that a `#[derive(Payload)]` field names: `name` is its Rust
    /// type as written; it implements `Payload` itself, and its fields and size are not known
    /// here (no field, size 0). Never set for a spec's structs.
    pub foreign: bool,
    /// Bytes of the fields before the first extension field, for a struct that has extension
    /// fields (then of a fixed size): what a frame format without extensions carries of it.
    pub base_size: Option<usize>,
}

/// One field of a payload struct.
#[derive(Debug, Clone, PartialEq)]
pub struct Field {
    /// Rust field name (snake_case as written; keywords become raw identifiers in expansion).
    /// Empty for padding.
    pub name: String,
    /// Documentation.
    pub doc: String,
    /// Byte offset within the struct.
    pub offset: usize,
    /// Wire size in bytes.
    pub size: usize,
    /// What the field is.
    pub kind: FieldKind,
    /// Physical unit, for docs (empty when none).
    pub unit: String,
}

/// What a struct field holds.
#[derive(Debug, Clone, PartialEq)]
pub enum FieldKind {
    /// Reserved bytes: written as zero, ignored when read.
    Padding,
    /// A value, or a fixed array of values.
    Value {
        /// Element type.
        ty: ValueType,
        /// `Some(n)` for a fixed array of n elements.
        count: Option<usize>,
    },
    /// Bytes: every byte left in the payload (only as the last field of a struct), or as many
    /// as an earlier field states.
    Bytes {
        /// The most bytes.
        max: usize,
        /// The integer field that holds the number of bytes: a field of this struct before
        /// this one, or of the struct that repeats this one.
        size_from: Option<String>,
    },
    /// Elements of a struct (index into [`Protocol::structs`]) repeated to the end of the
    /// payload (only as the last field of a struct).
    Group {
        /// The element struct.
        elem: usize,
        /// The most elements.
        max: usize,
    },
    /// `count` unsigned integers of `bits` bits each, back to back in `ceil(count * bits / 8)`
    /// bytes (the runtime's [`protocol_runtime::packed`]); an array of `prim` in Rust, or of
    /// the physical type with `scale`.
    Packed {
        /// Elements.
        count: usize,
        /// Bits of each element, 1 to 32.
        bits: u32,
        /// How the bits fill the bytes.
        order: BitOrder,
        /// Rust type of a raw element: the smallest unsigned type that holds `bits` bits.
        prim: Prim,
        /// Scaling of each element from raw to physical value.
        scale: Option<Scale>,
    },
    /// A value present only when bytes remain in the payload (only at the end of a struct).
    Optional(Box<FieldKind>),
    /// An integer whose bits are split into named members.
    Bits {
        /// The integer on the wire.
        word: Scalar,
        /// Members, lowest bit first as written in the spec.
        members: Vec<BitMember>,
    },
    /// Elements of a primitive or an enum, as many as the payload has left (only as the last
    /// field of a struct) or as an earlier integer field says: the runtime's `Group<T, max>`.
    Array {
        /// The element type: [`ValueType::Scalar`] (scaled or not) or [`ValueType::Enum`].
        ty: ValueType,
        /// The most elements.
        max: usize,
        /// The integer field that holds the number of elements: a field of this struct before
        /// this one, or of the struct that repeats this one.
        size_from: Option<String>,
    },
    /// NUL-terminated text of at most `max` bytes, the NUL not counted (the runtime's
    /// `NulStr<max>`): 1 to `max + 1` bytes on the wire, so the struct's size varies and the
    /// fields after it follow its NUL.
    NulText {
        /// The most bytes of text.
        max: usize,
    },
    /// A check value over a run of earlier fields of the struct (a CRC inside the payload):
    /// verified on decode, computed on encode, no field of the Rust struct.
    Check(PayloadCheck),
}

/// A check inside a payload struct ([`FieldKind::Check`]).
#[derive(Debug, Clone, PartialEq)]
pub struct PayloadCheck {
    /// The algorithm the engine runs: a `prefix` is already folded into a CRC's initial
    /// value, so the check covers the fields alone.
    pub algorithm: Algorithm,
    /// How the algorithm is named (its table's `static` is the struct's own).
    pub naming: CheckNaming,
    /// First field covered (index into the struct's fields).
    pub first: usize,
    /// Last field covered (index into the struct's fields), at or after `first`, before the
    /// check.
    pub last: usize,
    /// The covered fields as docs name them (`` `destination` to `data` ``).
    pub covered: String,
    /// Constant bytes covered before the fields, as the spec gives them (for docs).
    pub prefix: Vec<u8>,
    /// Byte order of the stored value.
    pub endian: ByteOrder,
}

impl Struct {
    /// Bytes of the fields after field `i` when they are all of fixed size (the checks that
    /// follow a field that takes every byte left): what that field leaves to them.
    pub fn bytes_after(&self, i: usize) -> usize {
        self.fields.iter().skip(i + 1).map(|f| f.size).sum()
    }
}

/// The element type of a value field.
#[derive(Debug, Clone, PartialEq)]
pub enum ValueType {
    /// A primitive. With `scale`, the Rust value is `raw as f64 * scale` (an `f32` or `f64`
    /// per `physical`).
    Scalar {
        /// Wire type.
        scalar: Scalar,
        /// Scaling from raw to physical value.
        scale: Option<Scale>,
    },
    /// A nested struct (index into [`Protocol::structs`]).
    Struct(usize),
    /// An enum (index into [`Protocol::enums`]) with its wire integer.
    Enum(usize, Scalar),
    /// This many bytes of NUL-padded text (a C `char[N]`): the runtime's `FixedStr<N>`, which
    /// keeps every byte as received.
    Text(usize),
}

/// Scaling of a raw integer into a physical value: `physical = raw * factor + offset`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scale {
    /// Multiplier.
    pub factor: f64,
    /// Added after multiplying.
    pub offset: f64,
    /// Rust type of the physical value (`F32` or `F64`).
    pub physical: Prim,
    /// How a physical value becomes a raw integer on encode.
    pub rounding: Rounding,
    /// Physical values are clamped into this range before encoding.
    pub clamp: Option<(f64, f64)>,
}

/// A named group of bits inside a `Bits` field or a header word.
#[derive(Debug, Clone, PartialEq)]
pub struct BitMember {
    /// Name (snake_case).
    pub name: String,
    /// Documentation.
    pub doc: String,
    /// Lowest bit, counted from the least significant bit of the word.
    pub shift: u32,
    /// Number of bits.
    pub width: u32,
    /// Rust type of the member: `Bool` for a one-bit flag unless written otherwise, else the
    /// smallest unsigned type that holds `width` bits.
    pub prim: Prim,
    /// The enum (index into [`Protocol::enums`]) the member holds, if any.
    pub enum_index: Option<usize>,
}

/// An enum with explicit values.
#[derive(Debug, Clone, PartialEq)]
pub struct Enum {
    /// Rust name (PascalCase, as written).
    pub name: String,
    /// Documentation.
    pub doc: String,
    /// Integer type of the values.
    pub prim: Prim,
    /// Variants in spec order.
    pub variants: Vec<EnumVariant>,
    /// What a value with no variant becomes.
    pub unknown: UnknownPolicy,
    /// A type of the user's crate that a `#[derive(Payload)]` field names with `repr`: `name` is
    /// its Rust type as written; it has `to_raw` and `from_raw` over `prim`, and its variants
    /// are not known here. Never set for a spec's enums.
    pub foreign: bool,
}

/// One enum variant.
#[derive(Debug, Clone, PartialEq)]
pub struct EnumVariant {
    /// Name as written in the spec (SCREAMING_SNAKE_CASE).
    pub name: String,
    /// Rust variant name (PascalCase of `name`).
    pub rust_name: String,
    /// Value (two's complement bits for signed enums).
    pub value: u64,
    /// Documentation.
    pub doc: String,
}

/// How frames travel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Transport {
    /// A byte stream (UART, USB serial, TCP): frames are found by their sync bytes.
    Serial,
    /// CAN: a frame is an id and up to 8 data bytes. The frame's first two values are the
    /// virtual `can_id` (a big-endian `u32` word) and `dlc` (a `u8`), so checks may cover them;
    /// the data bytes follow.
    Can {
        /// 29-bit ids (CAN 2.0B) instead of 11-bit ones.
        extended: bool,
    },
}

/// Bytes of the virtual `can_id` + `dlc` prefix of a CAN frame.
pub const CAN_PREFIX_LEN: usize = 5;

/// A frame format.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// Name as written (snake_case).
    pub name: String,
    /// The Rust names of the frame format's items.
    pub names: FrameNames,
    /// How the frames travel.
    pub transport: Transport,
    /// Documentation.
    pub doc: String,
    /// Sync bytes at offset 0 (empty when `sync_set` is not).
    pub sync: Vec<u8>,
    /// The values of a sync from a set (a field with `one_of` as the first element): the
    /// frame's first header value, a `u8` at offset 0, holds one of them, and the decoder
    /// searches for any of them. Empty for a frame that starts with `sync`.
    pub sync_set: Vec<u8>,
    /// Bytes from the frame start to the payload (sync, header fields, header checks).
    pub header_len: usize,
    /// Bytes after the payload (frame checks, trailers).
    pub trailer_len: usize,
    /// Bytes a stream decoder needs before it knows a frame's length and has verified its
    /// header: through the sync, the length field, the constants and the header checks
    /// (fields after them, such as a command id, are part of what the length counts).
    pub decide_len: usize,
    /// Smallest payload.
    pub payload_min: usize,
    /// Largest payload.
    pub payload_max: usize,
    /// Header values (fields and bitfield members) in wire order.
    pub values: Vec<HeaderValue>,
    /// How the total frame length is known.
    pub length: Length,
    /// Indices into `values` of the dispatch key fields, in key order (empty: no dispatch).
    pub dispatch: Vec<usize>,
    /// Checks in the order they are verified on decode and computed on encode (header checks
    /// first, then frame checks in wire order).
    pub checks: Vec<Check>,
    /// Constant byte runs after the payload (trailers such as an end word).
    pub trailers: Vec<Trailer>,
    /// The wire elements in order, for docs and diagrams.
    pub elements: Vec<Element>,
    /// Acknowledgements: the index of the one-bit flag in `values` (role [`Role::Ack`]), and
    /// the bytes of an acknowledgement's header (the dispatch fields are absent).
    pub ack: Option<(usize, usize)>,
    /// Length of a bare header, when the frame may be the header alone.
    pub bare_len: Option<usize>,
    /// Byte stuffing of the payload: the pattern, and the byte inserted after it.
    pub stuffing: Option<(Vec<u8>, u8)>,
    /// Trailing-zero truncation of command payloads: the sender drops the zeros at the end of
    /// a payload (keeping its first byte), the receiver zero-fills it to its struct's size.
    pub truncate_zeros: bool,
    /// For a frame format without dispatch key: the struct (index into [`Protocol::structs`])
    /// every frame carries.
    pub message: Option<usize>,
    /// What a whole decoded frame of this format holds, when it has a packet type.
    pub packet: PacketKind,
    /// False when the format carries payloads without their extension fields (a struct's
    /// [`Struct::base_size`] bytes).
    pub extensions: bool,
    /// The header value (index into [`Frame::values`]) that tells the direction, in a spec
    /// whose header tells its directions: set on the first format and on each format after it
    /// that carries the commands (the field of the same name).
    pub direction: Option<usize>,
    /// The commands (indices into [`Protocol::commands`]) this format carries: every command
    /// for the first format with a dispatch key; for a format with
    /// [`PacketKind::Commands`], those whose id fits its dispatch fields; else none.
    pub commands: Vec<usize>,
    /// Bytes at the end of the frame, after its checks and trailers, present when a header
    /// flag is set (the MAVLink 2 signature).
    pub flag_trailer: Option<FlagTrailer>,
    /// A wider length that a marker value of the length field announces (MSP v1 jumbo
    /// frames): its bytes follow the header, and the payload starts after them.
    pub length_extension: Option<LengthExtension>,
}

/// A wider length, right after the header, present when the length field holds a marker
/// value; it counts what the length field counts. A frame uses it exactly when the count does
/// not fit below the marker.
#[derive(Debug, Clone, PartialEq)]
pub struct LengthExtension {
    /// The wider length (index into [`Frame::values`], role [`Role::WideLength`]).
    pub value: usize,
    /// The length field's value that announces it.
    pub marker: u64,
    /// Its bytes.
    pub len: usize,
}

/// Bytes at the end of a frame present when a one-bit header flag is set: carried as they are
/// (a MAVLink 2 signature is not verified: that needs a key).
#[derive(Debug, Clone, PartialEq)]
pub struct FlagTrailer {
    /// Name (snake_case): the `Header` field that holds the bytes.
    pub name: String,
    /// Documentation.
    pub doc: String,
    /// The flag (index into [`Frame::values`], role [`Role::Flag`]).
    pub flag: usize,
    /// How many bytes.
    pub len: usize,
}

/// The packet type of a frame format: what a whole decoded frame holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PacketKind {
    /// No packet type of its own.
    None,
    /// The first frame format, with a dispatch key: a header and a command's message.
    Command,
    /// A serial frame format without dispatch key, in a spec whose first frame format has one:
    /// a header and the struct (index into [`Protocol::structs`]) every frame carries.
    Message(usize),
    /// A CAN frame format other than the first, in a spec without directions whose first frame
    /// format has a dispatch key: a header and a command's message, the command found from the
    /// CAN id.
    Can,
    /// A serial frame format after the first that carries the commands too (`commands =
    /// true`): a header and a command's message, the command found from its own dispatch key.
    /// The link's decoder finds its frames beside the first format's.
    Commands,
}

impl Frame {
    /// Smallest total frame length (not counting a bare header): an acknowledgement without
    /// dispatch fields and with no data may be shorter than the smallest command frame.
    pub fn min_len(&self) -> usize {
        let command = self.header_len + self.payload_min + self.trailer_len;
        match self.ack {
            Some((_, ack_header_len)) => command.min(ack_header_len + self.trailer_len),
            None => command,
        }
    }
    /// Largest total frame length (with a flag trailer, if the frame has one).
    pub fn max_len(&self) -> usize {
        self.header_len
            + self.length_extension.as_ref().map_or(0, |e| e.len)
            + self.payload_max
            + self.trailer_len
            + self.flag_trailer_len()
    }
    /// Bytes of the flag trailer when present (0 without one).
    pub fn flag_trailer_len(&self) -> usize {
        self.flag_trailer.as_ref().map_or(0, |t| t.len)
    }
}

/// The Rust names of a frame format's items. The first (default) frame format's items have
/// the plain names (`Header`, `Decoder`, ...); another's carry its PascalCase name
/// (`ScoutHeader`, `ScoutDecoder`, ...), and its consts its upper-case name (`SCOUT_`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FrameNames {
    /// PascalCase of the frame name (`scout` -> `Scout`).
    pub pascal: String,
    /// Prefix of the frame's consts and statics: empty for the first frame, else `NAME_`.
    pub const_prefix: String,
    /// The struct of the header values a sender sets.
    pub header: String,
    /// The type of a whole decoded frame.
    pub packet: String,
    /// The type of the frame's layout.
    pub layout: String,
    /// The stream decoder type.
    pub decoder: String,
    /// The function that makes a stream decoder.
    pub decoder_fn: String,
    /// The `FrameLayout` static (`LAYOUT`, `SCOUT_CAN_LAYOUT`).
    pub layout_static: String,
    /// The size consts (`MAX_FRAME_LEN`, `SCOUT_CAN_HEADER_LEN`, ...).
    pub sizes: FrameSizeNames,
    /// The `wire` const of each header value, in the order of [`Frame::values`].
    pub wire: Vec<String>,
}

/// The names of a frame format's size consts.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FrameSizeNames {
    /// Largest frame.
    pub max_frame_len: String,
    /// Smallest frame.
    pub min_frame_len: String,
    /// Largest payload.
    pub max_payload_len: String,
    /// Smallest payload.
    pub min_payload_len: String,
    /// Bytes before the payload.
    pub header_len: String,
    /// Bytes after the payload.
    pub trailer_len: String,
    /// The stream decoder's buffer.
    pub decoder_buffer_len: String,
}

/// One element of a frame layout, for docs.
#[derive(Debug, Clone, PartialEq)]
pub enum Element {
    /// Sync bytes.
    Sync(Vec<u8>),
    /// A header word (index of its first value in `Frame::values`; `len` values share it).
    Word {
        /// Name of the word (field name).
        name: String,
        /// Where the word is.
        at: Pos,
        /// Wire type.
        scalar: Scalar,
        /// Indices into `Frame::values`.
        values: Vec<usize>,
    },
    /// The payload.
    Payload,
    /// A check (index into `Frame::checks`).
    Check(usize),
    /// A trailer (index into `Frame::trailers`).
    Trailer(usize),
    /// The flag trailer ([`Frame::flag_trailer`]), last.
    FlagTrailer,
}

/// A value stored in the header: a whole field, or some bits of a header word.
#[derive(Debug, Clone, PartialEq)]
pub struct HeaderValue {
    /// Name (snake_case).
    pub name: String,
    /// Documentation.
    pub doc: String,
    /// Where the word is: from the start for header values, back from the end for values
    /// after the payload (such as a rolling counter before the checksum).
    pub at: Pos,
    /// The word on the wire.
    pub word: Scalar,
    /// Lowest bit of the value in the word (0 for a whole field).
    pub shift: u32,
    /// Number of bits (8 * size for a whole field).
    pub width: u32,
    /// Rust type of the value.
    pub prim: Prim,
    /// What the value is for.
    pub role: Role,
}

/// What a header value is for.
#[derive(Debug, Clone, PartialEq)]
pub enum Role {
    /// Set by the user, exposed in the generated `Header` struct.
    User {
        /// True when the spec marks the field as holding addresses of `[addresses]`.
        addresses: bool,
    },
    /// The length field (see [`Frame::length`]); computed on encode.
    Length,
    /// Part of the dispatch key; set from the command on encode.
    Dispatch,
    /// Must equal this value; written on encode, checked on decode.
    Const(u64),
    /// The acknowledgement flag: equals the value when the frame is an acknowledgement; set by
    /// the codec from the message.
    Ack(u64),
    /// The flag of the frame's flag trailer ([`Frame::flag_trailer`]): set when the trailer is
    /// present; set by the codec from the header's trailer.
    Flag,
    /// The wider length of a [`LengthExtension`]: computed on encode, present only when the
    /// length field holds the marker.
    WideLength,
}

/// How the total length of a frame is known.
#[derive(Debug, Clone, PartialEq)]
pub enum Length {
    /// Every frame has the same length.
    Fixed(usize),
    /// `total = value + adjust`, where `value` is the header value at index `value`.
    Field {
        /// Index into `Frame::values`.
        value: usize,
        /// Added to the field value to give the total frame length (may be negative).
        adjust: i64,
    },
}

/// A check: a checksum or CRC over a range of the frame, stored in the frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Check {
    /// Name (snake_case, defaults to the algorithm kind).
    pub name: String,
    /// Documentation.
    pub doc: String,
    /// The algorithm, as the runtime describes it: backends print or execute it as it is.
    pub algorithm: Algorithm,
    /// How the algorithm is named.
    pub naming: CheckNaming,
    /// A byte folded in after the covered bytes, picked by the command.
    pub extra: Option<CheckExtra>,
    /// Where the check value is stored.
    pub at: Pos,
    /// Bytes of the stored check value.
    pub size: usize,
    /// Byte order of the stored value.
    pub endian: ByteOrder,
    /// First byte covered.
    pub from: Pos,
    /// One past the last byte covered.
    pub to: Pos,
    /// True when the check is inside the header: it is verified before the length is trusted.
    pub header: bool,
}

/// The byte a check folds in after the bytes it covers, one per command (MAVLink's
/// CRC_EXTRA): the runtime's [`Extra`](protocol_runtime::checksum::Extra) without its CRC.
#[derive(Debug, Clone, PartialEq)]
pub struct CheckExtra {
    /// The header value (index into [`Frame::values`]) whose value is the key: the frame's one
    /// dispatch field.
    pub value: usize,
    /// Where the key sits, from the first covered byte.
    pub key: WordField,
    /// `(command id, byte)` of every command, sorted by id.
    pub bytes: Vec<(u32, u8)>,
}

/// The names of a check's algorithm: what docs show, and the Rust items a CRC is printed with.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CheckNaming {
    /// The name docs show: `sum-mod-255`, `CRC-16/UMTS`, or the `[checksums]` name of a
    /// custom algorithm.
    pub display: String,
    /// True for an algorithm defined under `[checksums]`.
    pub custom: bool,
    /// For a catalogue CRC, the `crc` crate's constant (`CRC_16_UMTS`).
    pub crc_constant: Option<String>,
    /// For a CRC, the `static` its table lives in (`CRC_TABLE`, `SCOUT_CRC_TABLE`).
    pub table_static: Option<String>,
    /// For a check with a per-command extra byte, the `static` of its runtime `Extra`
    /// (`CRC_EXTRA`).
    pub extra_static: Option<String>,
}

/// A constant byte run after the payload.
#[derive(Debug, Clone, PartialEq)]
pub struct Trailer {
    /// Name (snake_case).
    pub name: String,
    /// Documentation.
    pub doc: String,
    /// Where it starts.
    pub at: Pos,
    /// The bytes.
    pub bytes: Vec<u8>,
}

/// A direction of travel, which selects a command's payload.
#[derive(Debug, Clone, PartialEq)]
pub struct Direction {
    /// Name (`request` or `response`).
    pub name: String,
    /// Rust name of the direction's message enum and variant (PascalCase of `name`).
    pub rust_name: String,
    /// Documentation.
    pub doc: String,
    /// How a decoder tells this direction from the header.
    pub rule: DirectionRule,
    /// A direction the decoder is given ([`DirectionRule::Given`]) may carry one struct in
    /// every frame instead of a command: the struct's index, and the header length without the
    /// dispatch key, whose bytes the struct takes (they are the last header bytes).
    pub message: Option<(usize, usize)>,
}

/// How a decoder recognises a direction.
#[derive(Debug, Clone, PartialEq)]
pub enum DirectionRule {
    /// A header value (index into the first frame's `values`) lies in an address set (index
    /// into [`Protocol::addresses`]).
    InSet {
        /// Header value index.
        value: usize,
        /// Address set index.
        set: usize,
    },
    /// A header value equals a constant.
    Equals {
        /// Header value index.
        value: usize,
        /// The constant.
        equals: u64,
    },
    /// No header value tells the direction: the decoding side is given it (generated code has
    /// a decoder per direction; the run-time codec takes it as a parameter).
    Given,
}

impl DirectionRule {
    /// The rule as frame format `f` applies it: the header value is `f`'s direction field
    /// ([`Frame::direction`]), the rule's own when `f` has none.
    pub fn in_frame(&self, f: &Frame) -> DirectionRule {
        match (self, f.direction) {
            (DirectionRule::InSet { set, .. }, Some(value)) => {
                DirectionRule::InSet { value, set: *set }
            }
            (DirectionRule::Equals { equals, .. }, Some(value)) => DirectionRule::Equals {
                value,
                equals: *equals,
            },
            _ => self.clone(),
        }
    }
}

impl Protocol {
    /// The types of a command id's values, one per dispatch field: the widest of the link's
    /// command formats' fields (the first format's when it is the link's only one), so that a
    /// command carried only by a wider format (MSP v2's ids above 255) has its id.
    pub fn id_prims(&self) -> Vec<Prim> {
        let Some(first) = self.frames.first() else {
            return Vec::new();
        };
        let mut prims: Vec<Prim> = first
            .dispatch
            .iter()
            .map(|&i| first.values[i].prim)
            .collect();
        for f in self
            .link
            .iter()
            .skip(1)
            .filter_map(|&fi| self.frames.get(fi))
        {
            for (p, &vi) in prims.iter_mut().zip(&f.dispatch) {
                if f.values[vi].prim.size() > p.size() {
                    *p = f.values[vi].prim;
                }
            }
        }
        prims
    }

    /// True when the decoder is given the direction instead of reading it from the header.
    pub fn directions_given(&self) -> bool {
        self.directions
            .iter()
            .any(|d| d.rule == DirectionRule::Given)
    }
}

/// A command.
#[derive(Debug, Clone, PartialEq)]
pub struct Command {
    /// Name as written (SCREAMING_SNAKE_CASE).
    pub name: String,
    /// Rust variant name (PascalCase of `name`).
    pub rust_name: String,
    /// Key: one value per dispatch field of the first frame.
    pub id: Vec<u64>,
    /// The CAN id, when the spec has a CAN frame.
    pub can_id: Option<u64>,
    /// The byte a check with a per-command extra folds in for this command.
    pub check_extra: Option<u8>,
    /// Documentation.
    pub doc: String,
    /// Payload struct (index into [`Protocol::structs`]) per direction, in the order of
    /// [`Protocol::directions`]; a single entry when the spec has no directions. `None`: the
    /// payload is empty.
    pub payloads: Vec<Option<usize>>,
}
