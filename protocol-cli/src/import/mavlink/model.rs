//! The dialect as MAVLink defines it: messages (fields in declaration and in wire order,
//! extensions), enums and bitmasks, read from a dialect's XML and the files it includes.
//!
//! This module owns reading the XML into that model and MAVLink's rules on it (wire order,
//! include resolution, enums merged across files); it knows nothing of the spec language.

use std::path::{Path, PathBuf};

use super::xml::{self, Element};

/// A scalar type of a MAVLink field, as the XML names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scalar {
    /// `char`: a byte of text.
    Char,
    /// `uint8_t` (and `uint8_t_mavlink_version`).
    U8,
    /// `int8_t`.
    I8,
    /// `uint16_t`.
    U16,
    /// `int16_t`.
    I16,
    /// `uint32_t`.
    U32,
    /// `int32_t`.
    I32,
    /// `uint64_t`.
    U64,
    /// `int64_t`.
    I64,
    /// `float`.
    F32,
    /// `double`.
    F64,
}

impl Scalar {
    /// The type from its C name.
    fn parse(name: &str) -> Option<Scalar> {
        Some(match name {
            "char" => Scalar::Char,
            "uint8_t" | "uint8_t_mavlink_version" => Scalar::U8,
            "int8_t" => Scalar::I8,
            "uint16_t" => Scalar::U16,
            "int16_t" => Scalar::I16,
            "uint32_t" => Scalar::U32,
            "int32_t" => Scalar::I32,
            "uint64_t" => Scalar::U64,
            "int64_t" => Scalar::I64,
            "float" => Scalar::F32,
            "double" => Scalar::F64,
            _ => return None,
        })
    }

    /// The C name, as CRC_EXTRA hashes it.
    pub fn c_name(self) -> &'static str {
        match self {
            Scalar::Char => "char",
            Scalar::U8 => "uint8_t",
            Scalar::I8 => "int8_t",
            Scalar::U16 => "uint16_t",
            Scalar::I16 => "int16_t",
            Scalar::U32 => "uint32_t",
            Scalar::I32 => "int32_t",
            Scalar::U64 => "uint64_t",
            Scalar::I64 => "int64_t",
            Scalar::F32 => "float",
            Scalar::F64 => "double",
        }
    }

    /// Bytes on the wire.
    pub fn size(self) -> usize {
        match self {
            Scalar::Char | Scalar::U8 | Scalar::I8 => 1,
            Scalar::U16 | Scalar::I16 => 2,
            Scalar::U32 | Scalar::I32 | Scalar::F32 => 4,
            Scalar::U64 | Scalar::I64 | Scalar::F64 => 8,
        }
    }

    /// The largest value of an integer type (`None` for floats and `char`).
    pub fn max_value(self) -> Option<u64> {
        Some(match self {
            Scalar::U8 => u8::MAX.into(),
            Scalar::I8 => i8::MAX as u64,
            Scalar::U16 => u16::MAX.into(),
            Scalar::I16 => i16::MAX as u64,
            Scalar::U32 => u32::MAX.into(),
            Scalar::I32 => i32::MAX as u64,
            Scalar::U64 => u64::MAX,
            Scalar::I64 => i64::MAX as u64,
            Scalar::Char | Scalar::F32 | Scalar::F64 => return None,
        })
    }
}

/// A field of a message.
#[derive(Debug, Clone)]
pub struct Field {
    /// The name, as the XML spells it (CRC_EXTRA hashes it).
    pub name: String,
    /// The element type.
    pub scalar: Scalar,
    /// The array length, for `type[N]`.
    pub array: Option<usize>,
    /// The enum the values come from (`enum="..."`).
    pub enum_name: Option<String>,
    /// `display="bitmask"`: the values are bits of the enum, whatever the enum says.
    pub bitmask: bool,
    /// The unit (`units="..."`).
    pub units: Option<String>,
    /// The text of the element, whitespace collapsed.
    pub doc: String,
    /// Declared after `<extensions/>`.
    pub extension: bool,
}

impl Field {
    /// Bytes on the wire.
    pub fn size(&self) -> usize {
        self.scalar.size() * self.array.unwrap_or(1)
    }
}

/// A message.
#[derive(Debug, Clone)]
pub struct Message {
    /// The id.
    pub id: u32,
    /// The name, as the XML spells it.
    pub name: String,
    /// The description, whitespace collapsed.
    pub doc: String,
    /// The `<deprecated>` note, if any: `since`, `replaced_by` and its text.
    pub deprecated: Option<String>,
    /// The fields in wire order: the base fields sorted by element size, largest first (a
    /// stable sort, so equal sizes keep their declared order), then the extension fields in
    /// declared order.
    pub fields: Vec<Field>,
}

