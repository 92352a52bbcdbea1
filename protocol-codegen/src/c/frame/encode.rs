//! The encoders: a command's payload written after the header, then the frame sealed around
//! it (`pfx_seal`, `templates/seal.c` and `templates/seal_apart.c`: the header values, the
//! dispatch key, the sync, the trailers, the checks), and the encoder of a whole packet that
//! picks the command's. A format that escapes its bytes between flags has each encoder escape
//! the sealed frame last.

use crate::ir::{Frame, HeaderValue, Length, Protocol, Role, Transport};
use crate::layout::lower_layout;
use crate::rules::Carries;

use super::super::names::{self, Fx, Names};
use super::super::shape::{Slot, carries, slots_of};
use super::super::template::fill;
use super::wire::{self, check_args, truncate, word, write_sync, write_trailers};
use super::{escape, rules};

/// The encoders of format `x`: the tables of the commands' keys, the rules' helpers, the seal,
/// one encoder per slot, and `pfx_encode` of a packet.
pub(super) fn encode(p: &Protocol, n: &Names, x: &Fx, out: &mut String) {
    let f = &p.frames[x.fi];
    let kind = carries(p, x);
    if kind == Carries::Command {
        dispatch_ids(p, x, out);
    }
    if kind == Carries::CanCommand {
        can_ids(p, x, out);
    }
    rules::trimmed_fn(x, out);
    rules::stuff_fn(n, x, out);
    seal(p, n, x, out);
    for slot in slots_of(p, x) {
        encoder(p, n, x, &slot, out);
    }
    if kind == Carries::Bytes {
        encode_bytes(p, n, x, out);
    }
    rules::ack_encoder(f, n, x, out);
    encode_packet(p, n, x, out);
}

/// The dispatch key of every command, as the header values of the rules' key fields hold it
/// (the seal writes the command's).
fn dispatch_ids(p: &Protocol, x: &Fx, out: &mut String) {
    let f = &p.frames[x.fi];
    let xlo = &x.lo;
    let key = &x.rules.key;
    let prims: Vec<_> = key.iter().map(|k| f.values[k.value].prim).collect();
    let widest = prims.iter().map(|prim| prim.size()).max().unwrap_or(1);
    let (ty, commands, fields) = (
        names::unsigned_of(widest),
        p.commands.len().max(1),
        key.len(),
    );
    let mut rows = String::new();
    for c in &p.commands {
        let ids: Vec<String> = prims
            .iter()
            .zip(&c.id)
            .map(|(&prim, &v)| format!("{:#x}u", truncate(prim, v)))
            .collect();
        let ids = if ids.is_empty() {
            "0u".to_string()
        } else {
            ids.join(", ")
        };
        rows.push_str(&fill!("    {${ids}},\n", ids));
    }
    out.push_str(&fill!(
        r"
/* The dispatch key of every command, in command order (as the format's fields hold it). */
static const ${ty} ${xlo}ids[${commands}][${fields}] = {
${rows}};

",
        ty,
        xlo,
        commands,
        fields,
        rows
    ));
}

/// The CAN id of every command (the seal writes the command's as the frame's id).
fn can_ids(p: &Protocol, x: &Fx, out: &mut String) {
    let xlo = &x.lo;
    let ids: Vec<String> = p
        .commands
        .iter()
        .map(|c| format!("{:#x}u", c.can_id.unwrap_or(0)))
        .collect();
    let count = ids.len().max(1);
    let ids = if ids.is_empty() {
        "0u".to_string()
    } else {
        ids.join(", ")
    };
    out.push_str(&fill!(
        r"
/* The CAN id of every command, in command order (0: none). */
static const uint32_t ${xlo}can_ids[${count}] = {${ids}};

",
        xlo,
        count,
        ids
    ));
}

/// Whether a format's frames are sealed apart from where their encoder wrote the payload: a
/// wider length moves the payload, a flag trailer adds bytes, a direction's message starts
/// before the header's end. The seal then takes the buffer's size and the payload's start.
fn framed_apart(p: &Protocol, fi: usize) -> bool {
    let f = &p.frames[fi];
    f.length_extension.is_some()
        || f.flag_trailer.is_some()
        || (fi == 0 && p.directions.iter().any(|d| d.message.is_some()))
}

/// The arguments of `pfx_seal` before the payload's length: the buffer, and for a format
/// sealed apart its size and the payload's start.
fn seal_place(p: &Protocol, x: &Fx, start: &str) -> String {
    if framed_apart(p, x.fi) {
        format!("buf, cap, {start}, ")
    } else {
        "buf, ".to_string()
    }
}

