//! Payload structs between the wire and their C structs: a reader and a writer per struct,
//! field by field in wire order, every value through explicit byte-order helpers (never a
//! `memcpy` of a struct), with the runtime's field rules: an enum value without variant is
//! an error when the enum rejects unknown values, a bit member or a 24-bit integer that does
//! not fit is an encode error, bytes beyond their maximum are an error.

use std::fmt::Write as _;

use crate::ir::{
    BitMember, BitOrder, Enum, Field, FieldKind, PayloadCheck, Prim, Protocol, Scalar, Struct,
    UnknownPolicy, ValueType,
};

use super::names::{self, Names, mask, prim as c_prim, value_type};
use super::prelude::{put_call, take_call};
use super::shape::any_field;

/// The reader and writer of every struct, dependencies first (the IR's order).
pub fn payloads(p: &Protocol, n: &Names) -> String {
    let mut out = String::new();
    if any_scaled(p) {
        out.push_str(&super::scale::helpers(n));
    }
    out.push_str("/* ---- Payload structs ---- */\n\n");
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

/// A struct's reader or writer: its fields in wire order. A check inside the payload covers
/// the bytes from the start of its first field (`from<i>`) to the end of its last (`to<i>`).
fn walk(p: &Protocol, n: &Names, s: &Struct, dir: Dir) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let read = dir == Dir::Read;
    let this = if read { "out" } else { "v" };
    let pos = if read { "r->pos" } else { "w->pos" };
    let checks: Vec<&PayloadCheck> = s
        .fields
        .iter()
        .filter_map(|f| match &f.kind {
            FieldKind::Check(c) => Some(c),
            _ => None,
        })
        .collect();
    let mut marks = Vec::new();
    let mut body = String::new();
    for (i, f) in s.fields.iter().enumerate() {
        let here = format!("{this}->{}", names::field(&f.name));
        if checks.iter().any(|c| c.first == i) {
            let _ = writeln!(body, "    from{i} = {pos};");
            marks.push(format!("from{i}"));
        }
        match &f.kind {
            FieldKind::Check(c) => {
                let name = super::checks::payload_check_name(n, s, f);
                let (width, big) = (
                    c.algorithm.width(),
                    u8::from(c.endian == crate::ir::ByteOrder::Big),
                );
                let (from, to) = (format!("from{}", c.first), format!("to{}", c.last));
                if read {
                    // The runtime's `field::verify_check`: the stored value, then the check.
                    let _ = writeln!(
                        body,
                        "    if ((e = {}) != 0) return e;\n    if (!{name}(r->p + {from}, {to} - {from}, &word) || word != raw) return {up}ERR_PAYLOAD_CHECK;",
                        take_call(n, width, big, "raw")
                    );
                } else {
                    let _ = writeln!(
                        body,
                        "    (void){name}(w->p + {from}, {to} - {from}, &word);\n    if ((e = {}) != 0) return e;",
                        put_call(n, width, big, "word")
                    );
                }
            }
            // Every byte left but the fixed fields after it (the runtime's `rest_but`).
            FieldKind::Bytes {
                max,
                size_from: None,
            } if read && s.bytes_after(i) > 0 => {
                let keep = s.bytes_after(i);
                let _ = writeln!(
                    body,
                    "    {here}_len = r->len - r->pos > {keep}u ? r->len - r->pos - {keep}u : 0;\n    if ({here}_len > {max}u) return {up}ERR_PAYLOAD_LENGTH;\n    memcpy({here}, r->p + r->pos, {here}_len);\n    r->pos += {here}_len;"
                );
            }
            _ => body.push_str(&field(p, n, s, f, &f.kind, dir, &here)),
        }
        if checks.iter().any(|c| c.last == i) {
            let _ = writeln!(body, "    to{i} = {pos};");
            marks.push(format!("to{i}"));
        }
    }
    let mut decls = String::from("    int e = 0;\n    uint64_t raw = 0, word = 0;\n");
    if body.contains("[i]") {
        decls.push_str("    size_t i;\n");
    }
    if body.contains("stated") {
        decls.push_str("    uint64_t stated = 0;\n");
    }
    if !marks.is_empty() {
        let _ = writeln!(decls, "    size_t {};", marks.join(", "));
    }
    // A struct repeated by another whose fields size its bytes gets their values (`ctx`).
    let ctx = if s.context.is_empty() {
        ""
    } else {
        ", const uint64_t *ctx"
    };
    let (what, signature) = match dir {
        Dir::Read => (
            format!("Reads `{}` ({} bytes on the wire)", s.name, s.size),
            format!(
                "read_{}(struct {lo}rd *r, {} *out{ctx})",
                names::snake(&s.name),
                n.ty(&s.name)
            ),
        ),
        Dir::Write => (
            format!("Writes `{}`", s.name),
            format!(
                "write_{}(struct {lo}wr *w, const {} *v{ctx})",
                names::snake(&s.name),
                n.ty(&s.name)
            ),
        ),
    };
    let unused_ctx = if s.context.is_empty() {
        ""
    } else {
        "    (void)ctx;\n"
    };
    format!(
        "/* {what}. */\nstatic int {lo}{signature}\n{{\n{decls}{body}    (void)raw;\n    (void)word;\n{unused_ctx}    return e;\n}}\n"
    )
}

