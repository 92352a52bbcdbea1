//! `#[derive(Payload)]` through the spec rules. The derive lowers its struct into a draft spec
//! of one struct (each field a `[structs.NAME]` field that also carries the Rust type it
//! declares) and the types of the user's crate that its fields name ([`Foreign`]); this checks
//! the draft with the rules and diagnostics of the spec's types, plus the one rule a spec has
//! no use for (a declared Rust type is the one the wire form decodes to), and gives the IR
//! that the payload printer prints.

use toml::Spanned;

use super::{Ctx, types};
use crate::diag::Diagnostics;
use crate::ir::{self, ByteOrder, FieldKind, Prim, ValueType};
use crate::spec::model::{FieldDef, SpecFile};

/// A type of the user's crate that a derived struct's field names, by its Rust type as written:
/// a nested payload (it implements `Payload`) or, with `repr`, a type with `to_raw` and
/// `from_raw` over that integer (such as a generated enum).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Foreign {
    /// The Rust type as written (tokens joined by spaces, as `quote` prints them).
    pub path: String,
    /// The integer of `to_raw`/`from_raw`, for an enum-like type.
    pub repr: Option<Prim>,
}

/// Check the draft of a `#[derive(Payload)]` (a spec with one struct) whose fields may name
/// the `foreign` types. The derived struct is the last of the IR's structs; `None` when it
/// could not be lowered. Errors are in `diags`.
pub fn validate_derive(
    spec: &SpecFile,
    foreign: &[Foreign],
    diags: &mut Diagnostics,
) -> Option<ir::Protocol> {
    let mut ctx = Ctx {
        spec,
        diags,
        default_endian: ByteOrder::Little,
        foreign,
    };
    let enums = types::lower_enums(&mut ctx);
    let structs = types::lower_structs(&mut ctx, &enums, &[]);
    let (_, def) = spec.structs.first()?;
    let derived = structs.structs.last().filter(|s| !s.foreign)?;
    for f in def.get_ref().fields.get_ref() {
        check_rust_type(&mut ctx, f, derived);
    }
    Some(ir::Protocol {
        name: String::new(),
        version: String::new(),
        doc: String::new(),
        constants: Vec::new(),
        addresses: Vec::new(),
        enums: enums.enums,
        structs: structs.structs,
        frames: Vec::new(),
        directions: Vec::new(),
        commands: Vec::new(),
        link: Vec::new(),
        session: None,
        registers: None,
    })
}

/// Rule (derives): a field's declared Rust type is the type its wire form decodes to: the
/// primitive's own (`u32` for a `u24`), and for a scaled value the declared `f32` or `f64`.
/// Nested payloads and enum-like types are the user's own and are not checked here (the
/// compiler checks that they implement what the code calls).
fn check_rust_type(ctx: &mut Ctx<'_>, f: &Spanned<FieldDef>, s: &ir::Struct) {
    let d = f.get_ref();
    let (Some(name), Some(rust)) = (&d.name, &d.rust) else {
        return;
    };
    let Some(field) = s.fields.iter().find(|x| &x.name == name.get_ref()) else {
        return;
    };
    let FieldKind::Value {
        ty: ValueType::Scalar { scalar, scale },
        ..
    } = &field.kind
    else {
        return;
    };
    let (decoded, what) = match scale {
        Some(sc) => (sc.physical, "a scaled value".to_string()),
        None => (
            scalar.prim,
            format!("its wire type `{}`", scalar.prim.spec_name()),
        ),
    };
    if decoded.rust_name() == rust.get_ref() {
        return;
    }
    let help = match scale {
        Some(_) => "a scaled field is an `f32` or `f64` in Rust: declare it as one".to_string(),
        None => format!(
            "declare `{}` as `{}`, or give it a wire type that decodes to `{}`",
            name.get_ref(),
            decoded.rust_name(),
            rust.get_ref()
        ),
    };
    ctx.error(
        rust.span(),
        format!(
            "field `{}` is `{}`, but {what} decodes to `{}`",
            name.get_ref(),
            rust.get_ref(),
            decoded.rust_name()
        ),
        help,
    );
}
