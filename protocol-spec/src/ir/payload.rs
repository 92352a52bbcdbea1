//! The payload types of the IR: structs and their fields, scalars, scaling, bit members and
//! enums.

use super::{Algorithm, BitOrder, ByteOrder, CheckNaming, Rounding, UnknownPolicy};

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
    /// `u40`: five bytes, a `u64` in Rust; a value above 40 bits is an encode error
    U40,
    /// `i40`: five bytes of two's complement, an `i64` in Rust (sign-extended on decode); a
    /// value outside the 40-bit range is an encode error
    I40,
    /// `u48`: six bytes, a `u64` in Rust; a value above 48 bits is an encode error
    U48,
    /// `i48`: six bytes of two's complement, an `i64` in Rust, as `I40`
    I48,
    /// `u56`: seven bytes, a `u64` in Rust; a value above 56 bits is an encode error
    U56,
    /// `i56`: seven bytes of two's complement, an `i64` in Rust, as `I40`
    I56,
    /// `u32`
    U32,
    /// `i32`
    I32,
    /// `u64`
    U64,
    /// `i64`
    I64,
    /// `f16`, IEEE 754 binary16: two bytes, an `f32` in Rust (exact on decode, rounded to
    /// the nearest on encode; a finite value beyond the largest half is an encode error)
    F16,
    /// `f32`, IEEE 754 binary32
    F32,
    /// `f64`, IEEE 754 binary64
    F64,
    /// `bool`, one byte: 0 is false, anything else true (encoded as 1)
    Bool,
    /// `bool` with `invert = true`, one byte: 0 is true, anything else false (true encoded as
    /// 0, false as 1)
    BoolInverted,
}

impl Prim {
    /// Size on the wire, in bytes.
    pub fn size(self) -> usize {
        match self {
            Prim::U8 | Prim::I8 | Prim::Bool | Prim::BoolInverted => 1,
            Prim::U16 | Prim::I16 | Prim::F16 => 2,
            Prim::U24 | Prim::I24 => 3,
            Prim::U32 | Prim::I32 | Prim::F32 => 4,
            Prim::U40 | Prim::I40 => 5,
            Prim::U48 | Prim::I48 => 6,
            Prim::U56 | Prim::I56 => 7,
            Prim::U64 | Prim::I64 | Prim::F64 => 8,
        }
    }

