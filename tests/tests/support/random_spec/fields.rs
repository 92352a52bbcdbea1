//! The fields of the random spec's structs: fixed-size fields of every kind, the payload
//! structs with their sized fields, checks, extension fields and variable tails.

use std::fmt::Write as _;

use super::{INTS, Payload, Spec, with_order};

/// A fixed-size field: its TOML inline table, its wire size, and whether a struct holding it
/// may be a repeated group's element.
pub(super) struct Field {
    pub(super) text: String,
    pub(super) size: usize,
    pub(super) repeatable: bool,
}

fn field(text: String, size: usize) -> Field {
    Field {
        text,
        size,
        repeatable: true,
    }
}

impl Spec {
    /// A field of fixed size named `name`.
    pub(super) fn fixed_field(&mut self, name: &str) -> Field {
        match self.rng.below(12) {
            0 | 1 => {
                self.feature("field-int");
                let int = *self.rng.pick(INTS);
                if (5..=7).contains(&int.size) {
                    self.feature("field-int-wide");
                }
                let ty = with_order(&mut self.rng, int.name, int.size);
                field(
                    format!("{{ name = \"{name}\", type = \"{ty}\" }}"),
                    int.size,
                )
            }
            2 => {
                let (ty, size) = *self
                    .rng
                    .pick(&[("f32", 4), ("f64", 8), ("bool", 1), ("f16", 2)]);
                self.feature(match ty {
                    "bool" => "field-bool",
                    "f16" => "field-f16",
                    _ => "field-float",
                });
                let invert = if ty == "bool" && self.rng.one_in(3) {
                    self.feature("field-bool-inverted");
                    ", invert = true"
                } else {
                    ""
                };
                field(
                    format!("{{ name = \"{name}\", type = \"{ty}\"{invert} }}"),
                    size,
                )
            }
            3 => self.array_field(name),
            4 if !self.enums.is_empty() => {
                self.feature("field-enum");
                let e = &self.enums[self.rng.below(self.enums.len() as u64) as usize];
                let (ty, size) = (e.name.clone(), e.size);
                field(format!("{{ name = \"{name}\", type = \"{ty}\" }}"), size)
            }
            5 => self.scaled_field(name),
            6 => {
                let mut f = self.bits_field(name);
                f.repeatable = false;
                f
            }
            7 if !self.leaves.is_empty() => {
                self.feature("field-nested");
                let l = &self.leaves[self.rng.below(self.leaves.len() as u64) as usize];
                Field {
                    text: format!("{{ name = \"{name}\", type = \"{}\" }}", l.name),
                    size: l.size,
                    repeatable: l.repeatable,
                }
            }
            8 => {
                self.feature("field-char");
                let n = self.rng.range(1, 6) as usize;
                Field {
                    text: format!("{{ name = \"{name}\", type = \"char[{n}]\" }}"),
                    size: n,
                    repeatable: false,
                }
            }
            9 => self.packed_field(name),
            10 => self.stream_field(name),
            _ => {
                self.feature("field-int");
                field(format!("{{ name = \"{name}\", type = \"u8\" }}"), 1)
            }
        }
    }

    /// A fixed array of integers, floats or an enum, its count a number or a constant.
    fn array_field(&mut self, name: &str) -> Field {
        self.feature("field-array");
        let (ty, size) = if !self.enums.is_empty() && self.rng.one_in(4) {
            let e = &self.enums[self.rng.below(self.enums.len() as u64) as usize];
            (e.name.clone(), e.size)
        } else if self.rng.one_in(5) {
            ("f32".to_string(), 4)
        } else {
            let int = *self.rng.pick(&INTS[..8]);
            (with_order(&mut self.rng, int.name, int.size), int.size)
        };
        let (count, n) = if !self.constants.is_empty() && self.rng.one_in(3) {
            self.feature("field-array-constant");
            let (c, v) =
                self.constants[self.rng.below(self.constants.len() as u64) as usize].clone();
            (format!("\"{c}\""), v as usize)
        } else {
            let n = self.rng.range(1, 4);
            (n.to_string(), n as usize)
        };
        field(
            format!("{{ name = \"{name}\", type = \"{ty}\", count = {count} }}"),
            size * n,
        )
    }

    /// A bit-packed array of unsigned elements (with a scale sometimes).
    fn packed_field(&mut self, name: &str) -> Field {
        self.feature("field-packed");
        let count = self.rng.range(1, 8) as usize;
        let bits = self.rng.range(1, 16) as usize;
        let order = *self.rng.pick(&["lsb-first", "msb-first"]);
        let scale = if self.rng.one_in(3) {
            ", scale = 0.5, offset = -1.0"
        } else {
            ""
        };
        Field {
            text: format!(
                "{{ name = \"{name}\", count = {count}, packed = {{ bits = {bits}, order = \"{order}\" }}{scale} }}"
            ),
            size: (count * bits).div_ceil(8),
            repeatable: false,
        }
    }

