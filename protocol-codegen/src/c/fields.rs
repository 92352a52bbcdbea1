//! The statements of one payload field, by kind, in a struct's reader or writer: checks
//! inside the payload, padding, values and arrays of them, bytes, text, bit-packed arrays,
//! groups of structs and optional fields, with the runtime's field rules (bytes or elements
//! beyond their maximum are an error, a stated length must be there and fit). One value's
//! statements are `values`'.

use crate::ir::{
    BitOrder, ByteOrder, Field, FieldKind, PayloadCheck, Prim, Protocol, Struct, ValueType,
};

use super::names::{self, Names, prim as c_prim, value_type};
use super::prelude::{put_call, take_call};
use super::template::fill;
use super::values::{read_bits, read_elem, try_call, write_bits, write_elem};

/// Which way a struct's walk goes: from the payload into the C struct, or back.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dir {
    Read,
    Write,
}

/// The statements that read or write one field of struct `s` (`kind`: the field's, or what
/// an optional field holds), whose C value is `here`.
pub fn field(
    p: &Protocol,
    n: &Names,
    s: &Struct,
    f: &Field,
    kind: &FieldKind,
    dir: Dir,
    here: &str,
) -> String {
    let read = dir == Dir::Read;
    let this = if read { "out" } else { "v" };
    match kind {
        // Printed by the struct's walk, which knows the covered fields.
        FieldKind::Check(_) => unreachable!("a check is printed by walk"),
        FieldKind::Padding => padding(n, f.size, dir),
        FieldKind::Value { ty, count } => value(p, n, ty, *count, dir, here),
        FieldKind::Bits { word, members } if read => read_bits(p, n, *word, members),
        FieldKind::Bits { word, members } => write_bits(p, n, *word, members),
        FieldKind::Bytes { max, size_from } => {
            let stated = size_from.as_ref().map(|size| stated(s, this, size));
            match dir {
                Dir::Read => read_bytes(n, *max, stated.as_deref(), here),
                Dir::Write => write_bytes(n, *max, stated.as_deref(), here),
            }
        }
        FieldKind::Array { ty, max, size_from } => {
            let stated = size_from.as_ref().map(|size| stated(s, this, size));
            match dir {
                Dir::Read => read_array(p, n, ty, *max, stated.as_deref(), here),
                Dir::Write => write_array(p, n, ty, *max, stated.as_deref(), here),
            }
        }
        FieldKind::NulText { max } => nul_text(n, *max, dir, here),
        FieldKind::Packed { .. } => packed(n, f, kind, dir, here),
        FieldKind::Group { elem, max } => {
            let es = &p.structs[*elem];
            group(n, es, *max, &context_args(s, es, this), dir, here)
        }
        FieldKind::Optional(inner) => {
            let inner = indent(&field(p, n, s, f, inner, dir, here), 1);
            let present = optional_flag(here, f);
            match dir {
                Dir::Read => fill!(
                    r"
    ${present} = r->pos < r->len;
    if (${present}) {
${inner}    }
",
                    present,
                    inner
                ),
                Dir::Write => fill!(
                    r"
    if (${present}) {
${inner}    }
",
                    present,
                    inner
                ),
            }
        }
    }
}

/// A check inside the payload over the bytes `from<first>..to<last>` (the runtime's
/// `field::verify_check`: the stored value, then the check; `field::put_check`).
pub fn payload_check(n: &Names, s: &Struct, f: &Field, c: &PayloadCheck, dir: Dir) -> String {
    let up = &n.up;
    let name = super::checks::payload_check_name(n, s, f);
    let (width, big) = (c.algorithm.width(), u8::from(c.endian == ByteOrder::Big));
    let (from, to) = (format!("from{}", c.first), format!("to{}", c.last));
    match dir {
        Dir::Read => {
            try_call(&take_call(n, width, big, "raw"))
                + &fill!(
                    r"
    if (!${name}(r->p + ${from}, ${to} - ${from}, &word) || word != raw) return ${up}ERR_PAYLOAD_CHECK;
",
                    name,
                    from,
                    to,
                    up
                )
        }
        Dir::Write => {
            fill!(
                "    (void)${name}(w->p + ${from}, ${to} - ${from}, &word);\n",
                name,
                from,
                to
            ) + &try_call(&put_call(n, width, big, "word"))
        }
    }
}