/// The call `seal` (the sealed frame's length, or an error), escaped in the caller's buffer
/// where the format escapes its bytes between flags.
fn sealed(p: &Protocol, x: &Fx, seal: String) -> String {
    let escapes = lower_layout(&p.frames[x.fi]).escape.is_some();
    escape::escaped(x, escapes, seal)
}

/// The length field's count of a frame of `body` bytes (the format's adjustment taken off).
fn adjust(f: &Frame) -> i64 {
    match &f.length {
        Length::Field { adjust, .. } => *adjust,
        Length::Fixed(_) => 0,
    }
}

/// `pfx_seal`: the frame around a payload already written after the header
/// (`templates/seal.c`), or, for a format sealed apart, at a start the encoder gives, moved
/// behind a wider length when the frame needs one, with the flag trailer when the header has
/// it (`templates/seal_apart.c`).
fn seal(p: &Protocol, n: &Names, x: &Fx, out: &mut String) {
    let (up, xlo, xup) = (&n.up, &x.lo, &x.up);
    let f = &p.frames[x.fi];
    let sync = write_sync(f);
    let values: String = (f.values.iter().enumerate())
        .map(|(vi, v)| header_value(f, n, x, vi, v))
        .collect();
    let (sync_set, trailers, checks) = (
        sync_in_set(n, x, f),
        write_trailers(f, n, "body"),
        stores(n, x, f),
    );
    if !framed_apart(p, x.fi) {
        out.push_str(&fill!(
            include_str!("../templates/seal.c"),
            xlo,
            xup,
            up,
            sync,
            values,
            sync_set,
            trailers,
            checks
        ));
        out.push('\n');
        return;
    }
    let (extension, flagged, flag_copy) = (extension(f), flagged(f), flag_copy(f));
    out.push_str(&fill!(
        include_str!("../templates/seal_apart.c"),
        xlo,
        xup,
        up,
        extension,
        flagged,
        sync,
        values,
        sync_set,
        trailers,
        checks,
        flag_copy
    ));
    out.push('\n');
}

/// The seal's test of a sync set: the first header value, written with the others, is one of
/// the set.
fn sync_in_set(n: &Names, x: &Fx, f: &Frame) -> String {
    if f.sync_set.is_empty() {
        return String::new();
    }
    let (up, xlo) = (&n.up, &x.lo);
    fill!(
        r"
    /* The first header value is the sync: one of its set. */
    if (!${xlo}sync_matches(buf, 1)) return ${up}ERR_OUT_OF_RANGE;
",
        xlo,
        up
    )
}

/// The seal's checks, each computed over its span and stored, in the format's order.
fn stores(n: &Names, x: &Fx, f: &Frame) -> String {
    let (lo, up) = (&n.lo, &n.up);
    (f.checks.iter())
        .map(|c| {
            let args = check_args(n, x, c, "body");
            fill!(
                "    if (!${lo}store(buf, ${args})) return ${up}ERR_OUT_OF_RANGE;\n",
                lo,
                args,
                up
            )
        })
        .collect()
}

/// The seal's wider length: taken when the count of the short form reaches the marker (the
/// runtime's `extension_for`).
fn extension(f: &Frame) -> String {
    let Some(e) = &f.length_extension else {
        return String::new();
    };
    let (adjust, marker, len) = (adjust(f), names::u64_lit(e.marker), e.len);
    fill!(
        r"
    if ((int64_t)body - (${adjust}) >= 0 \
        && (uint64_t)((int64_t)body - (${adjust})) >= ${marker}) ext = ${len}u;
",
        adjust,
        marker,
        len
    )
}

/// The seal's flag trailer length: the trailer's, when the header holds it.
fn flagged(f: &Frame) -> String {
    let Some(t) = &f.flag_trailer else {
        return String::new();
    };
    let (name, len) = (names::field(&t.name), t.len);
    fill!(
        "    if (h->${name}_present) flagged = ${len}u;\n",
        name,
        len
    )
}

/// The seal's last bytes: the flag trailer, when the header holds it.
fn flag_copy(f: &Frame) -> String {
    let Some(t) = &f.flag_trailer else {
        return String::new();
    };
    let name = names::field(&t.name);
    fill!(
        "    if (flagged > 0) memcpy(buf + body, h->${name}, flagged);\n",
        name
    )
}

