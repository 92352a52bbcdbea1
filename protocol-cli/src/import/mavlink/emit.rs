//! The spec text of a dialect: MAVLink's two frame formats (as the bundled `specs/mavlink.toml`
//! frames them), a command and a struct per message with its derived CRC_EXTRA, an enum per
//! MAVLink enum, and the bits of each bitmask as constants.
//!
//! This module owns how the model maps onto the spec language: names (structs and enums in
//! `PascalCase`, everything else as MAVLink spells it), field types, and which fields are typed
//! by an enum. The text is deterministic: the same XML gives the same bytes.

use std::fmt::Write;

use super::crc_extra::crc_extra;
use super::model::{Dialect, Enum, Field, Message, Scalar};

/// The framing every dialect shares: MAVLink 2 first (signed frames carried, unknown
/// incompatibility flags refused, trailing zeros truncated), then MAVLink 1.
const FRAMES: &str = include_str!("frames.toml");

/// The spec text of `dialect`, whose file is named `file` (shown in the header and docs).
///
/// # Errors
/// Two names of the spec would be one (a message and an enum of the same `PascalCase` name).
pub fn spec_text(dialect: &Dialect, stem: &str) -> Result<String, String> {
    let enums = enum_types(dialect);
    check_names(dialect)?;
    let mut out = String::new();
    header(&mut out, dialect, stem);
    out.push_str(FRAMES);
    constants(&mut out, dialect);
    commands(&mut out, dialect);
    for m in &dialect.messages {
        message_struct(&mut out, m, dialect, &enums);
    }
    for (e, ty) in dialect.enums.iter().zip(&enums) {
        if let Some(ty) = ty {
            enum_table(&mut out, e, *ty);
        }
    }
    Ok(out)
}

/// The header comment and `[protocol]`.
fn header(out: &mut String, dialect: &Dialect, stem: &str) {
    let files = dialect.files.join(", ");
    let _ = writeln!(
        out,
        "# MAVLink 1 and 2, the `{stem}` dialect: written by `protocol import mavlink {stem}.xml` \
         from\n# {files}. Do not edit: import it again.\n"
    );
    let _ = writeln!(
        out,
        "[protocol]\nname = \"mavlink_{}\"\nversion = \"2.0\"\nbyte_order = \"little\"",
        snake(stem)
    );
    let doc = format!(
        "MAVLink 1 and MAVLink 2, the `{stem}` dialect ({} messages, from {files}): two frame \
         formats of one link, told apart by their start marker and decoded by one decoder \
         (`any_decoder`). Each message's CRC_EXTRA is derived from its definition by the \
         importer. Enumerations are enums that keep unknown values; a bitmask field is an \
         integer, its bits constants.",
        dialect.messages.len()
    );
    let _ = writeln!(out, "doc = {}\n", quote(&doc));
}

/// The bits of every bitmask, as constants.
fn constants(out: &mut String, dialect: &Dialect) {
    out.push_str("[constants]\n");
    for e in dialect.enums.iter().filter(|e| is_bitmask(dialect, e)) {
        for entry in &e.entries {
            let doc = joined(&format!("A bit of {}.", e.name), &entry.doc);
            let _ = writeln!(
                out,
                "{} = {{ value = {:#x}, doc = {} }}",
                entry.name,
                entry.value,
                quote(&doc)
            );
        }
    }
    out.push('\n');
}

/// `[commands]`: one line per message, by id.
fn commands(out: &mut String, dialect: &Dialect) {
    out.push_str("[commands]\n");
    for m in &dialect.messages {
        let doc = match &m.deprecated {
            Some(note) => joined(&m.doc, note),
            None => m.doc.clone(),
        };
        let _ = write!(
            out,
            "{} = {{ id = {}, payload = \"{}\", check_extra = {}",
            m.name,
            m.id,
            pascal(&m.name),
            crc_extra(m)
        );
        if !doc.is_empty() {
            let _ = write!(out, ", doc = {}", quote(&doc));
        }
        out.push_str(" }\n");
    }
}

