//! The lowering of a frame format's packet rules ([`ir::Frame`]) to the runtime's
//! [`PacketRules`], once.
//!
//! [`lower_rules`] turns what validation decided about the packets of a format (what its frames
//! carry, the dispatch key, acknowledgements, the directions the header tells, stuffing,
//! trailing-zero truncation, the fields a format without extension fields carries) into the
//! runtime's own values. Two backends take its result as it is: the expansion prints it as the
//! format's `RULES` static, and the run-time codec builds a [`PacketRules`] value from it; the C
//! printer prints from the same plan. Each word field comes with the header value it is read
//! from, so printers can name it (`wire::NAME`).

use protocol_runtime::layout::{FrameLayout, WordField};
use protocol_runtime::rules::{AckRule, DirectionTest, PacketRules};
use protocol_runtime::stuffing::Stuffing;

use crate::ir::{self, DirectionRule, PacketKind, Protocol, Role, Transport};
use crate::layout::word_field;

/// What the frames of a format carry, as its packet type decodes them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Carries {
    /// A command, found from the format's dispatch key (its own fields, for a format after the
    /// first that carries the commands too).
    Command,
    /// A command, found from the CAN id.
    CanCommand,
    /// One struct (index into [`Protocol::structs`]), every frame.
    Struct(usize),
    /// No packet type: raw payload bytes.
    Bytes,
}

/// A word field of the rules, with the header value (index into [`ir::Frame::values`]) it reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Field {
    /// The header value.
    pub value: usize,
    /// The word field: the value's own, or (for a CAN id) its whole word.
    pub field: WordField,
}

impl Field {
    fn of(f: &ir::Frame, value: usize) -> Field {
        Field {
            value,
            field: word_field(&f.values[value]),
        }
    }

    /// True when the field is exactly its header value's (`wire::NAME` in generated code).
    pub fn is_value_field(&self, f: &ir::Frame) -> bool {
        f.values
            .get(self.value)
            .is_some_and(|v| word_field(v) == self.field)
    }
}

/// A frame format's packet rules, with the header values they read.
#[derive(Debug, Clone, PartialEq)]
pub struct RulesPlan<'f> {
    /// What the frames carry.
    pub carries: Carries,
    /// Bytes before the payload of a command frame.
    pub header_len: usize,
    /// Bytes after the payload, without a flag trailer.
    pub trailer_len: usize,
    /// Largest payload on the wire.
    pub max_payload: usize,
    /// The key's fields, in key order.
    pub key: Vec<Field>,
    /// Acknowledgements: the flag's header value and the rule.
    pub ack: Option<(usize, AckRule)>,
    /// The direction tests, in the order of [`Protocol::directions`], each with the header
    /// value it reads; empty when the spec has none or they are given.
    pub directions: Vec<(usize, DirectionTest)>,
    /// Byte stuffing of the payload.
    pub stuffing: Option<Stuffing<'f>>,
    /// Trailing-zero truncation of command payloads.
    pub truncate_zeros: bool,
}

/// What frame format `f` of `p` carries: its IR packet kind, read as the runtime needs it.
pub fn carries(f: &ir::Frame) -> Carries {
    match f.packet {
        PacketKind::Command | PacketKind::Commands => Carries::Command,
        PacketKind::Can => Carries::CanCommand,
        PacketKind::Message(si) => Carries::Struct(si),
        PacketKind::None => Carries::Bytes,
    }
}

/// Lowers the packet rules of frame format `f` of `p`.
pub fn lower_rules<'f>(p: &Protocol, f: &'f ir::Frame) -> RulesPlan<'f> {
    let carries = carries(f);
    RulesPlan {
        carries,
        header_len: f.header_len,
        trailer_len: f.trailer_len,
        max_payload: f.payload_max,
        key: lower_key(f, carries),
        ack: f
            .ack
            .map(|(flag, header_len)| lower_ack(f, flag, header_len)),
        directions: lower_directions(p, f, carries),
        stuffing: f.stuffing.as_ref().map(|(after, insert)| Stuffing {
            after,
            insert: *insert,
        }),
        truncate_zeros: f.truncate_zeros,
    }
}

/// The key: the dispatch fields; for a CAN format, the whole identifier word (bits above the
/// id's width, which no bus delivers, make an unknown command rather than another one).
fn lower_key(f: &ir::Frame, carries: Carries) -> Vec<Field> {
    match carries {
        Carries::Command => f.dispatch.iter().map(|&i| Field::of(f, i)).collect(),
        // The IR's CAN contract: the first value is the virtual `can_id`.
        Carries::CanCommand if matches!(f.transport, Transport::Can { .. }) => {
            let mut id = Field::of(f, 0);
            id.field = id.field.bits(0, id.field.size.saturating_mul(8));
            vec![id]
        }
        _ => Vec::new(),
    }
}

fn lower_ack(f: &ir::Frame, flag: usize, header_len: usize) -> (usize, AckRule) {
    // Validation gives the flag the role `Ack`; 1 is the usual flag.
    let equals = match f.values[flag].role {
        Role::Ack(equals) => equals,
        _ => 1,
    };
    let rule = AckRule {
        flag: word_field(&f.values[flag]),
        equals,
        header_len,
        bare: f.bare_len.is_some(),
    };
    (flag, rule)
}

/// The tests of the directions the header of `f` tells, each on `f`'s own direction field.
fn lower_directions(p: &Protocol, f: &ir::Frame, carries: Carries) -> Vec<(usize, DirectionTest)> {
    if carries != Carries::Command || p.directions_given() {
        return Vec::new();
    }
    p.directions
        .iter()
        .filter_map(|d| match d.rule.in_frame(f) {
            DirectionRule::InSet { value, set } => {
                let a = p.addresses.get(set)?;
                let v = f.values.get(value)?;
                let field = word_field(v);
                let bits = v.prim.size().saturating_mul(8);
                let (first, last) = (fit(bits, a.first), fit(bits, a.last));
                Some((value, DirectionTest::InRange { field, first, last }))
            }
            DirectionRule::Equals { value, equals } => {
                let field = word_field(f.values.get(value)?);
                Some((
                    value,
                    DirectionTest::Equals {
                        field,
                        value: equals,
                    },
                ))
            }
            DirectionRule::Given => None,
        })
        .collect()
}

/// `v` in the `bits` of a header value's type: the header value, of its type, is compared with
/// the address set's bounds in that type.
fn fit(bits: usize, v: u64) -> u64 {
    match bits {
        64.. => v,
        b => v & ((1u64 << b) - 1),
    }
}

impl<'f> RulesPlan<'f> {
    /// The rules, with `layout` as their frame rules and the key and direction slices built
    /// from this plan.
    pub fn rules<'a>(
        &'a self,
        layout: &'a FrameLayout<'a>,
        key: &'a [WordField],
        directions: &'a [DirectionTest],
    ) -> PacketRules<'a>
    where
        'f: 'a,
    {
        PacketRules {
            layout,
            header_len: self.header_len,
            trailer_len: self.trailer_len,
            max_payload: self.max_payload,
            key,
            ack: self.ack.map(|(_, a)| a),
            directions,
            stuffing: self.stuffing,
            truncate_zeros: self.truncate_zeros,
        }
    }

    /// The key's word fields.
    pub fn key_fields(&self) -> Vec<WordField> {
        self.key.iter().map(|k| k.field).collect()
    }

    /// The direction tests.
    pub fn direction_tests(&self) -> Vec<DirectionTest> {
        self.directions.iter().map(|(_, t)| *t).collect()
    }
}
