//! Payload structs between the wire and their C structs: a reader and a writer per struct,
//! field by field in wire order, every value through explicit byte-order helpers (never a
//! `memcpy` of a struct), with the runtime's field rules: an enum value without variant is
//! an error when the enum rejects unknown values, a bit member or a 24-bit integer that does
//! not fit is an encode error, bytes beyond their maximum are an error.

use std::fmt::Write as _;

use crate::ir::{
    BitMember, BitOrder, Enum, Field, FieldKind, Prim, Protocol, Scalar, Struct, UnknownPolicy,
    ValueType,
};

use super::names::{self, Names, prim as c_prim};

/// The reader and writer of every struct, dependencies first (the IR's order).
pub fn payloads(p: &Protocol, n: &Names) -> String {
    let mut out = String::from("/* ---- Payload structs ---- */\n\n");
    for s in &p.structs {
        out.push_str(&walk(p, n, s, Dir::Read));
        out.push('\n');
        out.push_str(&walk(p, n, s, Dir::Write));
        out.push('\n');
    }
    out
}

/// Which way a struct's walk goes: from the payload into the C struct, or back.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Dir {
    Read,
    Write,
}

/// The C type of a value field's element.
pub fn value_type(p: &Protocol, n: &Names, ty: &ValueType) -> String {
    match ty {
        ValueType::Scalar { scalar, .. } => c_prim(scalar.prim).to_string(),
        ValueType::Struct(si) => n.ty(&p.structs[*si].name),
        ValueType::Enum(ei, _) => n.ty(&p.enums[*ei].name),
        ValueType::Text(_) => "char".into(),
    }
}

/// What follows a value field's name in its declaration: a text's bytes (`[30]`).
fn value_suffix(ty: &ValueType) -> String {
    match ty {
        ValueType::Text(len) => format!("[{len}]"),
        _ => String::new(),
    }
}

/// The C type of a bit member.
pub fn member_type(p: &Protocol, n: &Names, m: &BitMember) -> String {
    match m.enum_index {
        Some(ei) => n.ty(&p.enums[ei].name),
        None => c_prim(m.prim).to_string(),
    }
}

fn big(s: Scalar) -> u8 {
    u8::from(s.endian == crate::ir::ByteOrder::Big)
}

/// The C value of raw bits `raw` of type `prim`.
pub fn from_raw(lo: &str, prim: Prim, raw: &str) -> String {
    match prim {
        Prim::Bool => format!("({raw} != 0)"),
        Prim::F32 => format!("{lo}f32({raw})"),
        Prim::F64 => format!("{lo}f64({raw})"),
        p if p.is_signed() => {
            format!("({}){lo}sext({raw}, {}u)", c_prim(p), 8 * p.size())
        }
        p => format!("({}){raw}", c_prim(p)),
    }
}

/// The raw bits of C value `v` of type `prim` (a signed value sign-extended to 64 bits).
pub fn to_raw(lo: &str, prim: Prim, v: &str) -> String {
    match prim {
        Prim::Bool => format!("({v} ? 1u : 0u)"),
        Prim::F32 => format!("{lo}f32_bits({v})"),
        Prim::F64 => format!("{lo}f64_bits({v})"),
        p if p.is_signed() => format!("(uint64_t)(int64_t){v}"),
        _ => format!("(uint64_t){v}"),
    }
}

/// The range check of a 24-bit integer before it is written.
fn range_check(prim: Prim, v: &str, up: &str) -> String {
    match prim {
        Prim::U24 => format!("    if ({v} > 0xFFFFFFu) return {up}ERR_OUT_OF_RANGE;\n"),
        Prim::I24 => {
            format!("    if ({v} < -8388608L || {v} > 8388607L) return {up}ERR_OUT_OF_RANGE;\n")
        }
        _ => String::new(),
    }
}

/// Whether an enum refuses values without variant.
fn rejects(e: &Enum) -> bool {
    e.unknown == UnknownPolicy::Reject
}

/// A struct's reader or writer: its fields in wire order.
fn walk(p: &Protocol, n: &Names, s: &Struct, dir: Dir) -> String {
    let lo = &n.lo;
    let this = if dir == Dir::Read { "out" } else { "v" };
    let mut body = String::new();
    for f in &s.fields {
        let here = format!("{this}->{}", names::field(&f.name));
        body.push_str(&field(p, n, f, &f.kind, dir, &here));
    }
    let mut decls = String::from("    int e = 0;\n    uint64_t raw = 0, word = 0;\n");
    if body.contains("[i]") {
        decls.push_str("    size_t i;\n");
    }
    let (what, signature) = match dir {
        Dir::Read => (
            format!("Reads `{}` ({} bytes on the wire)", s.name, s.size),
            format!(
                "read_{}(struct {lo}rd *r, {} *out)",
                names::snake(&s.name),
                n.ty(&s.name)
            ),
        ),
        Dir::Write => (
            format!("Writes `{}`", s.name),
            format!(
                "write_{}(struct {lo}wr *w, const {} *v)",
                names::snake(&s.name),
                n.ty(&s.name)
            ),
        ),
    };
    format!(
        "/* {what}. */\nstatic int {lo}{signature}\n{{\n{decls}{body}    (void)raw;\n    (void)word;\n    return e;\n}}\n"
    )
}

