//! What `protocol diff` says a frame element or a field is, in the words a spec uses (`i16
//! (little-endian), scale 0.01`, `byte 4`, `stored big-endian`), so that a reason reads as the
//! spec that changed rather than as the IR that compares it. Owns no comparison: `mod.rs` and
//! `payload.rs` decide what changed, this module only words it.

use protocol_runtime::layout::{ByteOrder, Pos};
use protocol_runtime::packed::BitOrder;
use protocol_spec::ir::{
    Field, FieldKind, HeaderValue, Length, Protocol, Scalar, Scale, Transport, UnknownPolicy,
    ValueType,
};

/// A byte order as a spec's `byte_order` means it.
pub(super) fn order(o: ByteOrder) -> &'static str {
    match o {
        ByteOrder::Little => "little-endian",
        ByteOrder::Big => "big-endian",
    }
}

/// A primitive type: its spec name, with its byte order when it has more than one byte.
pub(super) fn scalar(s: &Scalar) -> String {
    if s.prim.size() > 1 {
        format!("{} ({})", s.prim.spec_name(), order(s.endian))
    } else {
        s.prim.spec_name().to_string()
    }
}

/// A field's `scale` and `offset` keys, as suffix of its type (`, scale 0.01`).
pub(super) fn scale(s: Option<&Scale>) -> String {
    match s {
        None => String::new(),
        Some(s) if s.offset == 0.0 => format!(", scale {}", s.factor),
        Some(s) => format!(", scale {}, offset {}", s.factor, s.offset),
    }
}

/// A position in a frame: `byte 3`, or `2 bytes before the end`.
pub(super) fn pos(p: Pos) -> String {
    match p {
        Pos::Start(n) => format!("byte {n}"),
        Pos::End(0) => "the end".to_string(),
        Pos::End(n) => format!("{n} bytes before the end"),
    }
}

/// The bytes from `from` up to (not including) `to`.
pub(super) fn span(from: Pos, to: Pos) -> String {
    format!("from {} up to {}", pos(from), pos(to))
}

/// A frame's `transport`.
pub(super) fn transport(t: &Transport) -> &'static str {
    match t {
        Transport::Serial => "serial",
        Transport::Can { extended: false } => "CAN (11-bit ids)",
        Transport::Can { extended: true } => "CAN (29-bit ids)",
    }
}

/// A frame's length rule: fixed, or a header field's value plus a constant.
pub(super) fn length(l: &Length, values: &[HeaderValue]) -> String {
    match l {
        Length::Fixed(n) => format!("every frame {n} bytes"),
        Length::Field { value, adjust } => {
            let name = values.get(*value).map_or("?", |v| v.name.as_str());
            match adjust {
                0 => format!("`{name}` bytes"),
                a if *a > 0 => format!("`{name}` + {a} bytes"),
                a => format!("`{name}` - {} bytes", a.unsigned_abs()),
            }
        }
    }
}

/// Where a header value is and what type it has: `u16 (big-endian) at byte 2, bits 0..12`.
pub(super) fn header_value(v: &HeaderValue) -> String {
    let bits = u32::try_from(v.word.prim.size() * 8).unwrap_or(u32::MAX);
    let at = format!("{} at {}", scalar(&v.word), pos(v.at));
    if v.shift == 0 && v.width == bits {
        at
    } else {
        format!("{at}, bits {}..{}", v.shift, v.shift + v.width)
    }
}

/// An enum's `unknown` key.
pub(super) fn unknown(u: UnknownPolicy) -> &'static str {
    match u {
        UnknownPolicy::Keep => "unknown = \"keep\"",
        UnknownPolicy::Reject => "unknown = \"reject\"",
    }
}

/// A payload field's type as its spec entry gives it.
pub(super) fn field_type(p: &Protocol, f: &Field) -> String {
    kind(p, f, &f.kind)
}

fn kind(p: &Protocol, f: &Field, kind_of: &FieldKind) -> String {
    match kind_of {
        FieldKind::Bytes {
            max,
            size_from,
            text,
        } => {
            let what = if *text { "text" } else { "bytes" };
            match size_from {
                Some(n) => format!("{what} (as many bytes as `{n}`, at most {max})"),
                None => format!("{what} (the rest, at most {max})"),
            }
        }
        FieldKind::Group { elem, max } => {
            format!("repeated {} (at most {max})", p.structs[*elem].name)
        }
        FieldKind::Optional(inner) => format!("optional {}", kind(p, f, inner)),
        FieldKind::When {
            kind: inner,
            mask,
            bit,
        } => {
            format!("{} when bit {bit} of `{mask}` is set", kind(p, f, inner))
        }
        FieldKind::Padding => format!("{} padding bytes", f.size),
        FieldKind::NulText { max } => format!("NUL-terminated text (at most {max})"),
        FieldKind::Array {
            ty,
            max,
            size_from,
            by_mask,
        } => {
            let n = match size_from {
                Some(n) if *by_mask => format!("one per bit set in `{n}`"),
                Some(n) => format!("as many as `{n}`"),
                None => "the rest".to_string(),
            };
            format!("array of {} ({n}, at most {max})", value(p, ty))
        }
        FieldKind::Check(c) => {
            let after = if c.prefix.is_empty() {
                String::new()
            } else {
                let bytes: Vec<String> = c.prefix.iter().map(|b| format!("{b:#04x}")).collect();
                format!(" after the bytes [{}]", bytes.join(", "))
            };
            format!(
                "check {} over {}{after}, {} bytes stored {}",
                c.naming.display,
                c.covered,
                f.size,
                order(c.endian)
            )
        }
        FieldKind::Bits { word, .. } => format!("bit fields in a {}", scalar(word)),
        FieldKind::BitStream { .. } => format!("a bit stream of {} bytes, MSB first", f.size),
        FieldKind::Packed {
            count,
            bits,
            order: o,
            scale: s,
            ..
        } => {
            let o = match o {
                BitOrder::LsbFirst => "lsb-first",
                BitOrder::MsbFirst => "msb-first",
            };
            format!("{count} × {bits} bits packed {o}{}", scale(s.as_ref()))
        }
        FieldKind::Value { ty, count } => match count {
            Some(n) => format!("[{}; {n}]", value(p, ty)),
            None => value(p, ty),
        },
    }
}

fn value(p: &Protocol, ty: &ValueType) -> String {
    match ty {
        ValueType::Scalar {
            scalar: s,
            scale: k,
        } => format!("{}{}", scalar(s), scale(k.as_ref())),
        ValueType::Struct(i) => format!("struct {}", p.structs[*i].name),
        ValueType::Enum(i, s) => format!("enum {} ({})", p.enums[*i].name, scalar(s)),
        ValueType::Text(n) => format!("char[{n}]"),
    }
}
