//! The frame rules in C: the probe of a candidate (`probe`), the decoder of one frame's bytes
//! (`decode`), the encoders (`encode`), and the packet rules between a checked frame and a
//! packet, each with its decoding and encoding side by side (`rules`: acknowledgements, byte
//! stuffing, trailing-zero truncation); for a format that escapes its bytes between flags,
//! the unescaping and escaping of a whole frame (`escape`). Every position, size and bound is the IR's, through
//! the same lowerings as the Rust engine's `FrameLayout` ([`lower_layout`]) and `PacketRules`
//! (`crate::rules::lower_rules`, the format's `Fx::rules`). This module prints them in order,
//! with a format's sync; where things lie in a frame is `wire`'s, which the others share.

mod decode;
mod encode;
mod escape;
mod probe;
mod rules;
mod wire;

use crate::ir::{Frame, Protocol, Transport};
use crate::layout::lower_layout;

use super::names::{Fx, Names};
use super::template::fill;

/// The frame rules: the shared helpers (`templates/frame.c`), then for every frame format its
/// sync, probe, escaping (`templates/escape.c`, where it escapes its bytes), decoder of one
/// frame and encoders (and, for a CAN format, its CAN frame functions, `templates/can.c`).
pub fn frame(p: &Protocol, n: &Names) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let mut out = String::from("/* ---- Frame rules ---- */\n\n");
    out.push_str(&fill!(include_str!("../templates/frame.c"), lo, up));
    out.push('\n');
    for fi in 0..p.frames.len() {
        let x = Fx::new(p, fi);
        let f = &p.frames[fi];
        out.push_str(&format!("/* -- Frame format `{}` -- */\n\n", f.name));
        out.push_str(&sync_matches(f, n, &x));
        let plan = lower_layout(f);
        probe::probe(f, &plan, n, &x, &mut out);
        if let Some(e) = &plan.escape {
            escape::escape(e, n, &x, &mut out);
        }
        decode::decode(p, n, &x, &mut out);
        encode::encode(p, n, &x, &mut out);
        if let Transport::Can { .. } = f.transport {
            let (xlo, xup) = (&x.lo, &x.up);
            out.push_str(&fill!(include_str!("../templates/can.c"), lo, up, xlo, xup));
            out.push('\n');
        }
    }
    out
}

/// `SYNC_LEN` and `pfx_sync_matches` of a format: whether a candidate's first bytes match the
/// sync as far as they go (the runtime's `sync_matches`): the sync bytes, or after a byte of
/// the sync set the sync bytes that follow it.
fn sync_matches(f: &Frame, n: &Names, x: &Fx) -> String {
    let (up, xlo, xup) = (&n.up, &x.lo, &x.up);
    let lead = usize::from(!f.sync_set.is_empty());
    let mut body = String::new();
    if lead == 1 {
        let cases: String = f
            .sync_set
            .iter()
            .map(|b| format!("    case {b:#04x}:\n"))
            .collect();
        body.push_str(&fill!(
            r"
    if (avail == 0) return 1;
    switch (b[0]) {
${cases}        break;
    default:
        return 0;
    }
",
            cases
        ));
    }
    // One comparison per sync byte, unrolled: the stream decoder asks at every byte it scans.
    for (i, byte) in f.sync.iter().enumerate() {
        let (at, byte) = (lead + i, format!("{byte:#04x}"));
        body.push_str(&fill!(
            r"
    if (avail <= ${at}u) return 1;
    if (b[${at}] != ${byte}) return 0;
",
            at,
            byte
        ));
    }
    let len = lead + f.sync.len();
    fill!(
        r"
#define ${xup}SYNC_LEN ${len}u

/* Whether `b[0..avail]` matches the sync as far as it goes. */
${up}UNUSED static ${up}INLINE int ${xlo}sync_matches(const uint8_t *b, size_t avail)
{
${body}    (void)b;
    (void)avail;
    return 1;
}

",
        xup,
        len,
        up,
        xlo,
        body
    )
}
