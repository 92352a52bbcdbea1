//! The Markdown reference of a spec (`protocol doc`): overview, addresses and directions, each
//! frame format's layout and what it carries, the command table, the conversation (`session`),
//! every struct and every enum.
//!
//! One function per section, called in document order by [`render`], so that a section can be
//! added (packet diagrams of the frame formats, say) without touching the others. The layout
//! tables of frames and structs are the ones rustdoc shows on the generated items
//! ([`crate::codegen::docs`]), so the reference and the API docs cannot disagree.
//!
//! ```
//! let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../specs/hflink.toml"))?;
//! let source = protocol_codegen::source::SpecSource::new("specs/hflink.toml", text);
//! let protocol = protocol_codegen::compile(&source).map_err(|_| "invalid spec")?;
//! let md = protocol_codegen::docs_md::render(&protocol);
//! assert!(md.starts_with("# hflink"));
//! assert!(md.contains("| 0x0c | `SET_ROBOT_SPEED` |"));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod registers;
mod session;

use std::fmt::Write as _;

use crate::codegen::docs::{frame_doc, struct_doc};
use crate::ir::{
    ByteOrder, Check, DirectionRule, Element, Enum, Frame, PacketKind, Pos, Protocol, Role,
    Transport, UnknownPolicy,
};
use crate::resources;

/// The whole reference, sections in order.
pub fn render(p: &Protocol) -> String {
    let mut out = String::new();
    overview(p, &mut out);
    addresses(p, &mut out);
    directions(p, &mut out);
    constants(p, &mut out);
    frames(p, &mut out);
    commands(p, &mut out);
    session::session(p, &mut out);
    registers::registers(p, &mut out);
    structs(p, &mut out);
    enums(p, &mut out);
    // One trailing newline, whatever the last section left.
    while out.ends_with("\n\n") {
        out.pop();
    }
    out
}

/// A table cell: no line breaks, no unescaped pipes.
fn cell(text: &str) -> String {
    text.split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .replace('|', "\\|")
}

fn overview(p: &Protocol, out: &mut String) {
    let _ = writeln!(out, "# {}\n", p.name);
    if !p.version.is_empty() {
        let _ = writeln!(out, "Spec version: {}.\n", p.version);
    }
    if !p.doc.trim().is_empty() {
        let _ = writeln!(out, "{}\n", p.doc.trim());
    }
    let _ = writeln!(
        out,
        "{} frame format{}, {} command{}, {} struct{}, {} enum{}.\n",
        p.frames.len(),
        plural(p.frames.len()),
        p.commands.len(),
        plural(p.commands.len()),
        p.structs.len(),
        plural(p.structs.len()),
        p.enums.len(),
        plural(p.enums.len())
    );
}

fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}

fn addresses(p: &Protocol, out: &mut String) {
    if p.addresses.is_empty() {
        return;
    }
    out.push_str("## Addresses\n\n| name | addresses | meaning |\n|---|---|---|\n");
    for a in &p.addresses {
        let range = if a.first == a.last {
            format!("`{:#04x}`", a.first)
        } else {
            format!("`{:#04x}` ..= `{:#04x}`", a.first, a.last)
        };
        let _ = writeln!(out, "| `{}` | {range} | {} |", a.name, cell(&a.doc));
    }
    out.push('\n');
}

fn directions(p: &Protocol, out: &mut String) {
    if p.directions.is_empty() {
        return;
    }
    if p.directions_given() {
        given_directions(p, out);
        return;
    }
    out.push_str("## Directions\n\nA command's payload depends on the direction of the frame, told by its header (rules tested in order");
    if p.link.len() > 1 {
        // Each command format of the link has the field, under the same name.
        out.push_str(", in every command format of the link");
    }
    out.push_str("):\n\n| direction | when | meaning |\n|---|---|---|\n");
    let value = |i: usize| {
        p.frames
            .first()
            .and_then(|f| f.values.get(i))
            .map_or("?", |v| v.name.as_str())
    };
    for d in &p.directions {
        let rule = match &d.rule {
            DirectionRule::InSet { value: v, set } => format!(
                "`{}` in `{}`",
                value(*v),
                p.addresses.get(*set).map_or("?", |a| a.name.as_str())
            ),
            DirectionRule::Equals { value: v, equals } => {
                format!("`{}` = `{equals:#x}`", value(*v))
            }
            DirectionRule::Given => "given to the decoder".to_string(),
        };
        let meaning = if d.empty {
            format!(
                "The header and no payload, whatever the command. {}",
                cell(&d.doc)
            )
        } else {
            cell(&d.doc)
        };
        let _ = writeln!(out, "| {} | {rule} | {} |", d.name, meaning.trim_end());
    }
    out.push('\n');
}

