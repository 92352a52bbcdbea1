//! The stream decoder in C, with the runtime engine's rules (`protocol_runtime::decoder`): the
//! search for the sync (its bytes, or a byte of its set and the bytes after it; or a prefix
//! of them at the end of the input), the probe of each
//! candidate, a rejection that costs one byte (the search resumes at the byte after the
//! rejected start), the early-truncation rule (a candidate still waiting for bytes is
//! rejected as truncated as soon as a complete valid frame starts inside it), and the
//! counters, where every byte fed is counted once.
//!
//! There is a decoder per serial frame format and, where several formats carry the commands,
//! the link's decoder of all of them (the runtime's `LayoutRef::others`): a candidate goes to
//! the first of its formats whose sync it matches, bounded by that format's largest frame.
//!
//! A format that escapes its bytes between flags has the runtime's escaped path instead: a
//! flag opens and closes every candidate, its bytes unescaped into the buffer as they come.
//!
//! The caller's chunks are copied into a fixed buffer of the largest frame's size; a frame
//! event points into it. Frames longer than the buffer cannot exist: the buffer is the largest
//! frame of the decoder's formats, so the bound is theirs.

use protocol_runtime::escape::Escape;

use crate::ir::{Protocol, Transport};
use crate::layout::lower_layout;

use super::names::{Fx, Names};
use super::template::fill;

/// A stream decoder the C code has: one per serial frame format, and the link's decoder of
/// every command format when it has several.
pub struct Decoder {
    /// Lower-case prefix of its items (`mavlink_`, `mavlink_v1_`, `mavlink_any_`).
    pub lo: String,
    /// Upper-case prefix of its items.
    pub up: String,
    /// The frame formats it finds (indices into [`Protocol::frames`]), in the order a
    /// candidate is given to them (the runtime's `LayoutRef::others` after the first).
    pub formats: Vec<usize>,
    /// What it is, for its comment.
    pub what: String,
}

/// The stream decoders of a spec: one per serial frame format, then the link's (`any`).
pub fn decoders(p: &Protocol, n: &Names) -> Vec<Decoder> {
    let mut out: Vec<Decoder> = p
        .frames
        .iter()
        .enumerate()
        .filter(|(_, f)| matches!(f.transport, Transport::Serial))
        .map(|(fi, f)| {
            let x = Fx::new(p, fi);
            Decoder {
                lo: x.lo,
                up: x.up,
                formats: vec![fi],
                what: format!("A stream decoder of `{}` frames", f.name),
            }
        })
        .collect();
    if !p.link.is_empty() {
        out.push(Decoder {
            lo: format!("{}any_", n.lo),
            up: format!("{}ANY_", n.up),
            formats: p.link.clone(),
            what: "The link's stream decoder, of every command format".into(),
        });
    }
    out
}

/// Whether a spec's frames escape their bytes between flags: its stream decoder then has the
/// escaped path (`templates/escaped.c`) and its rejections the reason `BAD_ESCAPE`.
fn escapes(p: &Protocol) -> bool {
    p.frames.iter().any(|f| lower_layout(f).escape.is_some())
}

/// The stream decoder's types and functions, for the header.
pub fn declarations(p: &Protocol, n: &Names) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let escape_reason = if escapes(p) {
        fill!(
            "    ${up}REJECT_BAD_ESCAPE,       /**< An escape byte not followed by a substitute (counted as a bad header). */\n",
            up
        )
    } else {
        String::new()
    };
    let mut out = fill!(include_str!("templates/engine.h"), lo, up, escape_reason);
    out.push('\n');
    for d in decoders(p, n) {
        let (dlo, dup, what) = (&d.lo, &d.up, &d.what);
        let escape_state = if escaped(p, &d).is_some() {
            "    uint64_t owner;      /**< Stream offset of the pending candidate's opening flag. */\n    \
             unsigned state;      /**< The escaped path's state of the candidate. */\n"
        } else {
            ""
        };
        out.push_str(&fill!(
            include_str!("templates/decoder.h"),
            lo,
            dlo,
            dup,
            what,
            escape_state
        ));
        out.push('\n');
    }
    out
}

/// The stream decoders' functions, for the source: the shared ones, then each decoder's.
pub fn engine(p: &Protocol, n: &Names) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let (escape_name, escape_count) = if escapes(p) {
        (
            fill!(
                "    case ${up}REJECT_BAD_ESCAPE: return \"bad escape\";\n",
                up
            ),
            fill!(
                "    case ${up}REJECT_BAD_ESCAPE: s->bad_header++; break;\n",
                up
            ),
        )
    } else {
        (String::new(), String::new())
    };
    let mut out = fill!(
        include_str!("templates/engine.c"),
        lo,
        up,
        escape_name,
        escape_count
    );
    out.push('\n');
    for d in decoders(p, n) {
        match escaped(p, &d) {
            Some(e) => escaped_decoder(n, &d, &e, &mut out),
            None => decoder(p, n, &d, &mut out),
        }
    }
    out
}