/// The statements that read or write one field (`kind`: the field's, or what an optional
/// field holds), whose C value is `here`.
fn field(p: &Protocol, n: &Names, f: &Field, kind: &FieldKind, dir: Dir, here: &str) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let read = dir == Dir::Read;
    match kind {
        FieldKind::NulText { .. } | FieldKind::Array { .. } | FieldKind::Check(_) => {
            unreachable!("refused by support::unsupported")
        }
        FieldKind::Padding => {
            let op = if read { "skip(r" } else { "zero(w" };
            format!("    if ((e = {lo}{op}, {}u)) != 0) return e;\n", f.size)
        }
        FieldKind::Value { ty, count } => {
            let (here, indent, close) = match count {
                Some(c) => (
                    format!("{here}[i]"),
                    "    ",
                    format!("    for (i = 0; i < {c}u; i++) {{\n"),
                ),
                None => (here.to_string(), "", String::new()),
            };
            let elem = if read {
                read_elem(p, n, ty, &here)
            } else {
                write_elem(p, n, ty, &here)
            };
            let mut out = close.clone();
            for line in elem.lines() {
                let _ = writeln!(out, "{indent}{line}");
            }
            if count.is_some() {
                out.push_str("    }\n");
            }
            out
        }
        FieldKind::Bits { word, members } if read => read_bits(p, n, *word, members),
        FieldKind::Bits { word, members } => write_bits(p, n, *word, members),
        FieldKind::Bytes { max, .. } if read => format!(
            "    if (r->len - r->pos > {max}u) return {up}ERR_PAYLOAD_LENGTH;\n    {here}_len = r->len - r->pos;\n    memcpy({here}, r->p + r->pos, {here}_len);\n    r->pos = r->len;\n"
        ),
        FieldKind::Bytes { max, .. } => format!(
            "    if ({here}_len > {max}u) return {up}ERR_OUT_OF_RANGE;\n    if (w->cap - w->pos < {here}_len) return {up}ERR_SHORT_BUFFER;\n    memcpy(w->p + w->pos, {here}, {here}_len);\n    w->pos += {here}_len;\n"
        ),
        FieldKind::Packed {
            count,
            bits,
            order,
            prim,
            ..
        } => {
            let msb = u8::from(*order == BitOrder::MsbFirst);
            let size = f.size;
            if read {
                format!(
                    "    if (r->len - r->pos < {size}u) return {up}ERR_PAYLOAD_LENGTH;\n    for (i = 0; i < {count}u; i++) {{\n        {here}[i] = ({}){lo}get_packed(r->p + r->pos, {size}u, i, {bits}u, {msb});\n    }}\n    r->pos += {size}u;\n",
                    c_prim(*prim)
                )
            } else {
                format!(
                    "    if (w->cap - w->pos < {size}u) return {up}ERR_SHORT_BUFFER;\n    memset(w->p + w->pos, 0, {size}u);\n    for (i = 0; i < {count}u; i++) {{\n        if (!{lo}set_packed(w->p + w->pos, {size}u, i, {bits}u, {msb}, (uint64_t){here}[i])) return {up}ERR_OUT_OF_RANGE;\n    }}\n    w->pos += {size}u;\n"
                )
            }
        }
        FieldKind::Group { elem, max } => {
            let (ety, esnake) = (
                n.ty(&p.structs[*elem].name),
                names::snake(&p.structs[*elem].name),
            );
            if read {
                // An element past the capacity is read (its own errors first, as the runtime
                // reads it), then refused: the payload is longer than the struct's largest.
                format!(
                    "    {here}_len = 0;\n    while (r->pos < r->len) {{\n        if ({here}_len == {max}u) {{\n            {ety} spare;\n            if ((e = {lo}read_{esnake}(r, &spare)) != 0) return e;\n            return {up}ERR_PAYLOAD_LENGTH;\n        }}\n        if ((e = {lo}read_{esnake}(r, &{here}[{here}_len])) != 0) return e;\n        {here}_len++;\n    }}\n"
                )
            } else {
                format!(
                    "    if ({here}_len > {max}u) return {up}ERR_OUT_OF_RANGE;\n    for (i = 0; i < {here}_len; i++) {{\n        if ((e = {lo}write_{esnake}(w, &{here}[i])) != 0) return e;\n    }}\n"
                )
            }
        }
        FieldKind::Optional(inner) => {
            let inner = field(p, n, f, inner, dir, here);
            let inner: String = inner.lines().map(|l| format!("    {l}\n")).collect();
            let present = optional_flag(here, f);
            if read {
                format!("    {present} = r->pos < r->len;\n    if ({present}) {{\n{inner}    }}\n")
            } else {
                format!("    if ({present}) {{\n{inner}    }}\n")
            }
        }
    }
}

