//! The text form of a packet (`<prefix>_format`), compiled only with `<PREFIX>_WITH_FORMAT`
//! (it needs `snprintf`, which a firmware may not want): one line, `cmd=NAME [dir=NAME]
//! header.NAME=VALUE... payload.PATH=VALUE...`. Floats are printed as their bits (`f32:` and
//! eight hex digits), enums as their variant's spec name (the number when it has none), bytes
//! as `hex:` and their digits: a form that compares exactly, for logs and conformance tests.

use crate::ir::{FieldKind, Prim, Protocol, ValueType};
use crate::rules::Carries;

use super::kinds;
use super::names::{self, Fx, Names};
use super::shape::{any_field, carries, keyed_format, slots_of, user_values};
use super::template::fill;

/// The formatter, inside `#ifdef <PREFIX>_WITH_FORMAT`: the shared helpers
/// (`templates/text_open.c`, and `templates/text_utf8.c` for a spec with text), a function
/// per struct, a function per frame format.
pub fn format(p: &Protocol, n: &Names) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let mut out = fill!(include_str!("templates/text_open.c"), lo, up);
    out.push('\n');
    let text = |k: &FieldKind| {
        matches!(
            k,
            FieldKind::Value {
                ty: ValueType::Text(_),
                ..
            } | FieldKind::NulText { .. }
                | FieldKind::Bytes { text: true, .. }
        )
    };
    if any_field(p, text) {
        out.push_str(&fill!(include_str!("templates/text_utf8.c"), lo, up));
        out.push('\n');
    }
    for s in &p.structs {
        let body: String = s
            .fields
            .iter()
            .map(|f| kinds::of(p, &f.kind).text(n, f))
            .collect();
        let decls = if body.contains("(i = 0;") {
            "    size_t i;\n"
        } else {
            ""
        };
        let (snake, ty) = (names::snake(&s.name), n.ty(&s.name));
        // Unused for a struct no command carries, as its reader and writer are.
        out.push_str(&fill!(
            r"
${up}UNUSED static void ${lo}fmt_${snake}(struct ${lo}txt *t, const char *path, const ${ty} *v)
{
    char sub[192];
${decls}${body}    (void)sub;
    (void)v;
    (void)path;
}

",
            up,
            lo,
            snake,
            ty,
            decls,
            body
        ));
    }
    for fi in 0..p.frames.len() {
        packet_format(p, n, &Fx::new(p, fi), &mut out);
    }
    out.push_str(&fill!("#endif /* ${up}WITH_FORMAT */\n", up));
    out
}

/// `pfx_format` of frame format `x`: the command, the direction, the header values (and the
/// flag trailer's bytes, or `null`), then the payload.
fn packet_format(p: &Protocol, n: &Names, x: &Fx, out: &mut String) {
    let (lo, xlo) = (&n.lo, &x.lo);
    let f = &p.frames[x.fi];
    out.push_str(&fill!(
        r"
int ${xlo}format(const ${xlo}packet *packet, char *out, size_t cap)
{
    struct ${lo}txt text;
    struct ${lo}txt *t = &text;
    text.p = out;
    text.cap = cap;
    text.len = 0;
    if (cap > 0) out[0] = 0;

",
        xlo,
        lo
    ));
    let command = if x.rules.ack.is_some() {
        r#"    ${lo}emit(t, "cmd=%s", packet->ack ? "?" : ${lo}command_name(packet->command));"#
    } else if keyed_format(p, x) {
        r#"    ${lo}emit(t, "cmd=%s", ${lo}command_name(packet->command) ? ${lo}command_name(packet->command) : "?");"#
    } else {
        r#"    ${lo}emit(t, "cmd=?");"#
    };
    out.push_str(&fill!(command, lo));
    out.push('\n');
    if !p.directions.is_empty() && carries(p, x) == Carries::Command {
        out.push_str(&fill!(
            "    ${lo}emit(t, \" dir=%s\", ${lo}direction_name(packet->direction));\n",
            lo
        ));
    }
    for v in user_values(f) {
        let value = format!("packet->header.{}", names::field(&v.name));
        let label = Label {
            fmt: format!("header.{}=", v.name),
            args: String::new(),
        };
        let prim = if v.prim == Prim::Bool {
            Prim::Bool
        } else {
            Prim::U64
        };
        out.push_str(&scalar(lo, prim, &label, &value));
    }
    if let Some(tr) = &f.flag_trailer {
        let (name, field, len) = (&tr.name, names::field(&tr.name), tr.len);
        out.push_str(&fill!(
            r#"
    if (packet->header.${field}_present) {
        size_t i;
        ${lo}emit(t, " header.${name}=hex:");
        for (i = 0; i < ${len}u; i++) ${lo}emit(t, "%02x", (unsigned)packet->header.${field}[i]);
    } else {
        ${lo}emit(t, " header.${name}=null");
    }
"#,
            field,
            lo,
            name,
            len
        ));
    }
    if carries(p, x) == Carries::Bytes {
        let (guard, len, bytes) = ("", "packet->payload_len", "packet->payload");
        out.push_str(&hex_payload(lo, guard, len, bytes));
    }
    for slot in slots_of(p, x) {
        if let Some(si) = slot.si {
            let guard = slot.guard(p, n, "packet");
            let (snake, name) = (names::snake(&p.structs[si].name), &slot.name);
            out.push_str(&fill!(
                "    ${guard}${lo}fmt_${snake}(t, \"payload\", &packet->payload.${name});\n",
                guard,
                lo,
                snake,
                name
            ));
        }
    }
    if x.rules.ack.is_some() {
        let (len, bytes) = (
            "packet->payload.ack_data.len",
            "packet->payload.ack_data.bytes",
        );
        out.push_str(&hex_payload(lo, "if (packet->ack) ", len, bytes));
    }
    out.push_str(&fill!(
        r"
    return (int)text.len;
}

"
    ));
}

