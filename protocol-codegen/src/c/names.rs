//! The C names, types and literals of a spec's items: everything carries the spec's name as a
//! prefix (`hflink_chassis_coord`, `HFLINK_SET_ROBOT_SPEED`), so that the code of several specs
//! links into one program. Every other module of the printer names things through this one;
//! a frame format's prefixes ([`Fx`]) come with its packet rules, lowered once.

use crate::ir::{BitMember, Prim, Protocol, ValueType};
use crate::rules::{RulesPlan, lower_rules};

/// The prefixes of a spec's C names.
pub struct Names {
    /// Lower-case prefix with its underscore (`hflink_`).
    pub lo: String,
    /// Upper-case prefix with its underscore (`HFLINK_`).
    pub up: String,
    /// The prefixes after the spec's of the items of the formats after the first and of the
    /// link's decoder (`v1_`, `any_`): families of names too.
    formats: Vec<String>,
}

impl Names {
    /// The names of `p`.
    pub fn new(p: &Protocol) -> Self {
        Names {
            lo: format!("{}_", p.name),
            up: format!("{}_", p.name.to_uppercase()),
            formats: p
                .frames
                .iter()
                .skip(1)
                .map(|f| format!("{}_", f.name))
                .chain(std::iter::once("any_".to_string()))
                .collect(),
        }
    }

    /// The type of a struct or enum named in PascalCase (`ChassisCoord` -> `hflink_chassis_coord`);
    /// a name the generated code takes for itself (`Step`, `ReadAll`, `V1Packet` where a format
    /// is named `v1`) gets `_t` (`dynamixel_step_t`), so that a spec's names never clash with
    /// the code's.
    pub fn ty(&self, pascal: &str) -> String {
        let name = snake(pascal);
        if RESERVED.contains(&name.as_str())
            || FAMILIES
                .iter()
                .copied()
                .chain(self.formats.iter().map(String::as_str))
                .any(|f| name.starts_with(f))
        {
            format!("{}{name}_t", self.lo)
        } else {
            format!("{}{name}", self.lo)
        }
    }

    /// The prefix of an enum's constants (`HFLINK_CHASSIS_TYPE_`).
    pub fn enum_const(&self, pascal: &str) -> String {
        format!("{}{}_", self.up, snake(pascal).to_uppercase())
    }
}

/// The names after the prefix that the generated code gives its own functions and types.
const RESERVED: &[&str] = &[
    "clamp_f32",
    "clamp_f64",
    "command",
    "command_name",
    "count_reject",
    "cut_f32",
    "cut_f64",
    "decode",
    "decoder",
    "direction",
    "direction_name",
    "emit",
    "encode",
    "escape",
    "event",
    "event_kind",
    "f16",
    "f16_bits",
    "f32",
    "f32_bits",
    "f64",
    "f64_bits",
    "field",
    "find_candidate",
    "format",
    "frame_inside",
    "get",
    "get_packed",
    "header",
    "ids",
    "mag_f32",
    "mag_f64",
    "original",
    "packed_span",
    "packet",
    "path",
    "pos",
    "probe",
    "put_field",
    "put_u16be",
    "put_u16le",
    "put_u32be",
    "put_u32le",
    "put_u64be",
    "put_u64le",
    "put_u8",
    "put_uint",
    "quantize_f32",
    "quantize_f64",
    "rd",
    "reject",
    "reject_name",
    "seal",
    "set",
    "set_packed",
    "sext",
    "skip",
    "stage",
    "stats",
    "step",
    "store",
    "stuff",
    "substitute",
    "sync_matches",
    "take_u16be",
    "take_u16le",
    "take_u32be",
    "take_u32le",
    "take_u64be",
    "take_u64le",
    "take_u8",
    "take_uint",
    "to_physical_f32",
    "to_physical_f64",
    "trimmed",
    "txt",
    "unescape",
    "unescape_from",
    "unscale_f32",
    "unscale_f64",
    "utf8",
    "verify",
    "within_f32",
    "within_f64",
    "wr",
    "zero",
];

/// The prefixes after the spec's prefix of the generated code's families of names
/// (`read_<struct>`, `check_<check>`, `encode_<command>`).
const FAMILIES: &[&str] = &[
    "check_", "decode_", "decoder_", "encode_", "escaped_", "fmt_", "pcheck_", "probe_", "read_",
    "write_",
];

/// snake_case of a PascalCase name.
pub fn snake(pascal: &str) -> String {
    let mut out = String::new();
    let chars: Vec<char> = pascal.chars().collect();
    for (i, &c) in chars.iter().enumerate() {
        if c.is_ascii_uppercase() {
            let prev_lower =
                i > 0 && (chars[i - 1].is_ascii_lowercase() || chars[i - 1].is_ascii_digit());
            let next_lower = chars.get(i + 1).is_some_and(|n| n.is_ascii_lowercase());
            let prev_upper = i > 0 && chars[i - 1].is_ascii_uppercase();
            if i > 0 && (prev_lower || (prev_upper && next_lower)) {
                out.push('_');
            }
            out.push(c.to_ascii_lowercase());
        } else {
            out.push(c);
        }
    }
    out
}