/// A value of an enum.
#[derive(Debug, Clone)]
pub struct Entry {
    /// The name.
    pub name: String,
    /// The value.
    pub value: u64,
    /// The description, whitespace collapsed.
    pub doc: String,
}

/// An enum (or a bitmask: `bitmask="true"`).
#[derive(Debug, Clone)]
pub struct Enum {
    /// The name.
    pub name: String,
    /// The values are bits to combine.
    pub bitmask: bool,
    /// The description, whitespace collapsed.
    pub doc: String,
    /// The values, in the order of the files (included files first).
    pub entries: Vec<Entry>,
}

/// A dialect and everything it includes.
#[derive(Debug, Default)]
pub struct Dialect {
    /// The messages, by id.
    pub messages: Vec<Message>,
    /// The enums, in order of first definition (included files first).
    pub enums: Vec<Enum>,
    /// The names of the files read, the dialect's first, then its includes as they are met.
    pub files: Vec<String>,
}

impl Dialect {
    /// The enum named `name`.
    pub fn enum_named(&self, name: &str) -> Option<&Enum> {
        self.enums.iter().find(|e| e.name == name)
    }
}

/// Reads the dialect at `path` and the files it includes (paths relative to the including
/// file; a file included twice is read once).
///
/// # Errors
/// A file cannot be read or is not a MAVLink definition, a field type or enum value is not
/// MAVLink's, or two messages share an id or a name.
pub fn load(path: &Path) -> Result<Dialect, String> {
    let mut dialect = Dialect::default();
    let mut seen = Vec::new();
    load_file(path, &mut dialect, &mut seen)?;
    dialect.messages.sort_by_key(|m| m.id);
    for pair in dialect.messages.windows(2) {
        if pair[0].id == pair[1].id {
            return Err(format!(
                "messages {} and {} share id {}",
                pair[0].name, pair[1].name, pair[0].id
            ));
        }
    }
    Ok(dialect)
}

/// Reads one file into `dialect`, its includes first.
fn load_file(path: &Path, dialect: &mut Dialect, seen: &mut Vec<PathBuf>) -> Result<(), String> {
    let key = std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf());
    if seen.contains(&key) {
        return Ok(());
    }
    seen.push(key);
    let file_name = path.file_name().map(|n| n.to_string_lossy().into_owned());
    dialect.files.push(file_name.unwrap_or_default());
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read `{}`: {e}", path.display()))?;
    let root = xml::parse(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    if root.name != "mavlink" {
        return Err(format!(
            "{}: the root element is <{}>, not <mavlink>",
            path.display(),
            root.name
        ));
    }
    let dir = path.parent().unwrap_or(Path::new(""));
    for include in root.all("include") {
        load_file(&dir.join(include.text.trim()), dialect, seen)?;
    }
    let at = |e: String| format!("{}: {e}", path.display());
    for e in root.first("enums").iter().flat_map(|e| e.all("enum")) {
        let (new, explicit) = read_enum(e).map_err(at)?;
        merge_enum(dialect, new, &explicit);
    }
    for m in root.first("messages").iter().flat_map(|m| m.all("message")) {
        let message = read_message(m).map_err(at)?;
        if dialect.messages.iter().any(|old| old.name == message.name) {
            return Err(at(format!("message {} is defined twice", message.name)));
        }
        dialect.messages.push(message);
    }
    Ok(())
}

/// Adds an enum, or the entries of a second definition of it to the first, as MAVLink merges
/// an enum that several files extend. An entry without a value (`explicit` false) takes the one
/// after the previous entry's of the merged enum (0 first).
fn merge_enum(dialect: &mut Dialect, new: Enum, explicit: &[bool]) {
    let i = match dialect.enums.iter().position(|e| e.name == new.name) {
        Some(i) => i,
        None => {
            dialect.enums.push(Enum {
                entries: Vec::new(),
                ..new.clone()
            });
            dialect.enums.len() - 1
        }
    };
    let old = &mut dialect.enums[i];
    old.bitmask |= new.bitmask;
    for (mut entry, &explicit) in new.entries.into_iter().zip(explicit) {
        if !explicit {
            entry.value = old.entries.last().map_or(0, |p| p.value + 1);
        }
        if !old.entries.iter().any(|e| e.name == entry.name) {
            old.entries.push(entry);
        }
    }
}