/// The statements of the seal that write header value `v` (index `vi`) of the frame of
/// `body` bytes: the sender's, the length (and the wider length), the dispatch key, a constant,
/// the flag trailer's flag, a command frame's acknowledgement flag.
fn header_value(f: &Frame, n: &Names, x: &Fx, vi: usize, v: &HeaderValue) -> String {
    let (lo, up, xlo) = (&n.lo, &n.up, &x.lo);
    let (name, word) = (&v.name, word(v));
    let adjust = adjust(f);
    let is_can = matches!(f.transport, Transport::Can { .. });
    let mut out = String::new();
    let value = match &v.role {
        // A CAN frame's id is the command's.
        _ if is_can && v.name == "can_id" => format!("(uint64_t){xlo}can_ids[command]"),
        Role::User { .. } => format!("(uint64_t)h->{}", names::field(&v.name)),
        Role::Length => match (&f.length, &f.length_extension) {
            (Length::Field { .. }, Some(e)) => {
                // The runtime's `conditional_count`: the count in the wider field, the
                // marker in this one, when it does not fit below the marker.
                let (wide, marker, len) = (
                    wire::word(&f.values[e.value]),
                    names::u64_lit(e.marker),
                    e.len,
                );
                return fill!(
                    r"
    {
        uint64_t count;
        if ((int64_t)body - (${adjust}) < 0) return ${up}ERR_OUT_OF_RANGE;
        count = (uint64_t)((int64_t)body - (${adjust}));
        if (count >= ${marker}) {
            if (count - ${len}u < ${marker}) return ${up}ERR_OUT_OF_RANGE;
            if (!${lo}put_field(buf, body, ${wide}, count - ${len}u)) return ${up}ERR_OUT_OF_RANGE;
            count = ${marker};
        }
        /* ${name} */
        if (!${lo}put_field(buf, body, ${word}, count)) return ${up}ERR_OUT_OF_RANGE;
    }
",
                    adjust,
                    up,
                    marker,
                    len,
                    lo,
                    wide,
                    name,
                    word
                );
            }
            (Length::Field { .. }, None) => {
                out.push_str(&fill!(
                    "    if ((int64_t)body - (${adjust}) < 0) return ${up}ERR_OUT_OF_RANGE;\n",
                    adjust,
                    up
                ));
                format!("(uint64_t)((int64_t)body - ({adjust}))")
            }
            (Length::Fixed(_), _) => return out,
        },
        Role::Dispatch => {
            let k = x.rules.key.iter().position(|k| k.value == vi).unwrap_or(0);
            return fill!(
                r"
    /* ${name} */
    if (command != SIZE_MAX \
        && !${lo}put_field(buf, body, ${word}, (uint64_t)${xlo}ids[command][${k}])) return ${up}ERR_OUT_OF_RANGE;
",
                name,
                lo,
                word,
                xlo,
                k,
                up
            );
        }
        Role::Const(c) => names::u64_lit(*c),
        Role::Flag => "(uint64_t)(flagged > 0 ? 1u : 0u)".to_string(),
        Role::WideLength => return out,
        // A command frame's acknowledgement flag: not the acknowledgement's value.
        Role::Ack(_) => {
            let equals = x.rules.ack.map_or(1, |(_, ack)| ack.equals);
            names::u64_lit(1 - equals.min(1))
        }
    };
    out.push_str(&fill!(
        r"
    /* ${name} */
    if (!${lo}put_field(buf, body, ${word}, ${value})) return ${up}ERR_OUT_OF_RANGE;
",
        name,
        lo,
        word,
        value,
        up
    ));
    out
}

