//! The decoder of one frame's bytes: the checking entry point (the probe on the whole bytes),
//! then the reading of a checked frame (`templates/decode_frame.c`), one function per rule:
//! the header values, the flag trailer, the payload read into the packet's member. Which
//! command and direction the frame is, `dispatch` prints.

mod dispatch;

use crate::ir::{Length, Pos, Prim, Protocol};
use crate::layout::lower_layout;
use crate::rules::Carries;

use super::super::names::{self, Fx, Names};
use super::super::shape::{Slot, carries, slots_of, user_values};
use super::super::template::fill;
use super::wire::word;
use super::{escape, rules};

/// The decoders of format `x`: by direction where the caller gives it, the checking entry
/// point, and the reading of a checked frame.
pub(super) fn decode(p: &Protocol, n: &Names, x: &Fx, out: &mut String) {
    let given = x.fi == 0 && p.directions_given();
    if given {
        by_direction(p, n, x, out);
    }
    checking(p, n, x, given, out);
    decode_frame(p, n, x, given, out);
}

/// The decoder's parameters after the bytes: the direction, where the caller gives it.
fn params(n: &Names, given: bool) -> String {
    if given {
        format!("{}direction direction, ", n.lo)
    } else {
        String::new()
    }
}

/// The decoders of a format whose direction comes from the caller: one per direction, and
/// those without one (which decode no frame whose payload depends on it).
fn by_direction(p: &Protocol, n: &Names, x: &Fx, out: &mut String) {
    let (up, xlo) = (&n.up, &x.lo);
    let wrapper = |name: &str, to: &str, direction: &str| {
        fill!(
            r"
int ${xlo}${name}(const uint8_t *bytes, size_t len, ${xlo}packet *out)
{
    return ${xlo}${to}(bytes, len, ${up}${direction}, out);
}

",
            xlo,
            name,
            to,
            up,
            direction
        )
    };
    out.push_str(&wrapper("decode", "decode_given", "DIRECTION_COUNT"));
    for d in &p.directions {
        let name = format!("decode_{}", d.name);
        out.push_str(&wrapper(&name, "decode_given", &d.name.to_uppercase()));
    }
    out.push_str(&wrapper(
        "decode_frame",
        "decode_frame_given",
        "DIRECTION_COUNT",
    ));
}

/// The checking entry point: the probe of the stream decoder's rules on the whole bytes,
/// then the reading of a checked frame. A format that escapes its bytes has the frame
/// unescaped first, on the stack: exactly one frame from its opening flag to its closing one.
fn checking(p: &Protocol, n: &Names, x: &Fx, given: bool, out: &mut String) {
    let (up, xlo, xup) = (&n.up, &x.lo, &x.up);
    let (params, sfx, direction) = if given {
        (params(n, given), "_given", "direction, ")
    } else {
        (String::new(), "", "")
    };
    if lower_layout(&p.frames[x.fi]).escape.is_some() {
        out.push_str(&escape::checking(n, x, sfx, &params, direction));
        return;
    }
    out.push_str(&fill!(
        r"
int ${xlo}decode${sfx}(const uint8_t *bytes, size_t len, ${params}${xlo}packet *out)
{
    size_t n = 0;
    if (${xlo}probe(bytes, len, ${xup}MAX_FRAME_LEN, &n) != ${up}PROBE_FRAME || n != len) return ${up}ERR_FRAME;
    return ${xlo}decode_frame${sfx}(bytes, len, ${direction}out);
}

",
        xlo,
        sfx,
        params,
        xup,
        up,
        direction
    ));
}