    /// The Rust type name: the next wider type for the integers of odd widths (`u32` for
    /// `u24`, `i64` for `i40`), `f32` for `f16`.
    pub fn rust_name(self) -> &'static str {
        match self {
            Prim::U24 => "u32",
            Prim::I24 => "i32",
            Prim::U40 | Prim::U48 | Prim::U56 => "u64",
            Prim::I40 | Prim::I48 | Prim::I56 => "i64",
            Prim::F16 => "f32",
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
            Prim::Bool | Prim::BoolInverted => "bool",
        }
    }

    /// The name a spec writes (before an optional `le`/`be` suffix): the Rust type name, but
    /// the wire's own for the types Rust has not (`u24`, `i40`, `f16`).
    pub fn spec_name(self) -> &'static str {
        match self {
            Prim::U24 => "u24",
            Prim::I24 => "i24",
            Prim::U40 => "u40",
            Prim::I40 => "i40",
            Prim::U48 => "u48",
            Prim::I48 => "i48",
            Prim::U56 => "u56",
            Prim::I56 => "i56",
            Prim::F16 => "f16",
            other => other.rust_name(),
        }
    }

    /// The types a spec names that Rust has not: each is its Rust type
    /// ([`Prim::rust_name`]) on the wire in fewer bytes.
    pub const NARROW: [Prim; 9] = [
        Prim::U24,
        Prim::I24,
        Prim::U40,
        Prim::I40,
        Prim::U48,
        Prim::I48,
        Prim::U56,
        Prim::I56,
        Prim::F16,
    ];

    /// Bits of the wire value.
    pub fn bits(self) -> u32 {
        8 * self.size() as u32
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

    /// The primitive a spec name (`u8` ... `i64`, `u24`, `i40`, `f16`, `f32`, `f64`, `bool`)
    /// stands for: the inverse of [`Prim::spec_name`].
    pub fn from_spec_name(name: &str) -> Option<Prim> {
        Prim::NARROW
            .into_iter()
            .find(|p| p.spec_name() == name)
            .or_else(|| Prim::from_rust_name(name))
    }

    /// True for the unsigned integer types.
    pub fn is_unsigned(self) -> bool {
        matches!(
            self,
            Prim::U8
                | Prim::U16
                | Prim::U24
                | Prim::U32
                | Prim::U40
                | Prim::U48
                | Prim::U56
                | Prim::U64
        )
    }

    /// True for the signed integer types.
    pub fn is_signed(self) -> bool {
        matches!(
            self,
            Prim::I8
                | Prim::I16
                | Prim::I24
                | Prim::I32
                | Prim::I40
                | Prim::I48
                | Prim::I56
                | Prim::I64
        )
    }

    /// True for `bool`, inverted or not.
    pub fn is_bool(self) -> bool {
        matches!(self, Prim::Bool | Prim::BoolInverted)
    }

    /// True for `f16`, `f32` and `f64`.
    pub fn is_float(self) -> bool {
        matches!(self, Prim::F16 | Prim::F32 | Prim::F64)
    }

    /// True for the types whose wire is narrower than their Rust type ([`Prim::NARROW`]): a
    /// value of the Rust type may not fit, which is an encode error.
    pub fn is_narrow(self) -> bool {
        Prim::NARROW.contains(&self)
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
    /// The packets the struct carries (`carries`): bytes fields that hold the payload of the
    /// command an earlier field of the struct names.
    pub carries: Vec<Carried>,
}

/// A `bytes` field that holds the payload of a command of the spec (`carries`): the command
/// is the one whose id the key field holds, the direction that of the frame around it.
#[derive(Debug, Clone, PartialEq)]
pub struct Carried {
    /// The bytes field (index into the struct's fields).
    pub field: usize,
    /// The unsigned integer field that holds the command's id (index into the struct's
    /// fields, before `field`).
    pub key: usize,
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
        /// The bytes are text without a terminator (`type = "str"`, the runtime's `Str<max>`):
        /// where they end is as for bytes; what differs is the value (a string when it is
        /// UTF-8, else its bytes).
        text: bool,
    },
    /// Elements of a struct (index into [`Protocol::structs`](super::Protocol::structs))
    /// repeated to the end of the payload (only as the last field of a struct).
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
    /// A value of a fixed size present only when bit `bit` of the earlier unsigned integer
    /// field `mask` of the struct is set (anywhere in the struct).
    When {
        /// The value when present.
        kind: Box<FieldKind>,
        /// The mask field (a field of this struct before this one).
        mask: String,
        /// The bit of the mask, from its least significant bit.
        bit: u32,
    },
    /// Bytes read as one stream of bits, most significant bit of the first byte first, split
    /// into members of 1 to 64 bits that straddle bytes as they fall (the runtime's
    /// [`protocol_runtime::bitstream`]); `ceil(bits / 8)` bytes, the bits after the last
    /// member written as 0 and ignored when read.
    BitStream {
        /// Members in stream order; `shift` is each one's first bit.
        members: Vec<BitMember>,
    },
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
        /// `size_from` is a mask (a field of this struct): the number of elements is the
        /// number of its set bits, not its value.
        by_mask: bool,
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

impl FieldKind {
    /// The bit members of a bitfield word or a bit stream: each a field of the Rust struct in
    /// place of the field itself.
    pub fn members(&self) -> Option<&[BitMember]> {
        match self {
            FieldKind::Bits { members, .. } | FieldKind::BitStream { members } => Some(members),
            _ => None,
        }
    }
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
    /// A nested struct (index into [`Protocol::structs`](super::Protocol::structs)).
    Struct(usize),
    /// An enum (index into [`Protocol::enums`](super::Protocol::enums)) with its wire integer.
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
    /// In a word: the lowest bit, counted from the least significant bit of the word. In a
    /// bit stream ([`FieldKind::BitStream`]): the first bit, counted from the most significant
    /// bit of the stream's first byte.
    pub shift: u32,
    /// Number of bits.
    pub width: u32,
    /// Rust type of the raw member: `Bool` for a one-bit flag unless written otherwise, else
    /// the smallest unsigned type that holds `width` bits, or the integer type written. A
    /// signed type makes the member two's complement of `width` bits, sign-extended when read.
    pub prim: Prim,
    /// The enum (index into [`Protocol::enums`](super::Protocol::enums)) the member holds, if any.
    pub enum_index: Option<usize>,
    /// Scaling from the raw member to its physical value (payload members only).
    pub scale: Option<Scale>,
    /// Physical unit, for docs (empty when none).
    pub unit: String,
}

impl BitMember {
    /// Whether the member is two's complement of its width.
    pub fn is_signed(&self) -> bool {
        self.prim.is_signed()
    }
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
