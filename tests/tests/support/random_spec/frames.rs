//! The random spec's frame formats, as its [`Shape`](super::Shape) says: the first serial
//! format with every framing rule the shape allows, the link's other command formats, a CAN
//! format and a format that carries one struct. The `[directions]` and `[commands]` they
//! carry are `commands.rs`'s; [`Spec::emit_frames_and_commands`] writes both, in that order.

use std::fmt::Write as _;

use super::{Directions, Spec, with_order};

/// Catalogue algorithms of frame checks (and whether each is a CRC).
const CHECKS: &[(&str, bool)] = &[
    ("sum8", false),
    ("xor8", false),
    ("sum-mod-255", false),
    ("sum16", false),
    ("fletcher-16", false),
    ("fletcher-16-mod-256", false),
    ("crc-8-dvb-s2", true),
    ("crc-16-mcrf4xx", true),
    ("crc-16-modbus", true),
    ("crc-16-ibm-3740", true),
    ("crc-32-iso-hdlc", true),
    ("crc-32-iscsi", true),
    ("crc-64-xz", true),
];

/// A header element of the first format: its name and the rest of its inline table.
struct HeaderField {
    name: &'static str,
    rest: String,
}

impl Spec {
    /// The frame formats, `[directions]` and `[commands]`.
    pub(super) fn emit_frames_and_commands(&mut self) {
        let largest = self.payloads.iter().map(|p| p.max).max().unwrap_or(0);
        let wide_cmd = self.rng.one_in(4);
        if wide_cmd {
            self.feature("dispatch-u16");
        }
        if self.shape.two_key {
            self.feature("dispatch-two-fields");
        }
        // Distinct first sync bytes: the formats of a link differ in a byte both have.
        let mut syncs: Vec<u8> = Vec::new();
        while syncs.len() < 5 {
            let b = self.rng.range(1, 255) as u8;
            if !syncs.contains(&b) {
                syncs.push(b);
            }
        }
        let first = self.first_format(largest, wide_cmd, &syncs);
        self.out.push_str(&first);
        for (k, &sync) in syncs.iter().enumerate().take(self.shape.formats).skip(1) {
            self.feature("formats-several");
            let text = self.link_format(k, largest, sync);
            self.out.push_str(&text);
        }
        let can_max = self.shape.can.map(|extended| self.can_format(extended));
        if self.shape.message_format {
            self.message_format(syncs[4]);
        }
        let key_len = usize::from(wide_cmd) + 1 + usize::from(self.shape.two_key);
        self.emit_directions(key_len);
        self.emit_commands(wide_cmd, can_max);
    }

