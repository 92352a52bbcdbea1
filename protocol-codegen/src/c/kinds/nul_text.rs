//! NUL-terminated text ([`FieldKind::NulText`](crate::ir::FieldKind::NulText)): a `char`
//! array of `max + 1`; its text is a string when it is UTF-8, else its bytes.

use crate::ir::{Field, Struct};

use super::{Kind, member_head};
use crate::c::fields::Dir;
use crate::c::names::{self, Names};
use crate::c::template::fill;

/// Text of at most `max` bytes and its NUL.
pub(super) struct NulText {
    pub(super) max: usize,
}

impl Kind for NulText {
    fn members(&self, _n: &Names, f: &Field, out: &mut String) {
        let (name, doc) = member_head(f);
        let (max, len) = (self.max, self.max + 1);
        out.push_str(&fill!(
            "    char ${name}[${len}];${doc} /* At most ${max} bytes, then a NUL. */\n",
            name,
            len,
            doc,
            max
        ));
    }

    fn code(&self, n: &Names, _s: &Struct, _f: &Field, dir: Dir, here: &str) -> String {
        nul_text(n, self.max, dir, here)
    }

    // The text up to its NUL: a string when it is UTF-8, else its bytes.
    fn text(&self, n: &Names, f: &Field) -> String {
        let (lo, max) = (&n.lo, self.max);
        let (key, name) = (&f.name, names::field(&f.name));
        fill!(
            r#"
    for (i = 0; i <= ${max}u && v->${name}[i] != 0; i++) {
    }
    ${lo}path(sub, sizeof sub, "%s.${key}", path);
    ${lo}fmt_text(t, sub, (const uint8_t *)v->${name}, i);
"#,
            max,
            name,
            lo,
            key
        )
    }
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