    /// A float on the wire with a scale: a power of two and no offset, so that every value
    /// but NaN decodes and encodes back to its bits (an offset absorbs a tiny raw value).
    fn scaled_float_field(&mut self, name: &str) -> Field {
        self.feature("field-scaled-float");
        let (ty, size) = *self.rng.pick(&[("f16", 2), ("f32", 4)]);
        let ty = with_order(&mut self.rng, ty, size);
        let scale = *self.rng.pick(&["0.5", "0.25", "2.0", "4.0"]);
        field(
            format!("{{ name = \"{name}\", type = \"{ty}\", scale = {scale} }}"),
            size,
        )
    }

    /// An integer field with a scale (and an offset, a clamp, a rounding mode sometimes); a
    /// float with a scale one time in four.
    fn scaled_field(&mut self, name: &str) -> Field {
        if self.rng.one_in(4) {
            return self.scaled_float_field(name);
        }
        self.feature("field-scaled");
        let int = *self.rng.pick(&INTS[..8]);
        let ty = with_order(&mut self.rng, int.name, int.size);
        let scale = *self.rng.pick(&["0.5", "0.01", "2.0", "0.1", "0.25"]);
        let mut t = format!("{{ name = \"{name}\", type = \"{ty}\", scale = {scale}");
        if self.rng.one_in(2) {
            let offset = *self.rng.pick(&["-10.0", "3.5", "100.0"]);
            write!(t, ", offset = {offset}").unwrap();
        }
        if self.rng.one_in(3) {
            self.feature("field-clamp");
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
            self.feature("field-rounding");
            t.push_str(", rounding = \"truncate\"");
        }
        t.push_str(" }");
        field(t, int.size)
    }

