//! A seeded generator of valid specs: from a seed, the TOML text of a spec that combines the
//! language's parts at random, so that the backends are compared on specs no one wrote by
//! hand. It covers one serial frame format (sync bytes, header fields in any order, a length
//! that counts the payload, the frame or a run, a header check, a frame check of the sum, xor,
//! Fletcher and CRC kinds, a trailer), both byte orders, and payload structs of every
//! fixed-size field kind (integers of 8 to 64 bits with a byte order, floats, bools, arrays,
//! enums that keep or reject unknown values, scaled and clamped values, bit members, text,
//! nested structs, padding) with a variable tail (bytes, repeated integers or structs,
//! NUL-terminated text, an optional value). Directions, several frame formats, CAN, byte
//! stuffing and acknowledgements are not generated yet.
//!
//! Plain `std`, no dependencies: the tests crate's build script expands a batch of these specs
//! with `protocol!` (`tests/build.rs`), and the C peer's conformance test compiles the C that
//! `protocol gen c` prints for the same seeds (`protocol-cli/tests/it/c_peer.rs`). The same seed
//! gives the same text, so a failure names its seed and the spec is written out as a fixture.
//!
//! Every spec must validate: a spec the front end refuses is a bug here (or in validation), and
//! the tests that call this fail on it with the diagnostics.
#![allow(dead_code)]

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

