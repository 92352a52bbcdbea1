//! Validation: the spec model in, the checked [`ir::Protocol`] out. The only place that reports
//! user errors after loading; every rule is a `check_*` or `lower_*` function with its rule
//! stated in prose above it. Errors are accumulated: validation goes on after an error wherever
//! the rest can still be checked, and every error carries the span of what is wrong.

mod catalog;
mod checksum;
mod commands;
pub mod derive;
mod directions;
mod directions_empty;
mod extra;
mod frame;
mod names;
mod registers;
mod registers_each;
mod session;
mod session_answers;
mod session_match;
mod session_periodic;
mod session_result;
mod types;

use std::ops::Range;

use crate::diag::Diagnostics;
use crate::ir::{self, ByteOrder};
use crate::spec::model::{SStr, SpecFile};

pub use catalog::{catalog, display_name};
pub use names::{RESERVED_TYPE_NAMES, pascal_case};

/// Validation state shared by the rules: the spec, the error accumulator and what earlier
/// rules resolved.
pub(crate) struct Ctx<'a> {
    pub spec: &'a SpecFile,
    pub diags: &'a mut Diagnostics,
    pub default_endian: ByteOrder,
    /// The types of the user's crate a derive's draft may name (none for a spec).
    pub foreign: &'a [derive::Foreign],
}

impl Ctx<'_> {
    /// Record an error with a help line.
    pub fn error(
        &mut self,
        span: Range<usize>,
        message: impl Into<String>,
        help: impl Into<String>,
    ) {
        self.diags.error(span, message).help(help);
    }
}

/// Turn a loaded spec into the checked IR. Returns `None` when it cannot be built; errors are
/// in `diags` (which may also hold errors when `Some` is returned: callers check both).
pub fn validate(spec: &SpecFile, diags: &mut Diagnostics) -> Option<ir::Protocol> {
    let mut ctx = Ctx {
        spec,
        diags,
        default_endian: ByteOrder::Little,
        foreign: &[],
    };
    let p = spec.protocol.get_ref();
    ctx.default_endian = match &p.byte_order {
        Some(order) => names::parse_byte_order(&mut ctx, order).unwrap_or(ByteOrder::Little),
        None => ByteOrder::Little,
    };
    names::check_snake_name(&mut ctx, &p.name, "protocol name");

    let constants = types::lower_constants(&mut ctx);
    let addresses = commands::lower_addresses(&mut ctx);
    let enums = types::lower_enums(&mut ctx);
    let structs = types::lower_structs(&mut ctx, &enums, &constants);
    names::check_type_names(&mut ctx);
    let (frames, own_layouts) = frame::lower_frames(&mut ctx, &structs, &enums);
    // Directions name fields of the first frame: skip them when it failed to lower.
    let first_spec_frame = spec.frames.keys().next().map(|k| k.get_ref().as_str());
    let mut directions = match frames
        .first()
        .filter(|f| Some(f.name.as_str()) == first_spec_frame)
    {
        Some(first) => commands::lower_directions(&mut ctx, first, &addresses, &structs),
        None => Vec::new(),
    };
    let commands = commands::lower_commands(&mut ctx, &frames, &directions, &structs);
    let mut frames = frames;
    if let (Some(first), Some(d)) = (frames.first_mut(), directions.first()) {
        first.direction = match d.rule {
            ir::DirectionRule::InSet { value, .. } | ir::DirectionRule::Equals { value, .. } => {
                Some(value)
            }
            ir::DirectionRule::Given => None,
        };
    }
    frame::lower_packets(&mut frames, !directions.is_empty(), commands.len());
    let link = frame::lower_link(
        &mut ctx,
        &mut frames,
        &commands,
        &directions,
        &addresses,
        &structs,
    );
    extra::lower_extra_bytes(&mut frames, &commands);
    frame::attach_own_layouts(&mut directions, own_layouts, &frames, &commands);
    let session =
        session::lower_session(&mut ctx, &frames, &commands, &structs.structs, &directions);
    let registers = registers::lower_registers(
        &mut ctx,
        &commands,
        &structs.structs,
        &directions,
        session.as_ref(),
    );

    Some(ir::Protocol {
        name: p.name.get_ref().clone(),
        version: text(&p.version),
        doc: text(&p.doc),
        constants,
        addresses,
        enums: enums.enums,
        structs: structs.structs,
        frames,
        directions,
        commands,
        link,
        session,
        registers,
    })
}

/// The text of an optional spanned string, empty when absent.
pub(crate) fn text(s: &Option<SStr>) -> String {
    s.as_ref()
        .map(|s| s.get_ref().trim().to_string())
        .unwrap_or_default()
}