/// Directions no header field tells: which one a frame goes is the decoding side's to say.
fn given_directions(p: &Protocol, out: &mut String) {
    out.push_str("## Directions\n\nNo header field tells the directions apart: a decoder is given the direction of the frames it reads (generated code has a decoder per direction, `protocol decode` takes `--direction NAME`).\n\n| direction | frames carry | meaning |\n|---|---|---|\n");
    for d in &p.directions {
        let carries = match d.message.and_then(|(si, _)| p.structs.get(si)) {
            Some(s) => format!(
                "[`{}`](#{}) in place of the command",
                s.name,
                s.name.to_lowercase()
            ),
            None => "a command and its payload".to_string(),
        };
        let _ = writeln!(out, "| {} | {carries} | {} |", d.name, cell(&d.doc));
    }
    out.push('\n');
}

fn constants(p: &Protocol, out: &mut String) {
    if p.constants.is_empty() {
        return;
    }
    out.push_str("## Constants\n\n| name | value | meaning |\n|---|---:|---|\n");
    for c in &p.constants {
        let _ = writeln!(out, "| `{}` | {} | {} |", c.name, c.value, cell(&c.doc));
    }
    out.push('\n');
}

/// Each frame format: its transport, what a decoder of it takes, and its layout table.
fn frames(p: &Protocol, out: &mut String) {
    out.push_str("## Frame formats\n\n");
    for (i, f) in p.frames.iter().enumerate() {
        let _ = writeln!(out, "### `{}`\n", f.name);
        let transport = match f.transport {
            Transport::Serial => "a byte stream; frames are found by their sync bytes".to_string(),
            Transport::Can { extended } => format!(
                "CAN ({} ids); the table shows the frame as its checks see it: the id as a big-endian `u32`, the data length, then the data bytes",
                if extended { "29-bit" } else { "11-bit" }
            ),
        };
        let role = if i == 0 {
            " The default frame format."
        } else {
            ""
        };
        let _ = writeln!(out, "Transport: {transport}.{role}\n");
        let _ = writeln!(out, "Memory: {}.\n", resources::needs(f).summary());
        let notes = frame_notes(p, f);
        for note in &notes {
            let _ = writeln!(out, "- {note}");
        }
        if !notes.is_empty() {
            out.push('\n');
        }
        out.push_str("```text\n");
        out.push_str(&packet_diagram(f));
        out.push_str("```\n\n");
        out.push_str(frame_doc(f).trim_end());
        out.push_str("\n\n");
        if i == 0 {
            own_layouts(p, out);
        }
    }
}

/// The first frame format as each direction with fields of its own lays it out: the layout
/// above is every other direction's.
fn own_layouts(p: &Protocol, out: &mut String) {
    for d in &p.directions {
        let Some(f) = &d.frame else {
            continue;
        };
        let _ = writeln!(
            out,
            "#### `{}` as {}s lay it out

A {} has header fields the layout above has not; its frames are laid out so:\n",
            f.name, d.name, d.name
        );
        out.push_str("```text\n");
        out.push_str(&packet_diagram(f));
        out.push_str("```\n\n");
        out.push_str(frame_doc(f).trim_end());
        out.push_str("\n\n");
    }
}

/// How a check's value of more than one byte is stored (`, stored little-endian`): two specs
/// that differ there describe different links. Nothing for a one-byte value, which has no
/// byte order.
fn stored_order(c: &Check) -> &'static str {
    match (c.size > 1, c.endian) {
        (false, _) => "",
        (true, ByteOrder::Little) => ", stored little-endian",
        (true, ByteOrder::Big) => ", stored big-endian",
    }
}

/// Bytes per row of a packet diagram (32 bits, as in the RFCs).
const ROW_BYTES: usize = 4;
/// Characters per byte: two per bit.
const BYTE_CHARS: usize = 16;

