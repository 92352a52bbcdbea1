//! Helpers of the interpreter tests: loading specs and golden vectors, a deterministic random
//! generator, and `rust_debug`, which prints a decoded frame exactly as `{:?}` prints the
//! generated `Packet` of the same frame, so the two codecs are compared field for field.
#![allow(dead_code)]

use protocol_dynamic::{Decoded, Interpreter, Value, hex, value_f32, value_f64};
use protocol_spec::ir::{
    ByteOrder, FieldKind, Prim, Protocol, Role, Scalar, UnknownPolicy, ValueType,
};

/// The interpreter of `specs/NAME.toml`, or of `tests/fixtures/NAME.toml` when there is no
/// such spec.
pub fn interpreter(name: &str) -> Interpreter {
    let root = env!("CARGO_MANIFEST_DIR");
    let (path, shown) = [
        (
            format!("{root}/../specs/{name}.toml"),
            format!("specs/{name}.toml"),
        ),
        (
            format!("{root}/tests/fixtures/{name}.toml"),
            format!("tests/fixtures/{name}.toml"),
        ),
    ]
    .into_iter()
    .find(|(p, _)| std::path::Path::new(p).exists())
    .unwrap_or_else(|| panic!("no spec named {name}"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    Interpreter::from_text(shown, text).unwrap_or_else(|e| panic!("{name} is invalid:\n{e}"))
}

/// `tests/vectors/NAME`.
pub fn vectors(name: &str) -> serde_json::Value {
    let path = format!("{}/../tests/vectors/{name}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    serde_json::from_str(&text).expect("vector file is JSON")
}

/// Bytes of hex text.
pub fn unhex(text: &str) -> Vec<u8> {
    protocol_dynamic::parse_hex(text).expect("valid hex")
}

/// xorshift64*: deterministic test data without dependencies.
pub struct Rng(pub u64);

impl Rng {
    /// The next 64 random bits.
    pub fn bits(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// A number in `lo..=hi`.
    pub fn range(&mut self, lo: u64, hi: u64) -> u64 {
        lo + self.bits() % (hi - lo + 1)
    }

    /// Fills `buf` with random bytes.
    pub fn fill(&mut self, buf: &mut [u8]) {
        for b in buf {
            *b = (self.bits() >> 32) as u8;
        }
    }
}

/// `snake_case` to `PascalCase`, as generated type names are formed.
pub fn pascal(name: &str) -> String {
    protocol_spec::validate::pascal_case(name)
}

fn int_text(prim: Prim, v: &Value) -> String {
    match prim {
        Prim::Bool | Prim::BoolInverted => v.as_bool().expect("bool").to_string(),
        Prim::F16 | Prim::F32 => format!("{:?}", value_f32(v).expect("f32")),
        Prim::F64 => format!("{:?}", value_f64(v).expect("f64")),
        _ if prim.is_signed() => v.as_i64().expect("integer").to_string(),
        _ => v.as_u64().expect("integer").to_string(),
    }
}

fn enum_text(p: &Protocol, ei: usize, v: &Value) -> String {
    let e = &p.enums[ei];
    match v {
        Value::String(name) => e
            .variants
            .iter()
            .find(|x| x.name == *name)
            .map(|x| x.rust_name.clone())
            .expect("a variant name"),
        other => {
            assert_eq!(
                e.unknown,
                UnknownPolicy::Keep,
                "a number for a rejecting enum"
            );
            format!("Unknown({})", int_text(e.prim, other))
        }
    }
}

fn elem_text(p: &Protocol, ty: &ValueType, v: &Value) -> String {
    match ty {
        ValueType::Scalar {
            scalar,
            scale: None,
        } => int_text(scalar.prim, v),
        ValueType::Scalar {
            scale: Some(sc), ..
        } => int_text(sc.physical, v),
        ValueType::Struct(si) => struct_text(p, *si, v),
        ValueType::Enum(ei, _) => enum_text(p, *ei, v),
        ValueType::Text(n) => text_debug(*n, v),
    }
}

/// A text value as `{:?}` prints the runtime's `FixedStr`.
fn text_debug(n: usize, v: &Value) -> String {
    let mut bytes = vec![0u8; n];
    match v {
        Value::String(s) => bytes[..s.len()].copy_from_slice(s.as_bytes()),
        Value::Array(items) => {
            for (b, item) in bytes.iter_mut().zip(items) {
                *b = item.as_u64().expect("a byte") as u8;
            }
        }
        other => panic!("not a text: {other:?}"),
    }
    format!("{:?}", protocol_kit::text::TextDebug(&bytes))
}

/// A struct value as `{:?}` prints the generated struct.
pub fn struct_text(p: &Protocol, si: usize, v: &Value) -> String {
    let s = &p.structs[si];
    let mut fields = Vec::new();
    for f in &s.fields {
        field_text(p, &f.name, &f.kind, v, &mut fields);
    }
    if fields.is_empty() {
        s.name.clone()
    } else {
        format!("{} {{ {} }}", s.name, fields.join(", "))
    }
}

/// `name: value` of a field (its members' for a bitfield), as `{:?}` prints it.
fn field_text(p: &Protocol, name: &str, kind: &FieldKind, v: &Value, out: &mut Vec<String>) {
    match kind {
        FieldKind::Padding | FieldKind::Check(_) => {}
        FieldKind::NulText { .. } | FieldKind::Bytes { text: true, .. } => {
            let bytes: Vec<u8> = match &v[name] {
                Value::String(s) => s.as_bytes().to_vec(),
                Value::Array(items) => items
                    .iter()
                    .map(|b| b.as_u64().expect("a byte") as u8)
                    .collect(),
                other => panic!("not a text: {other:?}"),
            };
            // As the runtime's `NulStr` and `Str` print: its text's bytes, escaped, in quotes.
            out.push(format!("{name}: \"{}\"", bytes.escape_ascii()));
        }
        FieldKind::Array { ty, .. } => {
            let items: Vec<String> = v[name]
                .as_array()
                .expect("array")
                .iter()
                .map(|e| elem_text(p, ty, e))
                .collect();
            out.push(format!("{name}: [{}]", items.join(", ")));
        }
        FieldKind::Bits { members, .. } | FieldKind::BitStream { members } => {
            for m in members {
                let x = &v[m.name.as_str()];
                let text = match (m.enum_index, &m.scale) {
                    (Some(ei), _) => enum_text(p, ei, x),
                    (None, Some(sc)) => int_text(sc.physical, x),
                    (None, None) => int_text(m.prim, x),
                };
                out.push(format!("{}: {text}", m.name));
            }
        }
        FieldKind::Optional(inner) | FieldKind::When { kind: inner, .. } => {
            if v[name].is_null() {
                out.push(format!("{name}: None"));
            } else {
                let mut one = Vec::new();
                field_text(p, name, inner, v, &mut one);
                for t in one {
                    let (key, value) = t.split_once(": ").expect("name: value");
                    out.push(format!("{key}: Some({value})"));
                }
            }
        }
        FieldKind::Bytes { .. } => {
            out.push(format!(
                "{name}: Bytes({})",
                hex(v[name].as_bytes().expect("bytes"))
            ));
        }
        FieldKind::Group { elem, .. } => {
            let items: Vec<String> = v[name]
                .as_array()
                .expect("array")
                .iter()
                .map(|e| struct_text(p, *elem, e))
                .collect();
            out.push(format!("{name}: [{}]", items.join(", ")));
        }
        FieldKind::Packed { prim, scale, .. } => {
            let ty = ValueType::Scalar {
                scalar: Scalar {
                    prim: *prim,
                    endian: ByteOrder::Little,
                },
                scale: *scale,
            };
            let items: Vec<String> = v[name]
                .as_array()
                .expect("array")
                .iter()
                .map(|e| elem_text(p, &ty, e))
                .collect();
            out.push(format!("{name}: [{}]", items.join(", ")));
        }
        FieldKind::Value { ty, count } => {
            let x = &v[name];
            let text = match count {
                None => elem_text(p, ty, x),
                Some(_) => {
                    let items: Vec<String> = x
                        .as_array()
                        .expect("array")
                        .iter()
                        .map(|e| elem_text(p, ty, e))
                        .collect();
                    format!("[{}]", items.join(", "))
                }
            };
            out.push(format!("{name}: {text}"));
        }
    }
}

/// A decoded frame as `{:?}` prints the generated `Packet` (or `<Frame>Packet` of a CAN frame
/// format) of the same frame.
pub fn rust_debug(p: &Protocol, d: &Decoded) -> String {
    let f = &p.frames[d.format];
    let (packet, header) = if d.format == 0 {
        ("Packet".to_string(), "Header".to_string())
    } else {
        (
            format!("{}Packet", pascal(&f.name)),
            format!("{}Header", pascal(&f.name)),
        )
    };
    let header_fields: Vec<String> = f
        .values
        .iter()
        .filter(|v| matches!(v.role, Role::User { .. }))
        .map(|v| {
            format!(
                "{}: {}",
                v.name,
                int_text(v.prim, &d.header[v.name.as_str()])
            )
        })
        .chain(f.flag_trailer.iter().map(|t| {
            // `Option<[u8; N]>`: the bytes when the flag announces them.
            let text = match d.header[t.name.as_str()].as_bytes() {
                Some(b) => format!("Some({b:?})"),
                None => "None".to_string(),
            };
            format!("{}: {text}", t.name)
        }))
        .collect();
    let header = if header_fields.is_empty() {
        header
    } else {
        format!("{header} {{ {} }}", header_fields.join(", "))
    };
    // A direction that carries a struct in place of a command.
    if let Some((di, (si, _))) = d
        .direction
        .and_then(|di| Some((di, p.directions.get(di)?.message?)))
        .filter(|_| d.command.is_none())
    {
        return format!(
            "{packet} {{ header: {header}, message: {}({}) }}",
            pascal(&p.directions[di].name),
            struct_text(p, si, &d.payload)
        );
    }
    if d.command.is_none() && !d.ack {
        let si = f.message.expect("a message frame format");
        return format!(
            "{packet} {{ header: {header}, payload: {} }}",
            struct_text(p, si, &d.payload)
        );
    }
    let message = if d.ack {
        format!("Ack(Bytes({}))", hex(d.payload.as_bytes().expect("bytes")))
    } else {
        let c = &p.commands[d.command.expect("a command")];
        let slot = d.direction.unwrap_or(0);
        let inner = match c.payloads[slot] {
            None => c.rust_name.clone(),
            Some(si) => format!("{}({})", c.rust_name, struct_text(p, si, &d.payload)),
        };
        match d.direction {
            Some(di) => format!("{}({inner})", pascal(&p.directions[di].name)),
            None => inner,
        }
    };
    format!("{packet} {{ header: {header}, message: {message} }}")
}