/// A payload as `hex:` and its bytes' digits (`guard`: the statement's condition, if any).
fn hex_payload(lo: &str, guard: &str, len: &str, bytes: &str) -> String {
    fill!(
        r#"
    ${guard}{
        size_t i;
        ${lo}emit(t, " payload=hex:");
        for (i = 0; i < ${len}; i++) ${lo}emit(t, "%02x", (unsigned)${bytes}[i]);
    }
"#,
        guard,
        lo,
        len,
        bytes
    )
}

/// A value's label in the text form: the C format of its path (`%s.speed=`) and the
/// arguments the format takes (`, path`).
pub(super) struct Label {
    fmt: String,
    args: String,
}

impl Label {
    /// The label of a field's value.
    pub(super) fn of(name: &str) -> Label {
        Label {
            fmt: format!("%s.{name}="),
            args: ", path".into(),
        }
    }

    /// The label of element `i` of a field.
    pub(super) fn item(name: &str) -> Label {
        Label {
            fmt: format!("%s.{name}[%u]="),
            args: ", path, (unsigned)i".into(),
        }
    }
}

/// The statements of a field's text, one element `what` per `i` below `count`.
pub(super) fn each(count: &str, what: String) -> String {
    let what = indent(&what);
    fill!(
        r"
    for (i = 0; i < ${count}; i++) {
${what}    }
",
        count,
        what
    )
}

/// Lines indented one level more.
pub(super) fn indent(text: &str) -> String {
    text.lines().map(|l| format!("    {l}\n")).collect()
}

/// One value: ` LABEL=VALUE`.
pub(super) fn value(p: &Protocol, n: &Names, ty: &ValueType, label: &Label, v: &str) -> String {
    let lo = &n.lo;
    // A nested value's path, for the text of its own fields.
    let (path, args) = (label.fmt.trim_end_matches('='), &label.args);
    match ty {
        ValueType::Scalar { scalar: s, scale } => {
            scalar(lo, scale.map_or(s.prim, |sc| sc.physical), label, v)
        }
        ValueType::Enum(ei, _) => enum_value(n, &p.enums[*ei].name, p.enums[*ei].prim, label, v),
        ValueType::Struct(si) => {
            let snake = names::snake(&p.structs[*si].name);
            fill!(
                r#"
    ${lo}path(sub, sizeof sub, "${path}"${args});
    ${lo}fmt_${snake}(t, sub, &${v});
"#,
                lo,
                path,
                args,
                snake,
                v
            )
        }
        ValueType::Text(len) => fill!(
            r#"
    ${lo}path(sub, sizeof sub, "${path}"${args});
    ${lo}fmt_text(t, sub, (const uint8_t *)${v}, ${len}u);
"#,
            lo,
            path,
            args,
            v,
            len
        ),
    }
}

/// A number (a float as its bits) or a bool.
pub(super) fn scalar(lo: &str, prim: Prim, label: &Label, v: &str) -> String {
    let (spec, value) = match prim {
        Prim::Bool | Prim::BoolInverted => ("%s", format!("{v} ? \"true\" : \"false\"")),
        // A half is a `float` in C as it is an `f32` in Rust.
        Prim::F16 | Prim::F32 => (
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
    let (fmt, args) = (&label.fmt, &label.args);
    fill!(
        "    ${lo}emit(t, \" ${fmt}${spec}\"${args}, ${value});\n",
        lo,
        fmt,
        spec,
        args,
        value
    )
}

/// An enum value: its variant's spec name, or its number when it has none.
pub(super) fn enum_value(n: &Names, name: &str, prim: Prim, label: &Label, v: &str) -> String {
    let (lo, ty) = (&n.lo, n.ty(name));
    let (spec, cast) = if prim.is_signed() {
        ("%lld", "long long")
    } else {
        ("%llu", "unsigned long long")
    };
    let (fmt, args) = (&label.fmt, &label.args);
    fill!(
        r#"
    if (${ty}_name(${v})) ${lo}emit(t, " ${fmt}%s"${args}, ${ty}_name(${v}));
    else ${lo}emit(t, " ${fmt}${spec}"${args}, (${cast})${v});
"#,
        ty,
        v,
        lo,
        fmt,
        args,
        spec,
        cast
    )
}