/// An RFC-style packet picture of a frame format: the header elements four bytes to a row, the
/// payload as a variable block, then the elements after it; below, what each check covers.
pub fn packet_diagram(f: &Frame) -> String {
    let mut head: Vec<(String, usize)> = Vec::new();
    let mut tail: Vec<(String, usize)> = Vec::new();
    let mut legend: Vec<String> = Vec::new();
    let mut after_payload = false;
    for e in &f.elements {
        let item = match e {
            Element::Sync(b) => Some((
                format!(
                    "sync {}",
                    b.iter()
                        .map(|x| format!("{x:02X}"))
                        .collect::<Vec<_>>()
                        .join(" ")
                ),
                b.len(),
            )),
            Element::Word {
                name,
                scalar,
                values,
                ..
            } => {
                let members = values
                    .iter()
                    .map(|&i| format!("{}:{}", f.values[i].name, f.values[i].width))
                    .collect::<Vec<_>>()
                    .join(" ");
                if values.first() == Some(&0) && !f.sync_set.is_empty() {
                    let set: Vec<String> = f.sync_set.iter().map(|x| format!("{x:02X}")).collect();
                    legend.push(format!("{name} = the sync, one of {}", set.join(" ")));
                }
                let label =
                    if values.len() > 1 && members.len() < scalar.prim.size() * BYTE_CHARS - 1 {
                        members
                    } else {
                        if values.len() > 1 {
                            legend.push(format!("{name} = {members} (bits, lowest first)"));
                        }
                        name.clone()
                    };
                Some((label, scalar.prim.size()))
            }
            Element::Payload => {
                after_payload = true;
                None
            }
            Element::Check(i) => f.checks.get(*i).map(|c| (c.name.clone(), c.size)),
            Element::Trailer(i) => f.trailers.get(*i).map(|t| {
                (
                    format!(
                        "{} {}",
                        t.name,
                        t.bytes
                            .iter()
                            .map(|x| format!("{x:02X}"))
                            .collect::<Vec<_>>()
                            .join(" ")
                    ),
                    t.bytes.len(),
                )
            }),
            Element::FlagTrailer => f.flag_trailer.as_ref().map(|t| {
                (
                    format!("{} (when {})", t.name, f.values[t.flag].name),
                    t.len,
                )
            }),
        };
        if let Some(item) = item {
            if after_payload {
                tail.push(item)
            } else {
                head.push(item)
            }
        }
    }
    let mut out = String::new();
    out.push_str(" 0                   1                   2                   3\n");
    out.push_str(" 0 1 2 3 4 5 6 7 8 9 0 1 2 3 4 5 6 7 8 9 0 1 2 3 4 5 6 7 8 9 0 1\n");
    draw_rows(&head, &mut out, true);
    let full = ROW_BYTES * BYTE_CHARS - 1;
    let payload = if f.payload_min == f.payload_max {
        format!("payload, {}", crate::codegen::docs::bytes(f.payload_max))
    } else {
        format!("payload, {} to {} bytes", f.payload_min, f.payload_max)
    };
    if out.ends_with('\n') && !out.ends_with("+\n") {
        out.push_str(&separator(ROW_BYTES));
    }
    out.push_str(&format!(
        "|{}|\n~{}~\n|{}|\n",
        " ".repeat(full),
        center(&payload, full),
        " ".repeat(full)
    ));
    out.push_str(&separator(ROW_BYTES));
    draw_rows(&tail, &mut out, false);
    for line in &legend {
        out.push_str(line);
        out.push('\n');
    }
    for c in &f.checks {
        out.push_str(&format!(
            "{} covers bytes {} .. {}{}{}\n",
            c.name,
            pos_text(c.from),
            pos_text(c.to),
            stored_order(c),
            if c.header { " (a header check)" } else { "" }
        ));
    }
    out
}

fn pos_text(p: Pos) -> String {
    match p {
        Pos::Start(n) => n.to_string(),
        Pos::End(n) => format!("end - {n}"),
    }
}

fn separator(bytes: usize) -> String {
    format!("{}+\n", "+-".repeat(bytes * 8))
}

fn center(label: &str, width: usize) -> String {
    let label: String = label.chars().take(width).collect();
    let n = label.chars().count();
    let left = (width - n) / 2;
    format!(
        "{}{}{}",
        " ".repeat(left),
        label,
        " ".repeat(width - n - left)
    )
}