/// Whether a field of the spec holds scaled values.
fn any_scaled(p: &Protocol) -> bool {
    any_field(p, |k| match k {
        FieldKind::Value {
            ty: ValueType::Scalar { scale, .. },
            ..
        }
        | FieldKind::Array {
            ty: ValueType::Scalar { scale, .. },
            ..
        } => scale.is_some(),
        FieldKind::Packed { scale, .. } => scale.is_some(),
        _ => false,
    })
}

/// The C value of the unsigned integer field `name` that states a length, in struct `s`
/// being read or written through `this`: the struct's own field before it, or one of the
/// struct that repeats it (`ctx`, in the order of [`Struct::context`]).
fn stated(s: &Struct, this: &str, name: &str) -> String {
    match s.context.iter().position(|c| c == name) {
        Some(j) => format!("ctx[{j}]"),
        None => format!("(uint64_t){this}->{}", names::field(name)),
    }
}

/// The context values a struct that repeats `elem` passes to its reader or writer: the
/// fields `elem.context` names, from `this` (or from the repeating struct's own context).
fn context_args(s: &Struct, elem: &Struct, this: &str) -> String {
    if elem.context.is_empty() {
        return String::new();
    }
    let values: Vec<String> = elem.context.iter().map(|c| stated(s, this, c)).collect();
    format!(", (const uint64_t[]){{{}}}", values.join(", "))
}

