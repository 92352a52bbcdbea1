//! The C peer against the Rust codec: for every bundled spec (`specs/*.toml`) and fixture
//! (`protocol-codegen/tests/features`, `tests/c_peer/*.toml`), the C code
//! `protocol gen c` prints is compiled with the system C compiler (strict C99, warnings as
//! errors, AddressSanitizer and UndefinedBehaviorSanitizer) together with a small driver
//! (`tests/c_peer/driver.c`), and its output is compared line by line with what the run-time
//! codec (`protocol-dynamic`) gives for the same input:
//!
//! * every golden vector frame (`tests/vectors/*.json`) by every serial frame format (a
//!   vector's CAN frame by every CAN format; where the decoder is given the direction, also in
//!   each direction): the decoded values, and the bytes the decoded packet encodes to;
//! * every vector stream at every chunk size through every stream decoder (each format's, and
//!   the link's of several command formats), event by event, and its expected frames;
//! * 10,000 random frames per bundled spec and frame format, 2,000 per fixture (valid, and with
//!   unknown commands, wrong payload sizes, values without variant), decoded and encoded again;
//!   one in four of the first format's is encoded by the Rust codec from random payload values
//!   (text, stated lengths, checks inside a payload, acknowledgements that random bytes seldom
//!   make valid), and a format with bare headers gets some; a stuffed format's random bytes
//!   often hold its pattern, an escaped format's its reserved bytes and substitutes (its frames
//!   go escaped, as sent; its stream decoders' frames come unescaped, read by `decode_frame`);
//!   a CAN format's frames are CAN frames (id and data), the first format's too where the spec
//!   is a CAN-only link (whose command is a member of the id);
//! * edge frames per command: payloads of all-zero and all-`0xFF` bytes, and of one zero byte
//!   (the field rules' extreme values, trailing-zero truncation's kept first byte), and the
//!   bare header where the format has one;
//! * for every stream decoder, a fault-injection stream of its formats' frames (garbage,
//!   flipped bits, truncations, stray sync bytes) at several chunk sizes, event by event, with
//!   the counters.
//!
//! A spec the C printer refuses is listed with its unsupported features in the snapshot
//! `c_support` (a new spec changes it: the gap is visible in review, never a silent pass).
//! Also compiled, warnings as errors: the generated code with `gcc` and `clang` where found.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};

use protocol_dynamic::{Codec, DecodeIssue, Interpreter, Item, Value};
use protocol_runtime::CanFrame;
use protocol_spec::ir::{
    Command as Cmd, Direction, DirectionRule, Frame, PacketKind, Prim, Protocol, Role, Transport,
};
use protocol_spec::layout::word_field;

const RANDOM_FRAMES: usize = 10_000;

