//! Rules for constants, enums and payload structs: names, value ranges, field types, arrays,
//! padding, bitfields, scaling, and struct sizes (with reference cycles reported). Constants
//! and enums are here; structs, their fields and bit members have their own files.

mod bits;
mod carried;
mod checks;
mod fields;
mod mask;
mod structs;
mod variable;

use std::collections::HashMap;

use toml::Spanned;

use super::names::{check_pascal_name, check_screaming_name, parse_prim, pascal_case};
use super::{Ctx, text};
use crate::ir::{ByteOrder, Constant, Enum, EnumVariant, Prim, Scalar, UnknownPolicy};
use crate::spec::model::ConstantDef;

pub(crate) use bits::{MemberSite, lower_bits};
pub(crate) use fields::lower_scale;
pub(crate) use structs::{Structs, lower_structs};

/// Rule: constants have SCREAMING_SNAKE_CASE names and non-negative values.
pub(crate) fn lower_constants(ctx: &mut Ctx<'_>) -> Vec<Constant> {
    let spec = ctx.spec;
    let mut out = Vec::new();
    for (name, def) in &spec.constants {
        check_screaming_name(ctx, name, "constant");
        let (value, doc) = match def.get_ref() {
            ConstantDef::Bare(v) => (*v, String::new()),
            ConstantDef::Full(f) => (f.value, f.doc.clone().unwrap_or_default()),
        };
        if value < 0 {
            ctx.error(
                def.span(),
                format!("constant `{}` is negative", name.get_ref()),
                "constants are counts and values: use 0 or more",
            );
            continue;
        }
        out.push(Constant {
            name: name.get_ref().clone(),
            value: value as u64,
            doc,
        });
    }
    out
}

/// The enums, with a name index for references.
pub(crate) struct Enums {
    pub enums: Vec<Enum>,
    pub by_name: HashMap<String, usize>,
}

/// Does `value` (an i64 from TOML) fit in `prim`? Returns its two's complement bits.
pub(crate) fn fit(value: i64, prim: Prim) -> Option<u64> {
    let bits = (prim.size() * 8) as u32;
    if prim.is_signed() {
        let min = -(1i128 << (bits - 1));
        let max = (1i128 << (bits - 1)) - 1;
        let v = i128::from(value);
        (min..=max)
            .contains(&v)
            .then(|| (value as u64) & mask(bits))
    } else {
        (value >= 0 && (bits == 64 || (value as u64) <= mask(bits))).then_some(value as u64)
    }
}

/// A mask of the low `bits` bits.
pub(crate) fn mask(bits: u32) -> u64 {
    if bits >= 64 {
        u64::MAX
    } else {
        (1u64 << bits) - 1
    }
}

/// Rule: an enum has a PascalCase name, an integer type, at least one variant,
/// SCREAMING_SNAKE_CASE variant names whose Rust names do not collide, values that fit the
/// type and are unique, and an unknown-value policy of `reject` or `keep`.
pub(crate) fn lower_enums(ctx: &mut Ctx<'_>) -> Enums {
    let spec = ctx.spec;
    let mut enums = Vec::new();
    let mut by_name = HashMap::new();
    for (name, def) in &spec.enums {
        check_pascal_name(ctx, name, "enum");
        let d = def.get_ref();
        let scalar = match parse_prim(d.ty.get_ref(), ctx.default_endian) {
            Some(s) if s.prim.is_signed() || s.prim.is_unsigned() => s,
            _ => {
                ctx.error(
                    d.ty.span(),
                    format!("enum type `{}` is not an integer type", d.ty.get_ref()),
                    "use `u8`, `u16`, `i16be`, ...",
                );
                Scalar {
                    prim: Prim::U8,
                    endian: ByteOrder::Little,
                }
            }
        };
        let unknown = match d.unknown.as_ref().map(|u| u.get_ref().as_str()) {
            None | Some("reject") => UnknownPolicy::Reject,
            Some("keep") => UnknownPolicy::Keep,
            Some(other) => {
                let span = d.unknown.as_ref().map(Spanned::span).unwrap_or_default();
                ctx.error(span, format!("unknown policy `{other}`"), "write `unknown = \"reject\"` (decoding fails) or `unknown = \"keep\"` (an `Unknown(raw)` variant)");
                UnknownPolicy::Reject
            }
        };
        if d.values.is_empty() {
            ctx.error(
                def.span(),
                format!("enum `{}` has no values", name.get_ref()),
                "add `values = { NAME = 0, ... }`",
            );
        }
        let mut variants: Vec<EnumVariant> = Vec::new();
        for (vname, vdef) in &d.values {
            check_screaming_name(ctx, vname, "enum value");
            let (raw, doc) = match vdef.get_ref() {
                ConstantDef::Bare(v) => (*v, String::new()),
                ConstantDef::Full(f) => (f.value, f.doc.clone().unwrap_or_default()),
            };
            let Some(value) = fit(raw, scalar.prim) else {
                ctx.error(
                    vdef.span(),
                    format!(
                        "value {raw} of `{}` does not fit in {}",
                        vname.get_ref(),
                        scalar.prim.spec_name()
                    ),
                    "use a wider enum type or a smaller value",
                );
                continue;
            };
            let rust_name = pascal_case(vname.get_ref());
            if let Some(prev) = variants.iter().find(|v| v.value == value) {
                ctx.error(
                    vdef.span(),
                    format!(
                        "value {raw} of `{}` is already used by `{}`",
                        vname.get_ref(),
                        prev.name
                    ),
                    "give every enum value its own number",
                );
            } else if let Some(prev) = variants.iter().find(|v| v.rust_name == rust_name) {
                ctx.error(
                    vname.span(),
                    format!(
                        "`{}` and `{}` both become the Rust variant `{rust_name}`",
                        prev.name,
                        vname.get_ref()
                    ),
                    "rename one so their PascalCase forms differ",
                );
            } else if unknown == UnknownPolicy::Keep && rust_name == "Unknown" {
                ctx.error(vname.span(), "a value named `UNKNOWN` collides with the `Unknown(raw)` variant of `unknown = \"keep\"`", "rename it");
            } else {
                variants.push(EnumVariant {
                    name: vname.get_ref().clone(),
                    rust_name,
                    value,
                    doc,
                });
            }
        }
        by_name.insert(name.get_ref().clone(), enums.len());
        enums.push(Enum {
            name: name.get_ref().clone(),
            doc: text(&d.doc),
            prim: scalar.prim,
            variants,
            unknown,
            foreign: false,
        });
    }
    let mut out = Enums { enums, by_name };
    add_foreign_enums(ctx, &mut out);
    out
}

/// A derive's enum-like types of the user's crate (fields with `repr`): known by their integer
/// alone, with no variants; their own `from_raw` decides which values they take.
fn add_foreign_enums(ctx: &Ctx<'_>, out: &mut Enums) {
    for (f, prim) in ctx.foreign.iter().filter_map(|f| Some((f, f.repr?))) {
        out.by_name.insert(f.path.clone(), out.enums.len());
        out.enums.push(Enum {
            name: f.path.clone(),
            doc: String::new(),
            prim,
            variants: Vec::new(),
            unknown: UnknownPolicy::Reject,
            foreign: true,
        });
    }
}
