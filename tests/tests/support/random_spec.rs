//! A seeded generator of valid specs: from a seed, the TOML text of a spec that combines the
//! language's parts at random, so that the backends are compared on specs no one wrote by
//! hand. It owns the choice of a spec's shape ([`Shape`]: which frame formats, directions and
//! framing rules go together) and the spec's named parts (constants, addresses, checksums,
//! enums, structs); the fields of a struct are written by `random_spec/fields.rs`, the frame
//! formats by `random_spec/frames.rs` (with a format's escaping: `random_spec/escape.rs`), the
//! directions and commands by `random_spec/commands.rs`.
//!
//! What a spec may hold: one to three serial command formats on one link (`commands = true`,
//! `extensions = false`), a CAN format (standard or extended ids, the data length bounded by
//! the payload's `min` and `max`) and a format carrying one struct (`message`) besides them;
//! directions told by a header field (`equals`, or an address set with `in`) or given to the
//! decoder (one of them carrying a struct in place of a command); sync bytes or a sync set
//! (`one_of`); header fields in any order (a length counting the payload, the frame or a run,
//! a length that is a bit member, a length that a marker value extends, a dispatch key of one
//! or two fields, a
//! sequence number or frame counter, a constant, bit members with constant and flag bits); a
//! header check; a check stored before the payload it covers; a frame check of every built-in
//! kind, a catalogue CRC or a `[checksums]` CRC (of 8, 16 or 32 bits, or of another width:
//! 5, 12, 24, 40), sum (seeded with `init` or not) or XOR (seeded), with a lookup-table size
//! and a byte folded in per command (`extra`); a field after
//! the payload, a trailer, optional bytes after the checks; acknowledgements, bare headers,
//! byte stuffing, byte escaping between flags (the XOR form or a table) and trailing-zero
//! truncation. Payload structs take every fixed-size field kind
//! (integers of 8 to 64 bits with a byte order, 40, 48 and 56 bits among them, floats and
//! halves, bools (inverted too), arrays sized by a number or a constant, enums that keep or reject unknown
//! values, scaled, clamped and rounded values, scaled floats, bit
//! members (signed and scaled among them), bit streams, bit-packed arrays, fixed and NUL-terminated text, nested structs, padding), bytes
//! and arrays sized by an earlier field, checks inside a payload (with a CRC prefix), extension
//! fields and a variable tail (bytes, text without a terminator, repeated integers or structs,
//! an optional value). A
//! `[session]` table (answer, timeout, retries, backoff, sequence field, handshake, watchdog,
//! a command answered once by each id its payload lists) changes no byte on the wire: the front end validates it, generated code holds it.
//!
//! A shape never combines what the language refuses (`docs/spec-format.md`, "Not yet
//! expressible" and each feature's rules): the front end accepts every spec this writes, and
//! `protocol-spec/tests/random_specs.rs` checks that on a large batch.
//!
//! Plain `std`, no dependencies: the tests crate's build script expands a batch of these specs
//! with `protocol!` (`tests/build.rs`), and the C peer's conformance test compiles the C that
//! `protocol gen c` prints for the same seeds (`protocol-cli/tests/it/c_peer.rs`). The same seed
//! gives the same text, so a failure names its seed and the spec is written out as a fixture.
//! The C printer refuses escaped formats (`protocol gen c` says so), so the C peer's test counts
//! those specs as refused and compares the others.
#![allow(dead_code)]

#[path = "random_spec/commands.rs"]
mod commands;
#[path = "random_spec/escape.rs"]
mod escape;
#[path = "random_spec/fields.rs"]
mod fields;
#[path = "random_spec/frames.rs"]
mod frames;
#[path = "random_spec/session.rs"]
mod session;

use std::fmt::Write as _;

/// SplitMix64, as the robustness harness uses: seedable and small.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A value in `0..n` (0 when `n` is 0).
    fn below(&mut self, n: u64) -> u64 {
        if n <= 1 { 0 } else { self.next() % n }
    }

    fn range(&mut self, lo: u64, hi: u64) -> u64 {
        lo + self.below(hi - lo + 1)
    }

    fn one_in(&mut self, n: u64) -> bool {
        self.below(n) == 0
    }

    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len() as u64) as usize]
    }
}

/// An integer wire type: its spec name without byte order, its size, whether it is signed.
#[derive(Clone, Copy)]
struct Int {
    name: &'static str,
    size: usize,
    signed: bool,
}