/// Bytes that take every byte left but the `keep` bytes of the fixed fields after them (the
/// runtime's `rest_but`).
pub fn read_bytes_but(n: &Names, max: usize, keep: usize, here: &str) -> String {
    let up = &n.up;
    fill!(
        r"
    ${here}_len = r->len - r->pos > ${keep}u ? r->len - r->pos - ${keep}u : 0;
    if (${here}_len > ${max}u) return ${up}ERR_PAYLOAD_LENGTH;
    memcpy(${here}, r->p + r->pos, ${here}_len);
    r->pos += ${here}_len;
",
        here,
        keep,
        max,
        up
    )
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

/// Lines indented `levels` levels (four spaces each) more.
fn indent(text: &str, levels: usize) -> String {
    let pad = "    ".repeat(levels);
    text.lines().map(|l| format!("{pad}{l}\n")).collect()
}

/// The flag of an optional field whose value is `here` (`out->ports` -> `out->ports_present`).
fn optional_flag(here: &str, f: &Field) -> String {
    let base = here.rsplit_once("->").map_or("", |(b, _)| b);
    format!("{base}->{}_present", names::field(&f.name))
}

/// Padding: its bytes skipped, or written as zeros.
fn padding(n: &Names, size: usize, dir: Dir) -> String {
    let lo = &n.lo;
    match dir {
        Dir::Read => try_call(&fill!("${lo}skip(r, ${size}u)", lo, size)),
        Dir::Write => try_call(&fill!("${lo}zero(w, ${size}u)", lo, size)),
    }
}

/// A value, or a fixed count of them.
fn value(
    p: &Protocol,
    n: &Names,
    ty: &ValueType,
    count: Option<usize>,
    dir: Dir,
    here: &str,
) -> String {
    let Some(count) = count else {
        return match dir {
            Dir::Read => read_elem(p, n, ty, here),
            Dir::Write => write_elem(p, n, ty, here),
        };
    };
    let each = format!("{here}[i]");
    let elem = match dir {
        Dir::Read => read_elem(p, n, ty, &each),
        Dir::Write => write_elem(p, n, ty, &each),
    };
    let elem = indent(&elem, 1);
    fill!(
        r"
    for (i = 0; i < ${count}u; i++) {
${elem}    }
",
        count,
        elem
    )
}

/// Bytes read: every byte left, or the count a field states (the runtime's
/// `field::take_sized`: the stated bytes must be there, then fit `max`).
fn read_bytes(n: &Names, max: usize, stated: Option<&str>, here: &str) -> String {
    let up = &n.up;
    let Some(stated) = stated else {
        return fill!(
            r"
    if (r->len - r->pos > ${max}u) return ${up}ERR_PAYLOAD_LENGTH;
    ${here}_len = r->len - r->pos;
    memcpy(${here}, r->p + r->pos, ${here}_len);
    r->pos = r->len;
",
            max,
            up,
            here
        );
    };
    fill!(
        r"
    stated = ${stated};
    if (r->len - r->pos < stated) return ${up}ERR_PAYLOAD_LENGTH;
    if (stated > ${max}u) return ${up}ERR_SIZE_MISMATCH;
    ${here}_len = (size_t)stated;
    memcpy(${here}, r->p + r->pos, ${here}_len);
    r->pos += ${here}_len;
",
        stated,
        up,
        max,
        here
    )
}

/// The checks of a count before its bytes or elements are written: at most `max`, and the
/// count a field states (the runtime's `field::check_stated_len`).
fn count_fits(n: &Names, max: usize, stated: Option<&str>, here: &str) -> String {
    let up = &n.up;
    let mut out = fill!(
        "    if (${here}_len > ${max}u) return ${up}ERR_OUT_OF_RANGE;\n",
        here,
        max,
        up
    );
    if let Some(stated) = stated {
        out.push_str(&fill!(
            "    if ((uint64_t)${here}_len != ${stated}) return ${up}ERR_OUT_OF_RANGE;\n",
            here,
            stated,
            up
        ));
    }
    out
}

/// Bytes written.
fn write_bytes(n: &Names, max: usize, stated: Option<&str>, here: &str) -> String {
    let up = &n.up;
    count_fits(n, max, stated, here)
        + &fill!(
            r"
    if (w->cap - w->pos < ${here}_len) return ${up}ERR_SHORT_BUFFER;
    memcpy(w->p + w->pos, ${here}, ${here}_len);
    w->pos += ${here}_len;
",
            here,
            up
        )
}

/// An array read: elements to the payload's end, or the count a field states (the
/// runtime's `field::array_len`: the stated count must fit `max`).
fn read_array(
    p: &Protocol,
    n: &Names,
    ty: &ValueType,
    max: usize,
    stated: Option<&str>,
    here: &str,
) -> String {
    let up = &n.up;
    let Some(stated) = stated else {
        // An element past the capacity is read (its own errors first, as the runtime reads
        // it), then refused: the payload is longer than the struct's largest.
        let spare = indent(&read_elem(p, n, ty, "spare"), 2);
        let elem = indent(&read_elem(p, n, ty, &format!("{here}[{here}_len]")), 1);
        let ty = value_type(p, n, ty);
        return fill!(
            r"
    ${here}_len = 0;
    while (r->pos < r->len) {
        if (${here}_len == ${max}u) {
            ${ty} spare;
${spare}            (void)spare;
            return ${up}ERR_PAYLOAD_LENGTH;
        }
${elem}        ${here}_len++;
    }
",
            here,
            max,
            ty,
            spare,
            up,
            elem
        );
    };
    let elem = indent(&read_elem(p, n, ty, &format!("{here}[i]")), 1);
    fill!(
        r"
    stated = ${stated};
    if (stated > ${max}u) return ${up}ERR_SIZE_MISMATCH;
    ${here}_len = (size_t)stated;
    for (i = 0; i < ${here}_len; i++) {
${elem}    }
",
        stated,
        max,
        up,
        here,
        elem
    )
}

/// An array written.
fn write_array(
    p: &Protocol,
    n: &Names,
    ty: &ValueType,
    max: usize,
    stated: Option<&str>,
    here: &str,
) -> String {
    let elem = indent(&write_elem(p, n, ty, &format!("{here}[i]")), 1);
    count_fits(n, max, stated, here)
        + &fill!(
            r"
    for (i = 0; i < ${here}_len; i++) {
${elem}    }
",
            here,
            elem
        )
}

/// NUL-terminated text: read, a NUL within the first `max + 1` bytes left (the runtime's
/// `text::read_nul_text`); written, at most `max` bytes before the NUL (`text::nul_text_fits`).
fn nul_text(n: &Names, max: usize, dir: Dir, here: &str) -> String {
    let up = &n.up;
    match dir {
        Dir::Read => fill!(
            r"
    for (word = 0; word < r->len - r->pos && word <= ${max}u; word++) {
        if (r->p[r->pos + word] == 0) break;
    }
    if (word == r->len - r->pos || word > ${max}u) return ${up}ERR_UNTERMINATED;
    memcpy(${here}, r->p + r->pos, (size_t)word);
    ${here}[word] = 0;
    r->pos += (size_t)word + 1;
",
            max,
            up,
            here
        ),
        Dir::Write => fill!(
            r"
    for (word = 0; word <= ${max}u && ${here}[word] != 0; word++) {
    }
    if (word > ${max}u) return ${up}ERR_OUT_OF_RANGE;
    if (w->cap - w->pos < word + 1) return ${up}ERR_SHORT_BUFFER;
    memcpy(w->p + w->pos, ${here}, (size_t)word);
    w->p[w->pos + word] = 0;
    w->pos += (size_t)word + 1;
",
            max,
            here,
            up
        ),
    }
}

/// A bit-packed array of `count` elements of `bits` bits (scaled, or integers of `prim`).
fn packed(n: &Names, f: &Field, kind: &FieldKind, dir: Dir, here: &str) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let FieldKind::Packed {
        count,
        bits,
        order,
        prim,
        scale,
    } = kind
    else {
        unreachable!("a packed field")
    };
    let msb = u8::from(*order == BitOrder::MsbFirst);
    let size = f.size;
    let each = format!("{here}[i]");
    if dir == Dir::Read {
        let get = fill!(
            "${lo}get_packed(r->p + r->pos, ${size}u, i, ${bits}u, ${msb})",
            lo,
            size,
            bits,
            msb
        );
        let elem = match scale {
            Some(sc) => indent(&super::scale::read(n, Prim::U64, sc, &get, &each), 1),
            None => {
                let ty = c_prim(*prim);
                fill!("        ${each} = (${ty})${get};\n", each, ty, get)
            }
        };
        return fill!(
            r"
    if (r->len - r->pos < ${size}u) return ${up}ERR_PAYLOAD_LENGTH;
    for (i = 0; i < ${count}u; i++) {
${elem}    }
    r->pos += ${size}u;
",
            size,
            up,
            count,
            elem
        );
    }
    let raw = match scale {
        Some(sc) => indent(&super::scale::write(n, *prim, sc, &each), 1),
        None => fill!("        raw = (uint64_t)${each};\n", each),
    };
    fill!(
        r"
    if (w->cap - w->pos < ${size}u) return ${up}ERR_SHORT_BUFFER;
    memset(w->p + w->pos, 0, ${size}u);
    for (i = 0; i < ${count}u; i++) {
${raw}        if (!${lo}set_packed(w->p + w->pos, ${size}u, i, ${bits}u, ${msb}, raw)) return ${up}ERR_OUT_OF_RANGE;
    }
    w->pos += ${size}u;
",
        size,
        up,
        count,
        raw,
        lo,
        bits,
        msb
    )
}