/// An `<enum>`, and for each entry whether the XML gives its value.
fn read_enum(e: &Element) -> Result<(Enum, Vec<bool>), String> {
    let name = required(e, "name")?;
    let mut entries: Vec<Entry> = Vec::new();
    let mut explicit = Vec::new();
    for entry in e.all("entry") {
        let entry_name = required(entry, "name")?;
        let value = match entry.attr("value") {
            Some(v) => {
                parse_value(v).ok_or_else(|| format!("enum {name}: value `{v}` of {entry_name}"))?
            }
            None => 0,
        };
        explicit.push(entry.attr("value").is_some());
        entries.push(Entry {
            name: entry_name.to_string(),
            value,
            doc: description(entry),
        });
    }
    let new = Enum {
        name: name.to_string(),
        bitmask: e.attr("bitmask") == Some("true"),
        doc: description(e),
        entries,
    };
    Ok((new, explicit))
}

/// An enum value: decimal, `0x` hexadecimal, `0b` binary, or `2**N`.
fn parse_value(text: &str) -> Option<u64> {
    let t = text.trim();
    if let Some(hex) = t.strip_prefix("0x").or_else(|| t.strip_prefix("0X")) {
        u64::from_str_radix(hex, 16).ok()
    } else if let Some(bin) = t.strip_prefix("0b").or_else(|| t.strip_prefix("0B")) {
        u64::from_str_radix(bin, 2).ok()
    } else if let Some((base, exp)) = t.split_once("**") {
        let base: u64 = base.trim().parse().ok()?;
        base.checked_pow(exp.trim().parse().ok()?)
    } else {
        t.parse().ok()
    }
}

/// A `<message>`, its fields put in wire order.
fn read_message(m: &Element) -> Result<Message, String> {
    let name = required(m, "name")?;
    let id = required(m, "id")?;
    let id: u32 = id
        .parse()
        .ok()
        .filter(|&id| id <= 0xFF_FFFF)
        .ok_or_else(|| format!("message {name}: id `{id}` is not a 24-bit integer"))?;
    let mut fields = Vec::new();
    let mut extensions = Vec::new();
    for child in &m.children {
        match child.name.as_str() {
            // Every field after the marker is an extension field.
            "extensions" if extensions.is_empty() => extensions.push(None),
            "field" if extensions.is_empty() => fields.push(read_field(name, child)?),
            "field" => extensions.push(Some(read_field(name, child)?)),
            _ => {}
        }
    }
    fields.sort_by_key(|f: &Field| std::cmp::Reverse(f.scalar.size()));
    fields.extend(extensions.into_iter().flatten().map(|mut f| {
        f.extension = true;
        f
    }));
    Ok(Message {
        id,
        name: name.to_string(),
        doc: description(m),
        deprecated: m.first("deprecated").map(deprecation),
        fields,
    })
}

/// A `<field>`: `type` is a scalar or `scalar[N]`.
fn read_field(message: &str, f: &Element) -> Result<Field, String> {
    let name = required(f, "name")?;
    let ty = required(f, "type")?;
    let (scalar, array) = match ty.split_once('[') {
        Some((s, n)) => {
            let n = n.strip_suffix(']').and_then(|n| n.parse::<usize>().ok());
            (s, Some(n.filter(|&n| (1..=255).contains(&n))))
        }
        None => (ty, None),
    };
    let bad = || format!("message {message}: field {name} has type `{ty}`, not MAVLink's");
    let scalar = Scalar::parse(scalar).ok_or_else(bad)?;
    let array = match array {
        Some(n) => Some(n.ok_or_else(bad)?),
        None => None,
    };
    Ok(Field {
        name: name.to_string(),
        scalar,
        array,
        enum_name: f.attr("enum").map(str::to_string),
        bitmask: f.attr("display") == Some("bitmask"),
        units: f.attr("units").map(str::to_string),
        doc: collapse(&f.text),
        extension: false,
    })
}

/// The note of a `<deprecated>` element.
fn deprecation(d: &Element) -> String {
    let mut note = String::from("Deprecated");
    if let Some(since) = d.attr("since") {
        note.push_str(&format!(" since {since}"));
    }
    if let Some(by) = d.attr("replaced_by").filter(|b| !b.is_empty()) {
        note.push_str(&format!(", replaced by {by}"));
    }
    note.push('.');
    let text = collapse(&d.text);
    if !text.is_empty() {
        note.push(' ');
        note.push_str(&text);
    }
    note
}

/// The text of the `<description>` child, whitespace collapsed.
fn description(e: &Element) -> String {
    e.first("description")
        .map(|d| collapse(&d.text))
        .unwrap_or_default()
}

/// Runs of whitespace (the XML's line breaks and indentation) as one space, trimmed.
fn collapse(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// An attribute the element must have.
fn required<'a>(e: &'a Element, attr: &str) -> Result<&'a str, String> {
    e.attr(attr)
        .ok_or_else(|| format!("<{}> without `{attr}`", e.name))
}
