//! A frame format's items in the header: its header type (the values a sender sets), its
//! packet type (header, command, direction and the payload's union of the command's structs),
//! and the prototypes of its decoders, encoders and text form.

use crate::ir::{Prim, Protocol, Transport};
use crate::rules::Carries;

use super::names::{self, Fx, Names, doc_comment, unsigned_of};
use super::shape::{carries, keyed_format, slots_of, user_values};
use super::template::fill;

/// The header and packet types of frame format `x`.
pub fn types(p: &Protocol, n: &Names, x: &Fx, out: &mut String) {
    let f = &p.frames[x.fi];
    let (lo, up, format) = (&x.lo, &x.up, &f.name);
    out.push_str(&fill!(
        r"
/** The header values a sender sets in a `${format}` frame. */
typedef struct ${lo}header {
",
        format,
        lo
    ));
    let mut values = String::new();
    for v in user_values(f) {
        let ty = if v.prim == Prim::Bool {
            "bool"
        } else {
            unsigned_of(v.prim.size())
        };
        let (name, doc) = (names::field(&v.name), doc_comment(&v.doc, ""));
        values.push_str(&fill!("    ${ty} ${name};${doc}\n", ty, name, doc));
    }
    if let Some(t) = &f.flag_trailer {
        let (name, len, doc) = (names::field(&t.name), t.len, doc_comment(&t.doc, ""));
        values.push_str(&fill!(
            r"
    bool ${name}_present; /**< The frame carries `${name}` (its header flag is set). */
    uint8_t ${name}[${len}];${doc}
",
            name,
            len,
            doc
        ));
    }
    if values.is_empty() {
        values.push_str("    uint8_t unused_; /**< C has no empty struct. */\n");
    }
    out.push_str(&values);
    out.push_str(&fill!(
        r"
} ${lo}header;

/** A whole `${format}` frame: header, command and the command's payload. */
typedef struct ${lo}packet {
    ${lo}header header;
",
        lo,
        format
    ));
    let (nlo, nup) = (&n.lo, &n.up);
    if keyed_format(p, x) {
        out.push_str(&fill!("    ${nlo}command command;\n", nlo));
    }
    if x.rules.ack.is_some() {
        out.push_str(&fill!(
            r"
    /** An acknowledgement: no command (`${nup}COMMAND_COUNT`), its data in `payload.ack_data`. */
    bool ack;
",
            nup
        ));
    }
    if !p.directions.is_empty() && carries(p, x) == Carries::Command {
        out.push_str(&fill!("    ${nlo}direction direction;\n", nlo));
    }
    if carries(p, x) == Carries::Bytes {
        let max = x.rules.max_payload.max(1);
        out.push_str(&fill!(
            r"
    size_t payload_len; /**< The payload's bytes. */
    uint8_t payload[${max}];
} ${lo}packet;

",
            max,
            lo
        ));
        return;
    }
    out.push_str(&fill!(
        r"
    /** The payload of the command (and direction): the member named after them. */
    union {
        uint8_t none_; /**< Commands without payload. */
"
    ));
    for slot in slots_of(p, x) {
        if let Some(si) = slot.si {
            let (ty, name) = (n.ty(&p.structs[si].name), &slot.name);
            out.push_str(&fill!("        ${ty} ${name};\n", ty, name));
        }
    }
    if x.rules.ack.is_some() {
        out.push_str(&fill!(
            r"
        /** The data of an acknowledgement. */
        struct {
            size_t len;
            uint8_t bytes[${up}ACK_MAX_LEN > 0 ? ${up}ACK_MAX_LEN : 1];
        } ack_data;
",
            up
        ));
    }
    out.push_str(&fill!(
        r"
    } payload;
} ${lo}packet;

",
        lo
    ));
}

/// The prototypes of frame format `x`'s decoders, encoders and text form.
pub fn prototypes(p: &Protocol, n: &Names, x: &Fx, out: &mut String) {
    decoders(p, n, x, out);
    encoders(p, n, x, out);
    let (lo, up) = (&x.lo, &n.up);
    out.push_str(&fill!(
        r"

#ifdef ${up}WITH_FORMAT
/** The packet as one line of text (`snprintf` semantics: the length it needs). */
int ${lo}format(const ${lo}packet *packet, char *out, size_t cap);
#endif

",
        up,
        lo
    ));
}