const INTS: &[Int] = &[
    Int {
        name: "u8",
        size: 1,
        signed: false,
    },
    Int {
        name: "i8",
        size: 1,
        signed: true,
    },
    Int {
        name: "u16",
        size: 2,
        signed: false,
    },
    Int {
        name: "i16",
        size: 2,
        signed: true,
    },
    Int {
        name: "u24",
        size: 3,
        signed: false,
    },
    Int {
        name: "i24",
        size: 3,
        signed: true,
    },
    Int {
        name: "u32",
        size: 4,
        signed: false,
    },
    Int {
        name: "i32",
        size: 4,
        signed: true,
    },
    Int {
        name: "u64",
        size: 8,
        signed: false,
    },
    Int {
        name: "i64",
        size: 8,
        signed: true,
    },
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

/// A struct with a fixed wire size, usable as a nested field or a repeated element.
struct Leaf {
    name: String,
    size: usize,
}

/// The spec being written.
struct Spec {
    rng: Rng,
    out: String,
    enums: Vec<Enum>,
    leaves: Vec<Leaf>,
    /// Payload structs: name and largest wire size.
    payloads: Vec<(String, usize)>,
}

/// The TOML text of the random spec of `seed`, its protocol named `name`.
pub fn spec(seed: u64, name: &str) -> String {
    let mut s = Spec {
        rng: Rng(seed),
        out: String::new(),
        enums: Vec::new(),
        leaves: Vec::new(),
        payloads: Vec::new(),
    };
    let order = *s.rng.pick(&["little", "big"]);
    writeln!(s.out, "# A random spec (seed {seed}).").unwrap();
    writeln!(
        s.out,
        "[protocol]\nname = \"{name}\"\nbyte_order = \"{order}\"\n"
    )
    .unwrap();
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
    s.out
}

impl Spec {
    fn emit_enum(&mut self, i: u64) {
        let name = format!("E{i}");
        let (ty, size, signed) = *self.rng.pick(&[
            ("u8", 1, false),
            ("u8", 1, false),
            ("i8", 1, true),
            ("u16", 2, false),
        ]);
        let keep = self.rng.one_in(3);
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

    /// A field of fixed size: its TOML inline table (without the closing brace's content
    /// beyond the field) and its wire size.
    fn fixed_field(&mut self, name: &str) -> (String, usize) {
        match self.rng.below(10) {
            0 | 1 => {
                let int = *self.rng.pick(INTS);
                let ty = with_order(&mut self.rng, int.name, int.size);
                (
                    format!("{{ name = \"{name}\", type = \"{ty}\" }}"),
                    int.size,
                )
            }
            2 => {
                let (ty, size) = *self.rng.pick(&[("f32", 4), ("f64", 8), ("bool", 1)]);
                (format!("{{ name = \"{name}\", type = \"{ty}\" }}"), size)
            }
            3 => {
                let int = *self.rng.pick(&INTS[..8]);
                let n = self.rng.range(1, 4) as usize;
                let ty = with_order(&mut self.rng, int.name, int.size);
                (
                    format!("{{ name = \"{name}\", type = \"{ty}\", count = {n} }}"),
                    int.size * n,
                )
            }
            4 if !self.enums.is_empty() => {
                let e = &self.enums[self.rng.below(self.enums.len() as u64) as usize];
                (
                    format!("{{ name = \"{name}\", type = \"{}\" }}", e.name),
                    e.size,
                )
            }
            5 => self.scaled_field(name),
            6 => self.bits_field(name),
            7 if !self.leaves.is_empty() => {
                let l = &self.leaves[self.rng.below(self.leaves.len() as u64) as usize];
                (
                    format!("{{ name = \"{name}\", type = \"{}\" }}", l.name),
                    l.size,
                )
            }
            8 => {
                let n = self.rng.range(1, 6) as usize;
                (format!("{{ name = \"{name}\", type = \"char[{n}]\" }}"), n)
            }
            _ => (format!("{{ name = \"{name}\", type = \"u8\" }}"), 1),
        }
    }

    /// An integer field with a scale (and an offset, a clamp, a rounding mode sometimes).
    fn scaled_field(&mut self, name: &str) -> (String, usize) {
        let int = *self.rng.pick(&INTS[..8]);
        let ty = with_order(&mut self.rng, int.name, int.size);
        let scale = *self.rng.pick(&["0.5", "0.01", "2.0", "0.1", "0.25"]);
        let mut t = format!("{{ name = \"{name}\", type = \"{ty}\", scale = {scale}");
        if self.rng.one_in(2) {
            let offset = *self.rng.pick(&["-10.0", "3.5", "100.0"]);
            write!(t, ", offset = {offset}").unwrap();
        }
        if self.rng.one_in(3) {
            // A range inside what the raw type holds for every scale and offset above.
            let (lo, hi) = if int.signed {
                ("-0.5", "0.5")
            } else {
                ("0.0", "0.5")
            };
            let (lo, hi) = if int.size == 1 {
                (lo, hi)
            } else {
                (if int.signed { "-20.0" } else { "100.0" }, "150.0")
            };
            write!(t, ", clamp = [{lo}, {hi}]").unwrap();
        }
        if self.rng.one_in(3) {
            t.push_str(", rounding = \"truncate\"");
        }
        t.push_str(" }");
        (t, int.size)
    }

    /// An unsigned word split into bit members (bools, small integers, an enum).
    fn bits_field(&mut self, name: &str) -> (String, usize) {
        let (ty, size) = *self.rng.pick(&[("u8", 1usize), ("u16", 2), ("u32", 4)]);
        let width = size as u64 * 8;
        let mut used = 0;
        let mut members = Vec::new();
        for k in 0..self.rng.range(1, 4) {
            let bits = self.rng.range(1, 5).min(width - used);
            if bits == 0 {
                break;
            }
            let mut m = format!("{{ name = \"{name}_{k}\", bits = {bits}");
            let fits = self
                .enums
                .iter()
                .filter(|e| !e.signed && e.max_value < (1 << bits))
                .map(|e| e.name.clone())
                .collect::<Vec<_>>();
            if !fits.is_empty() && self.rng.one_in(3) {
                write!(m, ", type = \"{}\"", self.rng.pick(&fits)).unwrap();
            }
            m.push_str(" }");
            members.push(m);
            used += bits;
        }
        let reserved = if used < width && self.rng.one_in(3) {
            ", reserved = \"zero\""
        } else {
            ""
        };
        (
            format!(
                "{{ name = \"{name}\", type = \"{ty}\"{reserved}, bits = [{}] }}",
                members.join(", ")
            ),
            size,
        )
    }

    fn emit_leaf(&mut self, i: u64) {
        let name = format!("L{i}");
        let mut fields = Vec::new();
        let mut size = 0;
        for k in 0..self.rng.range(1, 3) {
            let (f, n) = self.fixed_field(&format!("l{k}"));
            fields.push(f);
            size += n;
        }
        self.write_struct(&name, &fields);
        self.leaves.push(Leaf { name, size });
    }

    fn write_struct(&mut self, name: &str, fields: &[String]) {
        writeln!(self.out, "[structs.{name}]\nfields = [").unwrap();
        for f in fields {
            writeln!(self.out, "  {f},").unwrap();
        }
        writeln!(self.out, "]\n").unwrap();
    }

    /// A payload struct: fixed fields, padding sometimes, and a variable tail sometimes.
    fn emit_payload(&mut self, i: u64) {
        let name = format!("P{i}");
        let mut fields = Vec::new();
        let mut size = 0;
        for k in 0..self.rng.range(1, 5) {
            if self.rng.one_in(8) {
                let n = self.rng.range(1, 3);
                fields.push(format!("{{ pad = {n} }}"));
                size += n as usize;
            }
            let (f, n) = self.fixed_field(&format!("f{k}"));
            fields.push(f);
            size += n;
        }
        if let Some((f, n)) = self.tail_field(&fields) {
            fields.push(f);
            size += n;
        }
        self.write_struct(&name, &fields);
        self.payloads.push((name, size));
    }

    /// The last field of a payload that varies in size: bytes, a repeated group (of integers
    /// or of a fixed struct), NUL-terminated text, or an optional value.
    fn tail_field(&mut self, _before: &[String]) -> Option<(String, usize)> {
        match self.rng.below(7) {
            0 => {
                let max = self.rng.range(1, 12) as usize;
                Some((
                    format!("{{ name = \"tail\", type = \"bytes\", max = {max} }}"),
                    max,
                ))
            }
            1 => {
                let int = *self.rng.pick(&INTS[..4]);
                let max = self.rng.range(1, 5) as usize;
                Some((
                    format!(
                        "{{ name = \"tail\", type = \"{}\", repeat = true, max = {max} }}",
                        int.name
                    ),
                    int.size * max,
                ))
            }
            2 if !self.leaves.is_empty() => {
                let l = &self.leaves[self.rng.below(self.leaves.len() as u64) as usize];
                let max = self.rng.range(1, 4) as usize;
                Some((
                    format!(
                        "{{ name = \"tail\", type = \"{}\", repeat = true, max = {max} }}",
                        l.name
                    ),
                    l.size * max,
                ))
            }
            3 => {
                let max = self.rng.range(1, 8) as usize;
                Some((
                    format!("{{ name = \"tail\", type = \"cstr\", max = {max} }}"),
                    max + 1,
                ))
            }
            4 => {
                let int = *self.rng.pick(&INTS[..6]);
                Some((
                    format!(
                        "{{ name = \"tail\", type = \"{}\", optional = true }}",
                        int.name
                    ),
                    int.size,
                ))
            }
            _ => None,
        }
    }

    /// The frame format(s) and the commands.
    fn emit_frames_and_commands(&mut self) {
        let largest = self.payloads.iter().map(|p| p.1).max().unwrap_or(0);
        let max = largest + self.rng.below(4) as usize;
        let commands = self.rng.range(1, 5);
        let wide_cmd = self.rng.one_in(4);
        let frame = self.serial_frame(max, wide_cmd);
        self.out.push_str(&frame);
        writeln!(self.out, "[commands]").unwrap();
        let mut id = self.rng.below(3);
        for c in 0..commands {
            let payload = if self.rng.one_in(5) {
                String::new()
            } else {
                let p = &self.payloads[self.rng.below(self.payloads.len() as u64) as usize];
                format!(", payload = \"{}\"", p.0)
            };
            writeln!(self.out, "C{c} = {{ id = {id}{payload} }}").unwrap();
            id += self.rng.range(1, 40);
        }
        self.out.push('\n');
    }

    /// A serial frame format: sync bytes, header fields in a random order (length, command,
    /// a sequence number, a constant), a header check sometimes, the payload, a frame check.
    fn serial_frame(&mut self, max: usize, wide_cmd: bool) -> String {
        let mut layout = Vec::new();
        let sync_len = self.rng.range(1, 2);
        let sync: Vec<String> = (0..sync_len)
            .map(|_| format!("{:#04X}", self.rng.range(1, 255)))
            .collect();
        layout.push(format!("{{ sync = [{}] }}", sync.join(", ")));
        let wide_len = max > 200 || self.rng.one_in(3);
        let len_ty = if wide_len {
            with_order(&mut self.rng, "u16", 2)
        } else {
            "u8".to_string()
        };
        let cmd_ty = if wide_cmd {
            with_order(&mut self.rng, "u16", 2)
        } else {
            "u8".to_string()
        };
        let mut header = vec![
            ("len", format!("type = \"{len_ty}\"")),
            ("cmd", format!("type = \"{cmd_ty}\"")),
        ];
        if self.rng.one_in(2) {
            header.push(("seq", "type = \"u8\"".to_string()));
        }
        if self.rng.one_in(4) {
            let v = self.rng.below(256);
            header.push(("ver", format!("type = \"u8\", value = {v}")));
        }
        // Shuffled.
        for i in (1..header.len()).rev() {
            let j = self.rng.below(i as u64 + 1) as usize;
            header.swap(i, j);
        }
        let first = header[0].0;
        let cmd_pos = header.iter().position(|h| h.0 == "cmd").unwrap_or(0);
        let len_pos = header.iter().position(|h| h.0 == "len").unwrap_or(0);
        let length_of = match self.rng.below(3) {
            0 => "payload".to_string(),
            1 => "frame".to_string(),
            // A run from a header field after the length to the payload.
            _ if len_pos + 1 < header.len() => format!("{}..payload", header[len_pos + 1].0),
            _ => "payload".to_string(),
        };
        for (name, rest) in &header {
            let extra = if *name == "len" {
                format!(", length_of = \"{length_of}\"")
            } else {
                String::new()
            };
            layout.push(format!("{{ field = \"{name}\", {rest}{extra} }}"));
        }
        let _ = cmd_pos;
        if self.rng.one_in(3) {
            let check = *self
                .rng
                .pick(&["crc-8-smbus", "xor8", "sum8", "crc-8-maxim-dow"]);
            let last = header[header.len() - 1].0;
            layout.push(format!(
                "{{ check = \"{check}\", name = \"hcheck\", over = \"sync..{last}\" }}"
            ));
        }
        layout.push(format!("{{ payload = {{ max = {max} }} }}"));
        let check = *self.rng.pick(&[
            "sum8",
            "xor8",
            "sum-mod-255",
            "crc-16-mcrf4xx",
            "crc-16-modbus",
            "crc-16-ibm-3740",
            "crc-32-iso-hdlc",
            "crc-8-dvb-s2",
            "fletcher-16",
        ]);
        let over = if self.rng.one_in(2) {
            "frame".to_string()
        } else {
            format!("{first}..payload")
        };
        let order = if self.rng.one_in(3) {
            format!(", byte_order = \"{}\"", self.rng.pick(&["little", "big"]))
        } else {
            String::new()
        };
        layout.push(format!(
            "{{ check = \"{check}\", name = \"fcheck\", over = \"{over}\"{order} }}"
        ));
        if self.rng.one_in(5) {
            layout.push("{ trailer = [0x0D, 0x0A], name = \"end\" }".to_string());
        }
        let mut t = String::from("[frames.main]\nlayout = [\n");
        for e in &layout {
            writeln!(t, "  {e},").unwrap();
        }
        t.push_str("]\ndispatch = [\"cmd\"]\n\n");
        t
    }
}