/// The statements that read or write one field of struct `s` (`kind`: the field's, or what
/// an optional field holds), whose C value is `here`.
fn field(
    p: &Protocol,
    n: &Names,
    s: &Struct,
    f: &Field,
    kind: &FieldKind,
    dir: Dir,
    here: &str,
) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let read = dir == Dir::Read;
    let this = if read { "out" } else { "v" };
    match kind {
        // Printed by `walk`, which knows the covered fields.
        FieldKind::Check(_) => unreachable!("a check is printed by walk"),
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
        FieldKind::Bytes {
            max,
            size_from: None,
        } if read => format!(
            "    if (r->len - r->pos > {max}u) return {up}ERR_PAYLOAD_LENGTH;\n    {here}_len = r->len - r->pos;\n    memcpy({here}, r->p + r->pos, {here}_len);\n    r->pos = r->len;\n"
        ),
        // The runtime's `field::take_sized`: the stated bytes must be there, then fit `max`.
        FieldKind::Bytes {
            max,
            size_from: Some(size),
        } if read => format!(
            "    stated = {};\n    if (r->len - r->pos < stated) return {up}ERR_PAYLOAD_LENGTH;\n    if (stated > {max}u) return {up}ERR_SIZE_MISMATCH;\n    {here}_len = (size_t)stated;\n    memcpy({here}, r->p + r->pos, {here}_len);\n    r->pos += {here}_len;\n",
            stated(s, this, size)
        ),
        FieldKind::Bytes { max, size_from } => {
            let mut out = format!("    if ({here}_len > {max}u) return {up}ERR_OUT_OF_RANGE;\n");
            if let Some(size) = size_from {
                // The runtime's `field::check_stated_len`.
                let _ = writeln!(
                    out,
                    "    if ((uint64_t){here}_len != {}) return {up}ERR_OUT_OF_RANGE;",
                    stated(s, this, size)
                );
            }
            let _ = write!(
                out,
                "    if (w->cap - w->pos < {here}_len) return {up}ERR_SHORT_BUFFER;\n    memcpy(w->p + w->pos, {here}, {here}_len);\n    w->pos += {here}_len;\n"
            );
            out
        }
        FieldKind::Array {
            ty,
            max,
            size_from: None,
        } if read => {
            // An element past the capacity is read (its own errors first, as the runtime
            // reads it), then refused: the payload is longer than the struct's largest.
            let spare = indent(&read_elem(p, n, ty, "spare"), 2);
            let elem = indent(&read_elem(p, n, ty, &format!("{here}[{here}_len]")), 1);
            format!(
                "    {here}_len = 0;\n    while (r->pos < r->len) {{\n        if ({here}_len == {max}u) {{\n            {} spare;\n{spare}            (void)spare;\n            return {up}ERR_PAYLOAD_LENGTH;\n        }}\n{elem}        {here}_len++;\n    }}\n",
                value_type(p, n, ty)
            )
        }
        // The runtime's `field::array_len`: the stated count must fit `max`.
        FieldKind::Array {
            ty,
            max,
            size_from: Some(size),
        } if read => {
            let elem = indent(&read_elem(p, n, ty, &format!("{here}[i]")), 1);
            format!(
                "    stated = {};\n    if (stated > {max}u) return {up}ERR_SIZE_MISMATCH;\n    {here}_len = (size_t)stated;\n    for (i = 0; i < {here}_len; i++) {{\n{elem}    }}\n",
                stated(s, this, size)
            )
        }
        FieldKind::Array { ty, max, size_from } => {
            let mut out = format!("    if ({here}_len > {max}u) return {up}ERR_OUT_OF_RANGE;\n");
            if let Some(size) = size_from {
                let _ = writeln!(
                    out,
                    "    if ((uint64_t){here}_len != {}) return {up}ERR_OUT_OF_RANGE;",
                    stated(s, this, size)
                );
            }
            let elem = indent(&write_elem(p, n, ty, &format!("{here}[i]")), 1);
            let _ = write!(
                out,
                "    for (i = 0; i < {here}_len; i++) {{\n{elem}    }}\n"
            );
            out
        }
        // The runtime's `text::read_nul_text`: a NUL within the first `max + 1` bytes left.
        FieldKind::NulText { max } if read => format!(
            "    for (word = 0; word < r->len - r->pos && word <= {max}u; word++) {{\n        if (r->p[r->pos + word] == 0) break;\n    }}\n    if (word == r->len - r->pos || word > {max}u) return {up}ERR_UNTERMINATED;\n    memcpy({here}, r->p + r->pos, (size_t)word);\n    {here}[word] = 0;\n    r->pos += (size_t)word + 1;\n"
        ),
        // The runtime's `text::nul_text_fits`: at most `max` bytes before the NUL.
        FieldKind::NulText { max } => format!(
            "    for (word = 0; word <= {max}u && {here}[word] != 0; word++) {{\n    }}\n    if (word > {max}u) return {up}ERR_OUT_OF_RANGE;\n    if (w->cap - w->pos < word + 1) return {up}ERR_SHORT_BUFFER;\n    memcpy(w->p + w->pos, {here}, (size_t)word);\n    w->p[w->pos + word] = 0;\n    w->pos += (size_t)word + 1;\n"
        ),
        FieldKind::Packed {
            count,
            bits,
            order,
            prim,
            scale,
        } => {
            let msb = u8::from(*order == BitOrder::MsbFirst);
            let size = f.size;
            if read {
                let elem = match scale {
                    Some(sc) => indent(
                        &super::scale::read(
                            n,
                            Prim::U64,
                            sc,
                            &format!("{lo}get_packed(r->p + r->pos, {size}u, i, {bits}u, {msb})"),
                            &format!("{here}[i]"),
                        ),
                        1,
                    ),
                    None => format!(
                        "        {here}[i] = ({}){lo}get_packed(r->p + r->pos, {size}u, i, {bits}u, {msb});\n",
                        c_prim(*prim)
                    ),
                };
                format!(
                    "    if (r->len - r->pos < {size}u) return {up}ERR_PAYLOAD_LENGTH;\n    for (i = 0; i < {count}u; i++) {{\n{elem}    }}\n    r->pos += {size}u;\n"
                )
            } else {
                let raw = match scale {
                    Some(sc) => {
                        indent(&super::scale::write(n, *prim, sc, &format!("{here}[i]")), 1)
                    }
                    None => format!("        raw = (uint64_t){here}[i];\n"),
                };
                format!(
                    "    if (w->cap - w->pos < {size}u) return {up}ERR_SHORT_BUFFER;\n    memset(w->p + w->pos, 0, {size}u);\n    for (i = 0; i < {count}u; i++) {{\n{raw}        if (!{lo}set_packed(w->p + w->pos, {size}u, i, {bits}u, {msb}, raw)) return {up}ERR_OUT_OF_RANGE;\n    }}\n    w->pos += {size}u;\n"
                )
            }
        }
        FieldKind::Group { elem, max } => {
            let es = &p.structs[*elem];
            let (ety, esnake) = (n.ty(&es.name), names::snake(&es.name));
            let ctx = context_args(s, es, this);
            if read {
                // An element past the capacity is read (its own errors first, as the runtime
                // reads it), then refused: the payload is longer than the struct's largest.
                format!(
                    "    {here}_len = 0;\n    while (r->pos < r->len) {{\n        if ({here}_len == {max}u) {{\n            {ety} spare;\n            if ((e = {lo}read_{esnake}(r, &spare{ctx})) != 0) return e;\n            return {up}ERR_PAYLOAD_LENGTH;\n        }}\n        if ((e = {lo}read_{esnake}(r, &{here}[{here}_len]{ctx})) != 0) return e;\n        {here}_len++;\n    }}\n"
                )
            } else {
                format!(
                    "    if ({here}_len > {max}u) return {up}ERR_OUT_OF_RANGE;\n    for (i = 0; i < {here}_len; i++) {{\n        if ((e = {lo}write_{esnake}(w, &{here}[i]{ctx})) != 0) return e;\n    }}\n"
                )
            }
        }
        FieldKind::Optional(inner) => {
            let inner = field(p, n, s, f, inner, dir, here);
            let inner = indent(&inner, 1);
            let present = optional_flag(here, f);
            if read {
                format!("    {present} = r->pos < r->len;\n    if ({present}) {{\n{inner}    }}\n")
            } else {
                format!("    if ({present}) {{\n{inner}    }}\n")
            }
        }
    }
}