const fn int(name: &'static str, size: usize, signed: bool) -> Int {
    Int { name, size, signed }
}

/// Unsigned and signed, by size; the first eight fit a scaled value's `f32`/`f64` exactly; the
/// last six are the widths Rust has not (`field-int-wide`).
const INTS: &[Int] = &[
    int("u8", 1, false),
    int("i8", 1, true),
    int("u16", 2, false),
    int("i16", 2, true),
    int("u24", 3, false),
    int("i24", 3, true),
    int("u32", 4, false),
    int("i32", 4, true),
    int("u64", 8, false),
    int("i64", 8, true),
    int("u40", 5, false),
    int("i40", 5, true),
    int("u48", 6, false),
    int("i48", 6, true),
    int("u56", 7, false),
    int("i56", 7, true),
];

/// The type name with a byte order suffix sometimes (multi-byte types only).
fn with_order(rng: &mut Rng, name: &str, size: usize) -> String {
    if size > 1 && rng.one_in(3) {
        format!("{name}{}", rng.pick(&["le", "be"]))
    } else {
        name.to_string()
    }
}

/// An enum of the spec: its name, wire size and the largest value a variant holds.
struct Enum {
    name: String,
    size: usize,
    signed: bool,
    max_value: u64,
}

/// A struct with a fixed wire size, usable as a nested field, and as a repeated group's
/// element when `repeatable` (no bit members, text or checks: the language refuses those in
/// an element).
struct Leaf {
    name: String,
    size: usize,
    repeatable: bool,
    /// An unscaled `u8` field of it: where an element names a device (`answers`).
    id_member: Option<String>,
}

/// A payload struct: its name, smallest and largest wire size.
#[derive(Clone)]
struct Payload {
    name: String,
    min: usize,
    max: usize,
    /// Where it lists one-byte ids at a fixed place (`tail`, `tail.l0`), for `answers`.
    ids: Option<String>,
}

/// What the spec combines, decided first: the frame formats, directions and framing rules,
/// and what they ask of the payload structs.
#[derive(Default)]
struct Shape {
    /// Serial command formats on the link (1 to 3).
    formats: usize,
    /// How directions are told, if the spec has them.
    directions: Directions,
    /// A CAN format after the serial ones: whether its ids are extended.
    can: Option<bool>,
    /// A serial format that carries one struct (`message`), after the others.
    message_format: bool,
    /// Acknowledgement frames (a one-bit header flag).
    ack: bool,
    /// Byte stuffing of the payload.
    stuffing: bool,
    /// Trailing-zero truncation: every command's struct has a fixed size.
    truncate: bool,
    /// A frame may be the header alone.
    bare: bool,
    /// Optional bytes after the checks, announced by a header flag.
    optional: bool,
    /// A length field that a marker value extends.
    marker: bool,
    /// A CRC frame check that folds in a byte per command.
    extra: bool,
    /// A dispatch key of two header fields.
    two_key: bool,
    /// A sync set (`one_of`) in place of sync bytes.
    one_of: bool,
    /// A later command format without the structs' extension fields.
    extensions_off: bool,
    /// Every payload struct has a fixed size.
    fixed_payloads: bool,
    /// The one frame format escapes its frames between flags (`escape`).
    escape: bool,
}

/// How the directions of a spec are told.
#[derive(Default, Clone, Copy, PartialEq, Eq)]
enum Directions {
    /// The spec has no directions.
    #[default]
    None,
    /// A header field equals a value per direction.
    Equals,
    /// A header field lies in an address set per direction.
    Addresses,
    /// The decoder is given the direction.
    Given,
    /// Given, and responses carry one struct in place of a command.
    GivenMessage,
}

/// The spec being written.
struct Spec {
    rng: Rng,
    out: String,
    shape: Shape,
    enums: Vec<Enum>,
    leaves: Vec<Leaf>,
    payloads: Vec<Payload>,
    /// Constants of the spec: name and value.
    constants: Vec<(String, u64)>,
    /// Checksums declared in `[checksums]`: name and whether it is a CRC.
    checksums: Vec<(String, bool)>,
    /// The language features this spec uses, for the coverage the tests report.
    features: Vec<&'static str>,
}

/// A generated spec: its text, the features it uses, and what a test harness must know to
/// drive its generated code.
pub struct Generated {
    /// The TOML text.
    pub text: String,
    /// The language features the spec uses (names of [`FEATURES`]).
    pub features: Vec<&'static str>,
    /// Whether its link has several command formats (generated code's `AnyPacket`).
    pub link: bool,
    /// Whether the decoder is given the direction (`decode_request`, ...).
    pub given: bool,
}