/// Rows of at most four bytes; an element crossing a row boundary continues on the next row.
fn draw_rows(items: &[(String, usize)], out: &mut String, leading_separator: bool) {
    let mut row: Vec<(String, usize)> = Vec::new();
    let mut used = 0;
    let mut first_row = leading_separator;
    let flush =
        |row: &mut Vec<(String, usize)>, used: usize, out: &mut String, first: &mut bool| {
            if row.is_empty() {
                return;
            }
            if *first {
                out.push_str(&separator(used));
                *first = false;
            }
            out.push('|');
            for (label, n) in row.iter() {
                out.push_str(&center(label, n * BYTE_CHARS - 1));
                out.push('|');
            }
            out.push('\n');
            out.push_str(&separator(used));
            row.clear();
        };
    for (label, size) in items {
        let mut left = *size;
        let mut cont = false;
        while left > 0 {
            let take = left.min(ROW_BYTES - used);
            row.push((
                if cont {
                    format!("{label} (cont.)")
                } else {
                    label.clone()
                },
                take,
            ));
            used += take;
            left -= take;
            cont = true;
            if used == ROW_BYTES {
                flush(&mut row, used, out, &mut first_row);
                used = 0;
            }
        }
    }
    flush(&mut row, used, out, &mut first_row);
}

/// The byte escaping of a frame format, in a sentence.
fn escape_note(e: &crate::ir::Escape) -> String {
    let (flag, esc) = (e.flag, e.escape);
    let rule = match e.xor {
        Some(x) => {
            let bytes: Vec<String> = e.pairs.iter().map(|[r, _]| format!("`{r:02X}`")).collect();
            format!(
                "each of {} goes as `{esc:02X}` and the byte XOR `{x:02X}`",
                bytes.join(", ")
            )
        }
        None => {
            let pairs: Vec<String> = e
                .pairs
                .iter()
                .map(|[r, s]| format!("`{r:02X}` as `{esc:02X} {s:02X}`"))
                .collect();
            pairs.join(", ")
        }
    };
    format!(
        "Byte escaping: the frame opens and closes with the flag `{flag:02X}`; between the flags, {rule}. The length and the checks count the bytes before escaping; a flag always ends a frame."
    )
}

/// What a frame format does besides its layout table: the struct it carries, its
/// acknowledgements, bare headers, byte stuffing, byte escaping.
fn frame_notes(p: &Protocol, f: &Frame) -> Vec<String> {
    let mut notes = Vec::new();
    if let Some(s) = f.message.and_then(|si| p.structs.get(si)) {
        notes.push(format!(
            "Every frame carries a [`{}`](#{}).",
            s.name,
            s.name.to_lowercase()
        ));
    }
    if let Some((flag, header_len)) = f.ack {
        let name = f.values.get(flag).map_or("?", |v| v.name.as_str());
        let value = match f.values.get(flag).map(|v| &v.role) {
            Some(Role::Ack(v)) => *v,
            _ => 1,
        };
        notes.push(format!(
            "Acknowledgements: when `{name}` is {value}, the frame has no command; its first {header_len} bytes are the header and the bytes up to the trailer are the acknowledgement's data."
        ));
    }
    if let Some(bare) = f.bare_len {
        notes.push(format!(
            "A frame may be its header alone: {bare} bytes, with no payload and no trailer."
        ));
    }
    if let Some((after, insert)) = &f.stuffing {
        let pattern: Vec<String> = after.iter().map(|b| format!("`{b:02X}`")).collect();
        notes.push(format!(
            "Byte stuffing: inside the payload, the sender inserts `{insert:02X}` after every {}; the length and the checks count the stuffed bytes.",
            pattern.join(" ")
        ));
    }
    if let Some(e) = &f.escape {
        notes.push(escape_note(e));
    }
    if f.packet == PacketKind::Commands {
        let first = p.frames.first().map_or("?", |f| f.name.as_str());
        notes.push(format!(
            "Carries the commands too, beside `{first}`: each command whose id fits its dispatch key ({} of {}). The link's one decoder finds the frames of every format by its sync.",
            f.commands.len(),
            p.commands.len()
        ));
    }
    if !f.extensions {
        notes.push("Without extension fields: a command's payload is its struct's fields before the first extension field; the extension fields decode as zero and are not sent.".to_string());
    }
    if f.truncate_zeros {
        notes.push("Trailing-zero truncation: the sender drops the zero bytes at the end of a command's payload (keeping its first byte), and the length and the checks count the bytes sent; the receiver zero-fills the payload to its struct's size.".to_string());
    }
    notes
}