/// The same comparison on a batch of random specs.
#[path = "../c_peer/random_specs.rs"]
mod random_specs;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The specs to compare, each with its number of random frames: the bundled specs (10,000
/// each), then the feature fixtures of `protocol-codegen/tests/features`, the regression specs
/// of feature combinations where C and Rust can part (`protocol-codegen/tests/c_regressions`)
/// and this test's own (`tests/c_peer/*.toml`, paths no bundled spec takes), 2,000 each.
fn specs() -> Vec<(PathBuf, usize)> {
    let toml_in = |dir: &str| {
        let mut out: Vec<PathBuf> = std::fs::read_dir(root().join(dir))
            .unwrap_or_else(|e| panic!("{dir}: {e}"))
            .map(|e| e.expect("entry").path())
            .filter(|p| p.extension().is_some_and(|e| e == "toml"))
            .collect();
        out.sort();
        out
    };
    let mut out: Vec<(PathBuf, usize)> = toml_in("specs")
        .into_iter()
        .map(|p| (p, RANDOM_FRAMES))
        .collect();
    for dir in [
        "protocol-codegen/tests/features",
        "protocol-codegen/tests/c_regressions",
        "protocol-cli/tests/c_peer",
    ] {
        out.extend(toml_in(dir).into_iter().map(|p| (p, RANDOM_FRAMES / 5)));
    }
    out
}

/// The vector files of a spec, and whether their streams' expected frames are the spec's: for a
/// bundled spec, the registry's `c-peer` suite (`tests/catalogue.toml`, which says why a file's
/// streams are not); for a fixture, `tests/vectors/NAME.json` if there is one.
fn vector_files(spec: &str) -> Vec<(String, bool)> {
    let catalogue = crate::support::catalogue();
    if catalogue.spec.iter().any(|e| e.name == spec) {
        return catalogue
            .vectors("c-peer")
            .filter(|(e, _)| e.name == spec)
            .map(|(_, v)| (v.file.clone(), v.streams))
            .collect();
    }
    let mut out = Vec::new();
    if root().join(format!("tests/vectors/{spec}.json")).exists() {
        out.push((format!("{spec}.json"), true));
    }
    out
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

fn unhex(text: &str) -> Vec<u8> {
    (0..text.len() / 2)
        .map(|i| u8::from_str_radix(&text[2 * i..2 * i + 2], 16).expect("hex"))
        .collect()
}

// ---- The Rust side: the text the driver prints, from protocol-dynamic ----

fn value_text(out: &mut String, path: &str, v: &Value) {
    match v {
        Value::Struct(fields) => {
            for (k, v) in fields.iter() {
                value_text(out, &format!("{path}.{k}"), v);
            }
        }
        Value::Array(items) => {
            for (i, v) in items.iter().enumerate() {
                value_text(out, &format!("{path}[{i}]"), v);
            }
        }
        Value::UInt(u) => write!(out, " {path}={u}").unwrap(),
        Value::Int(i) => write!(out, " {path}={i}").unwrap(),
        Value::Bool(b) => write!(out, " {path}={b}").unwrap(),
        Value::F32(f) => write!(out, " {path}=f32:{:08x}", f.to_bits()).unwrap(),
        Value::F64(f) => write!(out, " {path}=f64:{:016x}", f.to_bits()).unwrap(),
        Value::String(s) => {
            // As the C text form: a control character or backslash as `\xNN`.
            write!(out, " {path}=").unwrap();
            for c in s.chars() {
                if c < ' ' || c == '\x7f' || c == '\\' {
                    write!(out, "\\x{:02x}", u32::from(c)).unwrap();
                } else {
                    out.push(c);
                }
            }
        }
        Value::Bytes(b) => write!(out, " {path}=hex:{}", hex(b)).unwrap(),
        Value::Null => write!(out, " {path}=null").unwrap(),
    }
}

/// `ok TEXT` or `err NAME` (and `enc HEX` or `enc err`), as the driver's `describe`.
fn describe(
    codec: &Codec<'_>,
    decoded: Result<protocol_dynamic::Decoded, DecodeIssue>,
    bytes: &[u8],
    encode: bool,
) -> Vec<String> {
    let p = codec.protocol();
    let d = match decoded {
        Ok(d) => d,
        Err(e) => {
            return vec![format!(
                "err {}",
                protocol_codegen::c::error_name(&e.to_runtime())
            )];
        }
    };
    let mut text = format!(
        "ok cmd={}",
        d.command.map_or("?", |c| p.commands[c].name.as_str())
    );
    if let Some(di) = d.direction {
        write!(text, " dir={}", p.directions[di].name).unwrap();
    }
    for (k, v) in d.header.iter() {
        value_text(&mut text, &format!("header.{k}"), v);
    }
    value_text(&mut text, "payload", &d.payload);
    let mut out = vec![text];
    if encode {
        out.extend(carried_lines(codec, &d));
        out.push(match codec.encode(&codec.frame_value(&d, 0, bytes)) {
            Ok(e) => format!("enc {}", hex(&e.bytes)),
            Err(_) => "enc err".into(),
        });
    }
    out
}

/// The packets a decoded frame's payload carries, as the driver's `carried_FI`: `carried ok
/// TEXT` (the packet read into a packet of the format that carries every command, its header
/// zeroed) or `carried err NAME`.
fn carried_lines(codec: &Codec<'_>, d: &protocol_dynamic::Decoded) -> Vec<String> {
    let p = codec.protocol();
    let carried = codec.carried_packets(d);
    let Some(fi) = protocol_codegen::c::carried_format(p).filter(|_| !carried.is_empty()) else {
        return Vec::new();
    };
    let f = &p.frames[fi];
    carried
        .into_iter()
        .map(|read| {
            let (ci, payload) = match read {
                Ok(read) => read,
                Err(e) => {
                    let name = protocol_codegen::c::error_name(&e.to_runtime());
                    return format!("carried err {name}");
                }
            };
            let mut text = format!("carried ok cmd={}", p.commands[ci].name);
            if let Some(di) = d.direction {
                write!(text, " dir={}", p.directions[di].name).unwrap();
            }
            for v in f
                .values
                .iter()
                .filter(|v| matches!(v.role, Role::User { .. }))
            {
                let zero = if v.prim == Prim::Bool {
                    Value::Bool(false)
                } else {
                    Value::UInt(0)
                };
                value_text(&mut text, &format!("header.{}", v.name), &zero);
            }
            if let Some(t) = &f.flag_trailer {
                value_text(&mut text, &format!("header.{}", t.name), &Value::Null);
            }
            value_text(&mut text, "payload", &payload);
            text
        })
        .collect()
}

fn rust_frame(codec: &Codec<'_>, format: usize, bytes: &[u8]) -> Vec<String> {
    let mut out = describe(codec, codec.parse(format, bytes), bytes, true);
    out.push("end".into());
    out
}

/// A CAN frame of CAN format `format`, as the driver's `describe_can`: decoded, and the CAN
/// frame the decoded packet encodes to (`enc ID DATA`).
fn rust_can(codec: &Codec<'_>, format: usize, can: &CanFrame) -> Vec<String> {
    let mut out = describe(codec, codec.decode_can(format, can), can.data(), false);
    if let Ok(d) = codec.decode_can(format, can) {
        out.push(
            match codec
                .encode(&codec.frame_value(&d, 0, can.data()))
                .map(|e| e.can)
            {
                Ok(Some(c)) => format!("enc {} {}", c.id, hex(c.data())),
                _ => "enc err".into(),
            },
        );
    }
    out.push("end".into());
    out
}

/// The stream decoders the C code has, in its order: one per serial frame format, then the
/// link's decoder of every command format when the spec has several.
#[derive(Clone, Copy)]
enum Decoder {
    Format(usize),
    Link,
}

fn decoders(p: &Protocol) -> Vec<Decoder> {
    let mut out: Vec<Decoder> = (0..p.frames.len())
        .filter(|&fi| p.frames[fi].transport == Transport::Serial)
        .map(Decoder::Format)
        .collect();
    if !p.link.is_empty() {
        out.push(Decoder::Link);
    }
    out
}

fn rust_stream(codec: &Codec<'_>, decoder: Decoder, chunk: usize, data: &[u8]) -> Vec<String> {
    let mut out = Vec::new();
    let mut stream = match decoder {
        Decoder::Format(fi) => codec.stream(fi),
        Decoder::Link => codec.link_stream(),
    }
    .expect("a stream");
    let item_text = |item: Item<'_>, out: &mut Vec<String>| match item {
        Item::Frame {
            offset,
            bytes,
            decoded,
        } => {
            let d = describe(codec, decoded, bytes, false);
            out.push(format!("frame {offset} {} {}", hex(bytes), d[0]));
        }
        Item::Rejected { offset, reason } => out.push(format!("rejected {offset} {reason}")),
        Item::Skipped { offset, len } => out.push(format!("skipped {offset} {len}")),
    };
    for mut c in data.chunks(chunk.max(1)) {
        while let Some(item) = stream.next_item(&mut c) {
            item_text(item, &mut out);
        }
    }
    while let Some(item) = stream.flush_item() {
        item_text(item, &mut out);
    }
    let s = stream.stats();
    out.push(format!(
        "stats {} {} {} {} {} {} {} {} {}",
        s.frames,
        s.frame_bytes,
        s.skipped_bytes,
        s.bad_header,
        s.bad_header_check,
        s.bad_length,
        s.bad_checksum,
        s.bad_trailer,
        s.truncated
    ));
    out.push("end".into());
    out
}

/// Adjacent skipped runs merged: how a run of garbage is cut into events depends on where
/// the input was cut and where each engine holds it; the bytes skipped do not.
fn normalize(lines: Vec<String>) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for line in lines {
        let run = |l: &str| -> Option<(u64, u64)> {
            let mut w = l.strip_prefix("skipped ")?.split(' ');
            Some((w.next()?.parse().ok()?, w.next()?.parse().ok()?))
        };
        if let (Some((o2, n2)), Some((o1, n1))) = (run(&line), out.last().and_then(|l| run(l))) {
            if o1 + n1 == o2 {
                *out.last_mut().expect("a line") = format!("skipped {o1} {}", n1 + n2);
                continue;
            }
        }
        out.push(line);
    }
    out
}

// ---- Inputs ----

