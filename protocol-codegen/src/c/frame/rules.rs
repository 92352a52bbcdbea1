//! The packet rules between a checked frame and a packet, one function per rule and side, each
//! printed from the format's rules plan (`Fx::rules`, the runtime's `PacketRules` values):
//! acknowledgements (a flag in the header: no command, the data after the acknowledgement's
//! header), byte stuffing (the runtime's `Stuffing`), and truncation (a payload cut short of
//! its trailing zeros, or of the extension fields a format does not carry, zero-filled back
//! to its struct's size; which fields those are is the IR's, the plan has no word for it).

use protocol_runtime::stuffing::Stuffing;

use crate::ir::{Frame, Length, Protocol, Role};
use crate::layout::lower_layout;

use super::super::names::{self, Fx, Names};
use super::super::shape::{Slot, slots_of};
use super::super::template::fill;
use super::escape;
use super::wire::{byte_list, check_args, field_word, word, write_sync, write_trailers};

/// An acknowledgement in the decoder: when the flag holds its value, the frame carries no
/// command and its data follows the acknowledgement's header (to the frame's end for a bare
/// header, else to the trailer), at most its largest.
pub(super) fn ack_decode(n: &Names, x: &Fx, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let Some((_, ack)) = x.rules.ack else { return };
    let end = if ack.bare {
        format!("len == {up}ACK_HEADER_LEN ? len : len - {up}TRAILER_LEN")
    } else {
        format!("len - {up}TRAILER_LEN")
    };
    let (word, equals) = (field_word(ack.flag), names::u64_lit(ack.equals));
    out.push_str(&fill!(
        r"
    if (!${lo}field(bytes, len, ${word}, &raw)) return ${up}ERR_FRAME;
    if (raw == ${equals}) {
        size_t end;
        if (len < ${up}ACK_HEADER_LEN) return ${up}ERR_FRAME;
        end = ${end};
        if (end < ${up}ACK_HEADER_LEN) return ${up}ERR_FRAME;
        if (end - ${up}ACK_HEADER_LEN > ${up}ACK_MAX_LEN) return ${up}ERR_PAYLOAD_LENGTH;
        out->ack = true;
        out->command = ${up}COMMAND_COUNT;
        memset(&out->payload.ack_data, 0, sizeof out->payload.ack_data);
        out->payload.ack_data.len = end - ${up}ACK_HEADER_LEN;
        memcpy(out->payload.ack_data.bytes, bytes + ${up}ACK_HEADER_LEN, out->payload.ack_data.len);
        return 0;
    }
",
        lo,
        word,
        up,
        equals,
        end
    ));
}

