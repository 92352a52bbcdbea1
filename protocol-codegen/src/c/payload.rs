//! Payload structs between the wire and their C structs: a reader and a writer per struct,
//! field by field in wire order, every value through explicit byte-order helpers (never a
//! `memcpy` of a struct), with the runtime's field rules: an enum value without variant is
//! an error when the enum rejects unknown values, a bit member or a 24-bit integer that does
//! not fit is an encode error, bytes beyond their maximum are an error.

use std::fmt::Write as _;

use crate::ir::{
    BitMember, Enum, Field, FieldKind, Prim, Protocol, Scalar, Struct, UnknownPolicy, ValueType,
};

use super::names::{self, Names, prim as c_prim};

/// The reader and writer of every struct, dependencies first (the IR's order).
pub fn payloads(p: &Protocol, n: &Names) -> String {
    let mut out = String::from("/* ---- Payload structs ---- */\n\n");
    for s in &p.structs {
        out.push_str(&reader(p, n, s));
        out.push('\n');
        out.push_str(&writer(p, n, s));
        out.push('\n');
    }
    out
}

/// The C type of a value field's element.
pub fn value_type(p: &Protocol, n: &Names, ty: &ValueType) -> String {
    match ty {
        ValueType::Scalar { scalar, .. } => c_prim(scalar.prim).to_string(),
        ValueType::Struct(si) => n.ty(&p.structs[*si].name),
        ValueType::Enum(ei, _) => n.ty(&p.enums[*ei].name),
        // Refused by `support` before anything is printed.
        ValueType::Text(_) => String::new(),
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

fn reader(p: &Protocol, n: &Names, s: &Struct) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let ty = n.ty(&s.name);
    let mut body = String::new();
    let mut loops = false;
    for f in &s.fields {
        let name = names::field(&f.name);
        let dst = format!("out->{name}");
        match &f.kind {
            FieldKind::Padding => {
                let _ = writeln!(
                    body,
                    "    if ((e = {lo}skip(r, {}u)) != 0) return e;",
                    f.size
                );
            }
            FieldKind::Value { ty, count } => {
                let (dst, indent) = match count {
                    Some(c) => {
                        loops = true;
                        let _ = writeln!(body, "    for (i = 0; i < {c}u; i++) {{");
                        (format!("{dst}[i]"), "    ")
                    }
                    None => (dst, ""),
                };
                for line in read_elem(p, n, ty, &dst).lines() {
                    let _ = writeln!(body, "{indent}{line}");
                }
                if count.is_some() {
                    body.push_str("    }\n");
                }
            }
            FieldKind::Bits { word, members } => {
                let _ = writeln!(
                    body,
                    "    if ((e = {lo}read(r, {}u, {}, &raw)) != 0) return e;",
                    word.prim.size(),
                    big(*word)
                );
                for m in members {
                    let bits =
                        format!("((raw >> {}) & {})", m.shift, names::u64_lit(mask(m.width)));
                    if let Some(ei) = m.enum_index.filter(|&ei| rejects(&p.enums[ei])) {
                        let _ = writeln!(
                            body,
                            "    if (!{}known({bits})) return {up}ERR_INVALID_ENUM;",
                            n.ty(&p.enums[ei].name) + "_"
                        );
                    }
                    let value = match m.enum_index {
                        Some(ei) => format!("({}){bits}", n.ty(&p.enums[ei].name)),
                        None => from_raw(lo, m.prim, &bits),
                    };
                    let _ = writeln!(body, "    out->{} = {value};", names::field(&m.name));
                }
            }
            FieldKind::Bytes { max, .. } => {
                let _ = writeln!(
                    body,
                    "    if (r->len - r->pos > {max}u) return {up}ERR_PAYLOAD_LENGTH;\n    out->{name}_len = r->len - r->pos;\n    memcpy(out->{name}, r->p + r->pos, out->{name}_len);\n    r->pos = r->len;"
                );
            }
            FieldKind::Group { .. }
            | FieldKind::Packed { .. }
            | FieldKind::Optional(_)
            | FieldKind::NulText { .. }
            | FieldKind::Array { .. }
            | FieldKind::Check(_) => {
                unreachable!("refused by support::unsupported")
            }
        }
    }
    let mut decls = String::from("    int e = 0;\n    uint64_t raw = 0;\n");
    if loops {
        decls.push_str("    size_t i;\n");
    }
    format!(
        "/* Reads `{name}` ({size} bytes on the wire). */\nstatic int {lo}read_{snake}(struct {lo}rd *r, {ty} *out)\n{{\n{decls}{body}    (void)raw;\n    return e;\n}}\n",
        name = s.name,
        size = s.size,
        snake = names::snake(&s.name),
    )
}

fn read_elem(p: &Protocol, n: &Names, ty: &ValueType, dst: &str) -> String {
    let (lo, up) = (&n.lo, &n.up);
    match ty {
        ValueType::Scalar { scalar, .. } => format!(
            "    if ((e = {lo}read(r, {}u, {}, &raw)) != 0) return e;\n    {dst} = {};\n",
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
                "    if ((e = {lo}read(r, {}u, {}, &raw)) != 0) return e;\n",
                scalar.prim.size(),
                big(*scalar)
            );
            if rejects(e) {
                let _ = writeln!(s, "    if (!{ety}_known(raw)) return {up}ERR_INVALID_ENUM;");
            }
            let _ = writeln!(s, "    {dst} = ({ety}){};", from_raw(lo, e.prim, "raw"));
            s
        }
        // Refused by `support` before anything is printed.
        ValueType::Text(_) => String::new(),
    }
}