/// The reading of a checked frame (`templates/decode_frame.c`): the framing is trusted, but
/// any bytes are read within `len` (the payload's end is computed only when the trailer fits).
fn decode_frame(p: &Protocol, n: &Names, x: &Fx, given: bool, out: &mut String) {
    let (lo, up, xlo, xup) = (&n.lo, &n.up, &x.lo, &x.up);
    let (sfx, params) = (if given { "_given" } else { "" }, params(n, given));
    let fill = rules::fill_len(p, x);
    let filled = if fill > 0 {
        format!("    uint8_t filled[{fill}];\n")
    } else {
        String::new()
    };
    let short = if x.rules.trailer_len > 0 {
        format!(" || len < {xup}TRAILER_LEN")
    } else {
        String::new()
    };
    // Everything before the payload is zeroed, and a payload struct just before it is read:
    // not the whole union, whose largest member may be many times the frame's.
    let zero = if carries(p, x) == Carries::Bytes {
        "sizeof *out".to_string()
    } else {
        format!("offsetof({xlo}packet, payload)")
    };
    // The flag trailer first: the header values after the payload lie back from the end of
    // the frame without it.
    let flag_trailer = printed(|o| flag_trailer(p, n, x, o));
    let header = printed(|o| header_values(p, n, x, o));
    let ack = printed(|o| rules::ack_decode(n, x, o));
    let given_direction = if given {
        printed(|o| dispatch::given_direction(p, n, o))
    } else {
        String::new()
    };
    let Steps {
        key,
        can_command,
        unstuff,
        directions,
        payload,
    } = steps(p, n, x, given);
    out.push_str(&fill!(
        include_str!("../templates/decode_frame.c"),
        xlo,
        sfx,
        params,
        xup,
        lo,
        filled,
        short,
        up,
        zero,
        flag_trailer,
        header,
        ack,
        given_direction,
        key,
        can_command,
        unstuff,
        directions,
        payload
    ));
    out.push('\n');
}

/// The statements of [`decode_frame`] that depend on what the format carries, around the
/// refusal of a frame too short for its trailer.
struct Steps {
    /// Before the refusal: the command of a dispatch key.
    key: String,
    /// After it: the command of a CAN id.
    can_command: String,
    /// The payload unstuffed (but for a format that carries bytes).
    unstuff: String,
    /// The direction from the header.
    directions: String,
    /// The payload read, but for the function's last `return 0`.
    payload: String,
}

/// The steps of a format after its header: a frame too short for its trailer (a bare header
/// of a command) is refused once the command is known, as the runtime's rules read the key
/// before the payload (an unknown command is that, whatever its length); the payload is
/// unstuffed before the direction is read, as the runtime's rules do (a frame with both
/// faults is refused for its stuffing).
fn steps(p: &Protocol, n: &Names, x: &Fx, given: bool) -> Steps {
    let kind = carries(p, x);
    let only =
        |on: bool, print: &dyn Fn(&mut String)| if on { printed(print) } else { String::new() };
    Steps {
        key: only(kind == Carries::Command, &|o| {
            dispatch::dispatch_key(p, n, x, o)
        }),
        can_command: only(kind == Carries::CanCommand, &|o| {
            dispatch::can_command(p, n, x, o)
        }),
        unstuff: only(kind != Carries::Bytes, &|o| rules::unstuff(n, x, o)),
        directions: only(kind == Carries::Command && !given, &|o| {
            dispatch::directions(p, n, x, o);
        }),
        payload: if kind == Carries::Bytes {
            payload_bytes(n)
        } else {
            printed(|o| read_payload(p, n, x, o))
        },
    }
}

/// What `print` appends to an empty string.
fn printed(print: impl FnOnce(&mut String)) -> String {
    let mut out = String::new();
    print(&mut out);
    out
}

/// The header values a sender sets, into `out->header` (those after the payload back from the
/// end of the body, the frame without its flag trailer); the payload's start behind a wider
/// length when the length field holds its marker.
fn header_values(p: &Protocol, n: &Names, x: &Fx, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let f = &p.frames[x.fi];
    let body = body_len(p, x);
    for v in user_values(f) {
        let value = if v.prim == Prim::Bool {
            "(raw != 0)".to_string()
        } else {
            format!("({})raw", names::unsigned_of(v.prim.size()))
        };
        let (word, name) = (word(v), names::field(&v.name));
        let len = match v.at {
            Pos::End(_) => body.as_str(),
            Pos::Start(_) => "len",
        };
        out.push_str(&fill!(
            r"
    if (!${lo}field(bytes, ${len}, ${word}, &raw)) return ${up}ERR_FRAME;
    out->header.${name} = ${value};
",
            lo,
            len,
            word,
            up,
            name,
            value
        ));
    }
    if let (Some(e), Length::Field { value, .. }) = (&f.length_extension, &f.length) {
        let (word, marker, len) = (word(&f.values[*value]), names::u64_lit(e.marker), e.len);
        out.push_str(&fill!(
            r"
    /* The wider length, when the length field holds its marker. */
    if (${lo}field(bytes, len, ${word}, &raw) && raw == ${marker}) start += ${len}u;
",
            lo,
            word,
            marker,
            len
        ));
    }
}