/// xorshift64*: the same inputs every run. Its random bytes are, one in two, a byte of `bias`
/// when that is not empty (a spec's stuffing pattern and inserted byte: random bytes then
/// hold the pattern, stuffed or not).
struct Rng(u64, Vec<u8>);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    fn byte(&mut self) -> u8 {
        if self.1.is_empty() || self.below(2) == 0 {
            return self.next() as u8;
        }
        let i = self.below(self.1.len());
        self.1[i]
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// The payloads frames of format `fi` carry: `(command, direction, struct)` per command (and
/// direction) the format carries, or its message.
fn format_slots(p: &Protocol, fi: usize) -> Vec<(Option<&Cmd>, usize, Option<usize>)> {
    let f = &p.frames[fi];
    let mut out = Vec::new();
    match f.packet {
        PacketKind::Can => {
            for c in p.commands.iter().filter(|c| c.can_id.is_some()) {
                out.push((Some(c), 0, c.payloads.first().copied().flatten()));
            }
        }
        _ if f.dispatch.is_empty() || matches!(f.packet, PacketKind::Message(_)) => {
            out.push((None, 0, f.message));
        }
        _ => {
            for (ci, c) in p.commands.iter().enumerate() {
                if f.commands.contains(&ci) {
                    out.extend((0..c.payloads.len()).map(|slot| (Some(c), slot, c.payloads[slot])));
                }
            }
            // The message of a direction the decoder is given.
            for (di, d) in p.directions.iter().enumerate() {
                if let (0, Some((si, _))) = (fi, d.message) {
                    out.push((None, di, Some(si)));
                }
            }
        }
    }
    out
}

/// The sizes of struct `si` a frame of `f` carries: all of it, or in a format without
/// extension fields the bytes before them.
fn struct_sizes(p: &Protocol, f: &Frame, si: Option<usize>) -> (usize, usize) {
    match si {
        Some(si) => {
            let s = &p.structs[si];
            match s.base_size.filter(|_| !f.extensions) {
                Some(base) => (base, base),
                None => (s.min_size, s.size),
            }
        }
        None => (0, 0),
    }
}

/// Bytes of a frame of `f` with a payload of `payload` bytes, within the format's bounds.
fn frame_len(f: &Frame, payload: usize) -> usize {
    (f.header_len + payload + f.trailer_len).clamp(f.min_len(), f.max_len())
}

/// The payload bytes after the header of a frame carrying struct bytes `size` of slot
/// `(command, direction)`: a direction's message takes the dispatch key's bytes too.
fn after_header(
    p: &Protocol,
    f: &Frame,
    command: Option<&Cmd>,
    direction: usize,
    size: usize,
) -> usize {
    match (command, p.directions.get(direction).and_then(|d| d.message)) {
        (None, Some((_, start))) => size.saturating_sub(f.header_len - start),
        _ => size,
    }
}

/// The bytes random frames favour (one in two): a stuffed format's pattern and inserted byte,
/// so that payloads hold the pattern, stuffed or not; an escaped format's flag, escape byte,
/// reserved bytes and substitutes, so that frames hold bytes to escape and substitutes.
fn bias(p: &Protocol) -> Vec<u8> {
    let f = &p.frames[0];
    let mut out = f
        .stuffing
        .as_ref()
        .map(|(after, insert)| [after.as_slice(), &[*insert]].concat())
        .unwrap_or_default();
    if let Some(e) = &f.escape {
        out.extend([e.flag, e.escape]);
        out.extend(e.pairs.iter().flatten());
    }
    out
}

/// A frame of format `fi`, sealed by the runtime after `fill` wrote its bytes: the flag
/// trailer's bytes added when its flag came out set; escaped, as it goes on the wire, where
/// the format escapes its bytes. `None` when the runtime cannot seal it (a length no frame
/// has).
fn sealed(
    codec: &Codec<'_>,
    fi: usize,
    mut frame: Vec<u8>,
    trailer_byte: &mut dyn FnMut() -> u8,
) -> Option<Vec<u8>> {
    let layout = codec.layout(fi)?;
    let present = layout.flag_trailer_len(&frame);
    frame.extend((0..present).map(|_| trailer_byte()));
    layout.seal(&mut frame).ok()?;
    if let Some(escape) = layout.escape {
        let len = frame.len();
        frame.resize(escape.escaped_len(&frame), 0);
        let wire = escape.escape_in_place(&mut frame, len).ok()?;
        frame.truncate(wire);
    }
    Some(frame)
}

/// A random frame of format `fi`, sealed by the runtime: a command's payload of random bytes
/// (its size, or now and then another), the dispatch key or CAN id of a command (now and then
/// random), a sender in the direction's address set (now and then random).
fn random_frame(p: &Protocol, codec: &Codec<'_>, fi: usize, rng: &mut Rng) -> Vec<u8> {
    let f = &p.frames[fi];
    let slots = format_slots(p, fi);
    loop {
        let (c, slot, si) = slots[rng.below(slots.len())];
        if fi == 0 && rng.below(4) == 0 {
            if let Some(frame) = value_frame(p, codec, c, slot, si, rng) {
                return frame;
            }
        }
        let (min, max) = match (c, si, f.message) {
            // A format without dispatch key or message: its payload's bytes as they are.
            (None, None, None) => (f.payload_min, f.payload_max),
            _ => struct_sizes(p, f, si),
        };
        let mut payload = min + rng.below(max - min + 1);
        if rng.below(8) == 0 {
            payload = f.payload_min + rng.below(f.payload_max - f.payload_min + 1);
        }
        let payload = after_header(p, f, c, slot, payload);
        let mut frame: Vec<u8> = (0..frame_len(f, payload)).map(|_| rng.byte()).collect();
        if !f.sync_set.is_empty() {
            frame[0] = f.sync_set[rng.below(f.sync_set.len())];
        }
        if let Some(c) = c.filter(|_| rng.below(16) != 0) {
            write_key(f, c, &mut frame);
        }
        if let Some(d) = p
            .directions
            .get(slot)
            .filter(|_| fi == 0 && rng.below(8) != 0)
        {
            let sender = match &d.rule {
                DirectionRule::InSet { set, .. } => {
                    let a = &p.addresses[*set];
                    Some(a.first + (rng.next() % (a.last - a.first + 1)))
                }
                DirectionRule::Equals { equals, .. } => Some(*equals),
                // Nothing in the frame tells a direction the decoder is given.
                DirectionRule::Given => None,
            };
            if let Some(sender) = sender {
                write_direction(f, d, sender, &mut frame);
            }
        }
        // Now and then a bare header (the header alone), where the format has one.
        if let Some(bare) = f.bare_len.filter(|_| rng.below(8) == 0) {
            frame.truncate(bare);
        }
        if let Some(frame) = sealed(codec, fi, frame, &mut || rng.next() as u8) {
            return frame;
        }
    }
}

/// A frame the Rust codec encodes from random values: the command's payload struct (`si`)
/// from [`random_struct`], the header values random, the sender in the direction's set.
/// `None` when the codec refuses the value (a payload too long for the frame, say).
fn value_frame(
    p: &Protocol,
    codec: &Codec<'_>,
    c: Option<&Cmd>,
    slot: usize,
    si: Option<usize>,
    rng: &mut Rng,
) -> Option<Vec<u8>> {
    let f = &p.frames[0];
    let mut header = protocol_dynamic::Fields::new();
    for v in f
        .values
        .iter()
        .filter(|v| matches!(v.role, protocol_spec::ir::Role::User { .. }))
    {
        let bits = rng.next() & mask(v.width);
        let value = if v.prim == protocol_spec::ir::Prim::Bool {
            Value::Bool(bits & 1 != 0)
        } else {
            Value::UInt(bits)
        };
        header.insert(v.name.clone(), value);
    }
    if let Some(d) = p.directions.get(slot) {
        let (DirectionRule::InSet { value, .. } | DirectionRule::Equals { value, .. }) = &d.rule
        else {
            return None;
        };
        let sender = match &d.rule {
            DirectionRule::InSet { set, .. } => {
                let a = &p.addresses[*set];
                a.first + (rng.next() % (a.last - a.first + 1))
            }
            DirectionRule::Equals { equals, .. } => *equals,
            DirectionRule::Given => return None,
        };
        let v = &f.values[*value];
        let sender = if v.prim == protocol_spec::ir::Prim::Bool {
            Value::Bool(sender != 0)
        } else {
            Value::UInt(sender)
        };
        header.insert(v.name.clone(), sender);
    }
    let mut frame = protocol_dynamic::Fields::new();
    frame.insert("header", Value::Struct(header));
    // Now and then an acknowledgement: its data, none at times (a bare header where the
    // format has one).
    if let Some((_, ack_header_len)) = f.ack.filter(|_| rng.below(4) == 0) {
        let most = f.max_len() - ack_header_len - f.trailer_len;
        let len = if rng.below(2) == 0 {
            0
        } else {
            rng.below(most.min(32) + 1)
        };
        frame.insert("ack", Value::Bool(true));
        frame.insert(
            "payload",
            Value::Bytes((0..len).map(|_| rng.next() as u8).collect()),
        );
        return codec.encode(&Value::Struct(frame)).ok().map(|e| e.bytes);
    }
    if let Some(c) = c {
        frame.insert("command", Value::from(c.name.clone()));
    }
    if let Some(si) = si {
        let outer = protocol_dynamic::Fields::new();
        frame.insert("payload", Value::Struct(random_struct(p, si, &outer, rng)));
    }
    codec.encode(&Value::Struct(frame)).ok().map(|e| e.bytes)
}

/// The low `width` bits set.
fn mask(width: u32) -> u64 {
    if width >= 64 {
        u64::MAX
    } else {
        (1u64 << width) - 1
    }
}

/// A random value of struct `si`, field by field: lengths that agree with the fields that
/// state them (`outer`: the fields of the struct that repeats this one), text without NUL,
/// enums mostly variants, scaled values from a random raw integer, optional fields present
/// or not.
fn random_struct(
    p: &Protocol,
    si: usize,
    outer: &protocol_dynamic::Fields,
    rng: &mut Rng,
) -> protocol_dynamic::Fields {
    let mut out = protocol_dynamic::Fields::new();
    for f in &p.structs[si].fields {
        random_field(p, &f.name, &f.kind, outer, &mut out, rng);
    }
    out
}

/// A text's value as the codec gives it: a string when it is UTF-8, else its bytes.
fn text_value(bytes: Vec<u8>) -> Value {
    match String::from_utf8(bytes) {
        Ok(s) => Value::from(s),
        Err(e) => Value::Array(
            e.into_bytes()
                .iter()
                .map(|&b| Value::UInt(u64::from(b)))
                .collect(),
        ),
    }
}

/// The length a field states for sized bytes or an array of at most `max`: the value of
/// field `size` (of this struct, else of the struct that repeats it), set to a random length
/// when this struct holds it.
fn stated_len(
    size: &Option<String>,
    max: usize,
    outer: &protocol_dynamic::Fields,
    out: &mut protocol_dynamic::Fields,
    rng: &mut Rng,
) -> usize {
    let len = rng.below(max + 1);
    match size {
        Some(n) if out.get(n).is_some() => {
            out.insert(n.clone(), Value::from(len));
            len
        }
        Some(n) => outer
            .get(n)
            .and_then(Value::as_u64)
            .map_or(len, |v| v as usize),
        None => len,
    }
}

/// The elements of an array counted by the set bits of the mask `mask` (a field of `out`,
/// random already): its set bits, the highest cleared while there are more than `max`.
fn mask_len(mask: &str, max: usize, out: &mut protocol_dynamic::Fields) -> usize {
    let mut bits = out.get(mask).and_then(Value::as_u64).unwrap_or(0);
    while bits.count_ones() as usize > max {
        bits &= !(1u64 << (63 - bits.leading_zeros()));
    }
    out.insert(mask.to_string(), Value::UInt(bits));
    bits.count_ones() as usize
}

fn random_field(
    p: &Protocol,
    name: &str,
    kind: &protocol_spec::ir::FieldKind,
    outer: &protocol_dynamic::Fields,
    out: &mut protocol_dynamic::Fields,
    rng: &mut Rng,
) {
    use protocol_spec::ir::{FieldKind, Prim};
    match kind {
        FieldKind::Padding | FieldKind::Check(_) => {}
        FieldKind::Value { ty, count } => {
            let v = match count {
                None => random_elem(p, ty, rng),
                Some(n) => Value::Array((0..*n).map(|_| random_elem(p, ty, rng)).collect()),
            };
            out.insert(name.to_string(), v);
        }
        FieldKind::Bits { members, .. } | FieldKind::BitStream { members } => {
            for m in members {
                let bits = rng.next() & mask(m.width);
                // A signed member's value is its bits as two's complement of its width; a
                // scaled member's the physical value of that raw integer.
                let raw = if m.prim.is_signed() {
                    protocol_runtime::bitstream::sign_extend(bits, m.width) as f64
                } else {
                    bits as f64
                };
                let v = match (m.enum_index, &m.scale) {
                    (Some(ei), _) => random_enum(p, ei, bits, rng),
                    (None, Some(sc)) => Value::F64(raw * sc.factor + sc.offset),
                    (None, None) if m.prim == Prim::Bool => Value::Bool(bits != 0),
                    (None, None) if m.prim.is_signed() => {
                        Value::Int(protocol_runtime::bitstream::sign_extend(bits, m.width))
                    }
                    (None, None) => Value::UInt(bits),
                };
                out.insert(m.name.clone(), v);
            }
        }
        FieldKind::Bytes {
            max,
            size_from,
            text,
        } => {
            let len = stated_len(size_from, *max, outer, out, rng);
            let bytes: Vec<u8> = (0..len).map(|_| rng.byte()).collect();
            let v = if *text {
                // Any byte is text (a NUL too); mostly printable ASCII, so the value is
                // often a string.
                let bytes = bytes
                    .iter()
                    .map(|&b| if b < 0xC0 { 0x20 + b % 0x5F } else { b - 0xC0 })
                    .collect();
                text_value(bytes)
            } else {
                Value::Bytes(bytes)
            };
            out.insert(name.to_string(), v);
        }
        FieldKind::Array {
            ty,
            max,
            size_from: Some(m),
            by_mask: true,
        } => {
            let len = mask_len(m, *max, out);
            let items = (0..len).map(|_| random_elem(p, ty, rng)).collect();
            out.insert(name.to_string(), Value::Array(items));
        }
        FieldKind::When { kind, mask, bit } => {
            let bits = out.get(mask).and_then(Value::as_u64).unwrap_or(0);
            if protocol_runtime::field::mask_bit(bits, *bit) {
                random_field(p, name, kind, outer, out, rng);
            } else {
                out.insert(name.to_string(), Value::Null);
            }
        }
        FieldKind::Array {
            ty, max, size_from, ..
        } => {
            let len = stated_len(size_from, *max, outer, out, rng);
            let items = (0..len).map(|_| random_elem(p, ty, rng)).collect();
            out.insert(name.to_string(), Value::Array(items));
        }
        FieldKind::NulText { max } => {
            let len = rng.below(max + 1);
            // Printable ASCII, now and then a control character, a backslash or a byte that
            // is not UTF-8 (given as byte values).
            let bytes: Vec<u8> = (0..len)
                .map(|_| match rng.below(16) {
                    0 => 1 + rng.below(255) as u8,
                    1 => b'\\',
                    _ => 0x20 + rng.below(0x5F) as u8,
                })
                .collect();
            out.insert(name.to_string(), text_value(bytes));
        }
        FieldKind::Group { elem, max } => {
            let count = rng.below(max.min(&8) + 1);
            let items = (0..count)
                .map(|_| Value::Struct(random_struct(p, *elem, out, rng)))
                .collect();
            out.insert(name.to_string(), Value::Array(items));
        }
        FieldKind::Packed {
            count, bits, scale, ..
        } => {
            let items = (0..*count)
                .map(|_| {
                    let raw = rng.next() & mask(*bits);
                    match scale {
                        Some(sc) => Value::F64(raw as f64 * sc.factor + sc.offset),
                        None => Value::UInt(raw),
                    }
                })
                .collect();
            out.insert(name.to_string(), Value::Array(items));
        }
        FieldKind::Optional(inner) => {
            if rng.below(2) == 0 {
                random_field(p, name, inner, outer, out, rng);
            } else {
                match &**inner {
                    FieldKind::Bits { members, .. } | FieldKind::BitStream { members } => {
                        for m in members {
                            out.insert(m.name.clone(), Value::Null);
                        }
                    }
                    _ => out.insert(name.to_string(), Value::Null),
                }
            }
        }
    }
}

/// A random element of a value field.
fn random_elem(p: &Protocol, ty: &protocol_spec::ir::ValueType, rng: &mut Rng) -> Value {
    use protocol_spec::ir::{Prim, ValueType};
    match ty {
        ValueType::Scalar { scalar, scale } => {
            let width = 8 * scalar.prim.size() as u32;
            let bits = rng.next() & mask(width);
            let signed = |bits: u64| {
                let shift = 64 - width;
                ((bits << shift) as i64) >> shift
            };
            match (scale, scalar.prim) {
                (Some(sc), Prim::F16 | Prim::F32 | Prim::F64) => {
                    let raw = match scalar.prim {
                        Prim::F16 => f64::from(protocol_runtime::wire::f16_to_f32(bits as u16)),
                        Prim::F32 => f64::from(f32::from_bits(bits as u32)),
                        _ => f64::from_bits(bits),
                    };
                    Value::F64(raw * sc.factor + sc.offset)
                }
                (Some(sc), prim) => {
                    let raw = if prim.is_signed() {
                        signed(bits) as f64
                    } else {
                        bits as f64
                    };
                    Value::F64(raw * sc.factor + sc.offset)
                }
                (None, prim) if prim.is_bool() => Value::Bool(bits & 1 != 0),
                (None, Prim::F16) => Value::F32(protocol_runtime::wire::f16_to_f32(bits as u16)),
                (None, Prim::F32) => Value::F32(f32::from_bits(bits as u32)),
                (None, Prim::F64) => Value::F64(f64::from_bits(bits)),
                (None, prim) if prim.is_signed() => Value::Int(signed(bits)),
                (None, _) => Value::UInt(bits),
            }
        }
        ValueType::Struct(si) => {
            let outer = protocol_dynamic::Fields::new();
            Value::Struct(random_struct(p, *si, &outer, rng))
        }
        ValueType::Enum(ei, scalar) => {
            let bits = rng.next() & mask(8 * scalar.prim.size() as u32);
            random_enum(p, *ei, bits, rng)
        }
        ValueType::Text(n) => {
            let len = rng.below(*n + 1);
            Value::from(
                (0..len)
                    .map(|_| char::from(0x20 + rng.below(0x5F) as u8))
                    .collect::<String>(),
            )
        }
    }
}

/// A variant's name (three times in four), else the raw bits `bits`.
fn random_enum(p: &Protocol, ei: usize, bits: u64, rng: &mut Rng) -> Value {
    let e = &p.enums[ei];
    if rng.below(4) != 0 && !e.variants.is_empty() {
        let v = &e.variants[rng.below(e.variants.len())];
        return Value::from(v.name.clone());
    }
    Value::UInt(bits)
}

/// Writes the dispatch key of `c` (of a CAN format: its CAN id).
fn write_key(f: &Frame, c: &Cmd, frame: &mut [u8]) {
    if let (Transport::Can { .. }, Some(id)) = (f.transport, c.can_id) {
        let v = f
            .values
            .iter()
            .find(|v| v.name == "can_id")
            .expect("a CAN id");
        word_field(v).write(frame, id).expect("CAN id");
        return;
    }
    for (&vi, &id) in f.dispatch.iter().zip(&c.id) {
        let v = &f.values[vi];
        let id = id & (u64::MAX >> (64 - v.width));
        word_field(v).write(frame, id).expect("dispatch value");
    }
}

/// Writes `sender` (an address of the direction's set, or the value it equals).
fn write_direction(f: &Frame, d: &Direction, sender: u64, frame: &mut [u8]) {
    let (DirectionRule::InSet { value, .. } | DirectionRule::Equals { value, .. }) = &d.rule else {
        return;
    };
    word_field(&f.values[*value])
        .write(frame, sender)
        .expect("direction value");
}

/// Frames of format `fi` at the edges of the field rules, for every command (and direction):
/// the payload's bytes all zero and all `0xFF` (every field's smallest and largest raw value,
/// or none of an enum's variants; a flag trailer's flag clear and set), at the struct's size
/// and at one byte (a payload a sender cut short of its trailing zeros keeps its first byte).
fn edge_frames(p: &Protocol, codec: &Codec<'_>, fi: usize) -> Vec<Vec<u8>> {
    let f = &p.frames[fi];
    let mut out = Vec::new();
    for (c, slot, si) in format_slots(p, fi) {
        let size = after_header(p, f, c, slot, struct_sizes(p, f, si).1);
        for (fill, payload) in [(0x00, size), (0xFF, size), (0x00, size.min(1))] {
            let mut frame = vec![fill; frame_len(f, payload)];
            if let Some(&lead) = f.sync_set.first() {
                frame[0] = lead;
            }
            if let Some(c) = c {
                write_key(f, c, &mut frame);
            }
            if let Some(d) = p.directions.get(slot).filter(|_| fi == 0) {
                let sender = match &d.rule {
                    DirectionRule::InSet { set, .. } => Some(p.addresses[*set].first),
                    DirectionRule::Equals { equals, .. } => Some(*equals),
                    // Nothing in the frame tells a direction the decoder is given.
                    DirectionRule::Given => None,
                };
                if let Some(sender) = sender {
                    write_direction(f, d, sender, &mut frame);
                }
            }
            out.extend(sealed(codec, fi, frame, &mut || fill));
        }
    }
    // The bare header, all zero and all `0xFF`, where the format has one.
    if let Some(bare) = f.bare_len {
        for fill in [0x00, 0xFF] {
            let mut frame = vec![fill; bare];
            if let Some(&lead) = f.sync_set.first() {
                frame[0] = lead;
            }
            out.extend(sealed(codec, fi, frame, &mut || fill));
        }
    }
    out
}

/// The frames with faults between and in them: garbage (stray sync bytes of the formats
/// `formats` among it), flipped bits, cut frames.
fn faulty_stream(p: &Protocol, formats: &[usize], frames: &[Vec<u8>], rng: &mut Rng) -> Vec<u8> {
    let mut out = Vec::new();
    for frame in frames {
        let f = &p.frames[formats[rng.below(formats.len())]];
        match rng.below(12) {
            0 => out.extend((0..rng.below(9)).map(|_| rng.next() as u8)),
            1 if f.sync_set.is_empty() => {
                out.extend_from_slice(&f.sync[..1 + rng.below(f.sync.len())]);
            }
            1 => {
                // A byte of the sync set and a prefix of the sync bytes after it.
                out.push(f.sync_set[rng.below(f.sync_set.len())]);
                out.extend_from_slice(&f.sync[..rng.below(f.sync.len() + 1)]);
            }
            _ => {}
        }
        let mut frame = frame.clone();
        match rng.below(10) {
            0 => {
                let bit = rng.below(frame.len() * 8);
                frame[bit / 8] ^= 1 << (bit % 8);
            }
            1 => frame.truncate(1 + rng.below(frame.len() - 1)),
            _ => {}
        }
        out.extend_from_slice(&frame);
    }
    out
}

/// The CAN frame a virtual frame (id, length, data) of format `f` stands for.
fn can_frame(f: &Frame, virt: &[u8]) -> CanFrame {
    let frame = CanFrame::from_virtual(virt).expect("a CAN frame");
    match f.transport {
        Transport::Can { extended: true } => frame.into_extended(),
        _ => CanFrame {
            extended: false,
            ..frame
        },
    }
}

/// The C prefixes of frame format `fi`'s items, as the C printer names them.
fn prefixes(p: &Protocol, fi: usize) -> (String, String) {
    let lo = if fi == 0 {
        format!("{}_", p.name)
    } else {
        format!("{}_{}_", p.name, p.frames[fi].name)
    };
    (lo.clone(), lo.to_uppercase())
}

// ---- The C side ----

/// The C compilers found on PATH, by name.
fn compilers() -> Vec<&'static str> {
    ["gcc", "clang"]
        .into_iter()
        .filter(|cc| {
            Command::new(cc)
                .arg("--version")
                .output()
                .is_ok_and(|o| o.status.success())
        })
        .collect()
}