/// Every feature the generator can use: a large batch uses each (the coverage test checks).
pub const FEATURES: &[&str] = &[
    "constants",
    "addresses",
    "checksum-crc",
    "checksum-crc-24",
    "checksum-crc-other-width",
    "checksum-sum",
    "checksum-sum-init",
    "checksum-xor",
    "enum-keep",
    "enum-reject",
    "struct-byte-order",
    "field-int",
    "field-int-wide",
    "field-float",
    "field-f16",
    "field-bool",
    "field-bool-inverted",
    "field-array",
    "field-array-constant",
    "field-enum",
    "field-scaled",
    "field-scaled-float",
    "field-clamp",
    "field-rounding",
    "field-bits",
    "field-bits-enum",
    "field-bits-reserved-zero",
    "field-bits-signed",
    "field-bits-scaled",
    "field-bitstream",
    "field-packed",
    "field-char",
    "field-nested",
    "field-pad",
    "field-sized-bytes",
    "field-sized-array",
    "field-when",
    "field-mask-array",
    "field-payload-check",
    "field-payload-check-prefix",
    "field-extension",
    "tail-bytes",
    "tail-repeat-int",
    "tail-repeat-struct",
    "tail-cstr",
    "tail-str",
    "tail-optional",
    "tail-bytes-before-check",
    "sync",
    "sync-set",
    "length-payload",
    "length-frame",
    "length-run",
    "length-bits",
    "length-marker",
    "dispatch-u16",
    "dispatch-two-fields",
    "header-seq",
    "header-counter",
    "header-constant",
    "header-bits",
    "header-check",
    "frame-check",
    "check-table",
    "check-before-payload",
    "check-byte-order",
    "check-extra",
    "field-after-payload",
    "trailer",
    "optional-element",
    "ack",
    "bare-header",
    "stuffing",
    "escape",
    "escape-map",
    "truncate-zeros",
    "formats-several",
    "extensions-off",
    "can-standard",
    "can-extended",
    "message-format",
    "directions-equals",
    "directions-addresses",
    "directions-given",
    "directions-message",
    "session",
    "session-sequence",
    "session-handshake",
    "session-watchdog",
    "session-answers",
];

/// The TOML text of the random spec of `seed`, its protocol named `name`.
pub fn spec(seed: u64, name: &str) -> String {
    generate(seed, name).text
}

/// The random spec of `seed`, its protocol named `name`.
pub fn generate(seed: u64, name: &str) -> Generated {
    let mut rng = Rng(seed);
    let shape = Shape::pick(&mut rng);
    let mut s = Spec {
        rng,
        out: String::new(),
        shape,
        enums: Vec::new(),
        leaves: Vec::new(),
        payloads: Vec::new(),
        constants: Vec::new(),
        checksums: Vec::new(),
        features: Vec::new(),
    };
    let order = *s.rng.pick(&["little", "big"]);
    writeln!(s.out, "# A random spec (seed {seed}).").unwrap();
    writeln!(
        s.out,
        "[protocol]\nname = \"{name}\"\nbyte_order = \"{order}\"\n"
    )
    .unwrap();
    s.emit_constants();
    s.emit_checksums();
    for i in 0..s.rng.below(3) {
        s.emit_enum(i);
    }
    for i in 0..s.rng.below(3) {
        s.emit_leaf(i);
    }
    for i in 0..s.rng.range(1, 4) {
        s.emit_payload(i);
    }
    s.emit_frames_and_commands();
    s.emit_session();
    let mut features = s.features;
    features.sort_unstable();
    features.dedup();
    Generated {
        text: s.out,
        features,
        link: s.shape.formats > 1,
        given: matches!(
            s.shape.directions,
            Directions::Given | Directions::GivenMessage
        ),
    }
}