/// The length of the body of the frame being decoded (the frame without its flag trailer,
/// once [`flag_trailer`] has left it out of `end`), back from whose end the header values
/// after the payload lie.
fn body_len(p: &Protocol, x: &Fx) -> String {
    if p.frames[x.fi].flag_trailer.is_some() {
        format!("end + {}TRAILER_LEN", x.up)
    } else {
        "len".to_string()
    }
}

/// The flag trailer: the last bytes, before the trailer, when its header flag is set.
fn flag_trailer(p: &Protocol, n: &Names, x: &Fx, out: &mut String) {
    let (lo, up, xup) = (&n.lo, &n.up, &x.up);
    let f = &p.frames[x.fi];
    let Some(t) = &f.flag_trailer else { return };
    let (key, name, flag, len) = (
        &t.name,
        names::field(&t.name),
        word(&f.values[t.flag]),
        t.len,
    );
    out.push_str(&fill!(
        r"
    /* `${key}`: the last bytes, when its flag is set. */
    if (${lo}field(bytes, len, ${flag}, &raw) && raw != 0) {
        if (end < ${len}u) return ${up}ERR_FRAME;
        end -= ${len}u;
        out->header.${name}_present = 1;
        memcpy(out->header.${name}, bytes + end + ${xup}TRAILER_LEN, ${len}u);
    }
",
        key,
        lo,
        flag,
        len,
        up,
        name,
        xup
    ));
}

/// The payload of a format without dispatch key or message: its bytes as they are.
fn payload_bytes(n: &Names) -> String {
    let up = &n.up;
    fill!(
        r"
    /* The payload's bytes as they are. */
    if (end - start > sizeof out->payload) return ${up}ERR_PAYLOAD_LENGTH;
    out->payload_len = end - start;
    if (out->payload_len > 0) memcpy(out->payload, bytes + start, out->payload_len);
    r.p = NULL;
    r.len = r.pos = 0;
    (void)r;
    (void)e;
",
        up
    )
}

/// The payload `bytes[start..end]` read into the packet's member of its slot (zero-filled
/// first where the format's truncation rule says so).
fn read_payload(p: &Protocol, n: &Names, x: &Fx, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    // A stuffed payload is read where `unstuff` left it.
    if x.rules.stuffing.is_none() {
        out.push_str(&fill!(
            r"
    r.p = bytes + start;
    r.len = end - start;
"
        ));
    }
    out.push_str("    r.pos = 0;\n");
    let slots: Vec<Slot> = slots_of(p, x)
        .into_iter()
        .filter(|s| s.si.is_some() && s.keyless.is_none())
        .collect();
    if rules::fill_len(p, x) > 0 {
        rules::zero_fill(p, n, x, &slots, out);
    }
    // The member is zeroed, then read: `e` holds the reader's result.
    let read = |slot: &Slot| {
        let snake = names::snake(&p.structs[slot.si.unwrap_or_default()].name);
        let name = &slot.name;
        fill!(
            r"
e = (memset(&out->payload.${name}, 0, sizeof out->payload.${name}), \
${lo}read_${snake}(&r, &out->payload.${name}));",
            name,
            lo,
            snake
        )
    };
    if slots.len() > 1 && slots.iter().all(|s| s.command.is_some()) {
        // One case per command, then its directions: a jump rather than a test per slot.
        out.push_str("    switch (out->command) {\n");
        let mut commands: Vec<usize> = slots.iter().filter_map(|s| s.command).collect();
        commands.dedup();
        for ci in commands {
            let name = &p.commands[ci].name;
            out.push_str(&fill!("    case ${up}${name}:\n", up, name));
            for (k, slot) in slots.iter().filter(|s| s.command == Some(ci)).enumerate() {
                let otherwise = if k == 0 { "" } else { "else " };
                let test = p.directions.get(slot.direction).map_or(String::new(), |d| {
                    format!("if (out->direction == {up}{}) ", d.name.to_uppercase())
                });
                let read = read(slot);
                out.push_str(&fill!(
                    "        ${otherwise}${test}${read}\n",
                    otherwise,
                    test,
                    read
                ));
            }
            out.push_str("        break;\n");
        }
        out.push_str(&fill!(
            r"
    default:
        break;
    }
"
        ));
    } else {
        for slot in &slots {
            let (guard, read) = (slot.guard(p, n, "out"), read(slot));
            out.push_str(&fill!("    ${guard}${read}\n", guard, read));
        }
    }
    out.push_str(&fill!(
        r"
    if (e != 0) return e;
    if (r.pos != r.len) return ${up}ERR_PAYLOAD_LENGTH;
",
        up
    ));
}