    /// The first frame format: sync bytes or a sync set, header fields in a random order, a
    /// header check sometimes, the payload, a field after it, a frame check, a trailer, and
    /// optional bytes; acknowledgements, bare headers, stuffing and truncation as the shape
    /// says.
    fn first_format(&mut self, largest: usize, wide_cmd: bool, syncs: &[u8]) -> String {
        let shape = &self.shape;
        let (ack, optional, marker) = (shape.ack, shape.optional, shape.marker);
        let stuffing = shape.stuffing;
        let mut layout = Vec::new();
        let first_name = if self.shape.one_of {
            self.feature("sync-set");
            let n = self.rng.range(2, 4) as usize;
            let set: Vec<String> = syncs[..n].iter().map(|b| format!("{b:#04X}")).collect();
            layout.push(format!(
                "{{ field = \"addr\", type = \"u8\", one_of = [{}] }}",
                set.join(", ")
            ));
            "addr"
        } else {
            self.feature("sync");
            let mut sync = vec![format!("{:#04X}", syncs[0])];
            // An escaped frame opens with its flag alone; the draw is made anyway.
            let second = self.rng.one_in(2).then(|| self.rng.range(0, 255));
            if let Some(b) = second.filter(|_| !self.shape.escape) {
                sync.push(format!("{b:#04X}"));
            }
            layout.push(format!("{{ sync = [{}] }}", sync.join(", ")));
            "sync"
        };
        let max = if stuffing {
            largest * 2 + 2
        } else {
            largest + self.rng.below(4) as usize
        };
        let mut header = self.header_fields(max, wide_cmd);
        // Acknowledgements and a direction's struct in place of a command take the bytes of
        // the dispatch key: it is the last header field.
        if ack || self.shape.directions == Directions::GivenMessage {
            for key in ["cset", "cmd"] {
                if let Some(at) = header.iter().position(|h| h.name == key) {
                    let field = header.remove(at);
                    header.push(field);
                }
            }
        }
        self.length_of(&mut header, ack || marker);
        if marker {
            self.feature("length-marker");
            let m = self.rng.range(4, 40);
            let ty = with_order(&mut self.rng, "u16", 2);
            header.push(HeaderField {
                name: "xlen",
                rest: format!("type = \"{ty}\", extends = \"len\", marker = {m}"),
            });
        }
        let last = header.last().unwrap().name;
        for h in &header {
            layout.push(format!("{{ field = \"{}\", {} }}", h.name, h.rest));
        }
        // A header check between the dispatch key and the payload would part them where
        // acknowledgements or a direction's struct need them adjacent.
        let key_last = ack || self.shape.directions == Directions::GivenMessage;
        if !marker && !optional && !key_last && self.rng.one_in(3) {
            self.feature("header-check");
            let check = *self
                .rng
                .pick(&["crc-8-smbus", "xor8", "sum8", "crc-8-maxim-dow"]);
            layout.push(format!(
                "{{ check = \"{check}\", name = \"hcheck\", over = \"{first_name}..{last}\" }}"
            ));
        }
        // A check stored before the payload it covers (verified once the frame is complete);
        // a bare header holds no check of its payload, and a wider length is right before it.
        let mut side = self.side();
        if !self.shape.bare && !key_last && !marker && side.one_in(6) {
            self.feature("check-before-payload");
            let check = *side.pick(&["crc-16-xmodem", "sum8", "crc-32-iso-hdlc"]);
            layout.push(format!(
                "{{ check = \"{check}\", name = \"pcheck\", over = \"payload\" }}"
            ));
        }
        layout.push(format!("{{ payload = {{ max = {max} }} }}"));
        if self.rng.one_in(5) {
            self.feature("field-after-payload");
            let counter =
                if !header.iter().any(|h| h.rest.contains("counter")) && self.rng.one_in(2) {
                    self.feature("header-counter");
                    ", counter = true"
                } else {
                    ""
                };
            layout.push(format!("{{ field = \"after\", type = \"u8\"{counter} }}"));
        }
        let over = if self.rng.one_in(2) {
            "frame".to_string()
        } else {
            format!("{first_name}..payload")
        };
        let check = self.frame_check(&over, self.shape.extra);
        layout.push(check);
        if self.rng.one_in(5) {
            self.feature("trailer");
            layout.push("{ trailer = [0x0D, 0x0A], name = \"end\" }".to_string());
        }
        if optional {
            self.feature("optional-element");
            let size = self.rng.range(1, 6);
            layout.push(format!(
                "{{ optional = \"sig\", size = {size}, when = \"fopt\" }}"
            ));
        }
        if self.shape.escape {
            layout.push(format!(
                "{{ trailer = [{:#04X}], name = \"close\" }}",
                syncs[0]
            ));
        }
        let mut t = format_table("main", &layout);
        t.push_str(self.dispatch());
        if ack {
            self.feature("ack");
            t.push_str("ack = { field = \"fack\", equals = 1 }\n");
        }
        if self.shape.bare {
            self.feature("bare-header");
            t.push_str("bare_header = true\n");
        }
        if stuffing {
            self.feature("stuffing");
            let after: Vec<String> = (0..self.rng.range(1, 2))
                .map(|_| format!("{:#04X}", self.rng.range(0, 255)))
                .collect();
            let insert = self.rng.range(0, 255);
            writeln!(
                t,
                "stuffing = {{ after = [{}], insert = {insert:#04X} }}",
                after.join(", ")
            )
            .unwrap();
        }
        if self.shape.truncate {
            self.feature("truncate-zeros");
            t.push_str("truncate_zeros = true\n");
        }
        if self.shape.escape {
            let rule = self.escape_rule(syncs[0]);
            writeln!(t, "escape = {rule}").unwrap();
        }
        t.push('\n');
        t
    }

