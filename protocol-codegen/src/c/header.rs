//! The header file: sizes, result codes, the spec's constants, enums and payload structs, the
//! commands and directions, then each frame format's types and prototypes (`packet`) and the
//! stream decoder's types (`engine`).

use crate::ir::{Enum, Prim, Protocol, Transport};

use super::kinds;
use super::names::{self, Fx, Names, doc_comment, mask, one_line};
use super::template::fill;

/// The whole header file.
pub fn header(p: &Protocol, n: &Names) -> String {
    let (up, name) = (&n.up, &p.name);
    let version = if p.version.is_empty() {
        String::new()
    } else {
        format!(" {}", p.version)
    };
    let mut out = fill!(include_str!("templates/header_open.h"), name, version, up);
    out.push_str("\n/* ---- Sizes ---- */\n");
    for fi in 0..p.frames.len() {
        sizes(p, &Fx::new(p, fi), &mut out);
    }
    out.push('\n');
    out.push_str(&fill!(include_str!("templates/results.h"), up));
    out.push('\n');
    constants(p, n, &mut out);
    if !p.enums.is_empty() {
        out.push_str("/* ---- Enums ---- */\n\n");
        for e in &p.enums {
            enum_decl(n, e, &mut out);
        }
    }
    out.push_str("/* ---- Payload structs ---- */\n\n");
    for s in &p.structs {
        let mut fields = String::new();
        for field in &s.fields {
            kinds::of(p, &field.kind).members(n, field, &mut fields);
        }
        if fields.is_empty() {
            fields.push_str("    uint8_t unused_; /**< C has no empty struct. */\n");
        }
        let (doc, ty) = (one_line(&s.doc), n.ty(&s.name));
        out.push_str(&fill!(
            r"
/** ${doc} */
typedef struct ${ty} {
${fields}} ${ty};

",
            doc,
            ty,
            fields
        ));
    }
    commands(p, n, &mut out);
    for fi in 0..p.frames.len() {
        super::packet::types(p, n, &Fx::new(p, fi), &mut out);
    }
    out.push_str(&super::engine::declarations(p, n));
    for fi in 0..p.frames.len() {
        super::packet::prototypes(p, n, &Fx::new(p, fi), &mut out);
    }
    out.push_str(&super::carried::prototypes(p, n));
    out.push_str(&fill!(
        r"
#ifdef __cplusplus
}
#endif

#endif /* ${up}H */
",
        up
    ));
    out
}

/// The spec's constants and address ranges, as `#define`s.
fn constants(p: &Protocol, n: &Names, out: &mut String) {
    let up = &n.up;
    if p.constants.is_empty() && p.addresses.is_empty() {
        return;
    }
    out.push_str("/* ---- Constants and addresses of the spec ---- */\n\n");
    for c in &p.constants {
        let (name, value, doc) = (&c.name, names::u64_lit(c.value), doc_comment(&c.doc, ""));
        out.push_str(&fill!(
            "#define ${up}${name} ${value}${doc}\n",
            up,
            name,
            value,
            doc
        ));
    }
    for a in &p.addresses {
        let (name, doc) = (a.name.to_uppercase(), doc_comment(&a.doc, ""));
        let (first, last) = (names::u64_lit(a.first), names::u64_lit(a.last));
        out.push_str(&fill!(
            r"
#define ${up}ADDR_${name}_FIRST ${first}${doc}
#define ${up}ADDR_${name}_LAST ${last}
",
            up,
            name,
            first,
            doc,
            last
        ));
    }
    out.push('\n');
}

/// A C literal of an enum value's bits as its (possibly signed) type.
fn enum_literal(e: &Enum, bits: u64) -> String {
    let width = 8 * e.prim.size() as u32;
    if e.prim.is_signed() {
        let shift = 64 - width;
        let v = ((bits << shift) as i64) >> shift;
        if v == i64::MIN {
            "(-INT64_C(9223372036854775807) - 1)".into()
        } else {
            format!("({v})")
        }
    } else {
        format!("{:#x}u", bits & mask(width))
    }
}

/// An enum's integer type and a constant per variant.
fn enum_decl(n: &Names, e: &Enum, out: &mut String) {
    let ty = n.ty(&e.name);
    let base = if e.prim == Prim::Bool {
        "uint8_t"
    } else {
        names::prim(e.prim)
    };
    let doc = one_line(&e.doc);
    out.push_str(&fill!(
        r"
/** ${doc} */
typedef ${base} ${ty};
",
        doc,
        base,
        ty
    ));
    for v in &e.variants {
        let (name, value) = (
            format!("{}{}", n.enum_const(&e.name), v.name),
            enum_literal(e, v.value),
        );
        let doc = doc_comment(&v.doc, "");
        out.push_str(&fill!(
            "#define ${name} ((${ty})${value})${doc}\n",
            name,
            ty,
            value,
            doc
        ));
    }
    out.push_str(&fill!(
        r"
/** The spec name of a value, NULL for a value without variant. */
const char *${ty}_name(${ty} value);

",
        ty
    ));
}