const STRICT: &[&str] = &["-std=c99", "-Wall", "-Wextra", "-Wpedantic", "-Werror"];

fn run_cc(cc: &str, args: &[&str], dir: &Path) {
    let out = Command::new(cc)
        .args(STRICT)
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap_or_else(|e| panic!("{cc}: {e}"));
    assert!(
        out.status.success(),
        "{cc} {args:?} failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Builds the driver with the spec's C code, sanitized, and checks the code compiles
/// cleanly with every compiler found.
fn build(p: &Protocol, files: &protocol_codegen::c::CFiles, dir: &Path) -> PathBuf {
    std::fs::write(dir.join(&files.header_name), &files.header).unwrap();
    std::fs::write(dir.join(&files.source_name), &files.source).unwrap();
    std::fs::copy(
        root().join("protocol-cli/tests/c_peer/driver.c"),
        dir.join("driver.c"),
    )
    .unwrap();
    let list = |items: Vec<(usize, String, String)>| -> String {
        items
            .into_iter()
            .map(|(i, lo, up)| format!(" X({i}, {lo}, {up})"))
            .collect()
    };
    let formats = (0..p.frames.len())
        .map(|fi| {
            let (lo, up) = prefixes(p, fi);
            (fi, lo, up)
        })
        .collect();
    let can_formats = (0..p.frames.len())
        .filter(|&fi| p.frames[fi].transport != Transport::Serial)
        .map(|fi| {
            let (lo, up) = prefixes(p, fi);
            (fi, lo, up)
        })
        .collect();
    let given = if p.directions_given() {
        let (lo, up) = prefixes(p, 0);
        vec![(0, lo, up)]
    } else {
        Vec::new()
    };
    let decoders: Vec<(usize, String, String)> = decoders(p)
        .into_iter()
        .enumerate()
        .map(|(di, d)| match d {
            Decoder::Format(fi) => {
                let (lo, up) = prefixes(p, fi);
                (di, lo, up)
            }
            Decoder::Link => (
                di,
                format!("{}_any_", p.name),
                format!("{}_ANY_", p.name.to_uppercase()),
            ),
        })
        .collect();
    // Per format, whether it escapes its bytes, and how its frames on the wire are unescaped.
    let mut escaped = String::new();
    for (fi, f) in p.frames.iter().enumerate() {
        let (lo, _) = prefixes(p, fi);
        let unescape = if f.escape.is_some() {
            format!("{lo}unescape(w, n, o, c)")
        } else {
            "((void)(w), (void)(n), (void)(o), (void)(c), -1)".into()
        };
        let _ = writeln!(
            escaped,
            "#define ESCAPED_{fi} {}\n#define UNESCAPE_{fi}(w, n, o, c) {unescape}",
            u8::from(f.escape.is_some())
        );
    }
    if decoders.is_empty() {
        escaped.push_str("#define NO_DECODERS\n");
    }
    std::fs::write(
        dir.join("spec.h"),
        format!(
            "#include \"{}\"\n#define P(x) {}_##x\n#define U(x) {}_##x\n#define FORMATS(X){}\n#define CAN_FORMATS(X){}\n#define GIVEN(X){}\n#define DECODERS(X){}\n{escaped}",
            files.header_name,
            p.name,
            p.name.to_uppercase(),
            list(formats),
            list(can_formats),
            list(given),
            list(decoders)
        ),
    )
    .unwrap();
    std::fs::write(dir.join("carried.h"), carried_header(p)).unwrap();
    let with_format = format!("-D{}_WITH_FORMAT", p.name.to_uppercase());
    let compilers = compilers();
    assert!(
        !compilers.is_empty(),
        "no C compiler (gcc or clang) on PATH"
    );
    for cc in &compilers {
        run_cc(
            cc,
            &["-c", "-O2", &files.source_name, "-o", "/dev/null"],
            dir,
        );
        run_cc(
            cc,
            &[
                "-c",
                "-O2",
                &with_format,
                &files.source_name,
                "-o",
                "/dev/null",
            ],
            dir,
        );
    }
    let exe = dir.join("driver");
    run_cc(
        compilers[0],
        &[
            "-O1",
            "-g",
            "-fsanitize=address,undefined",
            "-fno-sanitize-recover=all",
            &with_format,
            "driver.c",
            &files.source_name,
            "-o",
            "driver",
        ],
        dir,
    );
    exe
}

/// `carried.h`: per format FI, `carried_FI()`, which reads each packet a decoded packet's
/// carrying fields carry with the C's reader, and prints it by the text form of the format it
/// is read into (`carried ok TEXT`) or its error (`carried err NAME`).
fn carried_header(p: &Protocol) -> String {
    let mut out = String::new();
    let target = protocol_codegen::c::carried_format(p);
    for fi in 0..p.frames.len() {
        let (lo, _) = prefixes(p, fi);
        let mut body = String::new();
        let Some(to) = target else {
            writeln!(
                out,
                "static void carried_{fi}(const {lo}packet *pk) {{ (void)pk; }}"
            )
            .unwrap();
            continue;
        };
        let (tlo, _) = prefixes(p, to);
        for &ci in &p.frames[fi].commands {
            let c = &p.commands[ci];
            for (di, si) in c.payloads.iter().enumerate() {
                let Some(s) = si.map(|si| &p.structs[si]) else {
                    continue;
                };
                let (member, test) = match p.directions.get(di) {
                    Some(d) => (
                        format!("{}_{}", c.name.to_lowercase(), d.name),
                        format!(
                            "pk->command == U({}) && pk->direction == U({})",
                            c.name,
                            d.name.to_uppercase()
                        ),
                    ),
                    None => (
                        c.name.to_lowercase(),
                        format!("pk->command == U({})", c.name),
                    ),
                };
                let direction = if p.directions.is_empty() {
                    ""
                } else {
                    "pk->direction, "
                };
                for carried in &s.carries {
                    let reader = protocol_codegen::c::carried_reader(p, s, carried);
                    writeln!(
                        body,
                        "    if ({test}) {{\n        e = {reader}(&pk->payload.{member}, {direction}&out);\n        if (e != 0) {{\n            printf(\"carried err %s\\n\", err_name(e));\n        }} else {{\n            {tlo}format(&out, text, sizeof text);\n            printf(\"carried ok %s\\n\", text);\n        }}\n    }}"
                    )
                    .unwrap();
                }
            }
        }
        if body.is_empty() {
            writeln!(
                out,
                "static void carried_{fi}(const {lo}packet *pk) {{ (void)pk; }}"
            )
            .unwrap();
        } else {
            writeln!(
                out,
                "static void carried_{fi}(const {lo}packet *pk)\n{{\n    static {tlo}packet out;\n    int e = 0;\n{body}    (void)e;\n}}"
            )
            .unwrap();
        }
    }
    out
}

fn run_driver(exe: &Path, input: &str) -> Vec<String> {
    let mut child = Command::new(exe)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the driver runs");
    let mut stdin = child.stdin.take().expect("stdin");
    let input = input.to_string();
    let writer = std::thread::spawn(move || stdin.write_all(input.as_bytes()));
    let out = child.wait_with_output().expect("the driver ends");
    writer.join().expect("writer").expect("input written");
    assert!(
        out.status.success(),
        "the driver failed: {}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout)
        .expect("utf-8")
        .lines()
        .map(String::from)
        .collect()
}

/// What was compared for a spec.
#[derive(Default)]
struct Tally {
    vector_frames: usize,
    can_frames: usize,
    vector_streams: usize,
    chunkings: usize,
    random_frames: usize,
    /// Random frames the Rust codec decodes (the others are errors, compared too).
    random_decoded: usize,
    edge_frames: usize,
    stream_bytes: usize,
}

/// Compares the C driver's output for `input` with the Rust lines, command by command.
fn compare(spec: &str, exe: &Path, input: &str, expected: Vec<Vec<String>>) {
    let got = run_driver(exe, input);
    let mut got = got.split(|l| l == "end");
    for (i, want) in expected.into_iter().enumerate() {
        let mut want = normalize(want);
        want.pop(); // "end"
        let have = normalize(got.next().unwrap_or_default().to_vec());
        if have != want {
            let command = input.lines().nth(i).unwrap_or_default();
            let at = have.iter().zip(&want).take_while(|(a, b)| a == b).count();
            panic!(
                "{spec}: C and Rust differ on `{}` at its line {at}:\n  C:    {:?}\n  Rust: {:?}\n({} lines from C, {} from Rust)",
                &command[..command.len().min(120)],
                have.get(at),
                want.get(at),
                have.len(),
                want.len()
            );
        }
    }
}

/// A frame of serial format `fi` for the driver: decoded (`P`), and for a spec whose decoder is
/// given the direction, decoded as sent in each direction (`D`, `given` holding a codec per
/// direction).
fn push_frame(
    input: &mut String,
    expected: &mut Vec<Vec<String>>,
    codec: &Codec<'_>,
    given: &[Codec<'_>],
    fi: usize,
    bytes: &[u8],
) {
    writeln!(input, "P {fi} {}", hex(bytes)).unwrap();
    expected.push(rust_frame(codec, fi, bytes));
    if fi == 0 {
        for (d, codec) in given.iter().enumerate() {
            writeln!(input, "D {fi} {d} {}", hex(bytes)).unwrap();
            expected.push(rust_frame(codec, fi, bytes));
        }
    }
}

/// Compares the C peer with the Rust codec on one spec; returns the spec's path as shown and
/// what was compared (or why the C generator refused it).
fn check_spec(path: &Path, random_frames: usize) -> (String, String) {
    let shown = path
        .strip_prefix(root())
        .unwrap_or(path)
        .display()
        .to_string();
    let interp = Interpreter::load(path).expect("a valid spec");
    let p = interp.protocol();
    // The C peer's structs hold a carrying field's bytes, as the Rust structs do: compared
    // with the codec's view of the same bytes.
    let codec = interp.codec().with_carried_packets(false);
    let files = match protocol_codegen::c::generate(p) {
        Ok(files) => files,
        Err(refused) => return (shown, format!("refused: {}", refused.join("; "))),
    };
    let dir = tempfile::tempdir().expect("a temporary directory");
    let exe = build(p, &files, dir.path());
    let mut tally = Tally::default();
    let (mut input, mut expected) = (String::new(), Vec::new());

    let serial: Vec<usize> = (0..p.frames.len())
        .filter(|&fi| p.frames[fi].transport == Transport::Serial)
        .collect();
    let can_formats: Vec<usize> = (0..p.frames.len())
        .filter(|&fi| p.frames[fi].transport != Transport::Serial)
        .collect();
    // For a spec whose decoder is given the direction, a codec per direction.
    let given: Vec<Codec<'_>> = if p.directions_given() {
        (0..p.directions.len())
            .map(|d| {
                let codec = interp.codec().with_carried_packets(false);
                codec.with_direction(Some(d))
            })
            .collect()
    } else {
        Vec::new()
    };
    let decoders = decoders(p);

    // Golden vectors: frames (by every serial format; CAN frames by every CAN format), then
    // streams at every chunk size through every stream decoder.
    for (file, primary) in vector_files(&p.name) {
        let text = std::fs::read_to_string(root().join("tests/vectors").join(&file)).unwrap();
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        for frame in v["frames"].as_array().into_iter().flatten() {
            if let Some(h) = frame["hex"].as_str().or(frame["uart"]["hex"].as_str()) {
                let bytes = unhex(h);
                for &fi in &serial {
                    push_frame(&mut input, &mut expected, &codec, &given, fi, &bytes);
                }
                tally.vector_frames += 1;
            }
            // A CAN frame as `can: { can_id, data_hex }`, or as `can_id` and `data` beside the
            // frame's values.
            let can = &frame["can"];
            let id = can["can_id"].as_u64().or(frame["can_id"].as_u64());
            if let (Some(id), Some(h)) = (id, can["data_hex"].as_str().or(frame["data"].as_str())) {
                for &fi in &can_formats {
                    let extended =
                        matches!(p.frames[fi].transport, Transport::Can { extended: true });
                    let mut c = CanFrame::new(id as u32, &unhex(h)).expect("a CAN frame");
                    c.extended = extended;
                    writeln!(input, "C {fi} {} {id} {h}", u8::from(extended)).unwrap();
                    expected.push(rust_can(&codec, fi, &c));
                }
                tally.can_frames += 1;
            }
        }
        for s in v["streams"].as_array().into_iter().flatten() {
            let Some(h) = s["hex"].as_str() else { continue };
            let data = unhex(h);
            tally.vector_streams += 1;
            for (di, &d) in decoders.iter().enumerate() {
                let formats = match d {
                    Decoder::Format(fi) => vec![fi],
                    Decoder::Link => p.link.clone(),
                };
                // The expected frames a decoder finds: those of its formats.
                let want: Vec<String> = s["expected_frames"]
                    .as_array()
                    .into_iter()
                    .flatten()
                    .filter_map(|f| {
                        let hex = f["hex"].as_str().unwrap_or("");
                        let bytes = unhex(hex);
                        formats
                            .iter()
                            .any(|&fi| codec.layout(fi).is_some_and(|l| l.sync_matches(&bytes)))
                            .then(|| format!("{} {hex}", f["offset"]))
                    })
                    .collect();
                for chunk in 1..=data.len() {
                    writeln!(input, "S {di} {chunk} {h}").unwrap();
                    let lines = rust_stream(&codec, d, chunk, &data);
                    if primary {
                        let frames: Vec<String> = lines
                            .iter()
                            .filter_map(|l| l.strip_prefix("frame "))
                            .map(|l| l.split(' ').take(2).collect::<Vec<_>>().join(" "))
                            .collect();
                        assert_eq!(frames, want, "{}: {file} stream at chunk {chunk}", p.name);
                    }
                    expected.push(lines);
                    tally.chunkings += 1;
                }
            }
        }
    }

    // Random and edge frames of every format, then the fault-injection stream of each
    // decoder's formats' random frames at several chunk sizes.
    let bias = bias(p);
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15 ^ p.name.len() as u64, bias);
    let mut frames: Vec<Vec<Vec<u8>>> = Vec::new();
    for fi in 0..p.frames.len() {
        let of_format: Vec<Vec<u8>> = (0..random_frames)
            .map(|_| random_frame(p, &codec, fi, &mut rng))
            .collect();
        let edges = edge_frames(p, &codec, fi);
        for (i, frame) in of_format.iter().chain(&edges).enumerate() {
            let f = &p.frames[fi];
            let at = expected.len();
            if f.transport == Transport::Serial {
                push_frame(&mut input, &mut expected, &codec, &given, fi, frame);
            } else {
                let c = can_frame(f, frame);
                writeln!(
                    input,
                    "C {fi} {} {} {}",
                    u8::from(c.extended),
                    c.id,
                    hex(c.data())
                )
                .unwrap();
                expected.push(rust_can(&codec, fi, &c));
            }
            // Decoded by one of its decoders (where the decoder is given the direction, the
            // frame's own).
            if i < of_format.len() && expected[at..].iter().any(|l| l[0].starts_with("ok ")) {
                tally.random_decoded += 1;
            }
        }
        tally.random_frames += of_format.len();
        tally.edge_frames += edges.len();
        frames.push(of_format);
    }
    for (di, d) in decoders.iter().enumerate() {
        let formats = match d {
            Decoder::Format(fi) => vec![*fi],
            Decoder::Link => p.link.clone(),
        };
        // The formats' frames, mixed.
        let mut mixed: Vec<Vec<u8>> = formats.iter().flat_map(|&fi| frames[fi].clone()).collect();
        for i in (1..mixed.len()).rev() {
            mixed.swap(i, rng.below(i + 1));
        }
        let stream = faulty_stream(p, &formats, &mixed, &mut rng);
        tally.stream_bytes += stream.len();
        for chunk in [1, 17, 1000, stream.len()] {
            writeln!(input, "S {di} {chunk} {}", hex(&stream)).unwrap();
            expected.push(rust_stream(&codec, *d, chunk, &stream));
        }
    }
    compare(&p.name, &exe, &input, expected);
    let mut what = format!(
        "C matches Rust: {} vector frames, {} vector streams, {} random frames ({} decoded), {} edge frames",
        tally.vector_frames,
        tally.vector_streams,
        tally.random_frames,
        tally.random_decoded,
        tally.edge_frames,
    );
    if decoders.is_empty() {
        what.push_str(", no stream decoder");
    } else {
        let _ = write!(
            what,
            ", a {}-byte fault-injection stream",
            tally.stream_bytes
        );
    }
    let mut more = Vec::new();
    if p.frames.len() > 1 {
        more.push(format!(
            "{} frame formats, {} stream decoders",
            p.frames.len(),
            decoders.len()
        ));
    }
    if !can_formats.is_empty() {
        more.push(format!("{} CAN vector frames", tally.can_frames));
    }
    if !more.is_empty() {
        let _ = write!(what, " ({})", more.join(", "));
    }
    eprintln!(
        "{}: {} vector frames, {} CAN vector frames, {} vector streams at {} chunkings, {} random frames, {} edge frames, {} stream bytes at 4 chunkings",
        p.name,
        tally.vector_frames,
        tally.can_frames,
        tally.vector_streams,
        tally.chunkings,
        tally.random_frames,
        tally.edge_frames,
        tally.stream_bytes
    );
    (shown, what)
}

#[test]
fn c_peer_matches_the_rust_codec() {
    // The specs are independent (each in its own temporary directory): one worker per core
    // takes the next spec until none is left, since each spends most of its time in the C
    // compilers, its sanitized driver and the unoptimised Rust codec, one core each.
    let specs = specs();
    let next = AtomicUsize::new(0);
    let workers = std::thread::available_parallelism().map_or(1, |n| n.get());
    let support: BTreeMap<String, String> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..workers.min(specs.len()))
            .map(|_| {
                scope.spawn(|| {
                    let mut done = Vec::new();
                    while let Some((path, random_frames)) =
                        specs.get(next.fetch_add(1, Ordering::Relaxed))
                    {
                        done.push(check_spec(path, *random_frames));
                    }
                    done
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| {
                h.join()
                    .expect("a spec's comparison failed (its message is above)")
            })
            .collect()
    });
    let table: String = support
        .iter()
        .map(|(spec, what)| format!("{spec}: {what}\n"))
        .collect();
    insta::assert_snapshot!("c_support", table);
}