    /// The `dispatch` line of a command format.
    fn dispatch(&self) -> &'static str {
        if self.shape.two_key {
            "dispatch = [\"cset\", \"cmd\"]\n"
        } else {
            "dispatch = [\"cmd\"]\n"
        }
    }

    /// The header fields of the first format, shuffled: the length, the dispatch key, and
    /// sometimes a sequence number, a constant, a direction field and a word of bit members
    /// (with the acknowledgement and optional-bytes flags the shape needs).
    fn header_fields(&mut self, max: usize, wide_cmd: bool) -> Vec<HeaderField> {
        let marker = self.shape.marker;
        let len = if !marker && self.rng.one_in(5) {
            self.feature("length-bits");
            let ty = with_order(&mut self.rng, "u16", 2);
            let bits = self.rng.range(10, 12);
            HeaderField {
                name: "len",
                rest: format!(
                    "type = \"{ty}\", bits = [{{ name = \"n\", bits = {bits}, length_of = \"LEN\" }}, {{ name = \"lver\", bits = {}, value = 0 }}]",
                    16 - bits
                ),
            }
        } else {
            let ty = if !marker && (max > 200 || self.rng.one_in(3)) {
                with_order(&mut self.rng, "u16", 2)
            } else {
                "u8".to_string()
            };
            HeaderField {
                name: "len",
                rest: format!("type = \"{ty}\", length_of = \"LEN\""),
            }
        };
        let cmd_ty = if wide_cmd {
            with_order(&mut self.rng, "u16", 2)
        } else {
            "u8".to_string()
        };
        let mut header = vec![
            len,
            HeaderField {
                name: "cmd",
                rest: format!("type = \"{cmd_ty}\""),
            },
        ];
        if self.shape.two_key {
            header.push(HeaderField {
                name: "cset",
                rest: "type = \"u8\"".to_string(),
            });
        }
        if self.rng.one_in(2) {
            self.feature("header-seq");
            let counter = if self.rng.one_in(2) {
                self.feature("header-counter");
                ", counter = true"
            } else {
                ""
            };
            header.push(HeaderField {
                name: "seq",
                rest: format!("type = \"u8\"{counter}"),
            });
        }
        if self.rng.one_in(4) {
            self.feature("header-constant");
            let v = self.rng.below(256);
            header.push(HeaderField {
                name: "ver",
                rest: format!("type = \"u8\", value = {v}"),
            });
        }
        match self.shape.directions {
            Directions::Equals | Directions::Addresses => {
                let addresses = if self.shape.directions == Directions::Addresses {
                    ", addresses = true"
                } else {
                    ""
                };
                header.push(HeaderField {
                    name: "src",
                    rest: format!("type = \"u8\"{addresses}"),
                });
            }
            _ => {}
        }
        if self.shape.ack || self.shape.optional || self.rng.one_in(4) {
            header.push(self.flags_field());
        }
        for i in (1..header.len()).rev() {
            let j = self.rng.below(i as u64 + 1) as usize;
            header.swap(i, j);
        }
        header
    }

    /// A `u8` of bit members: the acknowledgement flag, the optional bytes' flag, a user
    /// value, and reserved bits that must be zero.
    fn flags_field(&mut self) -> HeaderField {
        self.feature("header-bits");
        let mut members = Vec::new();
        let mut used = 0;
        if self.shape.ack {
            members.push("{ name = \"fack\", bits = 1 }".to_string());
            used += 1;
        }
        if self.shape.optional {
            members.push("{ name = \"fopt\", bits = 1 }".to_string());
            used += 1;
        }
        let user = self.rng.range(1, 3);
        members.push(format!("{{ name = \"fuser\", bits = {user} }}"));
        used += user;
        if self.rng.one_in(2) {
            members.push(format!(
                "{{ name = \"fzero\", bits = {}, value = 0 }}",
                8 - used
            ));
        }
        HeaderField {
            name: "flags",
            rest: format!("type = \"u8\", bits = [{}]", members.join(", ")),
        }
    }

    /// What the length counts: the payload, the frame, or a run from a header field after
    /// it to the payload (only the payload or the frame where some frames lack the key, or a
    /// marker extends the length).
    fn length_of(&mut self, header: &mut [HeaderField], simple: bool) {
        let at = header.iter().position(|h| h.name == "len").unwrap();
        let choice = if simple {
            self.rng.below(2)
        } else {
            self.rng.below(3)
        };
        let counts = match choice {
            0 => {
                self.feature("length-payload");
                "payload".to_string()
            }
            1 if !self.shape.marker => {
                self.feature("length-frame");
                "frame".to_string()
            }
            _ if at + 1 < header.len() => {
                self.feature("length-run");
                format!("{}..payload", header[at + 1].name)
            }
            _ => {
                self.feature("length-payload");
                "payload".to_string()
            }
        };
        header[at].rest = header[at].rest.replace("LEN", &counts);
    }

    /// A frame check over `over`: a catalogue algorithm or one of `[checksums]`, a CRC
    /// (folding in a byte per command) when `extra`, with a table size and a byte order
    /// sometimes.
    fn frame_check(&mut self, over: &str, extra: bool) -> String {
        self.feature("frame-check");
        let mut names: Vec<(String, bool)> = CHECKS
            .iter()
            .map(|(n, crc)| (n.to_string(), *crc))
            .collect();
        names.extend(self.checksums.iter().cloned());
        if extra {
            names.retain(|(_, crc)| *crc);
        }
        let (check, crc) = self.rng.pick(&names).clone();
        let mut t = format!("{{ check = \"{check}\", name = \"fcheck\", over = \"{over}\"");
        if extra {
            self.feature("check-extra");
            t.push_str(", extra = \"command\"");
        }
        if crc && self.rng.one_in(3) {
            self.feature("check-table");
            write!(t, ", table = {}", self.rng.pick(&[0, 1, 16])).unwrap();
        }
        if self.rng.one_in(3) {
            self.feature("check-byte-order");
            write!(
                t,
                ", byte_order = \"{}\"",
                self.rng.pick(&["little", "big"])
            )
            .unwrap();
        }
        t.push_str(" }");
        t
    }

    /// Another command format of the link: its own sync, length, key and check.
    fn link_format(&mut self, k: usize, largest: usize, sync: u8) -> String {
        let len = if largest > 200 || self.rng.one_in(3) {
            with_order(&mut self.rng, "u16", 2)
        } else {
            "u8".to_string()
        };
        let mut layout = vec![
            format!("{{ sync = [{sync:#04X}] }}"),
            format!("{{ field = \"len\", type = \"{len}\", length_of = \"payload\" }}"),
        ];
        if self.rng.one_in(2) {
            layout.push("{ field = \"seq\", type = \"u8\" }".to_string());
        }
        if matches!(
            self.shape.directions,
            Directions::Equals | Directions::Addresses
        ) {
            layout.push("{ field = \"src\", type = \"u8\" }".to_string());
        }
        let cmd = if self.rng.one_in(3) { "u16" } else { "u8" };
        if self.shape.two_key {
            layout.push("{ field = \"cset\", type = \"u8\" }".to_string());
        }
        layout.push(format!("{{ field = \"cmd\", type = \"{cmd}\" }}"));
        layout.push(format!("{{ payload = {{ max = {largest} }} }}"));
        let check = self.frame_check("len..payload", self.shape.extra);
        layout.push(check);
        let mut t = format_table(&format!("f{k}"), &layout);
        t.push_str(self.dispatch());
        t.push_str("commands = true\n");
        if self.shape.extensions_off && (k == 1 || self.rng.one_in(2)) {
            self.feature("extensions-off");
            t.push_str("extensions = false\n");
        }
        t.push('\n');
        t
    }

    /// A CAN format after the serial ones: the payload, a counter and a check sometimes.
    /// Returns the largest payload it carries.
    fn can_format(&mut self, extended: bool) -> usize {
        self.feature(if extended {
            "can-extended"
        } else {
            "can-standard"
        });
        let mut trailer = Vec::new();
        if self.rng.one_in(2) {
            trailer.push("{ field = \"cnt\", type = \"u8\" }".to_string());
        }
        if self.rng.one_in(2) {
            let check = *self.rng.pick(&["sum8", "xor8", "crc-8-smbus"]);
            trailer.push(format!("{{ check = \"{check}\", over = \"frame\" }}"));
        }
        let max = 8 - trailer.len();
        let min = if self.rng.one_in(3) {
            self.rng.below(max as u64 + 1) as usize
        } else {
            0
        };
        let mut layout = vec![format!("{{ payload = {{ min = {min}, max = {max} }} }}")];
        layout.extend(trailer);
        let kind = if extended { "extended" } else { "standard" };
        let mut t = format!("[frames.can]\ntransport = \"can\"\ncan_id = \"{kind}\"\n");
        t.push_str(&format_table("", &layout)["[frames.]\n".len()..]);
        t.push_str("dispatch = [\"can_id\"]\n\n");
        self.out.push_str(&t);
        max
    }

    /// A serial format whose every frame carries one struct.
    fn message_format(&mut self, sync: u8) {
        self.feature("message-format");
        let p = self.payloads[self.rng.below(self.payloads.len() as u64) as usize].clone();
        let layout = vec![
            format!("{{ sync = [{sync:#04X}] }}"),
            "{ field = \"len\", type = \"u8\", length_of = \"payload\" }".to_string(),
            format!("{{ payload = {{ max = {} }} }}", p.max),
            "{ check = \"crc-16-modbus\", over = \"frame\" }".to_string(),
        ];
        let mut t = format_table("msg", &layout);
        writeln!(t, "message = \"{}\"\n", p.name).unwrap();
        self.out.push_str(&t);
    }
}

/// `[frames.NAME]` with its layout, one element a line.
fn format_table(name: &str, layout: &[String]) -> String {
    let mut t = format!("[frames.{name}]\nlayout = [\n");
    for e in layout {
        writeln!(t, "  {e},").unwrap();
    }
    t.push_str("]\n");
    t
}
