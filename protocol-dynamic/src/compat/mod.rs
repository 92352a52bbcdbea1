//! Compatibility between two versions of a spec (`protocol diff OLD NEW`) at two levels: the
//! wire (a frame written by one version is read differently, or refused, by the other) and the
//! Rust source generated from it (code written against one version's module no longer
//! compiles against the other's). Every change is reported once, with its reason, at the most
//! severe level it reaches.
//!
//! This module compares two checked IRs. Commands are matched by their id (what is on the
//! wire), frame formats by name, struct fields by position; a rename keeps the wire and breaks
//! the source (the generated item's name changes). Struct and field comparison lives in the
//! `payload` submodule, the wording of types and positions in the spec's words in `words`.
//!
//! An addition (a command, an enum value) gives a generated enum a variant. `#[non_exhaustive]`
//! binds only other crates, and the crate that matches on `Message` is the one that expands the
//! spec, so its exhaustive `match` stops compiling: additions are source-breaking. (A hidden
//! catch-all variant would keep such a `match` compiling only by forcing a wildcard arm on every
//! user, and with it the compiler's list of the commands a firmware forgot to handle.)

mod payload;
mod registers;
mod words;

use std::fmt;

use protocol_spec::ir::{
    Algorithm, Check, Command, CrcTable, DirectionRule, Frame, Protocol, Role,
};

/// How a change affects the wire and the generated Rust source, most severe first.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Class {
    /// Frames of one version are refused or misread by the other. Such a change mostly
    /// changes the generated types too; it is reported at this level only.
    Breaking,
    /// The wire format is unchanged, but the generated module is not: code written against
    /// one version does not compile against the other (a renamed field, command, enum value
    /// or module; another physical type; an added command or enum value, which an exhaustive
    /// `match` in the crate that expands the spec must name).
    SourceBreaking,
    /// Neither the wire nor the names and types of the generated API change: docs, units,
    /// versions, added frame formats.
    Compatible,
}

impl Class {
    /// The word `protocol diff` prints for the class.
    pub const fn label(self) -> &'static str {
        match self {
            Class::Breaking => "breaking",
            Class::SourceBreaking => "source-breaking",
            Class::Compatible => "compatible",
        }
    }
}

/// One change between two specs.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Change {
    /// Breaking the wire, breaking the source only, or compatible.
    pub class: Class,
    /// What changed (`command READ_SYSTEM_INFO (id 0x01)`, `frame link`).
    pub subject: String,
    /// How, and why it matters.
    pub reason: String,
}

impl fmt::Display for Change {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{:<15}  {}: {}",
            self.class.label(),
            self.subject,
            self.reason
        )
    }
}

/// Collects changes about one subject.
struct Report<'a> {
    out: &'a mut Vec<Change>,
    subject: String,
}

impl Report<'_> {
    fn breaking(&mut self, reason: impl Into<String>) {
        self.out.push(Change {
            class: Class::Breaking,
            subject: self.subject.clone(),
            reason: reason.into(),
        });
    }

    fn source(&mut self, reason: impl Into<String>) {
        self.out.push(Change {
            class: Class::SourceBreaking,
            subject: self.subject.clone(),
            reason: reason.into(),
        });
    }

    fn compatible(&mut self, reason: impl Into<String>) {
        self.out.push(Change {
            class: Class::Compatible,
            subject: self.subject.clone(),
            reason: reason.into(),
        });
    }
}

/// Why an addition breaks the source, said with every added command or enum value.
const ADDED_VARIANT: &str = "the generated enum gains a variant: an exhaustive `match` in the crate that expands the spec needs one more arm";

/// Every change from `old` to `new`, breaking ones first (each group in spec order).
pub fn diff(old: &Protocol, new: &Protocol) -> Vec<Change> {
    let mut out = Vec::new();
    {
        let mut r = Report {
            out: &mut out,
            subject: format!("protocol {}", new.name),
        };
        if old.name != new.name {
            r.source(format!(
                "renamed from `{}` (the generated module's name changes)",
                old.name
            ));
        }
        if old.version != new.version {
            r.compatible(format!("version `{}` → `{}`", old.version, new.version));
        }
        if old.doc != new.doc {
            r.compatible("doc changed");
        }
    }
    diff_frames(old, new, &mut out);
    diff_directions(old, new, &mut out);
    diff_commands(old, new, &mut out);
    registers::diff_registers(old, new, &mut out);
    out.sort_by_key(|c| c.class);
    out
}