/// The command enum and, where the spec has directions, the direction enum.
fn commands(p: &Protocol, n: &Names, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    out.push_str(&fill!(
        r"
/* ---- Commands, directions, header, packet ---- */

/** The commands, in spec order (not their wire ids). */
typedef enum ${lo}command {
",
        lo
    ));
    for c in &p.commands {
        let (name, doc) = (&c.name, doc_comment(&c.doc, ""));
        out.push_str(&fill!("    ${up}${name},${doc}\n", up, name, doc));
    }
    out.push_str(&fill!(
        r"
    ${up}COMMAND_COUNT
} ${lo}command;

/** The spec name of a command, NULL for no command (`COMMAND_COUNT`: a frame without one). */
const char *${lo}command_name(${lo}command command);

",
        lo,
        up
    ));
    if p.directions.is_empty() {
        return;
    }
    out.push_str(&fill!(
        r"
/** The directions, which select a command's payload. */
typedef enum ${lo}direction {
",
        lo
    ));
    for d in &p.directions {
        let (name, doc) = (d.name.to_uppercase(), doc_comment(&d.doc, ""));
        out.push_str(&fill!("    ${up}${name},${doc}\n", up, name, doc));
    }
    out.push_str(&fill!(
        r"
    ${up}DIRECTION_COUNT
} ${lo}direction;

/** The spec name of a direction. */
const char *${lo}direction_name(${lo}direction direction);

",
        lo,
        up
    ));
}

/// The sizes of frame format `x` (the runtime layout's bounds, and its packet rules' header,
/// trailer, payload and acknowledgement header).
fn sizes(p: &Protocol, x: &Fx, out: &mut String) {
    let (f, rules) = (&p.frames[x.fi], &x.rules);
    let up = &x.up;
    out.push_str(&format!("\n/* Frame format `{}`. */\n", f.name));
    for (name, v) in [
        ("MAX_FRAME_LEN", f.max_len()),
        ("MIN_FRAME_LEN", f.min_len()),
        ("HEADER_LEN", rules.header_len),
        ("TRAILER_LEN", rules.trailer_len),
        ("MAX_PAYLOAD_LEN", rules.max_payload),
        ("MIN_PAYLOAD_LEN", f.payload_min),
        ("DECODER_BUFFER_LEN", f.max_len()),
    ] {
        out.push_str(&fill!("#define ${up}${name} ${v}u\n", up, name, v));
    }
    if f.escape.is_some() {
        // Every byte between the flags may go as two.
        let max = 2 * f.max_len() - 2;
        out.push_str(&fill!(
            r"
/** The longest frame on the wire, escaped: the size of an encoder's buffer for every
 *  packet (${up}MAX_FRAME_LEN counts a frame unescaped). */
#define ${up}MAX_WIRE_LEN ${max}u
",
            up,
            max
        ));
    }
    if let Some(t) = &f.flag_trailer {
        let (name, len) = (t.name.to_uppercase(), t.len);
        out.push_str(&fill!("#define ${up}${name}_LEN ${len}u\n", up, name, len));
    }
    if let Some((_, ack)) = rules.ack {
        let header_len = ack.header_len;
        let max = f.max_len() - header_len - rules.trailer_len;
        out.push_str(&fill!(
            r"
/** An acknowledgement's header, before its data. */
#define ${up}ACK_HEADER_LEN ${header_len}u
/** The most data of an acknowledgement. */
#define ${up}ACK_MAX_LEN ${max}u
",
            up,
            header_len,
            max
        ));
    }
    if let Transport::Can { extended } = f.transport {
        let (kind, flag) = if extended {
            ("extended (29-bit)", 1)
        } else {
            ("standard (11-bit)", 0)
        };
        out.push_str(&fill!(
            r"
/** The format's CAN ids are ${kind} ones. */
#define ${up}CAN_EXTENDED ${flag}
",
            kind,
            up,
            flag
        ));
    }
    if x.fi == 0 && !p.link.is_empty() {
        let max = p
            .link
            .iter()
            .map(|&fi| p.frames[fi].max_len())
            .max()
            .unwrap_or(0);
        out.push_str(&fill!(
            r"

/* The link's decoder of every command format. */
#define ${up}ANY_DECODER_BUFFER_LEN ${max}u
",
            up,
            max
        ));
    }
}
