//! What the payload generator reads: a struct as [`PayloadDef`], its fields in wire order.

use proc_macro2::{Ident, TokenStream};

use crate::ir::{BitOrder, ByteOrder, Prim, Scalar, Scale};

/// A struct as the payload generator sees it.
pub struct PayloadDef {
    /// The struct's name.
    pub name: Ident,
    /// Fields in wire order (generic structs are not supported: payloads are plain data).
    pub fields: Vec<PField>,
    /// The wire size when the caller knows it (spec structs); otherwise it is computed as a
    /// const expression over the fields (derive, whose nested types are opaque).
    pub size: Option<usize>,
    /// The smallest wire size, for structs whose size varies (spec structs).
    pub min_size: Option<usize>,
}

/// One field (or padding run) in wire order.
pub struct PField {
    /// The field (`None` for padding and for the word of a bitfield).
    pub ident: Option<Ident>,
    /// What is on the wire.
    pub kind: PKind,
}

/// The wire form of a field.
pub enum PKind {
    /// Bytes written as zero and skipped when read.
    Pad(usize),
    /// A primitive (or array of them), optionally scaled to a physical float.
    Scalar {
        /// Wire type.
        scalar: Scalar,
        /// Raw to physical scaling.
        scale: Option<Scale>,
        /// Array length.
        count: Option<usize>,
    },
    /// A type that implements `Payload` itself (or an array of it).
    Nested {
        /// The type.
        ty: TokenStream,
        /// Array length.
        count: Option<usize>,
    },
    /// A generated enum with `to_raw`/`from_raw` over `scalar`.
    Enum {
        /// The enum type.
        ty: TokenStream,
        /// Wire type of the raw value.
        scalar: Scalar,
        /// Array length.
        count: Option<usize>,
    },
    /// Bytes, as `ty` (the runtime's `Bytes<max>`): every byte left, or as many as the
    /// integer field `size_from` says.
    Bytes {
        /// The field's type.
        ty: TokenStream,
        /// The most bytes.
        max: usize,
        /// The field holding the number of bytes (of this struct, or of the struct that
        /// repeats this one).
        size_from: Option<Ident>,
    },
    /// Elements repeated to the end of the payload, as `ty` (the runtime's `Group<elem, max>`),
    /// read and written inline so that an element's sized bytes can use this struct's fields.
    Group {
        /// The field's type.
        ty: TokenStream,
        /// The element type.
        elem_ty: TokenStream,
        /// The element's fields.
        elem: Vec<PField>,
        /// The most elements.
        max: usize,
        /// The element's largest wire size.
        elem_size: usize,
    },
    /// A bit-packed array (the runtime's `packed`), read and written as `size` bytes.
    Packed {
        /// Elements.
        count: usize,
        /// Bits of each element.
        bits: u32,
        /// How the bits fill the bytes.
        order: BitOrder,
        /// Rust type of a raw element.
        prim: Prim,
        /// Raw to physical scaling of each element.
        scale: Option<Scale>,
        /// Bytes on the wire.
        size: usize,
    },
    /// A value present when bytes remain.
    Optional(Box<PKind>),
    /// An unsigned word whose bits are the struct fields `members`.
    Bits {
        /// The word on the wire.
        word: Scalar,
        /// Members, each a field of the struct.
        members: Vec<PBit>,
    },
    /// Elements of a primitive or enum (`elem`, without count) as `ty` (the runtime's
    /// `Group<T, max>`): to the end of the payload, or as many as the integer field
    /// `size_from` says.
    Array {
        /// The field's type.
        ty: TokenStream,
        /// One element.
        elem: Box<PKind>,
        /// The most elements.
        max: usize,
        /// The field holding the number of elements.
        size_from: Option<Ident>,
        /// Bytes of one element.
        elem_size: usize,
    },
    /// A runtime type whose wire size varies (`NulStr<N>`), read, written and sized by its
    /// own `Payload` impl; fields may follow it.
    Var {
        /// The type.
        ty: TokenStream,
    },
    /// A check value over the fields `first..=last` of the struct (indices into its fields),
    /// verified on read and computed on write by the runtime (`verify_check`, `put_check`);
    /// no field of the Rust struct.
    Check {
        /// The `Checksum` expression.
        checksum: TokenStream,
        /// First field covered.
        first: usize,
        /// Last field covered.
        last: usize,
        /// Byte order of the stored value.
        endian: ByteOrder,
        /// Bytes of the stored value.
        width: usize,
    },
}

/// A bit member of a [`PKind::Bits`] word.
pub struct PBit {
    /// Field name.
    pub ident: Ident,
    /// Lowest bit.
    pub shift: u32,
    /// Number of bits.
    pub width: u32,
    /// The field's type.
    pub ty: BitType,
}

/// The Rust type of a bit member.
pub enum BitType {
    /// `bool` (one bit).
    Bool,
    /// An unsigned integer.
    Uint(Prim),
    /// A generated enum; its raw type is given.
    Enum(TokenStream, Prim),
}
