//! The text form of a packet (`<prefix>_format`), compiled only with `<PREFIX>_WITH_FORMAT`
//! (it needs `snprintf`, which a firmware may not want): one line, `cmd=NAME [dir=NAME]
//! header.NAME=VALUE... payload.PATH=VALUE...`. Floats are printed as their bits (`f32:` and
//! eight hex digits), enums as their variant's spec name (the number when it has none), bytes
//! as `hex:` and their digits: a form that compares exactly, for logs and conformance tests.

use std::fmt::Write as _;

use crate::ir::{FieldKind, Prim, Protocol, Role, ValueType};

use super::names::{self, Names};
use super::types::{slot_name, slots};

/// The formatter, inside `#ifdef <PREFIX>_WITH_FORMAT`.
pub fn format(p: &Protocol, n: &Names) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let mut out = format!(
        "/* ---- Text form ---- */\n\n#ifdef {up}WITH_FORMAT\n#include <stdarg.h>\n#include <stdio.h>\n\nstruct {lo}txt {{ char *p; size_t cap; size_t len; }};\n\nstatic void {lo}emit(struct {lo}txt *t, const char *fmt, ...)\n{{\n    va_list ap;\n    int n;\n    va_start(ap, fmt);\n    n = vsnprintf(t->len < t->cap ? t->p + t->len : NULL, t->len < t->cap ? t->cap - t->len : 0, fmt, ap);\n    va_end(ap);\n    if (n > 0) t->len += (size_t)n;\n}}\n\n"
    );
    for s in &p.structs {
        let mut body = String::new();
        let mut loops = false;
        for f in &s.fields {
            let name = names::field(&f.name);
            match &f.kind {
                FieldKind::Padding => {}
                FieldKind::Value { ty, count } => match count {
                    None => body.push_str(&value(
                        p,
                        n,
                        ty,
                        &format!("\"%s.{}=\", path", f.name),
                        &format!("v->{name}"),
                        "",
                    )),
                    Some(c) => {
                        loops = true;
                        let _ = writeln!(body, "    for (i = 0; i < {c}u; i++) {{");
                        body.push_str(&value(
                            p,
                            n,
                            ty,
                            &format!("\"%s.{}[%u]=\", path, (unsigned)i", f.name),
                            &format!("v->{name}[i]"),
                            "    ",
                        ));
                        body.push_str("    }\n");
                    }
                },
                FieldKind::Bits { members, .. } => {
                    for m in members {
                        let v = format!("v->{}", names::field(&m.name));
                        let label = format!("\"%s.{}=\", path", m.name);
                        let _ = match m.enum_index {
                            Some(ei) => write!(
                                body,
                                "{}",
                                enum_value(n, &p.enums[ei].name, p.enums[ei].prim, &label, &v, "")
                            ),
                            None => write!(body, "{}", scalar(lo, m.prim, &label, &v, "")),
                        };
                    }
                }
                FieldKind::Bytes { .. } => {
                    loops = true;
                    let _ = writeln!(
                        body,
                        "    {lo}emit(t, \" %s.{}=hex:\", path);\n    for (i = 0; i < v->{name}_len; i++) {lo}emit(t, \"%02x\", (unsigned)v->{name}[i]);",
                        f.name
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
        let decls = if loops { "    size_t i;\n" } else { "" };
        let _ = write!(
            out,
            "static void {lo}fmt_{snake}(struct {lo}txt *t, const char *path, const {ty} *v)\n{{\n    char sub[192];\n{decls}{body}    (void)sub;\n    (void)v;\n    (void)path;\n}}\n\n",
            snake = names::snake(&s.name),
            ty = n.ty(&s.name)
        );
    }
    let _ = writeln!(
        out,
        "int {lo}format(const {lo}packet *packet, char *out, size_t cap)\n{{\n    struct {lo}txt text;\n    struct {lo}txt *t = &text;\n    text.p = out;\n    text.cap = cap;\n    text.len = 0;\n    if (cap > 0) out[0] = 0;\n    {lo}emit(t, \"cmd=%s\", {lo}command_name(packet->command));"
    );
    if !p.directions.is_empty() {
        let _ = writeln!(
            out,
            "    {lo}emit(t, \" dir=%s\", {lo}direction_name(packet->direction));"
        );
    }
    for v in p.frames[0]
        .values
        .iter()
        .filter(|v| matches!(v.role, Role::User { .. }))
    {
        let value = format!("packet->header.{}", names::field(&v.name));
        let label = format!("\"header.{}=\"", v.name);
        let prim = if v.prim == Prim::Bool {
            Prim::Bool
        } else {
            Prim::U64
        };
        out.push_str(&scalar(lo, prim, &label, &value, ""));
    }
    for (ci, di, si) in slots(p) {
        let dir = if p.directions.is_empty() {
            String::new()
        } else {
            format!(
                " && packet->direction == {up}{}",
                p.directions[di].name.to_uppercase()
            )
        };
        let _ = writeln!(
            out,
            "    if (packet->command == {up}{}{dir}) {lo}fmt_{}(t, \"payload\", &packet->payload.{});",
            p.commands[ci].name,
            names::snake(&p.structs[si].name),
            slot_name(p, ci, di)
        );
    }
    let _ = writeln!(
        out,
        "    return (int)text.len;\n}}\n#endif /* {up}WITH_FORMAT */"
    );
    out
}

/// One value: ` LABEL=VALUE`, `label` being the format and arguments of the label.
fn value(p: &Protocol, n: &Names, ty: &ValueType, label: &str, v: &str, indent: &str) -> String {
    match ty {
        ValueType::Scalar { scalar: s, .. } => scalar(&n.lo, s.prim, label, v, indent),
        ValueType::Enum(ei, _) => {
            enum_value(n, &p.enums[*ei].name, p.enums[*ei].prim, label, v, indent)
        }
        ValueType::Struct(si) => {
            let (fmt, args) = split(label);
            format!(
                "{indent}    snprintf(sub, sizeof sub, {}{args});\n{indent}    {}fmt_{}(t, sub, &{v});\n",
                fmt.replace("=\"", "\""),
                n.lo,
                names::snake(&p.structs[*si].name)
            )
        }
        // Refused by `support` before anything is printed.
        ValueType::Text(_) => String::new(),
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
