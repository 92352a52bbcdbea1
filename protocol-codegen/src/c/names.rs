//! The C names of a spec's items: everything carries the spec's name as a prefix
//! (`hflink_chassis_coord`, `HFLINK_SET_ROBOT_SPEED`), so that the code of several specs links
//! into one program.

use crate::ir::{Prim, Protocol};

/// The prefixes of a spec's C names.
pub struct Names {
    /// Lower-case prefix with its underscore (`hflink_`).
    pub lo: String,
    /// Upper-case prefix with its underscore (`HFLINK_`).
    pub up: String,
}

impl Names {
    /// The names of `p`.
    pub fn new(p: &Protocol) -> Self {
        Names {
            lo: format!("{}_", p.name),
            up: format!("{}_", p.name.to_uppercase()),
        }
    }

    /// The type of a struct or enum named in PascalCase (`ChassisCoord` -> `hflink_chassis_coord`).
    pub fn ty(&self, pascal: &str) -> String {
        format!("{}{}", self.lo, snake(pascal))
    }

    /// The prefix of an enum's constants (`HFLINK_CHASSIS_TYPE_`).
    pub fn enum_const(&self, pascal: &str) -> String {
        format!("{}{}_", self.up, snake(pascal).to_uppercase())
    }
}

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
        Prim::U64 => "uint64_t",
        Prim::I64 => "int64_t",
        Prim::F32 => "float",
        Prim::F64 => "double",
        Prim::Bool => "bool",
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
/// side names a format after the first (`V1Packet`, `SCOUT_CAN_LAYOUT`).
pub struct Fx {
    /// The frame format (index into [`Protocol::frames`]).
    pub fi: usize,
    /// Lower-case prefix with its underscore.
    pub lo: String,
    /// Upper-case prefix with its underscore.
    pub up: String,
}

impl Fx {
    /// The prefixes of frame format `fi` of `p`.
    pub fn new(p: &Protocol, fi: usize) -> Self {
        let lo = if fi == 0 {
            format!("{}_", p.name)
        } else {
            format!("{}_{}_", p.name, p.frames[fi].name)
        };
        Fx {
            fi,
            up: lo.to_uppercase(),
            lo,
        }
    }
}