    /// An unsigned word split into bit members (bools, small integers, an enum).
    fn bits_field(&mut self, name: &str) -> Field {
        self.feature("field-bits");
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
                self.feature("field-bits-enum");
                write!(m, ", type = \"{}\"", self.rng.pick(&fits)).unwrap();
            } else if bits > 1 {
                m.push_str(&self.member_number(bits));
            }
            m.push_str(" }");
            members.push(m);
            used += bits;
        }
        let reserved = if used < width && self.rng.one_in(3) {
            self.feature("field-bits-reserved-zero");
            ", reserved = \"zero\""
        } else {
            ""
        };
        field(
            format!(
                "{{ name = \"{name}\", type = \"{ty}\"{reserved}, bits = [{}] }}",
                members.join(", ")
            ),
            size,
        )
    }

    /// The keys that make a bit member of `bits` bits signed or scaled, sometimes: two's
    /// complement in the smallest signed type that holds it, a scale (and an offset) on a
    /// member of up to 32 bits (whose raw values an `f64` holds exactly).
    fn member_number(&mut self, bits: u64) -> String {
        let mut keys = String::new();
        if self.rng.one_in(4) {
            self.feature("field-bits-signed");
            let ty = match bits {
                0..=8 => "i8",
                9..=16 => "i16",
                17..=32 => "i32",
                _ => "i64",
            };
            write!(keys, ", type = \"{ty}\"").unwrap();
        }
        if bits <= 32 && self.rng.one_in(4) {
            self.feature("field-bits-scaled");
            let scale = *self.rng.pick(&["0.5", "0.25", "2.0", "0.1"]);
            write!(keys, ", scale = {scale}").unwrap();
            if self.rng.one_in(2) {
                keys.push_str(", offset = -3.0, unit = \"m\"");
            }
        }
        keys
    }

    /// A bit stream: members of 1 to 40 bits, MSB first across bytes, flags, integers (signed
    /// and scaled sometimes) and an enum.
    fn stream_field(&mut self, name: &str) -> Field {
        self.feature("field-bitstream");
        let mut used = 0;
        let mut members = Vec::new();
        for k in 0..self.rng.range(1, 5) {
            let bits = if self.rng.one_in(4) {
                1
            } else {
                self.rng.range(2, 40)
            };
            let mut m = format!("{{ name = \"{name}_{k}\", bits = {bits}");
            let fits = self
                .enums
                .iter()
                .filter(|e| !e.signed && e.max_value < (1 << bits.min(63)))
                .map(|e| e.name.clone())
                .collect::<Vec<_>>();
            if !fits.is_empty() && self.rng.one_in(4) {
                write!(m, ", type = \"{}\"", self.rng.pick(&fits)).unwrap();
            } else if bits > 1 {
                m.push_str(&self.member_number(bits));
            }
            m.push_str(" }");
            members.push(m);
            used += bits;
        }
        Field {
            text: format!(
                "{{ name = \"{name}\", type = \"bitstream\", bits = [{}] }}",
                members.join(", ")
            ),
            size: used.div_ceil(8) as usize,
            repeatable: true,
        }
    }

    /// A payload struct: fixed fields, padding sometimes, fields sized by an earlier field, a
    /// check over some fields, extension fields, and a variable tail sometimes.
    pub(super) fn emit_payload(&mut self, i: u64) {
        let name = format!("P{i}");
        let fixed = self.shape.fixed_payloads;
        let mut fields = Vec::new();
        let (mut min, mut max) = (0, 0);
        let mut names = Vec::new();
        let mut ids = None;
        for k in 0..self.rng.range(1, 4) {
            if self.rng.one_in(8) {
                self.feature("field-pad");
                let n = self.rng.range(1, 3) as usize;
                fields.push(format!("{{ pad = {n} }}"));
                min += n;
                max += n;
            }
            let f = self.fixed_field(&format!("f{k}"));
            fields.push(f.text);
            min += f.size;
            max += f.size;
            names.push(format!("f{k}"));
        }
        // Whether a field of variable size (or a check) comes before the tail.
        let mut variable = false;
        if !fixed && self.rng.one_in(5) {
            variable = true;
            let (f, most) = self.sized_fields();
            fields.extend(f);
            min += 1;
            max += 1 + most;
            names.clear();
        }
        if !fixed && self.rng.one_in(5) {
            variable = true;
            let (f, most) = self.masked_fields();
            fields.extend(f);
            min += 1;
            max += 1 + most;
            names.clear();
        }
        if !names.is_empty() && self.rng.one_in(5) {
            variable = true;
            let (f, n) = self.payload_check(&names);
            fields.push(f);
            min += n;
            max += n;
        }
        if self.shape.extensions_off && self.rng.one_in(2) {
            self.feature("field-extension");
            for k in 0..self.rng.range(1, 2) {
                let int = *self.rng.pick(&INTS[..4]);
                fields.push(format!(
                    "{{ name = \"x{k}\", type = \"{}\", extension = true }}",
                    int.name
                ));
                min += int.size;
                max += int.size;
            }
        } else if !fixed && let Some((f, lo, hi)) = self.tail_field() {
            if !variable {
                ids = self.listed_ids(&f);
            }
            fields.extend(f);
            min += lo;
            max += hi;
        }
        self.write_struct(&name, &fields);
        self.payloads.push(Payload {
            name,
            min,
            max,
            ids,
        });
    }

    /// Where a tail after fields of a fixed size lists one-byte ids, two at least: a repeated
    /// `u8` (`tail`), or a `u8` of repeated structs (`tail.l0`).
    fn listed_ids(&self, tail: &[String]) -> Option<String> {
        let [only] = tail else {
            return None;
        };
        let rest = only.strip_prefix("{ name = \"tail\", type = \"")?;
        let (ty, rest) = rest.split_once('"')?;
        let most: usize = rest
            .strip_prefix(", repeat = true, max = ")?
            .trim_end_matches(" }")
            .parse()
            .ok()?;
        if most < 2 {
            return None;
        }
        if ty == "u8" {
            return Some("tail".to_string());
        }
        let leaf = self.leaves.iter().find(|l| l.name == ty)?;
        Some(format!("tail.{}", leaf.id_member.as_ref()?))
    }

    /// A count, then bytes or an array of integers of as many elements as it says; the
    /// largest number of bytes they take.
    fn sized_fields(&mut self) -> (Vec<String>, usize) {
        let most = self.rng.range(1, 6) as usize;
        let count = "{ name = \"n\", type = \"u8\" }".to_string();
        if self.rng.one_in(2) {
            self.feature("field-sized-bytes");
            (
                vec![
                    count,
                    format!("{{ name = \"data\", type = \"bytes\", size = \"n\", max = {most} }}"),
                ],
                most,
            )
        } else {
            self.feature("field-sized-array");
            let int = *self.rng.pick(&INTS[..4]);
            (
                vec![
                    count,
                    format!(
                        "{{ name = \"data\", type = \"{}\", repeat = true, size = \"n\", max = {most} }}",
                        int.name
                    ),
                ],
                most * int.size,
            )
        }
    }

    /// A mask, then an integer present when one of its bits is set, an array of one integer
    /// per set bit, or both; the largest number of bytes they take after the mask.
    fn masked_fields(&mut self) -> (Vec<String>, usize) {
        let mut fields = vec!["{ name = \"m\", type = \"u8\" }".to_string()];
        let mut most = 0;
        let both = self.rng.one_in(3);
        if both || self.rng.one_in(2) {
            self.feature("field-when");
            let (int, bit) = (*self.rng.pick(&INTS[..4]), self.rng.range(0, 7));
            fields.push(format!(
                "{{ name = \"mv\", type = \"{}\", when = {{ field = \"m\", bit = {bit} }} }}",
                int.name
            ));
            most += int.size;
        }
        if both || fields.len() == 1 {
            self.feature("field-mask-array");
            let int = *self.rng.pick(&INTS[..4]);
            fields.push(format!(
                "{{ name = \"md\", type = \"{}\", repeat = true, mask = \"m\", max = 8 }}",
                int.name
            ));
            most += 8 * int.size;
        }
        (fields, most)
    }

    /// A check over a run of the fields `names` (a CRC with a prefix sometimes); its size.
    fn payload_check(&mut self, names: &[String]) -> (String, usize) {
        self.feature("field-payload-check");
        let (algorithm, size, is_crc) = *self.rng.pick(&[
            ("xor8", 1, false),
            ("sum8", 1, false),
            ("crc-8-smbus", 1, true),
            ("crc-16-xmodem", 2, true),
        ]);
        let from = self.rng.below(names.len() as u64) as usize;
        let to = from + self.rng.below((names.len() - from) as u64) as usize;
        let over = if from == to {
            names[from].clone()
        } else {
            format!("{}..{}", names[from], names[to])
        };
        let mut t = format!("{{ name = \"pcheck\", check = \"{algorithm}\", over = \"{over}\"");
        if is_crc && self.rng.one_in(2) {
            self.feature("field-payload-check-prefix");
            let p = self.rng.range(0, 255);
            write!(t, ", prefix = [{p:#04X}]").unwrap();
        }
        if size > 1 && self.rng.one_in(2) {
            let order = *self.rng.pick(&["little", "big"]);
            write!(t, ", byte_order = \"{order}\"").unwrap();
        }
        t.push_str(" }");
        (t, size)
    }

    /// The last fields of a payload that vary in size: bytes or text without a terminator
    /// (followed by a check sometimes), a repeated group (of integers or of a fixed struct), NUL-terminated text, or
    /// an optional value; their smallest and largest sizes.
    fn tail_field(&mut self) -> Option<(Vec<String>, usize, usize)> {
        match self.rng.below(7) {
            0 => {
                let max = self.rng.range(1, 12) as usize;
                // Text without a terminator ends as bytes do; chosen by the size already
                // drawn, so the generator's other choices stay those of its seed.
                let ty = if matches!(max % 3, 0) { "str" } else { "bytes" };
                self.feature(if ty == "str" {
                    "tail-str"
                } else {
                    "tail-bytes"
                });
                let bytes = format!("{{ name = \"tail\", type = \"{ty}\", max = {max} }}");
                if self.rng.one_in(3) {
                    self.feature("tail-bytes-before-check");
                    let check = "{ name = \"tcheck\", check = \"xor8\", over = \"tail\" }";
                    Some((vec![bytes, check.to_string()], 1, max + 1))
                } else {
                    Some((vec![bytes], 0, max))
                }
            }
            1 => {
                self.feature("tail-repeat-int");
                let int = *self.rng.pick(&INTS[..4]);
                let max = self.rng.range(1, 5) as usize;
                Some((
                    vec![format!(
                        "{{ name = \"tail\", type = \"{}\", repeat = true, max = {max} }}",
                        int.name
                    )],
                    0,
                    int.size * max,
                ))
            }
            2 => {
                let leaves: Vec<(String, usize)> = self
                    .leaves
                    .iter()
                    .filter(|l| l.repeatable)
                    .map(|l| (l.name.clone(), l.size))
                    .collect();
                if leaves.is_empty() {
                    return None;
                }
                self.feature("tail-repeat-struct");
                let (leaf, size) = self.rng.pick(&leaves).clone();
                let max = self.rng.range(1, 4) as usize;
                Some((
                    vec![format!(
                        "{{ name = \"tail\", type = \"{leaf}\", repeat = true, max = {max} }}"
                    )],
                    0,
                    size * max,
                ))
            }
            3 => {
                self.feature("tail-cstr");
                let max = self.rng.range(1, 8) as usize;
                Some((
                    vec![format!(
                        "{{ name = \"tail\", type = \"cstr\", max = {max} }}"
                    )],
                    1,
                    max + 1,
                ))
            }
            4 => {
                self.feature("tail-optional");
                let int = *self.rng.pick(&INTS[..6]);
                Some((
                    vec![format!(
                        "{{ name = \"tail\", type = \"{}\", optional = true }}",
                        int.name
                    )],
                    0,
                    int.size,
                ))
            }
            _ => None,
        }
    }

    /// The payload structs of at most `most` bytes.
    pub(super) fn payloads_within(&self, most: usize) -> Vec<Payload> {
        self.payloads
            .iter()
            .filter(|p| p.max <= most)
            .cloned()
            .collect()
    }
}