/// A group: structs `es` to the payload's end, at most `max` (read: one past it is read,
/// its own errors first as the runtime reads it, then refused), each given `ctx`.
fn group(n: &Names, es: &Struct, max: usize, ctx: &str, dir: Dir, here: &str) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let (ety, esnake) = (n.ty(&es.name), names::snake(&es.name));
    match dir {
        Dir::Read => fill!(
            r"
    ${here}_len = 0;
    while (r->pos < r->len) {
        if (${here}_len == ${max}u) {
            ${ety} spare;
            if ((e = ${lo}read_${esnake}(r, &spare${ctx})) != 0) return e;
            return ${up}ERR_PAYLOAD_LENGTH;
        }
        if ((e = ${lo}read_${esnake}(r, &${here}[${here}_len]${ctx})) != 0) return e;
        ${here}_len++;
    }
",
            here,
            max,
            ety,
            lo,
            esnake,
            ctx,
            up
        ),
        Dir::Write => fill!(
            r"
    if (${here}_len > ${max}u) return ${up}ERR_OUT_OF_RANGE;
    for (i = 0; i < ${here}_len; i++) {
        if ((e = ${lo}write_${esnake}(w, &${here}[i]${ctx})) != 0) return e;
    }
",
            here,
            max,
            up,
            lo,
            esnake,
            ctx
        ),
    }
}
