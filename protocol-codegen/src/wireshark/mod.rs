//! The Wireshark dissector (`protocol gen wireshark`): one Lua file per spec, printed from the
//! IR and the plans the other backends execute.
//!
//! Like the C printer, this backend decides nothing. The frame rules of each format come from
//! [`crate::layout::lower_layout`], its packet rules (what it carries, its key,
//! acknowledgements, directions, stuffing, zero-fill) from [`crate::rules::lower_rules`], the
//! payloads from the IR's structs; all of them are printed as Lua tables (`formats`,
//! `fields`), and a fixed engine (`lua/*.lua`, printed as it is) executes the tables as the
//! runtime's engine executes its layouts: the checks (every checksum, and any CRC of up to 32
//! bits from its parameters), the framing (an escaped link cut at its flags and unescaped), the
//! payload reader (bit members read bit by bit, exact to 64 bits; a packet carried in a
//! payload read one level in a subtree of its bytes), the packet rules and the
//! registration (a user link type for raw serial captures, UDP and TCP ports from the
//! preferences, SocketCAN frames for a CAN format).
//!
//! Every header value, check, struct field and bit member is a filterable field named
//! `<protocol>.<owner>.<name>` (`hflink.link.sender`, `hflink.ChassisCoord.x`), its unit in
//! its label. What Lua cannot compute is refused with one line per feature before anything is
//! printed ([`generate`]'s error); what it shows less exactly than the run-time codec decodes
//! it is listed in [`Dissector::degraded`].

mod fields;
mod formats;
mod lua;

use crate::ir::{Protocol, Transport};
use fields::{Fields, StructPrinter};

/// The engine every dissector holds, in the order its parts use each other.
const ENGINE: [&str; 6] = [
    include_str!("lua/checks.lua"),
    include_str!("lua/framing.lua"),
    include_str!("lua/payload.lua"),
    include_str!("lua/packet.lua"),
    include_str!("lua/escaped.lua"),
    include_str!("lua/register.lua"),
];