/// The prototypes of the decoders of frame format `x` (and its CAN frame functions).
fn decoders(p: &Protocol, n: &Names, x: &Fx, out: &mut String) {
    let (lo, up, nlo) = (&x.lo, &n.up, &n.lo);
    let f = &p.frames[x.fi];
    let format = &f.name;
    out.push_str(&fill!(
        r"
/* ---- Frames of format `${format}` ---- */

/** Decodes `len` bytes that are exactly one `${format}` frame into `out`: 0, or a negative ${up}ERR_.
 *  Takes any bytes: checks the framing (sync, length, checks, trailers) first. */
int ${lo}decode(const uint8_t *bytes, size_t len, ${lo}packet *out);

/** Decodes a frame whose framing a stream decoder has checked (the bytes and length of a
 *  frame event of this format) into `out`, as ${lo}decode without checking the framing again:
 *  0, or a negative ${up}ERR_. Other bytes are read within `len`, never beyond, but may
 *  decode to values no sender sent. */
int ${lo}decode_frame(const uint8_t *bytes, size_t len, ${lo}packet *out);

/** Encodes a packet into `buf`: the frame's length, or a negative ${up}ERR_. */
int ${lo}encode(const ${lo}packet *packet, uint8_t *buf, size_t cap);

",
        format,
        up,
        lo
    ));
    if x.fi == 0 && p.directions_given() {
        out.push_str(&fill!(
            r"
/** Decodes `len` bytes that are exactly one frame sent in `direction` (no header value
 *  tells it: the side that reads the frame knows it): 0, or a negative ${up}ERR_. Without a
 *  direction (${lo}decode), a frame gives ${up}ERR_UNKNOWN_DIRECTION. */
int ${lo}decode_given(const uint8_t *bytes, size_t len, ${nlo}direction direction, ${lo}packet *out);

/** ${lo}decode_given of a frame a stream decoder has checked, as ${lo}decode_frame. */
int ${lo}decode_frame_given(const uint8_t *bytes, size_t len, ${nlo}direction direction, ${lo}packet *out);

",
            up,
            lo,
            nlo
        ));
        for d in &p.directions {
            let direction = &d.name;
            out.push_str(&fill!(
                r"
/** Decodes a frame sent in direction `${direction}`, as ${lo}decode_given. */
int ${lo}decode_${direction}(const uint8_t *bytes, size_t len, ${lo}packet *out);

",
                direction,
                lo
            ));
        }
    }
    if f.escape.is_some() {
        out.push_str(&fill!(
            r"
/** The frame at the start of `wire[0..len]`, from its opening flag to the next flag,
 *  unescaped into `out[0..cap]` (${up}MAX_FRAME_LEN holds every frame), flags included: what
 *  ${lo}decode_frame reads. Its length, or ${up}ERR_FRAME (no opening or closing flag, an
 *  escape byte not followed by a substitute, a frame longer than `cap`). */
int ${lo}unescape(const uint8_t *wire, size_t len, uint8_t *out, size_t cap);

",
            up,
            lo
        ));
    }
    if matches!(f.transport, Transport::Can { .. }) {
        out.push_str(&fill!(
            r"
/** Decodes one received CAN frame (its id, whether the id is extended, its `len` data
 *  bytes, at most 8) into `out`: 0, or a negative ${up}ERR_ (${up}ERR_FRAME for an id of the
 *  other kind or more than 8 bytes). */
int ${lo}decode_can(uint32_t id, bool extended, const uint8_t *data, size_t len, ${lo}packet *out);

/** Encodes a packet as a CAN frame: its id in `*id`, its data in `data`; the number of data
 *  bytes, or a negative ${up}ERR_. */
int ${lo}encode_can(const ${lo}packet *packet, uint32_t *id, uint8_t data[8]);

",
            up,
            lo
        ));
    }
}

/// The prototypes of the encoders of frame format `x`: of the payload's bytes, of each
/// command (and direction), of an acknowledgement.
fn encoders(p: &Protocol, n: &Names, x: &Fx, out: &mut String) {
    let lo = &x.lo;
    if carries(p, x) == Carries::Bytes {
        out.push_str(&fill!(
            r"
/** Encodes a frame around `len` payload bytes: the frame's length, or a negative error. */
int ${lo}encode_bytes(const ${lo}header *header, const uint8_t *payload, size_t len, uint8_t *buf, size_t cap);
",
            lo
        ));
    }
    out.push_str(
        "/* One encoder per command (and direction): the frame's length, or a negative error. */\n",
    );
    for slot in slots_of(p, x) {
        let payload = match slot.si {
            Some(si) => format!("const {} *payload, ", n.ty(&p.structs[si].name)),
            None => String::new(),
        };
        let name = &slot.name;
        out.push_str(&fill!(
            "int ${lo}encode_${name}(const ${lo}header *header, ${payload}uint8_t *buf, size_t cap);\n",
            lo,
            name,
            payload
        ));
    }
    if x.rules.ack.is_some() {
        out.push_str(&fill!(
            r"
/** An acknowledgement of `len` bytes of data (with none, the bare header where the format has one). */
int ${lo}encode_ack(const ${lo}header *header, const uint8_t *data, size_t len, uint8_t *buf, size_t cap);
",
            lo
        ));
    }
}
