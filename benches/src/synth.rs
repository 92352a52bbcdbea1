//! Synthetic specs of N commands (N up to 256), to see how the generated code and the macro's
//! expansion time grow with the size of a spec.
//!
//! The frame is HFLink's (a `u8` command id, so 256 commands at most, and directions from the
//! sender's address range). Command `i` carries a request struct of `1 + i % 8` fields whose
//! types cycle through the primitive types; every other command also has a response struct, and
//! every fourth request nests a shared struct, so the spec exercises the same generators a real
//! one does.

use std::fmt::Write;

/// Field types the synthetic structs cycle through.
const TYPES: [&str; 8] = ["u8", "i16", "u32", "f32", "u16", "i32", "f64", "bool"];

/// The text of a synthetic spec with `commands` commands (at most 256).
///
/// # Panics
///
/// If `commands` exceeds 256 (the id is a `u8`).
pub fn spec(commands: usize) -> String {
    assert!(commands <= 256, "a u8 command id allows 256 commands");
    let mut s = String::new();
    let _ = write!(
        s,
        r#"[protocol]
name = "synth"
version = "{commands}"
byte_order = "little"
doc = "A synthetic spec of {commands} commands, for the size and expansion-time scaling."

[addresses]
master = {{ range = [0x01, 0x10], doc = "Masters." }}
slave = {{ range = [0x11, 0x40], doc = "Slaves." }}

[frames.link]
doc = "HFLink's frame."
layout = [
  {{ sync = [0xFF, 0xFF] }},
  {{ field = "sender", type = "u8", addresses = true, doc = "Sender." }},
  {{ field = "receiver", type = "u8", addresses = true, doc = "Receiver." }},
  {{ field = "length", type = "u16be", length_of = "command..payload", doc = "Bytes of command and payload." }},
  {{ field = "command", type = "u8", doc = "Command id." }},
  {{ payload = {{ max = 119 }} }},
  {{ check = "sum-mod-255", over = "frame", doc = "Sum modulo 255." }},
]
dispatch = ["command"]

[directions]
request = {{ field = "sender", in = "master", doc = "From a master." }}
response = {{ field = "sender", in = "slave", doc = "From a slave." }}

[commands]
"#
    );
    for i in 0..commands {
        let response = if i % 2 == 1 {
            format!(", response = \"Reply{i:03}\"")
        } else {
            String::new()
        };
        let _ = writeln!(
            s,
            "CMD_{i:03} = {{ id = {i}, request = \"Request{i:03}\"{response}, doc = \"Command {i}.\" }}"
        );
    }
    s.push_str(
        r#"
[structs.Shared]
doc = "A struct nested in some requests."
fields = [
  { name = "x", type = "f32" },
  { name = "y", type = "f32" },
  { name = "flags", type = "u8" },
]
"#,
    );
    for i in 0..commands {
        let _ = writeln!(
            s,
            "\n[structs.Request{i:03}]\ndoc = \"Request of command {i}.\"\nfields = ["
        );
        for f in 0..=(i % 8) {
            let _ = writeln!(
                s,
                "  {{ name = \"f{f}\", type = \"{}\" }},",
                TYPES[(i + f) % TYPES.len()]
            );
        }
        if i % 4 == 0 {
            let _ = writeln!(s, "  {{ name = \"shared\", type = \"Shared\" }},");
        }
        s.push_str("]\n");
        if i % 2 == 1 {
            let _ = writeln!(
                s,
                "\n[structs.Reply{i:03}]\ndoc = \"Response of command {i}.\"\nfields = [\n  {{ name = \"status\", type = \"u8\" }},\n  {{ name = \"value\", type = \"{}\" }},\n]",
                TYPES[i % TYPES.len()]
            );
        }
    }
    s
}