/// `[structs.Name]` of a message: its fields in wire order.
fn message_struct(out: &mut String, m: &Message, dialect: &Dialect, enums: &[Option<Scalar>]) {
    let _ = writeln!(out, "\n[structs.{}]\nfields = [", pascal(&m.name));
    for f in &m.fields {
        let _ = write!(out, "  {{ name = {}, type = ", quote(&field_name(&f.name)));
        let typed = field_enum(f, dialect, enums);
        match (typed, f.scalar, f.array) {
            (Some(e), _, _) => out.push_str(&quote(&pascal(&e.name))),
            (None, Scalar::Char, Some(n)) => {
                let _ = write!(out, "\"char[{n}]\"");
            }
            (None, s, n) => {
                let _ = write!(out, "\"{}\"", rust_type(s));
                if let Some(n) = n {
                    let _ = write!(out, ", count = {n}");
                }
            }
        }
        if let Some(unit) = &f.units {
            let _ = write!(out, ", unit = {}", quote(unit));
        }
        if f.extension {
            out.push_str(", extension = true");
        }
        let doc = field_doc(f, dialect, typed.is_some());
        if !doc.is_empty() {
            let _ = write!(out, ", doc = {}", quote(&doc));
        }
        out.push_str(" },\n");
    }
    out.push_str("]\n");
}

/// A field's doc: its text, and the enum or bitmask its values come from when its type does
/// not say so.
fn field_doc(f: &Field, dialect: &Dialect, typed: bool) -> String {
    let doc = if field_name(&f.name) == f.name {
        f.doc.clone()
    } else {
        joined(&f.doc, &format!("`{}` in MAVLink's definition.", f.name))
    };
    match (&f.enum_name, typed) {
        (Some(name), false) => {
            let bits = dialect
                .enum_named(name)
                .is_some_and(|e| is_bitmask(dialect, e));
            let what = if bits { "Bits" } else { "Values" };
            joined(&doc, &format!("{what} of {name}."))
        }
        _ => doc,
    }
}

/// `[enums.Name]`: the enum's type and values; unknown values are kept, as a receiver of an
/// older definition meets values added later.
fn enum_table(out: &mut String, e: &Enum, ty: Scalar) {
    let _ = writeln!(
        out,
        "\n[enums.{}]\ntype = \"{}\"\nunknown = \"keep\"",
        pascal(&e.name),
        rust_type(ty)
    );
    if !e.doc.is_empty() {
        let _ = writeln!(out, "doc = {}", quote(&e.doc));
    }
    let _ = writeln!(out, "\n[enums.{}.values]", pascal(&e.name));
    for entry in &e.entries {
        let _ = write!(out, "{} = {{ value = {}", entry.name, entry.value);
        if !entry.doc.is_empty() {
            let _ = write!(out, ", doc = {}", quote(&entry.doc));
        }
        out.push_str(" }\n");
    }
}

/// The enum a field is typed by: a scalar field of a plain (not bitmask) enum whose type is
/// the enum's.
fn field_enum<'a>(f: &Field, dialect: &'a Dialect, enums: &[Option<Scalar>]) -> Option<&'a Enum> {
    let name = f.enum_name.as_deref().filter(|_| f.array.is_none())?;
    let i = dialect.enums.iter().position(|e| e.name == name)?;
    (enums[i] == Some(f.scalar)).then_some(&dialect.enums[i])
}

