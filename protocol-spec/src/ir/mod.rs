//! The checked, resolved protocol: what validation produces and every consumer (expansion,
//! docs, interpreter, diff) reads.
//!
//! Nothing here carries a span, a default still to apply or a string still to parse: every
//! size, offset, byte order and reference is resolved. Downstream code trusts it and never
//! reports a user error. Order is always the spec's order.
//!
//! Its parts: the protocol, its directions and commands (here), the payload types (structs,
//! fields, enums: `payload`) and the frame formats (`frame`).
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

mod frame;
mod payload;
mod registers;
mod session;

pub use frame::*;
pub use payload::*;
pub use registers::*;
pub use session::*;

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
    /// The conversation (`[session]`), when the spec declares one.
    pub session: Option<Session>,
    /// The register map (`[registers]`), when the spec declares one.
    pub registers: Option<RegisterMap>,
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
/// A direction of travel, which selects a command's payload.
#[derive(Debug, Clone, PartialEq)]
pub struct Direction {
    /// Name (`request`, `response`, or the name of an empty direction).
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
    /// A direction besides `request` and `response` whose frames carry the header and no
    /// payload, whatever the command (MSP's error replies: the command the sender refuses).
    /// Told by a header field; every command's payload in it is empty.
    pub empty: bool,
    /// The first frame format as this direction's frames lay it out, when a header field
    /// belongs to this direction only (`direction = "NAME"` on a layout element, Sensirion
    /// SHDLC's state byte): the frame with that field, its offsets, length rule and checks
    /// placed accordingly. `None`: the direction's frames are the first format's
    /// ([`Protocol::frame_in`]). Only directions the decoder is given have one.
    pub frame: Option<Frame>,
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

    /// The commands a frame of `f` can be decoded as by its struct alone, each with that
    /// struct: on a link without directions or acknowledgements (where a key names one struct
    /// and every frame carries a key), the commands whose struct no other command carries (a
    /// struct two commands carry does not tell which one a frame must hold). Empty elsewhere.
    pub fn sole_carriers<'a>(&'a self, f: &Frame) -> impl Iterator<Item = (&'a Command, usize)> {
        let typed = self.directions.is_empty() && f.ack.is_none();
        let first = |c: &Command| c.payloads.first().copied().flatten();
        self.commands
            .iter()
            .filter(move |_| typed)
            .filter_map(move |c| {
                let si = first(c)?;
                let carriers = self.commands.iter().filter(|o| first(o) == Some(si));
                (carriers.count() == 1).then_some((c, si))
            })
    }

    /// Frame format `format` as the frames of direction `direction` (an index into
    /// [`Protocol::directions`]) lay it out: the direction's own [`Direction::frame`] for the
    /// first format when it has one, else the format itself. `None` for a format out of range.
    pub fn frame_in(&self, format: usize, direction: Option<usize>) -> Option<&Frame> {
        let own = direction
            .filter(|_| format == 0)
            .and_then(|d| self.directions.get(d))
            .and_then(|d| d.frame.as_ref());
        own.or_else(|| self.frames.get(format))
    }

    /// True when a direction lays the first frame format out with fields of its own.
    pub fn directed_layouts(&self) -> bool {
        self.directions.iter().any(|d| d.frame.is_some())
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