/// The encoder of an acknowledgement: its data after the acknowledgement's header, the header
/// values, the flag at its value and no dispatch key; with no data and a bare header, the
/// header alone (no frame checks, no trailers), as the runtime's `seal` does.
pub(super) fn ack_encoder(f: &Frame, n: &Names, x: &Fx, out: &mut String) {
    let (lo, up, xlo, xup) = (&n.lo, &n.up, &x.lo, &x.up);
    let Some((_, ack)) = x.rules.ack else { return };
    let plan = lower_layout(f);
    let bare = if ack.bare { "len == 0" } else { "0" };
    out.push_str(&fill!(
        r"
int ${xlo}encode_ack(const ${xlo}header *h, const uint8_t *data, size_t len, uint8_t *buf, size_t cap)
{
    int bare = ${bare};
    size_t total;
    if (len > ${xup}ACK_MAX_LEN) return ${up}ERR_OUT_OF_RANGE;
    total = ${xup}ACK_HEADER_LEN + len + (bare ? 0u : ${xup}TRAILER_LEN);
    if (!bare && total < ${xup}MIN_FRAME_LEN) return ${up}ERR_OUT_OF_RANGE;
    if (cap < total) return ${up}ERR_SHORT_BUFFER;
    memset(buf, 0, ${xup}ACK_HEADER_LEN);
    memcpy(buf + ${xup}ACK_HEADER_LEN, data, len);
    if (!bare) memset(buf + ${xup}ACK_HEADER_LEN + len, 0, ${xup}TRAILER_LEN);
",
        xlo,
        bare,
        xup,
        up
    ));
    out.push_str(&write_sync(f));
    for v in &f.values {
        let value = match &v.role {
            Role::User { .. } => format!("(uint64_t)h->{}", names::field(&v.name)),
            Role::Length => match &f.length {
                Length::Field { adjust, .. } => {
                    out.push_str(&fill!(
                        "    if ((int64_t)total - (${adjust}) < 0) return ${up}ERR_OUT_OF_RANGE;\n",
                        adjust,
                        up
                    ));
                    format!("(uint64_t)((int64_t)total - ({adjust}))")
                }
                Length::Fixed(_) => continue,
            },
            Role::Const(c) => names::u64_lit(*c),
            Role::Ack(_) => names::u64_lit(ack.equals),
            // An acknowledgement has no dispatch key: its data takes those bytes.
            Role::Dispatch | Role::Flag | Role::WideLength => continue,
        };
        let (name, word) = (&v.name, word(v));
        out.push_str(&fill!(
            r"
    /* ${name} */
    if (!${lo}put_field(buf, total, ${word}, ${value})) return ${up}ERR_OUT_OF_RANGE;
",
            name,
            lo,
            word,
            value,
            up
        ));
    }
    if !f.sync_set.is_empty() {
        out.push_str(&fill!(
            "    if (!${xlo}sync_matches(buf, 1)) return ${up}ERR_OUT_OF_RANGE;\n",
            xlo,
            up
        ));
    }
    let store = |ci: usize| {
        let args = check_args(n, x, &f.checks[ci], "total");
        fill!(
            "    if (!${lo}store(buf, ${args})) return ${up}ERR_OUT_OF_RANGE;\n",
            lo,
            args,
            up
        )
    };
    for &ci in &plan.header_checks {
        out.push_str(&store(ci));
    }
    out.push_str("    if (bare) return (int)total;\n");
    out.push_str(&write_trailers(f, n, "total"));
    for &ci in &plan.frame_checks {
        out.push_str(&store(ci));
    }
    let sealed = escape::escaped(x, plan.escape.is_some(), "(int)total".into());
    out.push_str(&fill!(
        r"
    return ${sealed};
}

",
        sealed
    ));
}

/// The payload unstuffed (the runtime's `Stuffing::unstuff`) into a buffer of the largest
/// payload, which the payload is then read from: after every run of the pattern in the
/// output, the next byte must be the inserted one, and is dropped.
pub(super) fn unstuff(n: &Names, x: &Fx, out: &mut String) {
    let (up, xup) = (&n.up, &x.up);
    let Some(Stuffing { after, insert }) = x.rules.stuffing else {
        return;
    };
    let (pattern, k, insert) = (byte_list(after), after.len(), format!("{insert:#04x}"));
    out.push_str(&fill!(
        r"
    {
        static const uint8_t pattern[${k}] = {${pattern}};
        static uint8_t plain[${xup}MAX_PAYLOAD_LEN > 0 ? ${xup}MAX_PAYLOAD_LEN : 1];
        const uint8_t *s = bytes + start;
        size_t sn = end - start, i = 0, o = 0;
        while (i < sn) {
            if (o >= ${xup}MAX_PAYLOAD_LEN) return ${up}ERR_PAYLOAD_LENGTH;
            plain[o++] = s[i++];
            if (o >= ${k}u && memcmp(plain + o - ${k}u, pattern, ${k}u) == 0) {
                if (i < sn && s[i] == ${insert}) i++;
                else return ${up}ERR_INVALID_STUFFING;
            }
        }
        r.p = plain;
        r.len = o;
    }
",
        k,
        pattern,
        xup,
        up,
        insert
    ));
}

/// `pfx_stuff`, which an encoder calls on its written payload: stuffed in place (the
/// runtime's `Stuffing::stuff_in_place`, `templates/stuff.c`), where the format stuffs.
pub(super) fn stuff_fn(n: &Names, x: &Fx, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let Some(Stuffing { after, insert }) = x.rules.stuffing else {
        return;
    };
    let (pattern, k, insert) = (byte_list(after), after.len(), format!("{insert:#04x}"));
    out.push_str(&fill!(
        include_str!("../templates/stuff.c"),
        lo,
        up,
        pattern,
        k,
        insert
    ));
    out.push('\n');
}