fn hex_bytes(b: &[u8]) -> String {
    b.iter()
        .map(|x| format!("{x:02X}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// A check algorithm as the wire sees it: the table a CRC is computed with changes no byte.
fn on_the_wire(a: &Algorithm) -> Algorithm {
    let mut a = *a;
    match &mut a {
        Algorithm::Crc8(s) => s.table = CrcTable::Table16,
        Algorithm::Crc16(s) => s.table = CrcTable::Table16,
        Algorithm::Crc32(s) => s.table = CrcTable::Table16,
        Algorithm::Crc64(s) => s.table = CrcTable::Table16,
        _ => {}
    }
    a
}

fn algorithm_name(c: &Check) -> String {
    macro_rules! crc {
        ($s:expr) => {{
            let p = &$s.params;
            format!(
                "{} (poly {:#x}, init {:#x}, refin {}, refout {}, xorout {:#x})",
                c.naming.display, p.poly, p.init, p.refin, p.refout, p.xorout
            )
        }};
    }
    match &c.algorithm {
        Algorithm::Sum8 => "sum mod 256".into(),
        Algorithm::SumMod255 => "sum mod 255".into(),
        Algorithm::Xor8 => "xor".into(),
        Algorithm::Sum {
            width,
            init,
            xorout,
        } => format!(
            "sum mod {}, init {init:#x}, xorout {xorout:#x}",
            1u32 << (8 * u32::from(*width))
        ),
        Algorithm::Xor { init } => format!("xor, init {init:#x}"),
        Algorithm::Fletcher16 => "fletcher-16".into(),
        Algorithm::Fletcher16Mod256 => "fletcher-16-mod-256".into(),
        Algorithm::Crc8(s) => crc!(s),
        Algorithm::Crc16(s) => crc!(s),
        Algorithm::Crc32(s) => crc!(s),
        Algorithm::Crc64(s) => crc!(s),
    }
}

fn role_name(r: &Role) -> String {
    match r {
        Role::User { .. } => "a header value".into(),
        Role::Length => "the length".into(),
        Role::Dispatch => "a dispatch key".into(),
        Role::Const(v) => format!("the constant {v:#x}"),
        Role::Ack(v) => format!("the acknowledgement flag (set: {v})"),
        Role::Flag => "the flag of optional bytes".into(),
        Role::WideLength => "the wider length".into(),
    }
}

fn diff_frames(old: &Protocol, new: &Protocol, out: &mut Vec<Change>) {
    for (i, of) in old.frames.iter().enumerate() {
        let mut r = Report {
            out,
            subject: format!("frame `{}`", of.name),
        };
        match new.frames.iter().position(|f| f.name == of.name) {
            None => r.breaking("frame format removed"),
            Some(j) => {
                if i == 0 && j != 0 {
                    r.breaking(
                        "no longer the default (first) frame format, which carries the commands",
                    );
                }
                diff_frame(of, &new.frames[j], &mut r);
            }
        }
    }
    for nf in &new.frames {
        if !old.frames.iter().any(|f| f.name == nf.name) {
            let mut r = Report {
                out,
                subject: format!("frame `{}`", nf.name),
            };
            r.compatible("frame format added");
        }
    }
}

fn diff_frame(o: &Frame, n: &Frame, r: &mut Report<'_>) {
    if o.transport != n.transport {
        r.breaking(format!(
            "transport {}, was {}",
            words::transport(&n.transport),
            words::transport(&o.transport)
        ));
    }
    if o.sync != n.sync {
        r.breaking(format!(
            "sync bytes {} → {}",
            hex_bytes(&o.sync),
            hex_bytes(&n.sync)
        ));
    }
    if o.sync_set != n.sync_set {
        // A value removed rejects old frames; a value added is one old decoders reject.
        r.breaking(format!(
            "sync set {} → {}",
            hex_bytes(&o.sync_set),
            hex_bytes(&n.sync_set)
        ));
    }
    if (o.header_len, o.trailer_len) != (n.header_len, n.trailer_len) {
        r.breaking(format!(
            "header/trailer {}/{} bytes → {}/{} bytes",
            o.header_len, o.trailer_len, n.header_len, n.trailer_len
        ));
    }
    if (o.payload_min, o.payload_max) != (n.payload_min, n.payload_max) {
        r.breaking(format!(
            "payload bounds {}..={} → {}..={} bytes (decoders reject lengths outside them)",
            o.payload_min, o.payload_max, n.payload_min, n.payload_max
        ));
    }
    for (ov, nv) in o.values.iter().zip(&n.values) {
        let shape = |v: &protocol_spec::ir::HeaderValue| (v.at, v.word, v.shift, v.width);
        if shape(ov) != shape(nv) {
            r.breaking(format!(
                "header value `{}`: {}, was {}",
                nv.name,
                words::header_value(nv),
                words::header_value(ov)
            ));
        } else if std::mem::discriminant(&ov.role) != std::mem::discriminant(&nv.role)
            || matches!((&ov.role, &nv.role), (Role::Const(a), Role::Const(b)) if a != b)
        {
            r.breaking(format!(
                "header value `{}` was {}, is {}",
                nv.name,
                role_name(&ov.role),
                role_name(&nv.role)
            ));
        } else if ov.name != nv.name {
            r.source(format!(
                "header value `{}` renamed to `{}` (a field of `Header`)",
                ov.name, nv.name
            ));
        }
    }
    if o.values.len() != n.values.len() {
        r.breaking(format!(
            "{} header values → {}",
            o.values.len(),
            n.values.len()
        ));
    }
    if o.length != n.length {
        r.breaking(format!(
            "frame length {}, was {}",
            words::length(&n.length, &n.values),
            words::length(&o.length, &o.values)
        ));
    }
    if o.dispatch != n.dispatch {
        r.breaking("the dispatch key's fields changed");
    }
    for (oc, nc) in o.checks.iter().zip(&n.checks) {
        if on_the_wire(&oc.algorithm) != on_the_wire(&nc.algorithm) {
            r.breaking(format!(
                "check `{}`: {} → {}",
                nc.name,
                algorithm_name(oc),
                algorithm_name(nc)
            ));
        } else {
            diff_check_place(oc, nc, r);
        }
    }
    for (oc, nc) in o.checks.iter().zip(&n.checks) {
        if oc.extra.is_some() != nc.extra.is_some() {
            r.breaking(format!(
                "check `{}` {} a byte per command",
                nc.name,
                if nc.extra.is_some() {
                    "now folds in"
                } else {
                    "no longer folds in"
                }
            ));
        }
    }
    if o.checks.len() != n.checks.len() {
        r.breaking(format!("{} checks → {}", o.checks.len(), n.checks.len()));
    }
    let trailers = |f: &Frame| {
        f.trailers
            .iter()
            .map(|t| (t.at, t.bytes.clone()))
            .collect::<Vec<_>>()
    };
    if trailers(o) != trailers(n) {
        r.breaking("trailer bytes changed");
    }
    if o.doc != n.doc {
        r.compatible("doc changed");
    }
}

/// Where a check is stored, in what byte order, and which bytes it covers: each a change of
/// its own, said in the spec's words.
fn diff_check_place(o: &Check, n: &Check, r: &mut Report<'_>) {
    let name = &n.name;
    if o.endian != n.endian {
        r.breaking(format!(
            "check `{name}`: stored {}, was {}",
            words::order(n.endian),
            words::order(o.endian)
        ));
    }
    if (o.at, o.size) != (n.at, n.size) {
        r.breaking(format!(
            "check `{name}`: {} bytes at {}, was {} bytes at {}",
            n.size,
            words::pos(n.at),
            o.size,
            words::pos(o.at)
        ));
    }
    if (o.from, o.to) != (n.from, n.to) {
        r.breaking(format!(
            "check `{name}`: covers the bytes {}, was {}",
            words::span(n.from, n.to),
            words::span(o.from, o.to)
        ));
    }
    if o.header != n.header {
        // A header check is verified before the length is trusted, a frame check after.
        let when = |h: bool| if h { "a header check" } else { "a frame check" };
        r.breaking(format!(
            "check `{name}`: {}, was {}",
            when(n.header),
            when(o.header)
        ));
    }
}

/// A direction rule with its references resolved, for comparison across specs.
fn rule_text(p: &Protocol, rule: &DirectionRule) -> String {
    let value_name = |i: usize| {
        p.frames
            .first()
            .and_then(|f| f.values.get(i))
            .map_or("?", |v| v.name.as_str())
    };
    match rule {
        DirectionRule::InSet { value, set } => {
            let (first, last) = p.addresses.get(*set).map_or((0, 0), |a| (a.first, a.last));
            format!("`{}` in {first:#x}..={last:#x}", value_name(*value))
        }
        DirectionRule::Equals { value, equals } => {
            format!("`{}` == {equals:#x}", value_name(*value))
        }
        DirectionRule::Given => "given to the decoder".to_string(),
    }
}

/// A direction's rule and what its frames carry in place of a command, for comparison.
fn direction_text(p: &Protocol, d: &protocol_spec::ir::Direction) -> String {
    let rule = rule_text(p, &d.rule);
    match d.message.and_then(|(si, _)| p.structs.get(si)) {
        Some(s) => format!("{rule}, carrying `{}`", s.name),
        None => rule,
    }
}

fn diff_directions(old: &Protocol, new: &Protocol, out: &mut Vec<Change>) {
    let names = |p: &Protocol| {
        p.directions
            .iter()
            .map(|d| d.name.clone())
            .collect::<Vec<_>>()
    };
    let mut r = Report {
        out,
        subject: "directions".into(),
    };
    if names(old) != names(new) {
        r.breaking(format!(
            "[{}] → [{}] (which payload a frame carries depends on them)",
            names(old).join(", "),
            names(new).join(", ")
        ));
        return;
    }
    for (od, nd) in old.directions.iter().zip(&new.directions) {
        let (a, b) = (direction_text(old, od), direction_text(new, nd));
        if a != b {
            r.breaking(format!("`{}`: {a} → {b}", nd.name));
        }
    }
}

fn id_text(c: &Command) -> String {
    let ids: Vec<String> = c.id.iter().map(|v| format!("{v:#04x}")).collect();
    match ids.as_slice() {
        [one] => one.clone(),
        many => format!("[{}]", many.join(", ")),
    }
}

fn diff_commands(old: &Protocol, new: &Protocol, out: &mut Vec<Change>) {
    for oc in &old.commands {
        let mut r = Report {
            out,
            subject: format!("command {} (id {})", oc.name, id_text(oc)),
        };
        let Some(nc) = new.commands.iter().find(|c| c.id == oc.id) else {
            match new.commands.iter().find(|c| c.name == oc.name) {
                Some(moved) => r.breaking(format!(
                    "id changed to {}: receivers of one version do not know the other's",
                    id_text(moved)
                )),
                None => r.breaking("removed: its frames become unknown commands"),
            }
            continue;
        };
        if nc.name != oc.name {
            r.source(format!(
                "renamed to {} (same id; the generated variant's name changes)",
                nc.name
            ));
        }
        if nc.check_extra != oc.check_extra {
            r.breaking(format!(
                "check_extra {} → {}: the frames of one version fail the other's check",
                oc.check_extra.map_or("none".into(), |v| v.to_string()),
                nc.check_extra.map_or("none".into(), |v| v.to_string())
            ));
        }
        if nc.can_id != oc.can_id {
            r.breaking(format!(
                "CAN id {} → {}",
                oc.can_id.map_or("none".into(), |v| format!("{v:#x}")),
                nc.can_id.map_or("none".into(), |v| format!("{v:#x}"))
            ));
        }
        for (di, (op, np)) in oc.payloads.iter().zip(&nc.payloads).enumerate() {
            let dir = old
                .directions
                .get(di)
                .map_or(String::from("payload"), |d| format!("{} payload", d.name));
            match (op, np) {
                (None, None) => {}
                (None, Some(s)) => r.breaking(format!(
                    "{dir}: none → `{}` ({} bytes); payload sizes are exact",
                    new.structs[*s].name, new.structs[*s].size
                )),
                (Some(s), None) => r.breaking(format!(
                    "{dir}: `{}` ({} bytes) → none",
                    old.structs[*s].name, old.structs[*s].size
                )),
                (Some(a), Some(b)) => {
                    let before = r.out.len();
                    payload::diff_struct(
                        old,
                        &old.structs[*a],
                        new,
                        &new.structs[*b],
                        &dir,
                        &mut r,
                    );
                    let reused = nc.name != oc.name
                        && r.out[before..].iter().any(|c| c.class == Class::Breaking);
                    if reused {
                        r.breaking(format!(
                            "the id is reused for another payload ({} is not {})",
                            nc.name, oc.name
                        ));
                    }
                }
            }
        }
        if oc.payloads.len() != nc.payloads.len() {
            r.breaking("payloads per direction changed");
        }
        if oc.doc != nc.doc {
            r.compatible("doc changed");
        }
    }
    for nc in &new.commands {
        // A command whose id changed is reported above, as that change, not again as added.
        let known = old
            .commands
            .iter()
            .any(|c| c.id == nc.id || c.name == nc.name);
        if !known {
            let mut r = Report {
                out,
                subject: format!("command {} (id {})", nc.name, id_text(nc)),
            };
            r.source(format!(
                "added (old receivers count its frames as unknown commands; {ADDED_VARIANT})"
            ));
        }
    }
}