/// Lines indented `levels` levels (four spaces each) more.
fn indent(text: &str, levels: usize) -> String {
    let pad = "    ".repeat(levels);
    text.lines().map(|l| format!("{pad}{l}\n")).collect()
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
        "    if ((e = {}) != 0) return e;\n",
        take_call(n, word.prim.size(), big(word), "raw")
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
            // A signed enum's value is its bits as a two's complement integer of its type.
            Some(ei) if p.enums[ei].prim.is_signed() => format!(
                "({}){}",
                n.ty(&p.enums[ei].name),
                from_raw(lo, p.enums[ei].prim, &bits)
            ),
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
        "    if ((e = {}) != 0) return e;",
        put_call(n, word.prim.size(), big(word), "word")
    );
    body
}

fn read_elem(p: &Protocol, n: &Names, ty: &ValueType, dst: &str) -> String {
    let (lo, up) = (&n.lo, &n.up);
    match ty {
        ValueType::Scalar {
            scalar,
            scale: Some(sc),
        } => format!(
            "    if ((e = {}) != 0) return e;\n{}",
            take_call(n, scalar.prim.size(), big(*scalar), "raw"),
            super::scale::read(n, scalar.prim, sc, "raw", dst)
        ),
        ValueType::Scalar { scalar, .. } => format!(
            "    if ((e = {}) != 0) return e;\n    {dst} = {};\n",
            take_call(n, scalar.prim.size(), big(*scalar), "raw"),
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
                "    if ((e = {}) != 0) return e;\n",
                take_call(n, scalar.prim.size(), big(*scalar), "raw")
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
        ValueType::Scalar {
            scalar,
            scale: Some(sc),
        } => format!(
            "{}    if ((e = {}) != 0) return e;\n",
            super::scale::write(n, scalar.prim, sc, src),
            put_call(n, scalar.prim.size(), big(*scalar), "raw")
        ),
        ValueType::Scalar { scalar, .. } => format!(
            "{}    if ((e = {}) != 0) return e;\n",
            range_check(scalar.prim, src, up),
            put_call(
                n,
                scalar.prim.size(),
                big(*scalar),
                &to_raw(lo, scalar.prim, src)
            )
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
                "    if ((e = {}) != 0) return e;",
                put_call(n, scalar.prim.size(), big(*scalar), "raw")
            );
            s
        }
        ValueType::Text(len) => format!(
            "    if (w->cap - w->pos < {len}u) return {up}ERR_SHORT_BUFFER;\n    memcpy(w->p + w->pos, {src}, {len}u);\n    w->pos += {len}u;\n"
        ),
    }
}