/// The statement of an encoder that stuffs a command's written payload, where the format
/// stuffs.
pub(super) fn stuff_written(n: &Names, x: &Fx, slot: &Slot) -> String {
    let lo = &n.lo;
    if x.rules.stuffing.is_some() && slot.command.is_some() {
        fill!("    if ((e = ${lo}stuff(&w)) != 0) return e;\n", lo)
    } else {
        String::new()
    }
}

/// `pfx_trimmed`, which an encoder calls on its written payload: the bytes kept of it, all
/// but its trailing zeros (`templates/trimmed.c`), where the format truncates.
pub(super) fn trimmed_fn(x: &Fx, out: &mut String) {
    let xlo = &x.lo;
    if x.rules.truncate_zeros {
        out.push_str(&fill!(include_str!("../templates/trimmed.c"), xlo));
        out.push('\n');
    }
}

/// The statement of an encoder that cuts a command's written payload short of its trailing
/// zeros, where the format truncates.
pub(super) fn trim_written(x: &Fx, slot: &Slot) -> String {
    let xlo = &x.lo;
    if x.rules.truncate_zeros && slot.command.is_some() {
        fill!("    w.pos = ${xlo}trimmed(w.p, w.pos);\n", xlo)
    } else {
        String::new()
    }
}

/// The bytes of the zero-filled copy a payload is read from when its format fills it (0: the
/// format reads every payload as sent): the largest of its structs and of its payloads.
pub(super) fn fill_len(p: &Protocol, x: &Fx) -> usize {
    let f = &p.frames[x.fi];
    let fills = x.rules.truncate_zeros || (!f.extensions && base_sizes(p, x));
    if !fills {
        return 0;
    }
    slots_of(p, x)
        .iter()
        .filter_map(|s| s.si)
        .map(|si| p.structs[si].size)
        .max()
        .unwrap_or(0)
        .max(x.rules.max_payload)
        .max(1)
}

/// Whether a payload of format `x` has extension fields (the format then carries the fields
/// before them, when it carries no extensions).
fn base_sizes(p: &Protocol, x: &Fx) -> bool {
    slots_of(p, x)
        .iter()
        .any(|s| s.si.is_some_and(|si| p.structs[si].base_size.is_some()))
}

/// The payload in `r` checked and zero-filled before it is read: in a format without
/// extension fields exactly the bytes before them, zero-filled to the struct's size (as a
/// payload its sender cut short of trailing zeros is, where the format says so).
pub(super) fn zero_fill(p: &Protocol, n: &Names, x: &Fx, slots: &[Slot], out: &mut String) {
    let up = &n.up;
    let f = &p.frames[x.fi];
    out.push_str(&fill!(
        r"
    {
        size_t size = 0, base = SIZE_MAX;
"
    ));
    for slot in slots {
        let s = &p.structs[slot.si.unwrap_or_default()];
        let base = s.base_size.filter(|_| !f.extensions);
        let size = if x.rules.truncate_zeros || base.is_some() {
            s.size
        } else {
            0
        };
        let base = base.map_or("SIZE_MAX".to_string(), |b| format!("{b}u"));
        let test = slot.test(p, n, "out");
        out.push_str(&fill!(
            r"
        if (${test}) {
            size = ${size}u;
            base = ${base};
        }
",
            test,
            size,
            base
        ));
    }
    out.push_str(&fill!(
        r"
        /* A format without extension fields carries the bytes before them. */
        if (base != SIZE_MAX && r.len != base) return ${up}ERR_PAYLOAD_LENGTH;
        /* A payload short of its struct's size is zero-filled. */
        if (r.len < size) {
            memcpy(filled, r.p, r.len);
            memset(filled + r.len, 0, size - r.len);
            r.p = filled;
            r.len = size;
        }
    }
",
        up
    ));
}
