//! The dissector's filterable fields (one `ProtoField` per header value, check, struct field
//! and bit member, named `<protocol>.<owner>.<name>` with its unit) and the struct tables the
//! payload reader walks. A struct field's table says what the IR says of it; reading it is
//! the template's.

use std::fmt::Write as _;

use super::lua;
use crate::ir::{BitMember, Field, FieldKind, Prim, Protocol, Scalar, ValueType};

/// The `ProtoField` declarations printed so far, each one line, named `F[n]`.
#[derive(Default)]
pub struct Fields {
    /// The declarations.
    pub lines: Vec<String>,
}

impl Fields {
    /// Declares a field; returns the Lua expression that names it.
    pub fn declare(&mut self, ctor: &str, abbrev: &str, label: &str, rest: &str) -> String {
        let n = self.lines.len() + 1;
        // The protocol's own name is the dissector's `NAME`, which a clash may change.
        let own = abbrev.split_once('.').map_or(abbrev, |(_, own)| own);
        self.lines.push(format!(
            "F[{n}] = ProtoField.{ctor}(NAME .. {}, {}{rest})",
            lua::string(&format!(".{own}")),
            lua::string(label)
        ));
        format!("F[{n}]")
    }

    /// A field of a primitive's type; `values` is a value-string table for an enum.
    pub fn prim(&mut self, prim: Prim, abbrev: &str, label: &str, values: Option<&str>) -> String {
        let vs = values.map_or(String::new(), |v| format!(", {v}"));
        match prim {
            Prim::Bool | Prim::BoolInverted => self.declare("bool", abbrev, label, ""),
            // A half is shown as the `f32` it decodes to.
            Prim::F16 | Prim::F32 => self.declare("float", abbrev, label, ""),
            Prim::F64 => self.declare("double", abbrev, label, ""),
            other => {
                let sign = if other.is_signed() { "int" } else { "uint" };
                // Wireshark's integer fields are 8, 16, 24, 32 or 64 bits wide; a 40-, 48- or
                // 56-bit value is a 64-bit field over its bytes.
                let bits = match other.size() * 8 {
                    40 | 48 | 56 => 64,
                    b => b,
                };
                let ctor = format!("{sign}{bits}");
                self.declare(&ctor, abbrev, label, &format!(", base.DEC{vs}"))
            }
        }
    }
}

/// The label of a field: its name, and its unit in brackets.
fn label(name: &str, unit: &str) -> String {
    if unit.is_empty() {
        name.to_string()
    } else {
        format!("{name} [{unit}]")
    }
}

/// The value-string table of enum `ei`: `{ [0] = "IDLE", ... }`, keys as the wire type reads.
fn enum_table(p: &Protocol, ei: usize, prim: Prim) -> String {
    let e = &p.enums[ei];
    let bits = prim.size() * 8;
    let items: Vec<String> = e
        .variants
        .iter()
        .map(|v| {
            let key = if prim.is_signed() && bits < 64 && v.value >= 1 << (bits - 1) {
                (v.value as i64) - (1i64 << bits)
            } else {
                v.value as i64
            };
            format!("[{key}] = {}", lua::string(&v.name))
        })
        .collect();
    format!("{{ {} }}", items.join(", "))
}

/// What a struct field's reader needs, and the degradations of the spec noted in `degraded`.
pub struct StructPrinter<'p> {
    /// The protocol.
    pub p: &'p Protocol,
    /// The fields declared.
    pub fields: Fields,
    /// What the dissector shows less exactly than the codec decodes it.
    pub degraded: Vec<String>,
    /// What it cannot show at all: the printer refuses the spec.
    pub refused: Vec<String>,
}