/// The command table: id, name, payload per direction with its size, doc.
fn commands(p: &Protocol, out: &mut String) {
    if p.commands.is_empty() {
        return;
    }
    let key: Vec<&str> = p
        .frames
        .first()
        .map(|f| {
            f.dispatch
                .iter()
                .filter_map(|&i| f.values.get(i))
                .map(|v| v.name.as_str())
                .collect()
        })
        .unwrap_or_default();
    let can = p.commands.iter().any(|c| c.can_id.is_some());
    let slots: Vec<String> = if p.directions.is_empty() {
        vec!["payload".into()]
    } else {
        // An empty direction (sorted last) carries no command's payload: no column.
        p.directions
            .iter()
            .filter(|d| !d.empty)
            .map(|d| d.name.clone())
            .collect()
    };
    let _ = writeln!(
        out,
        "## Commands\n\nThe id is the value of the dispatch key ({}).\n",
        key.iter()
            .map(|k| format!("`{k}`"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let mut head = String::from("| id |");
    let mut rule = String::from("|---|");
    if can {
        head.push_str(" CAN id |");
        rule.push_str("---|");
    }
    head.push_str(" name |");
    rule.push_str("---|");
    for s in &slots {
        let _ = write!(head, " {s} |");
        rule.push_str("---|");
    }
    head.push_str(" doc |");
    rule.push_str("---|");
    let _ = writeln!(out, "{head}\n{rule}");
    for c in &p.commands {
        let ids: Vec<String> = c.id.iter().map(|v| format!("{v:#04x}")).collect();
        let mut row = format!("| {} |", ids.join(", "));
        if can {
            let _ = write!(
                row,
                " {} |",
                c.can_id.map_or("-".into(), |v| format!("{v:#05x}"))
            );
        }
        let _ = write!(row, " `{}` |", c.name);
        for i in 0..slots.len() {
            let text = match c.payloads.get(i).copied().flatten() {
                Some(si) => {
                    let s = &p.structs[si];
                    let size = if s.min_size == s.size {
                        format!("{} B", s.size)
                    } else {
                        format!("{}..={} B", s.min_size, s.size)
                    };
                    format!("[`{}`](#{}) ({size})", s.name, s.name.to_lowercase())
                }
                None => "empty".into(),
            };
            let _ = write!(row, " {text} |");
        }
        let _ = writeln!(row, " {} |", cell(&c.doc));
        out.push_str(&row);
    }
    out.push('\n');
}

/// Every struct, with its wire layout table.
fn structs(p: &Protocol, out: &mut String) {
    if p.structs.is_empty() {
        return;
    }
    out.push_str("## Structs\n\n");
    for s in &p.structs {
        let _ = writeln!(out, "### {}\n", s.name);
        out.push_str(struct_doc(p, s).trim());
        out.push_str("\n\n");
        if let Some(base) = s.base_size {
            let _ = writeln!(
                out,
                "Extension fields: the fields from byte {base} on. A frame format without extension fields carries the first {base} bytes, and the extension fields decode as zero.\n"
            );
        }
    }
}

/// Every enum with its values.
fn enums(p: &Protocol, out: &mut String) {
    if p.enums.is_empty() {
        return;
    }
    out.push_str("## Enums\n\n");
    for e in &p.enums {
        enum_section(e, out);
    }
}

/// A variant's value: the IR holds two's complement bits, a signed enum shows the number.
fn value_text(e: &Enum, bits: u64) -> String {
    let width = 8 * e.prim.size() as u32;
    if e.prim.is_signed() && width < 64 {
        let shift = 64 - width;
        (((bits << shift) as i64) >> shift).to_string()
    } else if e.prim.is_signed() {
        (bits as i64).to_string()
    } else {
        bits.to_string()
    }
}

fn enum_section(e: &Enum, out: &mut String) {
    let _ = writeln!(out, "### {}\n", e.name);
    if !e.doc.trim().is_empty() {
        let _ = writeln!(out, "{}\n", e.doc.trim());
    }
    let unknown = match e.unknown {
        UnknownPolicy::Reject => "a value with no variant is a decode error",
        UnknownPolicy::Keep => "a value with no variant is kept as it is",
    };
    let _ = writeln!(out, "On the wire as `{}`; {unknown}.\n", e.prim.spec_name());
    out.push_str("| value | name | meaning |\n|---:|---|---|\n");
    for v in &e.variants {
        let _ = writeln!(
            out,
            "| {} | `{}` | {} |",
            value_text(e, v.value),
            v.name,
            cell(&v.doc)
        );
    }
    out.push('\n');
}