/// The flag of an optional field whose value is `here` (`out->ports` -> `out->ports_present`).
pub fn optional_flag(here: &str, f: &Field) -> String {
    let base = here.rsplit_once("->").map_or("", |(b, _)| b);
    format!("{base}->{}_present", names::field(&f.name))
}

/// The members of a bit field, read from its word.
fn read_bits(p: &Protocol, n: &Names, word: Scalar, members: &[BitMember]) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let mut body = format!(
        "    if ((e = {lo}take_uint(r, {}u, {}, &raw)) != 0) return e;\n",
        word.prim.size(),
        big(word)
    );
    for m in members {
        let bits = format!("((raw >> {}) & {})", m.shift, names::u64_lit(mask(m.width)));
        if let Some(ei) = m.enum_index.filter(|&ei| rejects(&p.enums[ei])) {
            let _ = writeln!(
                body,
                "    if (!{}_known({bits})) return {up}ERR_INVALID_ENUM;",
                n.ty(&p.enums[ei].name)
            );
        }
        let value = match m.enum_index {
            Some(ei) => format!("({}){bits}", n.ty(&p.enums[ei].name)),
            None => from_raw(lo, m.prim, &bits),
        };
        let _ = writeln!(body, "    out->{} = {value};", names::field(&m.name));
    }
    body
}

/// The members of a bit field, each checked to fit, written as their word.
fn write_bits(p: &Protocol, n: &Names, word: Scalar, members: &[BitMember]) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let mut body = String::from("    word = 0;\n");
    for m in members {
        let v = format!("v->{}", names::field(&m.name));
        let bits = match m.enum_index {
            Some(_) => format!("(uint64_t){v}"),
            None => to_raw(lo, m.prim, &v),
        };
        let _ = writeln!(body, "    raw = {bits};");
        if let Some(ei) = m.enum_index.filter(|&ei| rejects(&p.enums[ei])) {
            let _ = writeln!(
                body,
                "    if (!{}_known(raw)) return {up}ERR_OUT_OF_RANGE;",
                n.ty(&p.enums[ei].name)
            );
        }
        let _ = writeln!(
            body,
            "    if (raw > {}) return {up}ERR_OUT_OF_RANGE;\n    word |= raw << {};",
            names::u64_lit(mask(m.width)),
            m.shift
        );
    }
    let _ = writeln!(
        body,
        "    if ((e = {lo}put_uint(w, {}u, {}, word)) != 0) return e;",
        word.prim.size(),
        big(word)
    );
    body
}

fn read_elem(p: &Protocol, n: &Names, ty: &ValueType, dst: &str) -> String {
    let (lo, up) = (&n.lo, &n.up);
    match ty {
        ValueType::Scalar { scalar, .. } => format!(
            "    if ((e = {lo}take_uint(r, {}u, {}, &raw)) != 0) return e;\n    {dst} = {};\n",
            scalar.prim.size(),
            big(*scalar),
            from_raw(lo, scalar.prim, "raw")
        ),
        ValueType::Struct(si) => format!(
            "    if ((e = {lo}read_{}(r, &{dst})) != 0) return e;\n",
            names::snake(&p.structs[*si].name)
        ),
        ValueType::Enum(ei, scalar) => {
            let e = &p.enums[*ei];
            let ety = n.ty(&e.name);
            let mut s = format!(
                "    if ((e = {lo}take_uint(r, {}u, {}, &raw)) != 0) return e;\n",
                scalar.prim.size(),
                big(*scalar)
            );
            if rejects(e) {
                let _ = writeln!(s, "    if (!{ety}_known(raw)) return {up}ERR_INVALID_ENUM;");
            }
            let _ = writeln!(s, "    {dst} = ({ety}){};", from_raw(lo, e.prim, "raw"));
            s
        }
        // Every byte as received (the runtime's `FixedStr` keeps them).
        ValueType::Text(len) => format!(
            "    if (r->len - r->pos < {len}u) return {up}ERR_PAYLOAD_LENGTH;\n    memcpy({dst}, r->p + r->pos, {len}u);\n    r->pos += {len}u;\n"
        ),
    }
}

