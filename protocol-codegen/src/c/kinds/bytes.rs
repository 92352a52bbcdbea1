//! Bytes ([`FieldKind::Bytes`](crate::ir::FieldKind::Bytes)): a byte array (a `char` array for
//! text without a terminator) and its count used; read to the payload's end (but the fixed
//! fields after them) or as many as a field states, which must be there and fit; the text of
//! bytes is `hex:` and their digits, of text a string when it is UTF-8, else its bytes.

use crate::ir::{Field, Struct};

use super::{Kind, member_head, used};
use crate::c::fields::{Dir, count_fits, stated};
use crate::c::names::{self, Names};
use crate::c::template::fill;

/// Bytes of at most `max`, sized by the field `size_from` or by the end of the payload.
pub(super) struct Bytes<'a> {
    pub(super) max: usize,
    pub(super) size_from: &'a Option<String>,
    pub(super) text: bool,
}

impl Kind for Bytes<'_> {
    fn members(&self, _n: &Names, f: &Field, out: &mut String) {
        let (name, doc) = member_head(f);
        let len = self.max.max(1);
        let (ty, what) = if self.text {
            ("char", "Bytes of text (no NUL is added)")
        } else {
            ("uint8_t", "Bytes")
        };
        out.push_str(&fill!(
            "    ${ty} ${name}[${len}];${doc}\n",
            ty,
            name,
            len,
            doc
        ));
        out.push_str(&used(&name, what, self.max));
    }

    fn code(&self, n: &Names, s: &Struct, _f: &Field, dir: Dir, here: &str) -> String {
        let this = if dir == Dir::Read { "out" } else { "v" };
        let stated = self.size_from.as_ref().map(|size| stated(s, this, size));
        match dir {
            Dir::Read => read_bytes(n, self.max, stated.as_deref(), here),
            Dir::Write => write_bytes(n, self.max, stated.as_deref(), here),
        }
    }

    fn walk(&self, n: &Names, s: &Struct, i: usize, dir: Dir, here: &str) -> String {
        if self.size_from.is_none() && dir == Dir::Read && s.bytes_after(i) > 0 {
            read_bytes_but(n, self.max, s.bytes_after(i), here)
        } else {
            self.code(n, s, &s.fields[i], dir, here)
        }
    }

    fn text(&self, n: &Names, f: &Field) -> String {
        let lo = &n.lo;
        let (key, name) = (&f.name, names::field(&f.name));
        // Every byte is text, a NUL too: a string when all of them are UTF-8, else the bytes.
        if self.text {
            return fill!(
                r#"
    ${lo}path(sub, sizeof sub, "%s.${key}", path);
    if (${lo}utf8((const uint8_t *)v->${name}, v->${name}_len)) {
        ${lo}emit(t, " %s=", sub);
        for (i = 0; i < v->${name}_len; i++) {
            uint8_t c = (uint8_t)v->${name}[i];
            if (c < 0x20 || c == 0x7F || c == '\\') ${lo}emit(t, "\\x%02x", (unsigned)c);
            else ${lo}emit(t, "%c", c);
        }
    } else {
        for (i = 0; i < v->${name}_len; i++) ${lo}emit(t, " %s[%u]=%u", sub, (unsigned)i, (unsigned)(uint8_t)v->${name}[i]);
    }
"#,
                lo,
                key,
                name
            );
        }
        fill!(
            r#"
    ${lo}emit(t, " %s.${key}=hex:", path);
    for (i = 0; i < v->${name}_len; i++) ${lo}emit(t, "%02x", (unsigned)v->${name}[i]);
"#,
            lo,
            key,
            name
        )
    }
}

/// Bytes that take every byte left but the `keep` bytes of the fixed fields after them (the
/// runtime's `rest_but`).
fn read_bytes_but(n: &Names, max: usize, keep: usize, here: &str) -> String {
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