/// The fields every dissector has beside the spec's, and its expert notes.
const COMMON: &str = r#"
local F_format = ProtoField.string(NAME .. ".format", "Frame format")
local F_frame = ProtoField.bytes(NAME .. ".frame", "Frame")
local F_command = ProtoField.string(NAME .. ".command", "Command")
local F_direction = ProtoField.string(NAME .. ".direction", "Direction")
local F_ack = ProtoField.bool(NAME .. ".ack", "Acknowledgement")
local F_data = ProtoField.bytes(NAME .. ".data", "Data")
local F_skipped = ProtoField.bytes(NAME .. ".skipped", "Skipped bytes")
local F_rejected = ProtoField.string(NAME .. ".rejected", "Rejected candidate")
local F_cut = ProtoField.bytes(NAME .. ".cut", "Frame continued in the next packet")
local F_escaped = ProtoField.bytes(NAME .. ".escaped", "Frame as sent, escaped")
local EXPERT = {
  bad_check = ProtoExpert.new(NAME .. ".bad_check", "Bad check", expert.group.CHECKSUM, expert.severity.ERROR),
  payload = ProtoExpert.new(NAME .. ".payload", "Payload does not fit", expert.group.MALFORMED, expert.severity.ERROR),
  unknown = ProtoExpert.new(NAME .. ".unknown", "Unknown command", expert.group.UNDECODED, expert.severity.WARN),
  skipped = ProtoExpert.new(NAME .. ".skipped.note", "Bytes between frames", expert.group.SEQUENCE, expert.severity.NOTE),
  cut = ProtoExpert.new(NAME .. ".cut.note", "Frame continues in the next packet", expert.group.REASSEMBLE, expert.severity.NOTE),
}
proto.experts = { EXPERT.bad_check, EXPERT.payload, EXPERT.unknown, EXPERT.skipped, EXPERT.cut }
local all_fields = { F_format, F_frame, F_command, F_direction, F_ack, F_data, F_skipped, F_rejected, F_cut, F_escaped }
for _, f in ipairs(F) do all_fields[#all_fields + 1] = f end
proto.fields = all_fields
"#;

/// A printed dissector.
#[derive(Debug, Clone, PartialEq)]
pub struct Dissector {
    /// `NAME.lua`.
    pub file_name: String,
    /// The Lua source.
    pub text: String,
    /// What the dissector shows less exactly than the run-time codec decodes it, one line each.
    pub degraded: Vec<String>,
}

/// The dissector of `p`.
///
/// # Errors
/// One line per feature of the spec the dissector cannot express (a 64-bit CRC, a header word
/// wider than the 6 bytes a Lua number holds exactly); nothing is printed then.
pub fn generate(p: &Protocol) -> Result<Dissector, Vec<String>> {
    let mut printer = StructPrinter {
        p,
        fields: Fields::default(),
        degraded: Vec::new(),
        refused: Vec::new(),
    };
    // The dissector has one layout per format.
    for d in p.directions.iter().filter(|d| d.frame.is_some()) {
        printer.refused.push(format!(
            "{}: direction `{}` has header fields of its own (`direction` on a layout element)",
            p.name, d.name
        ));
    }
    for f in &p.frames {
        for v in f.values.iter().filter(|v| v.word.prim.size() > 6) {
            printer.refused.push(format!(
                "{}.{}.{}: a header word of {} bytes (a Lua number holds 6 exactly)",
                p.name,
                f.name,
                v.name,
                v.word.prim.size()
            ));
        }
    }
    let structs: Vec<String> = (0..p.structs.len())
        .map(|si| printer.structure(si))
        .collect();
    let mut refused = std::mem::take(&mut printer.refused);
    let formats: Vec<String> = p
        .frames
        .iter()
        .map(|f| formats::format(p, f, &mut printer.fields, &mut refused))
        .collect();
    if !refused.is_empty() {
        return Err(refused);
    }
    let mut text = preamble(p);
    text.push_str("local F = {}\n");
    for line in &printer.fields.lines {
        text.push_str(line);
        text.push('\n');
    }
    text.push_str(&spec_table(p, &structs, &formats));
    text.push_str(COMMON.strip_prefix('\n').unwrap_or(COMMON));
    for part in ENGINE {
        text.push('\n');
        text.push_str(part);
    }
    Ok(Dissector {
        file_name: format!("{}.lua", p.name),
        text,
        degraded: printer.degraded,
    })
}

fn preamble(p: &Protocol) -> String {
    let version = if p.version.is_empty() {
        String::new()
    } else {
        format!(" {}", p.version)
    };
    let doc = p.doc.lines().next().unwrap_or("").trim();
    format!(
        "-- @generated by `protocol gen wireshark`: the Wireshark dissector of the `{name}` protocol{version}.\n\
         -- Load it with `tshark -X lua_script:{name}.lua`, or copy it into Wireshark's Lua plugin\n\
         -- folder. Raw serial captures use link type DLT_USER0 (147; a preference picks another).\n\
         -- Wireshark may have a protocol of this name already: then this one is `NAME_spec`.\n\
         local NAME = {lname}\n\
         local made, proto = pcall(Proto, NAME, {title})\n\
         if not made then\n  NAME = NAME .. \"_spec\"\n  proto = Proto(NAME, {title})\nend\n\
         local resolve, read_uint, read_field, run_check, probe, select_format, extension_len\n\
         local read_payload, dissect_frame, dissect_stream, add_skipped, add_rejected, dissect_escaped\n",
        name = p.name,
        lname = lua::string(&p.name),
        title = lua::string(&format!("{} ({})", p.name, doc.trim_end_matches('.'))),
    )
}

/// The `SPEC` table: the link, the directions, the commands, the structs and the formats.
fn spec_table(p: &Protocol, structs: &[String], formats: &[String]) -> String {
    let link: Vec<usize> = if p.link.is_empty() {
        p.frames
            .iter()
            .position(|f| f.transport == Transport::Serial)
            .into_iter()
            .map(|i| i + 1)
            .collect()
    } else {
        p.link.iter().map(|i| i + 1).collect()
    };
    let can = p
        .frames
        .iter()
        .position(|f| matches!(f.transport, Transport::Can { .. }))
        .map_or("nil".to_string(), |i| (i + 1).to_string());
    let directions: Vec<String> = p.directions.iter().map(|d| lua::string(&d.name)).collect();
    let messages: Vec<String> = p
        .directions
        .iter()
        .enumerate()
        .filter_map(|(d, dir)| {
            let (si, start) = dir.message?;
            Some(format!(
                "[{}] = {{ struct = {}, start = {start} }}",
                d + 1,
                si + 1
            ))
        })
        .collect();
    let commands: Vec<String> = p
        .commands
        .iter()
        .map(|c| {
            let payloads: Vec<String> = c
                .payloads
                .iter()
                .map(|s| s.map_or("false".to_string(), |si| (si + 1).to_string()))
                .collect();
            // A command told by one id: the id a carried packet names it by.
            let id = match c.id.as_slice() {
                [id] => format!(", id = {id}"),
                _ => String::new(),
            };
            format!(
                "  {{ name = {}, payloads = {{ {} }}{id} }},",
                lua::string(&c.name),
                payloads.join(", ")
            )
        })
        .collect();
    let link: Vec<String> = link.iter().map(ToString::to_string).collect();
    format!(
        "local SPEC = {{\n  title = {},\n  link = {{ {} }},\n  can_format = {can},\n  \
         directions = {{ {} }},\n  directions_given = {},\n  direction_messages = {{ {} }},\n}}\n\
         SPEC.commands = {{\n{}\n}}\nSPEC.structs = {{\n{}\n}}\nSPEC.formats = {{\n{}\n}}\n\
         -- The commands by the id a carried packet names them by.\n\
         SPEC.command_by_id = {{}}\n\
         for ci, c in ipairs(SPEC.commands) do\n  if c.id then SPEC.command_by_id[c.id] = ci end\nend\n",
        lua::string(&p.name.to_uppercase()),
        link.join(", "),
        directions.join(", "),
        p.directions_given(),
        messages.join(", "),
        commands.join("\n"),
        structs.join("\n"),
        formats.join("\n")
    )
}