fn write_elem(p: &Protocol, n: &Names, ty: &ValueType, src: &str) -> String {
    let (lo, up) = (&n.lo, &n.up);
    match ty {
        ValueType::Scalar { scalar, .. } => format!(
            "{}    if ((e = {lo}put_uint(w, {}u, {}, {})) != 0) return e;\n",
            range_check(scalar.prim, src, up),
            scalar.prim.size(),
            big(*scalar),
            to_raw(lo, scalar.prim, src)
        ),
        ValueType::Struct(si) => format!(
            "    if ((e = {lo}write_{}(w, &{src})) != 0) return e;\n",
            names::snake(&p.structs[*si].name)
        ),
        ValueType::Enum(ei, scalar) => {
            let e = &p.enums[*ei];
            let mut s = format!("    raw = {};\n", to_raw(lo, e.prim, src));
            if rejects(e) {
                let _ = writeln!(
                    s,
                    "    if (!{}_known(raw & {})) return {up}ERR_OUT_OF_RANGE;",
                    n.ty(&e.name),
                    names::u64_lit(mask(8 * e.prim.size() as u32))
                );
            }
            let _ = writeln!(
                s,
                "    if ((e = {lo}put_uint(w, {}u, {}, raw)) != 0) return e;",
                scalar.prim.size(),
                big(*scalar)
            );
            s
        }
        ValueType::Text(len) => format!(
            "    if (w->cap - w->pos < {len}u) return {up}ERR_SHORT_BUFFER;\n    memcpy(w->p + w->pos, {src}, {len}u);\n    w->pos += {len}u;\n"
        ),
    }
}

/// Whether a field of a struct of `p` is a `kind` (or an optional field holds one): the
/// helpers only some fields need are printed for the specs that have them.
pub fn any_field(p: &Protocol, kind: fn(&FieldKind) -> bool) -> bool {
    fn holds(k: &FieldKind, kind: fn(&FieldKind) -> bool) -> bool {
        match k {
            FieldKind::Optional(inner) => holds(inner, kind),
            k => kind(k),
        }
    }
    p.structs
        .iter()
        .any(|s| s.fields.iter().any(|f| holds(&f.kind, kind)))
}

/// The low `width` bits set.
pub fn mask(width: u32) -> u64 {
    if width >= 64 {
        u64::MAX
    } else {
        (1u64 << width) - 1
    }
}

/// The declarations of a struct's fields in its C struct.
pub fn members(p: &Protocol, n: &Names, f: &Field, out: &mut String) {
    let name = names::field(&f.name);
    let doc = doc_comment(&f.doc, &f.unit);
    match &f.kind {
        FieldKind::NulText { .. } | FieldKind::Array { .. } | FieldKind::Check(_) => {
            unreachable!("refused by support::unsupported")
        }
        FieldKind::Padding => {}
        FieldKind::Value { ty, count } => {
            let count = count.map(|c| format!("[{c}]")).unwrap_or_default();
            let _ = writeln!(
                out,
                "    {} {name}{count}{};{doc}",
                value_type(p, n, ty),
                value_suffix(ty)
            );
        }
        FieldKind::Bits { members, .. } => {
            for m in members {
                let _ = writeln!(
                    out,
                    "    {} {};{}",
                    member_type(p, n, m),
                    names::field(&m.name),
                    doc_comment(&m.doc, "")
                );
            }
        }
        FieldKind::Bytes { max, .. } => {
            let _ = writeln!(out, "    uint8_t {name}[{}];{doc}", (*max).max(1));
            let _ = writeln!(
                out,
                "    size_t {name}_len; /**< Bytes of `{name}` used (at most {max}). */"
            );
        }
        FieldKind::Packed { count, prim, .. } => {
            let _ = writeln!(out, "    {} {name}[{count}];{doc}", c_prim(*prim));
        }
        FieldKind::Group { elem, max } => {
            let _ = writeln!(
                out,
                "    {} {name}[{max}];{doc}",
                n.ty(&p.structs[*elem].name)
            );
            let _ = writeln!(
                out,
                "    size_t {name}_len; /**< Elements of `{name}` used (at most {max}). */"
            );
        }
        FieldKind::Optional(inner) => {
            let _ = writeln!(
                out,
                "    bool {name}_present; /**< Whether the payload holds `{name}`. */"
            );
            let inner = Field {
                kind: (**inner).clone(),
                ..f.clone()
            };
            members(p, n, &inner, out);
        }
    }
}

/// A trailing ` /**< doc (unit) */` comment, or nothing.
pub fn doc_comment(doc: &str, unit: &str) -> String {
    let doc = doc
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .replace("*/", "* /");
    match (doc.is_empty(), unit.is_empty()) {
        (true, true) => String::new(),
        (false, true) => format!(" /**< {doc} */"),
        (true, false) => format!(" /**< Unit: {unit}. */"),
        (false, false) => format!(" /**< {doc} Unit: {unit}. */"),
    }
}