/// A field name as a C identifier: a C keyword gets a trailing underscore.
pub fn field(name: &str) -> String {
    const KEYWORDS: &[&str] = &[
        "auto", "break", "case", "char", "const", "continue", "default", "do", "double", "else",
        "enum", "extern", "float", "for", "goto", "if", "inline", "int", "long", "register",
        "restrict", "return", "short", "signed", "sizeof", "static", "struct", "switch", "typedef",
        "union", "unsigned", "void", "volatile", "while", "bool", "true", "false",
    ];
    if KEYWORDS.contains(&name) {
        format!("{name}_")
    } else {
        name.to_string()
    }
}

/// The C type of a primitive value.
pub fn prim(p: Prim) -> &'static str {
    match p {
        Prim::U8 => "uint8_t",
        Prim::I8 => "int8_t",
        Prim::U16 => "uint16_t",
        Prim::I16 => "int16_t",
        Prim::U24 | Prim::U32 => "uint32_t",
        Prim::I24 | Prim::I32 => "int32_t",
        Prim::U40 | Prim::U48 | Prim::U56 | Prim::U64 => "uint64_t",
        Prim::I40 | Prim::I48 | Prim::I56 | Prim::I64 => "int64_t",
        Prim::F16 | Prim::F32 => "float",
        Prim::F64 => "double",
        Prim::Bool | Prim::BoolInverted => "bool",
    }
}

/// The unsigned C type of `bytes` bytes (1, 2, 3 -> 4, 4, 8).
pub fn unsigned_of(bytes: usize) -> &'static str {
    match bytes {
        1 => "uint8_t",
        2 => "uint16_t",
        3 | 4 => "uint32_t",
        _ => "uint64_t",
    }
}

/// A C integer literal of type `uint64_t`.
pub fn u64_lit(v: u64) -> String {
    format!("UINT64_C({v:#x})")
}

/// The prefixes of one frame format's items (its sizes, header and packet types, decoder of one
/// frame, encoders, stream decoder, check functions): the spec's for the first format (`hflink_`),
/// the spec's and the format's name for the others (`mavlink_v1_`, `SCOUT_CAN_`), as the Rust
/// side names a format after the first (`V1Packet`, `SCOUT_CAN_LAYOUT`); with the format's
/// packet rules, lowered once ([`lower_rules`], the plan the Rust side prints as `RULES`) for
/// every printer of the format's items.
pub struct Fx<'p> {
    /// The frame format (index into [`Protocol::frames`]).
    pub fi: usize,
    /// Lower-case prefix with its underscore.
    pub lo: String,
    /// Upper-case prefix with its underscore.
    pub up: String,
    /// The format's packet rules.
    pub rules: RulesPlan<'p>,
}

impl<'p> Fx<'p> {
    /// The prefixes and packet rules of frame format `fi` of `p`.
    pub fn new(p: &'p Protocol, fi: usize) -> Self {
        let lo = if fi == 0 {
            format!("{}_", p.name)
        } else {
            format!("{}_{}_", p.name, p.frames[fi].name)
        };
        Fx {
            fi,
            up: lo.to_uppercase(),
            lo,
            rules: lower_rules(p, &p.frames[fi]),
        }
    }
}

/// The low `width` bits set.
pub fn mask(width: u32) -> u64 {
    if width >= 64 {
        u64::MAX
    } else {
        (1u64 << width) - 1
    }
}

/// The C float type of a scaled value's physical type, and the suffix of its helpers.
pub fn float_of(physical: Prim) -> (&'static str, &'static str) {
    match physical {
        Prim::F32 => ("float", "f32"),
        _ => ("double", "f64"),
    }
}

/// The C type of a value field's element.
pub fn value_type(p: &Protocol, n: &Names, ty: &ValueType) -> String {
    match ty {
        ValueType::Scalar {
            scale: Some(sc), ..
        } => float_of(sc.physical).0.to_string(),
        ValueType::Scalar { scalar, .. } => prim(scalar.prim).to_string(),
        ValueType::Struct(si) => n.ty(&p.structs[*si].name),
        ValueType::Enum(ei, _) => n.ty(&p.enums[*ei].name),
        ValueType::Text(_) => "char".into(),
    }
}

/// The C type of a bit member.
pub fn member_type(p: &Protocol, n: &Names, m: &BitMember) -> String {
    super::members::member_type(p, n, m)
}

/// A spec's documentation on one line, fit for a C comment.
fn doc_line(doc: &str) -> String {
    doc.split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .replace("*/", "* /")
}

/// A trailing ` /**< doc (unit) */` comment, or nothing.
pub fn doc_comment(doc: &str, unit: &str) -> String {
    let doc = doc_line(doc);
    match (doc.is_empty(), unit.is_empty()) {
        (true, true) => String::new(),
        (false, true) => format!(" /**< {doc} */"),
        (true, false) => format!(" /**< Unit: {unit}. */"),
        (false, false) => format!(" /**< {doc} Unit: {unit}. */"),
    }
}

/// The text of a `/** ... */` comment above an item: its documentation on one line.
pub fn one_line(doc: &str) -> String {
    let line = doc_line(doc);
    if line.is_empty() {
        "(No documentation.)".into()
    } else {
        line
    }
}