fn writer(p: &Protocol, n: &Names, s: &Struct) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let ty = n.ty(&s.name);
    let mut body = String::new();
    let mut loops = false;
    for f in &s.fields {
        let name = names::field(&f.name);
        let src = format!("v->{name}");
        match &f.kind {
            FieldKind::Padding => {
                let _ = writeln!(
                    body,
                    "    if ((e = {lo}zero(w, {}u)) != 0) return e;",
                    f.size
                );
            }
            FieldKind::Value { ty, count } => {
                let (src, indent) = match count {
                    Some(c) => {
                        loops = true;
                        let _ = writeln!(body, "    for (i = 0; i < {c}u; i++) {{");
                        (format!("{src}[i]"), "    ")
                    }
                    None => (src, ""),
                };
                for line in write_elem(p, n, ty, &src).lines() {
                    let _ = writeln!(body, "{indent}{line}");
                }
                if count.is_some() {
                    body.push_str("    }\n");
                }
            }
            FieldKind::Bits { word, members } => {
                body.push_str("    word = 0;\n");
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
                    "    if ((e = {lo}write(w, {}u, {}, word)) != 0) return e;",
                    word.prim.size(),
                    big(*word)
                );
            }
            FieldKind::Bytes { max, .. } => {
                let _ = writeln!(
                    body,
                    "    if ({src}_len > {max}u) return {up}ERR_OUT_OF_RANGE;\n    if (w->cap - w->pos < {src}_len) return {up}ERR_SHORT_BUFFER;\n    memcpy(w->p + w->pos, {src}, {src}_len);\n    w->pos += {src}_len;"
                );
            }
            FieldKind::Group { .. }
            | FieldKind::Packed { .. }
            | FieldKind::Optional(_)
            | FieldKind::NulText { .. }
            | FieldKind::Array { .. }
            | FieldKind::Check(_) => {
                unreachable!("refused by support::unsupported")
            }
        }
    }
    let mut decls = String::from("    int e = 0;\n    uint64_t raw = 0, word = 0;\n");
    if loops {
        decls.push_str("    size_t i;\n");
    }
    format!(
        "/* Writes `{name}`. */\nstatic int {lo}write_{snake}(struct {lo}wr *w, const {ty} *v)\n{{\n{decls}{body}    (void)raw;\n    (void)word;\n    return e;\n}}\n",
        name = s.name,
        snake = names::snake(&s.name),
    )
}

fn write_elem(p: &Protocol, n: &Names, ty: &ValueType, src: &str) -> String {
    let (lo, up) = (&n.lo, &n.up);
    match ty {
        ValueType::Scalar { scalar, .. } => format!(
            "{}    if ((e = {lo}write(w, {}u, {}, {})) != 0) return e;\n",
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
                "    if ((e = {lo}write(w, {}u, {}, raw)) != 0) return e;",
                scalar.prim.size(),
                big(*scalar)
            );
            s
        }
        // Refused by `support` before anything is printed.
        ValueType::Text(_) => String::new(),
    }
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
        FieldKind::Padding => {}
        FieldKind::Value { ty, count } => {
            let count = count.map(|c| format!("[{c}]")).unwrap_or_default();
            let _ = writeln!(out, "    {} {name}{count};{doc}", value_type(p, n, ty));
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
        FieldKind::Group { .. }
        | FieldKind::Packed { .. }
        | FieldKind::Optional(_)
        | FieldKind::NulText { .. }
        | FieldKind::Array { .. }
        | FieldKind::Check(_) => {
            unreachable!("refused by support::unsupported")
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
