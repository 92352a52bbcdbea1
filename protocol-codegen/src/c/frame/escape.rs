//! Byte escaping between flags in C (the runtime's `escape`, from the format's `FrameLayout`
//! plan): the table of reserved bytes and substitutes as two `switch`es, the unescaping of one
//! frame from the wire (`pfx_unescape`, which the checking decoder runs first) and the
//! escaping in place of a sealed frame (which every encoder runs last). The frame rules
//! between the flags are the format's own, over the unescaped bytes; the stream decoder
//! unescapes as bytes come (`templates/escaped.c`, printed by `engine`).

use protocol_runtime::escape::Escape;

use super::super::names::{Fx, Names};
use super::super::template::fill;

/// The escaping functions of format `x`, whose frames escape their bytes by `e`.
pub(super) fn escape(e: &Escape<'_>, n: &Names, x: &Fx, out: &mut String) {
    let (up, xlo) = (&n.up, &x.lo);
    let case = |from: u8, to: u8| format!("    case {from:#04x}: return {to:#04x};\n");
    let substitutes: String = e.pairs.iter().map(|[r, s]| case(*r, *s)).collect();
    let originals: String = e.pairs.iter().map(|[r, s]| case(*s, *r)).collect();
    let (flag, escape) = (format!("{:#04x}", e.flag), format!("{:#04x}", e.escape));
    out.push_str(&fill!(
        include_str!("../templates/escape.c"),
        up,
        xlo,
        substitutes,
        originals,
        flag,
        escape
    ));
    out.push('\n');
}

/// The encoders' last step: `sealed` (a call that returns the sealed frame's length, or an
/// error) escaped in the caller's buffer where the format escapes its bytes.
pub(super) fn escaped(x: &Fx, escapes: bool, sealed: String) -> String {
    if escapes {
        format!("{}escape(buf, cap, {sealed})", x.lo)
    } else {
        sealed
    }
}

/// The checking decoder of format `x` (`sfx`, `params`, `direction`: those of a decoder given
/// the direction): the frame unescaped on the stack, exactly one from its opening flag to its
/// closing one, then probed and read as the format's rules say.
pub(super) fn checking(n: &Names, x: &Fx, sfx: &str, params: &str, direction: &str) -> String {
    let (up, xlo, xup) = (&n.up, &x.lo, &x.up);
    fill!(
        r"
int ${xlo}decode${sfx}(const uint8_t *bytes, size_t len, ${params}${xlo}packet *out)
{
    uint8_t frame[${xup}MAX_FRAME_LEN];
    size_t n = 0, used = 0;
    int m = ${xlo}unescape_from(bytes, len, frame, sizeof frame, &used);
    if (m < 0 || used != len) return ${up}ERR_FRAME;
    if (${xlo}probe(frame, (size_t)m, ${xup}MAX_FRAME_LEN, &n) != ${up}PROBE_FRAME || n != (size_t)m) \
        return ${up}ERR_FRAME;
    return ${xlo}decode_frame${sfx}(frame, n, ${direction}out);
}

",
        xlo,
        sfx,
        params,
        xup,
        up,
        direction
    )
}