/// The wire type of each enum of the spec (`None`: a bitmask, or never written as an enum).
/// An enum takes the type of the first scalar field typed by it whose type holds every value;
/// an enum no field uses takes the smallest unsigned type that holds its values.
fn enum_types(dialect: &Dialect) -> Vec<Option<Scalar>> {
    let fields: Vec<&Field> = dialect.messages.iter().flat_map(|m| &m.fields).collect();
    dialect
        .enums
        .iter()
        .map(|e| {
            if is_bitmask(dialect, e) {
                return None;
            }
            let max = e.entries.iter().map(|x| x.value).max().unwrap_or(0);
            let fits = |s: Scalar| s.max_value().is_some_and(|m| max <= m);
            let used = fields.iter().filter(|f| f.array.is_none());
            let mut used = used.filter(|f| f.enum_name.as_deref() == Some(e.name.as_str()));
            match used.find(|f| fits(f.scalar)) {
                Some(f) => Some(f.scalar),
                None => [Scalar::U8, Scalar::U16, Scalar::U32, Scalar::U64]
                    .into_iter()
                    .find(|&s| fits(s)),
            }
        })
        .collect()
}

/// Whether an enum's values are bits: it says so, or a field shows it as a bitmask.
fn is_bitmask(dialect: &Dialect, e: &Enum) -> bool {
    e.bitmask
        || dialect
            .messages
            .iter()
            .flat_map(|m| &m.fields)
            .any(|f| f.bitmask && f.enum_name.as_deref() == Some(e.name.as_str()))
}

/// No struct and enum take the same `PascalCase` name.
fn check_names(dialect: &Dialect) -> Result<(), String> {
    for e in &dialect.enums {
        if let Some(m) = dialect
            .messages
            .iter()
            .find(|m| pascal(&m.name) == pascal(&e.name))
        {
            return Err(format!(
                "message {} and enum {} would both be `{}`",
                m.name,
                e.name,
                pascal(&e.name)
            ));
        }
    }
    Ok(())
}

/// The spec's primitive for a MAVLink scalar (`char` alone is a byte).
fn rust_type(s: Scalar) -> &'static str {
    match s {
        Scalar::Char | Scalar::U8 => "u8",
        Scalar::I8 => "i8",
        Scalar::U16 => "u16",
        Scalar::I16 => "i16",
        Scalar::U32 => "u32",
        Scalar::I32 => "i32",
        Scalar::U64 => "u64",
        Scalar::I64 => "i64",
        Scalar::F32 => "f32",
        Scalar::F64 => "f64",
    }
}

/// A field name as the spec's `snake_case` (`zoomLevel` as `zoom_level`, `ICAO_address` as
/// `icao_address`): the CRC_EXTRA hashes MAVLink's spelling, which the field's doc gives.
pub fn field_name(name: &str) -> String {
    let mut out = String::with_capacity(name.len() + 4);
    let mut previous_lower = false;
    for c in name.chars() {
        if c.is_ascii_uppercase() && previous_lower {
            out.push('_');
        }
        previous_lower = c.is_ascii_lowercase() || c.is_ascii_digit();
        out.push(c.to_ascii_lowercase());
    }
    out
}

/// `GPS_RAW_INT` as `GpsRawInt`.
pub fn pascal(name: &str) -> String {
    let mut out = String::with_capacity(name.len());
    for word in name.split('_').filter(|w| !w.is_empty()) {
        let mut chars = word.chars();
        if let Some(first) = chars.next() {
            out.push(first.to_ascii_uppercase());
            out.extend(chars.map(|c| c.to_ascii_lowercase()));
        }
    }
    out
}

/// A file stem as a `snake_case` name (`ASLUAV` as `asluav`, `cubepilot` unchanged).
fn snake(stem: &str) -> String {
    stem.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .collect()
}

/// Two doc texts as one, a space between.
fn joined(a: &str, b: &str) -> String {
    match (a.is_empty(), b.is_empty()) {
        (true, _) => b.to_string(),
        (_, true) => a.to_string(),
        _ => format!("{a} {b}"),
    }
}

/// A TOML basic string.
fn quote(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + 2);
    out.push('"');
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            c if c.is_control() => {
                let _ = write!(out, "\\u{:04X}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}
