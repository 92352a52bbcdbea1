//! The text form of a packet (`<prefix>_format`), compiled only with `<PREFIX>_WITH_FORMAT`
//! (it needs `snprintf`, which a firmware may not want): one line, `cmd=NAME [dir=NAME]
//! header.NAME=VALUE... payload.PATH=VALUE...`. Floats are printed as their bits (`f32:` and
//! eight hex digits), enums as their variant's spec name (the number when it has none), bytes
//! as `hex:` and their digits: a form that compares exactly, for logs and conformance tests.

use std::fmt::Write as _;

use crate::ir::{Field, FieldKind, Prim, Protocol, ValueType};

use super::names::Fx;
use super::names::{self, Names};
use super::shape::{Carries, any_field, carries, keyed_format, slots_of, user_values};

/// The formatter, inside `#ifdef <PREFIX>_WITH_FORMAT`.
pub fn format(p: &Protocol, n: &Names) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let mut out = format!(
        "/* ---- Text form ---- */\n\n#ifdef {up}WITH_FORMAT\n#include <stdarg.h>\n#include <stdio.h>\n\nstruct {lo}txt {{ char *p; size_t cap; size_t len; }};\n\nstatic void {lo}emit(struct {lo}txt *t, const char *fmt, ...)\n{{\n    va_list ap;\n    int n;\n    va_start(ap, fmt);\n    n = vsnprintf(t->len < t->cap ? t->p + t->len : NULL, t->len < t->cap ? t->cap - t->len : 0, fmt, ap);\n    va_end(ap);\n    if (n > 0) t->len += (size_t)n;\n}}\n\n"
    );
    out.push_str(&path_helper(n));
    if any_field(p, |k| {
        matches!(
            k,
            FieldKind::Value {
                ty: ValueType::Text(_),
                ..
            } | FieldKind::NulText { .. }
        )
    }) {
        out.push_str(&text_helpers(n));
    }
    for s in &p.structs {
        let mut body = String::new();
        for f in &s.fields {
            body.push_str(&field(p, n, f, &f.kind));
        }
        let loops = body.contains("(i = 0;");
        let decls = if loops { "    size_t i;\n" } else { "" };
        let _ = write!(
            out,
            "static void {lo}fmt_{snake}(struct {lo}txt *t, const char *path, const {ty} *v)\n{{\n    char sub[192];\n{decls}{body}    (void)sub;\n    (void)v;\n    (void)path;\n}}\n\n",
            snake = names::snake(&s.name),
            ty = n.ty(&s.name)
        );
    }
    for fi in 0..p.frames.len() {
        packet_format(p, n, &Fx::new(p, fi), &mut out);
    }
    let _ = writeln!(out, "#endif /* {up}WITH_FORMAT */");
    out
}