impl Shape {
    /// A shape the language accepts: each rule's exclusions are applied as it is drawn.
    fn pick(rng: &mut Rng) -> Shape {
        let mut s = Shape {
            formats: if rng.one_in(4) {
                rng.range(2, 3) as usize
            } else {
                1
            },
            ..Shape::default()
        };
        let link = s.formats > 1;
        s.directions = match rng.below(8) {
            0 => Directions::Equals,
            1 => Directions::Addresses,
            2 if !link => Directions::Given,
            3 if !link => Directions::GivenMessage,
            _ => Directions::None,
        };
        let directions = s.directions != Directions::None;
        let given_message = s.directions == Directions::GivenMessage;
        if !directions && rng.one_in(4) {
            s.can = Some(rng.one_in(2));
        }
        s.message_format = rng.one_in(6);
        s.ack = !link && !directions && rng.one_in(5);
        s.stuffing = !link && !given_message && rng.one_in(5);
        s.truncate = !s.stuffing && !given_message && rng.one_in(6);
        s.marker = !link && !s.ack && !s.stuffing && !s.truncate && !given_message && rng.one_in(6);
        s.bare = !s.marker && rng.one_in(6);
        s.optional = !s.ack && !s.bare && !s.stuffing && !s.marker && !link && rng.one_in(6);
        // A frame carrying a struct in place of a command, or an acknowledgement, has no byte
        // to fold in; the draw is made anyway so that the seeds' other choices stay as they are.
        let extra = rng.one_in(5) && !given_message;
        s.two_key = !extra && rng.one_in(5);
        s.extra = extra && !s.ack;
        s.one_of = !link && rng.one_in(6);
        s.extensions_off = link && !directions && rng.one_in(2);
        s.fixed_payloads = s.truncate || s.extensions_off;
        // Escaping is drawn from a stream of its own (the seeds' other choices stay as they
        // are), for a spec of one serial format that opens with its one sync byte, the flag,
        // and closes with it: no link, CAN or message format, stuffing, bare header, sync set
        // or optional bytes after the checks.
        let mut side = Rng(rng.0.rotate_left(29) ^ 0x0E5C_A9ED_F1A6_0001);
        let alone = s.formats == 1 && s.can.is_none() && !s.message_format;
        let delimited = !s.stuffing && !s.bare && !s.one_of && !s.optional;
        s.escape = alone && delimited && side.one_in(3);
        s
    }
}

impl Spec {
    fn feature(&mut self, name: &'static str) {
        debug_assert!(FEATURES.contains(&name), "{name} is not listed");
        self.features.push(name);
    }

    fn emit_constants(&mut self) {
        if !self.rng.one_in(3) {
            return;
        }
        self.feature("constants");
        writeln!(self.out, "[constants]").unwrap();
        for i in 0..self.rng.range(1, 2) {
            let value = self.rng.range(1, 4);
            writeln!(self.out, "N{i} = {value}").unwrap();
            self.constants.push((format!("N{i}"), value));
        }
        self.out.push('\n');
    }

    /// Checksums of `[checksums]`: a CRC of random parameters (its check value computed
    /// here; now and then of a width other than 8, 16, 32 or 64 bits, stored in the fewest
    /// bytes that hold it), a sum with a seed and a final XOR, a XOR with a seed.
    fn emit_checksums(&mut self) {
        // The choices the generator added later draw from a stream of their own, so that a
        // seed's spec keeps the parts it had.
        let mut side = self.side();
        if self.rng.one_in(3) {
            self.feature("checksum-crc");
            let mut width = *self.rng.pick(&[8u32, 16, 32]);
            if side.one_in(3) {
                // A spec integer holds 63 bits: a 64-bit CRC's parameters may not fit.
                width = *side.pick(&[24u32, 24, 5, 12, 40]);
                self.feature(if width == 24 {
                    "checksum-crc-24"
                } else {
                    "checksum-crc-other-width"
                });
            }
            let mask = if width == 64 {
                u64::MAX
            } else {
                (1 << width) - 1
            };
            let poly = (self.rng.next() & mask) | 1;
            let init = if self.rng.one_in(2) { 0 } else { mask };
            let refin = self.rng.one_in(2);
            let refout = self.rng.one_in(2);
            let xorout = if self.rng.one_in(2) { 0 } else { mask };
            let check = crc(width, poly, init, refin, refout, xorout, b"123456789");
            writeln!(
                self.out,
                "[checksums.rcrc]\ncrc = {{ width = {width}, poly = {poly:#x}, init = {init:#x}, refin = {refin}, refout = {refout}, xorout = {xorout:#x}, check = {check:#x} }}"
            )
            .unwrap();
            if self.rng.one_in(2) {
                let table = *self.rng.pick(&[0, 1, 16]);
                writeln!(self.out, "table = {table}").unwrap();
            }
            self.out.push('\n');
            self.checksums.push(("rcrc".into(), true));
        }
        if self.rng.one_in(4) {
            self.feature("checksum-sum");
            let width = *self.rng.pick(&[8u32, 16]);
            let xorout = if self.rng.one_in(2) {
                0
            } else {
                (1u64 << width) - 1
            };
            let init = if side.one_in(2) {
                self.feature("checksum-sum-init");
                format!("init = {:#x}, ", side.below(1 << width))
            } else {
                String::new()
            };
            writeln!(
                self.out,
                "[checksums.rsum]\nsum = {{ width = {width}, {init}xorout = {xorout:#x} }}\n"
            )
            .unwrap();
            self.checksums.push(("rsum".into(), false));
        }
        if side.one_in(5) {
            self.feature("checksum-xor");
            let init = side.range(1, 255);
            writeln!(self.out, "[checksums.rxor]\nxor = {{ init = {init:#x} }}\n").unwrap();
            self.checksums.push(("rxor".into(), false));
        }
    }