impl StructPrinter<'_> {
    /// The element table of a value type: a scalar, an enum, text or a nested struct.
    fn elem(&mut self, ty: &ValueType, abbrev: &str, label: &str, name: &str) -> String {
        match ty {
            ValueType::Scalar { scalar, scale } => {
                self.scalar(*scalar, scale.as_ref(), abbrev, label)
            }
            ValueType::Enum(ei, scalar) => {
                let table = enum_table(self.p, *ei, scalar.prim);
                let pf = self.fields.prim(scalar.prim, abbrev, label, Some(&table));
                format!(
                    "{{ size = {}, order = {}, pf = {pf} }}",
                    scalar.prim.size(),
                    lua::order(scalar.endian)
                )
            }
            ValueType::Text(n) => {
                let pf = self.fields.declare("string", abbrev, label, "");
                format!("{{ size = {n}, text = true, pf = {pf} }}")
            }
            ValueType::Struct(si) => {
                format!("{{ struct = {}, name = {} }}", si + 1, lua::string(name))
            }
        }
    }

    fn scalar(
        &mut self,
        s: Scalar,
        scale: Option<&crate::ir::Scale>,
        abbrev: &str,
        label: &str,
    ) -> String {
        let mut out = format!(
            "{{ size = {}, order = {}, signed = {}, float = {}",
            s.prim.size(),
            lua::order(s.endian),
            s.prim.is_signed(),
            s.prim.is_float()
        );
        if s.prim == Prim::F16 {
            out.push_str(", half = true");
        }
        if s.prim == Prim::BoolInverted {
            out.push_str(", inverted = true");
        }
        match scale {
            Some(sc) => {
                if s.prim.size() > 6 {
                    self.degraded.push(format!(
                        "{abbrev}: a scaled 64-bit integer is scaled from a double (exact to 2^53)"
                    ));
                }
                let pf = self.fields.declare("double", abbrev, label, "");
                let _ = write!(
                    out,
                    ", scale = {{ factor = {:?}, offset = {:?} }}, pf = {pf} }}",
                    sc.factor, sc.offset
                );
            }
            None => {
                let pf = self.fields.prim(s.prim, abbrev, label, None);
                let _ = write!(out, ", pf = {pf} }}");
            }
        }
        out
    }

    /// The tables of the members of a bitfield word or a bit stream of struct `owner`: where
    /// each lies, whether it is a flag, two's complement of its width or scaled, and its field
    /// (the physical value's, a double, for a scaled member).
    fn members(&mut self, owner: &str, members: &[BitMember]) -> String {
        let mut items = Vec::new();
        for m in members {
            let abbrev = format!("{}.{owner}.{}", self.p.name, m.name);
            let label = label(&m.name, &m.unit);
            // Wireshark's 64-bit fields take an Int64 or a UInt64, never a Lua number.
            let mut item = format!(
                "{{ shift = {}, width = {}, bool = {}, signed = {}, wide = {}",
                m.shift,
                m.width,
                m.prim == Prim::Bool && m.enum_index.is_none(),
                m.is_signed() && m.enum_index.is_none(),
                m.prim.size() > 4 && m.scale.is_none()
            );
            let pf = match (&m.scale, m.enum_index) {
                (Some(sc), None) => {
                    let _ = write!(
                        item,
                        ", scale = {{ factor = {:?}, offset = {:?} }}",
                        sc.factor, sc.offset
                    );
                    self.fields.declare("double", &abbrev, &label, "")
                }
                (_, ei) => {
                    let table = ei.map(|ei| enum_table(self.p, ei, m.prim));
                    self.fields.prim(m.prim, &abbrev, &label, table.as_deref())
                }
            };
            let _ = write!(item, ", pf = {pf} }}");
            items.push(item);
        }
        items.join(", ")
    }

    /// The table of field `i` of struct `si`.
    pub fn field(&mut self, si: usize, i: usize, f: &Field, kind: &FieldKind) -> String {
        let s = &self.p.structs[si];
        let abbrev = format!("{}.{}.{}", self.p.name, s.name, f.name);
        let label = label(&f.name, &f.unit);
        let name = lua::string(&f.name);
        match kind {
            FieldKind::Padding => format!("{{ kind = \"padding\", size = {} }}", f.size),
            FieldKind::Value { ty, count } => {
                let elem = self.elem(ty, &abbrev, &label, &f.name);
                let count = count.map_or(String::new(), |n| format!(", count = {n}"));
                format!("{{ kind = \"value\", name = {name}{count}, elem = {elem} }}")
            }
            FieldKind::Bytes {
                max,
                size_from,
                text,
            } => {
                let ty = if *text { "string" } else { "bytes" };
                let pf = self.fields.declare(ty, &abbrev, &label, "");
                let sized = match size_from {
                    Some(n) => format!(", size_from = {}", lua::string(n)),
                    None => format!(", keep = {}", s.bytes_after(i)),
                };
                // A packet carried in the bytes: the field that holds its command's id.
                let carries = s
                    .carries
                    .iter()
                    .find(|c| c.field == i)
                    .map_or(String::new(), |c| {
                        format!(", carries = {}", lua::string(&s.fields[c.key].name))
                    });
                format!("{{ kind = \"bytes\", max = {max}{sized}{carries}, pf = {pf} }}")
            }
            FieldKind::Group { elem, max } => format!(
                "{{ kind = \"group\", name = {name}, elem = {}, max = {max} }}",
                elem + 1
            ),
            FieldKind::Packed {
                count,
                bits,
                order,
                scale,
                ..
            } => {
                let pf = match scale {
                    Some(_) => self.fields.declare("double", &abbrev, &label, ""),
                    None => self.fields.declare("uint32", &abbrev, &label, ", base.DEC"),
                };
                let scale = scale.map_or(String::new(), |sc| {
                    format!(
                        ", scale = {{ factor = {:?}, offset = {:?} }}",
                        sc.factor, sc.offset
                    )
                });
                let msb = matches!(order, crate::ir::BitOrder::MsbFirst);
                format!(
                    "{{ kind = \"packed\", name = {name}, size = {}, count = {count}, bits = {bits}, \
                     msb = {msb}{scale}, pf = {pf} }}",
                    f.size
                )
            }
            FieldKind::Optional(inner) => {
                format!(
                    "{{ kind = \"optional\", inner = {} }}",
                    self.field(si, i, f, inner)
                )
            }
            FieldKind::When { .. } => {
                self.refused
                    .push(format!("{abbrev}: a field a mask bit announces (`when`)"));
                format!("{{ kind = \"padding\", size = {} }}", f.size)
            }
            FieldKind::BitStream { members } => {
                let members = self.members(&s.name, members);
                format!(
                    "{{ kind = \"bits\", name = {name}, size = {}, stream = true, members = {{ {members} }} }}",
                    f.size
                )
            }
            FieldKind::Bits { word, members } => {
                let members = self.members(&s.name, members);
                format!(
                    "{{ kind = \"bits\", name = {name}, size = {}, order = {}, members = {{ {members} }} }}",
                    word.prim.size(),
                    lua::order(word.endian)
                )
            }
            FieldKind::Array {
                ty,
                max,
                size_from,
                by_mask,
            } => {
                if *by_mask {
                    self.refused.push(format!(
                        "{abbrev}: an array counted by the set bits of a mask (`mask`)"
                    ));
                }
                let elem = self.elem(ty, &abbrev, &label, &f.name);
                let sized = size_from.as_ref().map_or(String::new(), |n| {
                    format!(", size_from = {}", lua::string(n))
                });
                format!("{{ kind = \"array\", name = {name}, max = {max}{sized}, elem = {elem} }}")
            }
            FieldKind::NulText { max } => {
                let pf = self.fields.declare("string", &abbrev, &label, "");
                format!("{{ kind = \"nul_text\", max = {max}, pf = {pf} }}")
            }
            FieldKind::Check(c) => {
                let pf = self.fields.declare("uint32", &abbrev, &label, ", base.HEX");
                let algorithm = lua::algorithm(&c.algorithm).unwrap_or_else(|| {
                    self.refused
                        .push(format!("{abbrev}: a 64-bit CRC (Lua's bit32 computes 32)"));
                    "{ kind = \"crc\", width = 0, poly = 0, init = 0, xorout = 0 }".to_string()
                });
                format!(
                    "{{ kind = \"check\", name = {name}, size = {}, order = {}, first = {}, \
                     last = {}, algorithm = {algorithm}, pf = {pf} }}",
                    f.size,
                    lua::order(c.endian),
                    c.first + 1,
                    c.last + 1
                )
            }
        }
    }

    /// The table of struct `si`: its name, sizes and fields.
    pub fn structure(&mut self, si: usize) -> String {
        let s = &self.p.structs[si];
        let fields: Vec<String> = s
            .fields
            .iter()
            .enumerate()
            .map(|(i, f)| format!("    {},", self.field(si, i, f, &f.kind)))
            .collect();
        let base = s
            .base_size
            .map_or(String::new(), |b| format!(", base_size = {b}"));
        format!(
            "  {{ name = {}, size = {}{base}, fields = {{\n{}\n  }} }},",
            lua::string(&s.name),
            s.size,
            fields.join("\n")
        )
    }
}
