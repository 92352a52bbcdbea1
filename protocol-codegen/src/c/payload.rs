//! Payload structs between the wire and their C structs: a reader and a writer per struct,
//! field by field in wire order (each field kind's statements in `fields`), every value
//! through explicit byte-order helpers (never a `memcpy` of a struct).

use crate::ir::{FieldKind, PayloadCheck, Protocol, Struct, ValueType};

use super::fields::Dir;
use super::kinds;
use super::names::{self, Names};
use super::shape::any_field;
use super::template::fill;

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

/// A struct's reader or writer: its fields in wire order. A check inside the payload covers
/// the bytes from the start of its first field (`from<i>`) to the end of its last (`to<i>`).
fn walk(p: &Protocol, n: &Names, s: &Struct, dir: Dir) -> String {
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
            body.push_str(&fill!("    from${i} = ${pos};\n", i, pos));
            marks.push(format!("from{i}"));
        }
        body.push_str(&kinds::of(p, &f.kind).walk(n, s, i, dir, &here));
        if checks.iter().any(|c| c.last == i) {
            body.push_str(&fill!("    to${i} = ${pos};\n", i, pos));
            marks.push(format!("to{i}"));
        }
    }
    let mut decls = fill!(
        r"
    int e = 0;
    uint64_t raw = 0, word = 0;
"
    );
    if body.contains("[i]") {
        decls.push_str("    size_t i;\n");
    }
    if body.contains("stated") {
        decls.push_str("    uint64_t stated = 0;\n");
    }
    if !marks.is_empty() {
        decls.push_str(&format!("    size_t {};\n", marks.join(", ")));
    }
    function(n, s, dir, &decls, &body)
}

/// A struct's reader or writer around its declarations and statements. A struct repeated by
/// another whose fields size its bytes gets their values (`ctx`). Both are marked unused: a
/// struct no command carries (a spec may declare one) has no caller, which strict builds
/// (`-Werror=unused-function`) refuse.
fn function(n: &Names, s: &Struct, dir: Dir, decls: &str, body: &str) -> String {
    let (lo, up, name, snake, ty) = (&n.lo, &n.up, &s.name, names::snake(&s.name), n.ty(&s.name));
    let (ctx, unused_ctx) = if s.context.is_empty() {
        ("", "")
    } else {
        (", const uint64_t *ctx", "    (void)ctx;\n")
    };
    let head = match dir {
        Dir::Read => {
            let size = s.size;
            fill!(
                r"
/* Reads `${name}` (${size} bytes on the wire). */
${up}UNUSED static int ${lo}read_${snake}(struct ${lo}rd *r, ${ty} *out${ctx})",
                name,
                size,
                up,
                lo,
                snake,
                ty,
                ctx
            )
        }
        Dir::Write => fill!(
            r"
/* Writes `${name}`. */
${up}UNUSED static int ${lo}write_${snake}(struct ${lo}wr *w, const ${ty} *v${ctx})",
            name,
            up,
            lo,
            snake,
            ty,
            ctx
        ),
    };
    fill!(
        r"
${head}
{
${decls}${body}    (void)raw;
    (void)word;
${unused_ctx}    return e;
}
",
        head,
        decls,
        body,
        unused_ctx
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
        FieldKind::Bits { members, .. } | FieldKind::BitStream { members } => {
            members.iter().any(|m| m.scale.is_some())
        }
        _ => false,
    })
}