    /// A generator of the choices added to the language after a seed's spec was first
    /// written: seeded by the spec's stream without advancing it.
    fn side(&self) -> Rng {
        Rng(self.rng.0.rotate_left(23) ^ 0x5DEE_CE66_D1CE_4E5B)
    }

    fn emit_enum(&mut self, i: u64) {
        let name = format!("E{i}");
        let (ty, size, signed) = *self.rng.pick(&[
            ("u8", 1, false),
            ("u8", 1, false),
            ("i8", 1, true),
            ("u16", 2, false),
        ]);
        let keep = self.rng.one_in(3);
        self.feature(if keep { "enum-keep" } else { "enum-reject" });
        let count = self.rng.range(1, 5);
        let mut values = Vec::new();
        let mut v: i64 = if signed {
            -(self.rng.below(3) as i64)
        } else {
            0
        };
        for k in 0..count {
            values.push(format!("V{k} = {v}"));
            v += self.rng.range(1, 3) as i64;
        }
        writeln!(self.out, "[enums.{name}]\ntype = \"{ty}\"").unwrap();
        if keep {
            writeln!(self.out, "unknown = \"keep\"").unwrap();
        }
        writeln!(self.out, "values = {{ {} }}\n", values.join(", ")).unwrap();
        self.enums.push(Enum {
            name,
            size,
            signed,
            max_value: (v - 1).max(0) as u64,
        });
    }

    fn emit_leaf(&mut self, i: u64) {
        let name = format!("L{i}");
        let mut fields = Vec::new();
        let mut size = 0;
        let mut repeatable = true;
        let mut id_member = None;
        for k in 0..self.rng.range(1, 3) {
            let member = format!("l{k}");
            let f = self.fixed_field(&member);
            repeatable &= f.repeatable;
            if id_member.is_none() && f.text == format!("{{ name = \"{member}\", type = \"u8\" }}")
            {
                id_member = Some(member);
            }
            fields.push(f.text);
            size += f.size;
        }
        self.write_struct(&name, &fields);
        self.leaves.push(Leaf {
            name,
            size,
            repeatable,
            id_member,
        });
    }

    fn write_struct(&mut self, name: &str, fields: &[String]) {
        writeln!(self.out, "[structs.{name}]").unwrap();
        if self.rng.one_in(6) {
            self.feature("struct-byte-order");
            let order = *self.rng.pick(&["little", "big"]);
            writeln!(self.out, "byte_order = \"{order}\"").unwrap();
        }
        writeln!(self.out, "fields = [").unwrap();
        for f in fields {
            writeln!(self.out, "  {f},").unwrap();
        }
        writeln!(self.out, "]\n").unwrap();
    }
}

/// The CRC of `data` in the Rocksoft model (bit by bit, for any width from 1 to 64): what a
/// `[checksums]` CRC's `check` must be for `123456789`.
fn crc(
    width: u32,
    poly: u64,
    init: u64,
    refin: bool,
    refout: bool,
    xorout: u64,
    data: &[u8],
) -> u64 {
    let mask = if width == 64 {
        u64::MAX
    } else {
        (1 << width) - 1
    };
    let mut reg = init & mask;
    for &b in data {
        let b = if refin { b.reverse_bits() } else { b };
        for i in (0..8).rev() {
            let top = (reg >> (width - 1)) & 1;
            reg = (reg << 1) & mask;
            if top ^ u64::from((b >> i) & 1) == 1 {
                reg ^= poly & mask;
            }
        }
    }
    if refout {
        reg = reg.reverse_bits() >> (64 - width);
    }
    (reg ^ xorout) & mask
}