/// `pfx_format` of frame format `x`: the command, the direction, the header values (and the
/// flag trailer's bytes, or `null`), then the payload.
fn packet_format(p: &Protocol, n: &Names, x: &Fx, out: &mut String) {
    let lo = &n.lo;
    let xlo = &x.lo;
    let f = &p.frames[x.fi];
    let _ = writeln!(
        out,
        "int {xlo}format(const {xlo}packet *packet, char *out, size_t cap)\n{{\n    struct {lo}txt text;\n    struct {lo}txt *t = &text;\n    text.p = out;\n    text.cap = cap;\n    text.len = 0;\n    if (cap > 0) out[0] = 0;\n"
    );
    if f.ack.is_some() {
        let _ = writeln!(
            out,
            "    {lo}emit(t, \"cmd=%s\", packet->ack ? \"?\" : {lo}command_name(packet->command));"
        );
    } else if keyed_format(p, x.fi) {
        let _ = writeln!(
            out,
            "    {lo}emit(t, \"cmd=%s\", {lo}command_name(packet->command) ? {lo}command_name(packet->command) : \"?\");"
        );
    } else {
        let _ = writeln!(out, "    {lo}emit(t, \"cmd=?\");");
    }
    if !p.directions.is_empty() && carries(p, x.fi) == Carries::Commands {
        let _ = writeln!(
            out,
            "    {lo}emit(t, \" dir=%s\", {lo}direction_name(packet->direction));"
        );
    }
    for v in user_values(f) {
        let value = format!("packet->header.{}", names::field(&v.name));
        let label = format!("\"header.{}=\"", v.name);
        let prim = if v.prim == Prim::Bool {
            Prim::Bool
        } else {
            Prim::U64
        };
        out.push_str(&scalar(lo, prim, &label, &value, ""));
    }
    if let Some(tr) = &f.flag_trailer {
        let name = names::field(&tr.name);
        let _ = writeln!(
            out,
            "    if (packet->header.{name}_present) {{\n        size_t i;\n        {lo}emit(t, \" header.{}=hex:\");\n        for (i = 0; i < {}u; i++) {lo}emit(t, \"%02x\", (unsigned)packet->header.{name}[i]);\n    }} else {{\n        {lo}emit(t, \" header.{}=null\");\n    }}",
            tr.name, tr.len, tr.name
        );
    }
    if carries(p, x.fi) == Carries::Bytes {
        let _ = writeln!(
            out,
            "    {{\n        size_t i;\n        {lo}emit(t, \" payload=hex:\");\n        for (i = 0; i < packet->payload_len; i++) {lo}emit(t, \"%02x\", (unsigned)packet->payload[i]);\n    }}"
        );
    }
    for slot in slots_of(p, x.fi) {
        if let Some(si) = slot.si {
            let _ = writeln!(
                out,
                "    {}{lo}fmt_{}(t, \"payload\", &packet->payload.{});",
                slot.guard(p, n, "packet"),
                names::snake(&p.structs[si].name),
                slot.name
            );
        }
    }
    if f.ack.is_some() {
        let _ = writeln!(
            out,
            "    if (packet->ack) {{\n        size_t i;\n        {lo}emit(t, \" payload=hex:\");\n        for (i = 0; i < packet->payload.ack_data.len; i++) {lo}emit(t, \"%02x\", (unsigned)packet->payload.ack_data.bytes[i]);\n    }}"
        );
    }
    let _ = writeln!(out, "    return (int)text.len;\n}}\n");
}

/// The text of one field (`kind`: the field's, or what an optional field holds).
fn field(p: &Protocol, n: &Names, f: &Field, kind: &FieldKind) -> String {
    let lo = &n.lo;
    let name = names::field(&f.name);
    let mut body = String::new();
    let each = |count: &dyn std::fmt::Display, what: String| {
        format!("    for (i = 0; i < {count}; i++) {{\n{what}    }}\n")
    };
    let item = format!("\"%s.{}[%u]=\", path, (unsigned)i", f.name);
    match kind {
        FieldKind::Padding | FieldKind::Check(_) => {}
        // The text up to its NUL: a string when it is UTF-8, else its bytes.
        FieldKind::NulText { max } => {
            let _ = writeln!(
                body,
                "    for (i = 0; i <= {max}u && v->{name}[i] != 0; i++) {{\n    }}\n    {lo}path(sub, sizeof sub, \"%s.{}\", path);\n    {lo}fmt_text(t, sub, (const uint8_t *)v->{name}, i);",
                f.name
            );
        }
        FieldKind::Array { ty, .. } => body.push_str(&each(
            &format!("v->{name}_len"),
            value(p, n, ty, &item, &format!("v->{name}[i]"), "    "),
        )),
        FieldKind::Value { ty, count } => match count {
            None => body.push_str(&value(
                p,
                n,
                ty,
                &format!("\"%s.{}=\", path", f.name),
                &format!("v->{name}"),
                "",
            )),
            Some(c) => body.push_str(&each(
                &format!("{c}u"),
                value(p, n, ty, &item, &format!("v->{name}[i]"), "    "),
            )),
        },
        FieldKind::Bits { members, .. } => {
            for m in members {
                let v = format!("v->{}", names::field(&m.name));
                let label = format!("\"%s.{}=\", path", m.name);
                body.push_str(&match m.enum_index {
                    Some(ei) => enum_value(n, &p.enums[ei].name, p.enums[ei].prim, &label, &v, ""),
                    None => scalar(lo, m.prim, &label, &v, ""),
                });
            }
        }
        FieldKind::Bytes { .. } => {
            let _ = writeln!(
                body,
                "    {lo}emit(t, \" %s.{}=hex:\", path);\n    for (i = 0; i < v->{name}_len; i++) {lo}emit(t, \"%02x\", (unsigned)v->{name}[i]);",
                f.name
            );
        }
        FieldKind::Packed {
            count, prim, scale, ..
        } => body.push_str(&each(
            &format!("{count}u"),
            scalar(
                lo,
                scale.map_or(*prim, |sc| sc.physical),
                &item,
                &format!("v->{name}[i]"),
                "    ",
            ),
        )),
        FieldKind::Group { elem, .. } => body.push_str(&each(
            &format!("v->{name}_len"),
            value(
                p,
                n,
                &ValueType::Struct(*elem),
                &item,
                &format!("v->{name}[i]"),
                "    ",
            ),
        )),
        FieldKind::Optional(inner) => {
            let keys: String = match &**inner {
                FieldKind::Bits { members, .. } => members
                    .iter()
                    .map(|m| format!("    {lo}emit(t, \" %s.{}=null\", path);\n", m.name))
                    .collect(),
                _ => format!("    {lo}emit(t, \" %s.{}=null\", path);\n", f.name),
            };
            let _ = write!(
                body,
                "    if (v->{name}_present) {{\n{}    }} else {{\n{}    }}\n",
                indent(&field(p, n, f, inner)),
                indent(&keys)
            );
        }
    }
    body
}