/// The escaping of a decoder's one format, when it escapes its bytes between flags (such a
/// spec has one frame format, so its decoder finds that format alone).
fn escaped<'p>(p: &'p Protocol, d: &Decoder) -> Option<Escape<'p>> {
    match d.formats.as_slice() {
        [fi] => lower_layout(&p.frames[*fi]).escape,
        _ => None,
    }
}

/// The functions of the stream decoder of a format that escapes its bytes (the runtime's
/// escaped path): a flag always ends a candidate, whose unescaped bytes the format's probe
/// then decides.
fn escaped_decoder(n: &Names, d: &Decoder, e: &Escape<'_>, out: &mut String) {
    let (lo, up, dlo, dup, what) = (&n.lo, &n.up, &d.lo, &d.up, &d.what);
    let xlo = dlo;
    let (flag, escape) = (format!("{:#04x}", e.flag), format!("{:#04x}", e.escape));
    out.push_str(&fill!(
        include_str!("templates/escaped.c"),
        what,
        dup,
        dlo,
        lo,
        up,
        flag,
        xlo,
        escape
    ));
    out.push('\n');
}

/// The functions of one stream decoder. A candidate goes to the first of its formats whose
/// sync it matches (the first format when none does), with the format's largest frame as the
/// bound (the runtime's `select` and `probe_link`).
fn decoder(p: &Protocol, n: &Names, d: &Decoder, out: &mut String) {
    let (lo, up, dlo, dup, what) = (&n.lo, &n.up, &d.lo, &d.up, &d.what);
    let formats: Vec<Fx> = d.formats.iter().map(|&fi| Fx::new(p, fi)).collect();
    let inside = inside_bound(p, d);
    let sync_at = |at: &str| -> String {
        let tests: Vec<String> = formats
            .iter()
            .map(|x| format!("{}sync_matches({at})", x.lo))
            .collect();
        tests.join(" || ")
    };
    let (sync_at_b, sync_at_i) = (sync_at("b, avail"), sync_at("b + i, len - i"));
    let lead = leads(p, d);
    let (lead_at_i, lead_at_k) = (lead("i"), lead("k"));
    let mut by_sync = String::new();
    for x in &formats {
        let (xlo, xup, fi) = (&x.lo, &x.up, x.fi);
        by_sync.push_str(&fill!(
            r"
    if (${xlo}sync_matches(b, avail)) {
        *format = ${fi};
        return ${xlo}probe_synced(b, avail, limit < ${xup}MAX_FRAME_LEN ? limit : ${xup}MAX_FRAME_LEN, n);
    }
",
            xlo,
            xup,
            fi
        ));
    }
    let first = &formats[0];
    let (first_fi, first_lo, first_up) = (first.fi, &first.lo, &first.up);
    out.push_str(&fill!(
        include_str!("templates/decoder.c"),
        what,
        lo,
        up,
        dlo,
        dup,
        by_sync,
        first_fi,
        first_lo,
        first_up,
        sync_at_b,
        sync_at_i,
        lead_at_i,
        lead_at_k,
        inside
    ));
    out.push('\n');
}

/// The test of a start's first byte against the first byte of every format's sync (`b[i] ==
/// 0xff && `), where each format has one: a start whose byte is none of them is no candidate,
/// decided without a call per byte. Nothing where a format has no such byte.
fn leads(p: &Protocol, d: &Decoder) -> impl Fn(&str) -> String {
    let mut leads: Vec<u8> = d
        .formats
        .iter()
        .filter_map(|&fi| {
            let f = &p.frames[fi];
            f.sync_set
                .is_empty()
                .then(|| f.sync.first().copied())
                .flatten()
        })
        .collect();
    leads.sort_unstable();
    leads.dedup();
    let all_led = d.formats.iter().all(|&fi| {
        let f = &p.frames[fi];
        f.sync_set.is_empty() && !f.sync.is_empty()
    });
    move |at: &str| -> String {
        if !all_led {
            return String::new();
        }
        let tests: Vec<String> = leads
            .iter()
            .map(|b| format!("b[{at}] == {b:#04x}"))
            .collect();
        format!("({}) && ", tests.join(" || "))
    }
}

/// The condition on a start `k` inside a pending candidate that the truncation rule tries:
/// the runtime tries only starts with room for its shortest frame after them, which matters
/// only where a frame can be shorter than that (a bare header).
fn inside_bound(p: &Protocol, d: &Decoder) -> String {
    let frames = || d.formats.iter().map(|&fi| &p.frames[fi]);
    if frames().all(|f| lower_layout(f).length.bare_len().is_none()) {
        return "k < pending".into();
    }
    let shortest = frames()
        .map(|f| {
            let plan = lower_layout(f);
            let span = plan
                .header_len
                .max(plan.sync.len() + usize::from(!f.sync_set.is_empty()));
            span.max(plan.min_len).max(1)
        })
        .min()
        .unwrap_or(1);
    format!("k < pending && pending - k >= {shortest}u")
}