/// The encoder of one slot: its payload written after the header (in a format without
/// extension fields, the bytes before them; then the format's rules), then the frame sealed
/// around it.
fn encoder(p: &Protocol, n: &Names, x: &Fx, slot: &Slot, out: &mut String) {
    let (lo, up, xlo, xup) = (&n.lo, &n.up, &x.lo, &x.up);
    let f = &p.frames[x.fi];
    let (arg, mut write) = match slot.si {
        Some(si) => {
            let (ty, snake) = (n.ty(&p.structs[si].name), names::snake(&p.structs[si].name));
            (
                format!("const {ty} *payload, "),
                fill!(
                    "    if ((e = ${lo}write_${snake}(&w, payload)) != 0) return e;\n",
                    lo,
                    snake
                ),
            )
        }
        None => (String::new(), String::new()),
    };
    // The message of a direction the decoder is given starts where the dispatch key would.
    let start = slot
        .keyless
        .map_or(format!("{xup}HEADER_LEN"), |start| format!("{start}u"));
    let mut decl = String::new();
    let mut place = fill!(
        r"
    w.p = buf + ${start};
    w.cap = cap - ${start} - ${xup}TRAILER_LEN;
    w.pos = 0;
",
        start,
        xup
    );
    let base = slot
        .si
        .and_then(|si| p.structs[si].base_size.filter(|_| !f.extensions));
    if let (Some(base), Some(si)) = (base, slot.si) {
        // The whole struct is written aside, then the bytes before its extension fields kept.
        decl = format!("    uint8_t whole[{}];\n", p.structs[si].size.max(1));
        place = fill!(
            r"
    w.p = whole;
    w.cap = sizeof whole;
    w.pos = 0;
"
        );
        write.push_str(&fill!(
            r"
    if (w.pos > ${base}u) w.pos = ${base}u;
    if (w.pos > cap - ${xup}HEADER_LEN - ${xup}TRAILER_LEN) return ${up}ERR_SHORT_BUFFER;
    memcpy(buf + ${xup}HEADER_LEN, whole, w.pos);
    w.p = buf + ${xup}HEADER_LEN;
",
            base,
            xup,
            up
        ));
    }
    write.push_str(&rules::trim_written(x, slot));
    write.push_str(&rules::stuff_written(n, x, slot));
    let command = match (slot.command, slot.keyless) {
        (Some(ci), _) => format!("{up}{}", p.commands[ci].name),
        (None, Some(_)) => "SIZE_MAX".into(),
        (None, None) => "0".into(),
    };
    let (name, place_args) = (&slot.name, seal_place(p, x, &start));
    let sealed = sealed(
        p,
        x,
        format!("{xlo}seal({place_args}w.pos, header, {command})"),
    );
    out.push_str(&fill!(
        r"
int ${xlo}encode_${name}(const ${xlo}header *header, ${arg}uint8_t *buf, size_t cap)
{
    struct ${lo}wr w;
    int e = 0;
${decl}    if (cap < ${start} + ${xup}TRAILER_LEN) return ${up}ERR_SHORT_BUFFER;
${place}${write}    (void)e;
    return ${sealed};
}

",
        xlo,
        name,
        arg,
        lo,
        decl,
        start,
        xup,
        up,
        place,
        write,
        sealed
    ));
}

/// The encoder of a format without dispatch key or message: a frame around the payload's
/// bytes.
fn encode_bytes(p: &Protocol, n: &Names, x: &Fx, out: &mut String) {
    let (up, xlo, xup) = (&n.up, &x.lo, &x.up);
    let place = seal_place(p, x, &format!("{xup}HEADER_LEN"));
    let sealed = sealed(p, x, format!("{xlo}seal({place}len, header, 0)"));
    out.push_str(&fill!(
        r"
int ${xlo}encode_bytes(const ${xlo}header *header, const uint8_t *payload, size_t len, uint8_t *buf, size_t cap)
{
    if (len > ${xup}MAX_PAYLOAD_LEN) return ${up}ERR_OUT_OF_RANGE;
    if (cap < ${xup}HEADER_LEN + ${xup}TRAILER_LEN \
        || len > cap - ${xup}HEADER_LEN - ${xup}TRAILER_LEN) return ${up}ERR_SHORT_BUFFER;
    if (len > 0) memcpy(buf + ${xup}HEADER_LEN, payload, len);
    return ${sealed};
}

",
        xlo,
        xup,
        up,
        sealed
    ));
}

/// `pfx_encode`: a packet by the encoder of its slot (an acknowledgement's, the bytes', or the
/// command's in its direction).
fn encode_packet(p: &Protocol, n: &Names, x: &Fx, out: &mut String) {
    let (up, xlo) = (&n.up, &x.lo);
    let kind = carries(p, x);
    out.push_str(&fill!(
        r"
int ${xlo}encode(const ${xlo}packet *packet, uint8_t *buf, size_t cap)
{
",
        xlo
    ));
    if x.rules.ack.is_some() {
        out.push_str(&fill!(
            r"
    if (packet->ack) return ${xlo}encode_ack(&packet->header, packet->payload.ack_data.bytes, \
        packet->payload.ack_data.len, buf, cap);
",
            xlo
        ));
    }
    if kind == Carries::Bytes {
        out.push_str(&fill!(
            r"
    return ${xlo}encode_bytes(&packet->header, packet->payload, packet->payload_len, buf, cap);
",
            xlo
        ));
    }
    for slot in slots_of(p, x) {
        let payload = match slot.si {
            Some(_) => format!("&packet->payload.{}, ", slot.name),
            None => String::new(),
        };
        let (guard, name) = (slot.guard(p, n, "packet"), &slot.name);
        out.push_str(&fill!(
            "    ${guard}return ${xlo}encode_${name}(&packet->header, ${payload}buf, cap);\n",
            guard,
            xlo,
            name,
            payload
        ));
    }
    if matches!(kind, Carries::Command | Carries::CanCommand) {
        out.push_str(&fill!("    return ${up}ERR_OUT_OF_RANGE;\n", up));
    }
    out.push_str("}\n\n");
}