/// The text of a `char[N]` field, as the run-time codec shows it: ` PATH=TEXT` when the bytes
/// are canonical (UTF-8 text, then only NUL bytes: the runtime's `text::is_canonical`), else
/// every byte, ` PATH[i]=BYTE`. A control character or backslash in the text is written
/// `\xNN`, so that the text form stays one line.
fn text_helpers(n: &Names) -> String {
    let (lo, up) = (&n.lo, &n.up);
    format!(
        "/* Whether `s[0..n]` is UTF-8 (no overlong form, no surrogate, nothing above U+10FFFF). */
{up}UNUSED static int {lo}utf8(const uint8_t *s, size_t n)
{{
    size_t i = 0, k, more;
    while (i < n) {{
        uint8_t c = s[i], lo = 0x80, hi = 0xBF;
        if (c < 0x80) {{
            i++;
            continue;
        }}
        if (c >= 0xC2 && c <= 0xDF) more = 1;
        else if (c >= 0xE0 && c <= 0xEF) more = 2;
        else if (c >= 0xF0 && c <= 0xF4) more = 3;
        else return 0;
        if (c == 0xE0) lo = 0xA0;
        if (c == 0xED) hi = 0x9F;
        if (c == 0xF0) lo = 0x90;
        if (c == 0xF4) hi = 0x8F;
        if (n - i - 1 < more) return 0;
        for (k = 1; k <= more; k++) {{
            if (s[i + k] < (k == 1 ? lo : 0x80) || s[i + k] > (k == 1 ? hi : 0xBF)) return 0;
        }}
        i += more + 1;
    }}
    return 1;
}}

{up}UNUSED static void {lo}fmt_text(struct {lo}txt *t, const char *path, const uint8_t *b, size_t n)
{{
    size_t len = 0, i;
    int canonical;
    while (len < n && b[len] != 0) len++;
    canonical = {lo}utf8(b, len);
    for (i = len; i < n; i++) canonical = canonical && b[i] == 0;
    if (canonical) {{
        {lo}emit(t, \" %s=\", path);
        for (i = 0; i < len; i++) {{
            if (b[i] < 0x20 || b[i] == 0x7F || b[i] == '\\\\') {lo}emit(t, \"\\\\x%02x\", (unsigned)b[i]);
            else {lo}emit(t, \"%c\", b[i]);
        }}
        return;
    }}
    for (i = 0; i < n; i++) {lo}emit(t, \" %s[%u]=%u\", path, (unsigned)i, (unsigned)b[i]);
}}

"
    )
}

/// The path of a nested value, for the text of its fields.
fn path_helper(n: &Names) -> String {
    let (lo, up) = (&n.lo, &n.up);
    format!(
        "/* The path of a nested value into `sub` (cut short when it does not fit). */
{up}UNUSED static void {lo}path(char *sub, size_t cap, const char *fmt, ...)
{{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(sub, cap, fmt, ap);
    va_end(ap);
}}

"
    )
}

/// Lines indented one level more.
fn indent(text: &str) -> String {
    text.lines().map(|l| format!("    {l}\n")).collect()
}

/// One value: ` LABEL=VALUE`, `label` being the format and arguments of the label.
fn value(p: &Protocol, n: &Names, ty: &ValueType, label: &str, v: &str, indent: &str) -> String {
    match ty {
        ValueType::Scalar { scalar: s, scale } => scalar(
            &n.lo,
            scale.map_or(s.prim, |sc| sc.physical),
            label,
            v,
            indent,
        ),
        ValueType::Enum(ei, _) => {
            enum_value(n, &p.enums[*ei].name, p.enums[*ei].prim, label, v, indent)
        }
        ValueType::Struct(si) => {
            let (fmt, args) = split(label);
            format!(
                "{indent}    {lo}path(sub, sizeof sub, {}{args});\n{indent}    {lo}fmt_{}(t, sub, &{v});\n",
                fmt.replace("=\"", "\""),
                names::snake(&p.structs[*si].name),
                lo = n.lo
            )
        }
        ValueType::Text(len) => {
            let (fmt, args) = split(label);
            format!(
                "{indent}    {lo}path(sub, sizeof sub, {}{args});\n{indent}    {lo}fmt_text(t, sub, (const uint8_t *){v}, {len}u);\n",
                fmt.replace("=\"", "\""),
                lo = n.lo
            )
        }
    }
}

/// The format string of a label (with its leading space) and its arguments.
fn split(label: &str) -> (String, String) {
    let end = label[1..].find('"').map_or(label.len(), |i| i + 2);
    (label[..end].to_string(), label[end..].to_string())
}

fn scalar(lo: &str, prim: Prim, label: &str, v: &str, indent: &str) -> String {
    let (fmt, args) = split(label);
    let fmt = format!("\" {}", &fmt[1..]);
    let (spec, value) = match prim {
        Prim::Bool => ("%s", format!("{v} ? \"true\" : \"false\"")),
        Prim::F32 => (
            "f32:%08llx",
            format!("(unsigned long long){lo}f32_bits({v})"),
        ),
        Prim::F64 => (
            "f64:%016llx",
            format!("(unsigned long long){lo}f64_bits({v})"),
        ),
        p if p.is_signed() => ("%lld", format!("(long long){v}")),
        _ => ("%llu", format!("(unsigned long long){v}")),
    };
    let fmt = fmt.trim_end_matches('"').to_string() + spec + "\"";
    format!("{indent}    {lo}emit(t, {fmt}{args}, {value});\n")
}

fn enum_value(n: &Names, name: &str, prim: Prim, label: &str, v: &str, indent: &str) -> String {
    let ty = n.ty(name);
    let (fmt, args) = split(label);
    let fmt = format!("\" {}", &fmt[1..]);
    let fmt = fmt.trim_end_matches('"');
    let (spec, cast) = if prim.is_signed() {
        ("%lld", "long long")
    } else {
        ("%llu", "unsigned long long")
    };
    format!(
        "{indent}    if ({ty}_name({v})) {lo}emit(t, {fmt}%s\"{args}, {ty}_name({v}));\n{indent}    else {lo}emit(t, {fmt}{spec}\"{args}, ({cast}){v});\n",
        lo = n.lo
    )
}
