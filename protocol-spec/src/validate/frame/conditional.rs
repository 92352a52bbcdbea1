//! Rules for the parts of a frame that header values decide: bytes at the very end of a frame
//! present when a one-bit header flag is set (`optional`, the MAVLink 2 signature), and a
//! wider length present when the length field holds a marker value (`extends`, MSP v1 jumbo
//! frames).

use std::ops::Range;

use toml::Spanned;

use super::super::names::check_snake_name;
use super::super::types::mask;
use super::super::{Ctx, text};
use super::length::Layout;
use super::{Draft, El, Kind};
use crate::diag::did_you_mean;
use crate::ir::{FlagTrailer, HeaderValue, Length, LengthExtension, Pos, Role};
use crate::spec::model::{ElementDef, FrameDef, SInt, SStr};

/// Largest flag trailer, in bytes.
const MAX_OPTIONAL: i64 = 255;

/// An `optional` element as declared: its name, size, flag and place.
pub(super) struct OptionalDecl<'s> {
    name: String,
    doc: String,
    size: usize,
    when: &'s SStr,
    /// Index of the element in the layout.
    index: usize,
    span: Range<usize>,
}

/// What the flag trailer's rules look at besides the declaration.
pub(super) struct Context<'a, 'd, 's> {
    pub def: &'a FrameDef,
    pub lay: &'a Layout<'d, 's>,
    pub first: bool,
    pub length: &'a Length,
    pub header_checks: bool,
}

/// Rule: an `optional` element has a snake_case name, a `size` from 1 to 255, a flag (`when`),
/// and follows the payload.
pub(super) fn lower_optional<'s>(
    ctx: &mut Ctx<'_>,
    draft: &mut Draft<'s>,
    el: &'s Spanned<ElementDef>,
) {
    let d = el.get_ref();
    let Some(name) = d.optional.as_ref() else {
        return;
    };
    check_snake_name(ctx, name, "optional element name");
    let size = match &d.size {
        Some(s) if (1..=MAX_OPTIONAL).contains(s.get_ref()) => *s.get_ref() as usize,
        Some(s) => {
            ctx.error(
                s.span(),
                format!("an optional element of {} bytes", s.get_ref()),
                format!("`size` is the number of bytes, from 1 to {MAX_OPTIONAL}"),
            );
            draft.broken = true;
            return;
        }
        None => {
            ctx.error(
                el.span(),
                format!("optional element `{}` has no `size`", name.get_ref()),
                "add `size = N`, its number of bytes (13 for a MAVLink 2 signature)",
            );
            draft.broken = true;
            return;
        }
    };
    let Some(when) = d.when.as_ref() else {
        ctx.error(
            el.span(),
            format!("optional element `{}` has no `when`", name.get_ref()),
            "add `when = \"flag\"`, the one-bit header value that is set when the bytes are present",
        );
        draft.broken = true;
        return;
    };
    if draft.payload.is_none() || draft.optional.is_some() {
        ctx.error(
            el.span(),
            "an optional element is the last element of the layout, after the payload",
            "move it to the end of the layout; a frame has at most one",
        );
        draft.broken = true;
        return;
    }
    draft.optional = Some(OptionalDecl {
        name: name.get_ref().clone(),
        doc: text(&d.doc),
        size,
        when,
        index: draft.els.len(),
        span: el.span(),
    });
    // No bytes at a fixed place: the elements before it keep their distance from the end of
    // the frame without it.
    draft.els.push(El {
        name: name.get_ref().clone(),
        def: Some(el),
        kind: Kind::Optional,
        size: 0,
    });
}

/// Rules: the flag trailer is the layout's last element, of the first frame format, serial,
/// with a length field and without header checks or a bare header (the length of a frame
/// follows from its header and its flag); its flag is a one-bit header value set by the
/// sender, which becomes the codec's to set.
pub(super) fn lower_flag_trailer(
    ctx: &mut Ctx<'_>,
    cx: &Context<'_, '_, '_>,
    decl: Option<OptionalDecl<'_>>,
    values: &mut [HeaderValue],
    ok: &mut bool,
) -> Option<FlagTrailer> {
    let decl = decl?;
    let mut refuse = |ctx: &mut Ctx<'_>, message: &str, help: &str| {
        ctx.error(decl.span.clone(), message, help);
        *ok = false;
    };
    if decl.index + 1 != cx.lay.els.len() {
        refuse(
            ctx,
            "an optional element is the last element of the layout",
            "move it after the checks and trailers",
        );
    }
    if !cx.first || cx.lay.els.iter().any(|e| e.def.is_none()) {
        refuse(
            ctx,
            "only the first frame format, a serial one, may have an optional element",
            "move this frame format first",
        );
    }
    if cx.def.dispatch.is_none() || cx.def.ack.is_some() {
        refuse(
            ctx,
            "an optional element needs a frame format with `dispatch` and without `ack`",
            "a frame format that carries commands has a `Packet` whose header holds the bytes",
        );
    }
    if !matches!(cx.length, Length::Field { .. }) {
        refuse(
            ctx,
            "a frame with an optional element needs a length field",
            "add a field with `length_of`: the frame's length without the optional bytes",
        );
    }
    if cx.header_checks || cx.def.bare_header.as_ref().is_some_and(|b| *b.get_ref()) {
        refuse(
            ctx,
            "an optional element does not combine with header checks or a bare header",
            "check the header in a frame check instead",
        );
    }
    let flag = lower_flag(ctx, cx.lay, decl.when, values);
    if flag.is_none() {
        *ok = false;
    }
    Some(FlagTrailer {
        name: decl.name,
        doc: decl.doc,
        flag: flag?,
        len: decl.size,
    })
}

/// Rule: `when` names a one-bit header value before the payload that the sender sets; it
/// becomes the trailer's flag.
fn lower_flag(
    ctx: &mut Ctx<'_>,
    lay: &Layout<'_, '_>,
    when: &SStr,
    values: &mut [HeaderValue],
) -> Option<usize> {
    let name = when.get_ref();
    let Some(vi) = values.iter().position(|v| &v.name == name) else {
        let help = match did_you_mean(name, values.iter().map(|v| v.name.as_str())) {
            Some(b) => format!("did you mean `{b}`?"),
            None => "name a one-bit member of a header field (`bits = [{ name, bits = 1 }]`)"
                .to_string(),
        };
        ctx.error(
            when.span(),
            format!("the frame has no header value `{name}`"),
            help,
        );
        return None;
    };
    let v = &mut values[vi];
    let in_header = matches!(v.at, Pos::Start(n) if n < lay.header_len);
    if v.width != 1 || !in_header || !matches!(v.role, Role::User { .. }) {
        ctx.error(
            when.span(),
            format!("`{name}` cannot flag the optional bytes"),
            "the flag is a one-bit member of a header field before the payload, without \
             `value`, `length_of` or a part in `dispatch` or `ack`",
        );
        return None;
    }
    v.role = Role::Flag;
    Some(vi)
}

/// A field with `extends` as declared: its value, its element, and its keys.
pub(super) struct ExtensionDecl<'s> {
    value: usize,
    index: usize,
    size: usize,
    extends: &'s SStr,
    marker: Option<&'s SInt>,
    span: Range<usize>,
}

/// Rule: one field at most is a wider length (`extends`), a whole field without `bits`. Its
/// bytes do not count in the header's fixed length: the payload starts after them only when
/// the marker announces them.
pub(super) fn find_extension<'s>(
    ctx: &mut Ctx<'_>,
    draft: &mut Draft<'s>,
) -> Option<ExtensionDecl<'s>> {
    let mut found: Option<ExtensionDecl<'s>> = None;
    for (index, el) in draft.els.iter_mut().enumerate() {
        let Some(def) = el.def else { continue };
        let d = def.get_ref();
        let Some(extends) = d.extends.as_ref() else {
            continue;
        };
        let value = match &el.kind {
            Kind::Word(_, idx) if d.bits.is_none() && idx.len() == 1 => idx[0],
            _ => {
                ctx.error(
                    extends.span(),
                    "a wider length is a whole field",
                    "remove `bits`: the field holds the length",
                );
                continue;
            }
        };
        if found.is_some() {
            ctx.error(
                extends.span(),
                "a frame has one wider length",
                "remove `extends` from all but one field",
            );
            continue;
        }
        found = Some(ExtensionDecl {
            value,
            index,
            size: el.size,
            extends,
            marker: d.marker.as_ref(),
            span: def.span(),
        });
        el.size = 0;
    }
    found
}

/// Rules: the wider length follows the header's other fields, right before the payload; it
/// extends the frame's length field, whose `marker` value (from 1, within the field) announces
/// it, and it holds the count of the largest frame; the frame is the first, serial, with
/// `dispatch`, and without header checks, bare header, acknowledgements, byte stuffing or
/// trailing-zero truncation (an encoder knows the payload's size before it places it).
pub(super) fn lower_extension(
    ctx: &mut Ctx<'_>,
    cx: &Context<'_, '_, '_>,
    decl: Option<ExtensionDecl<'_>>,
    values: &[HeaderValue],
    ok: &mut bool,
) -> Option<LengthExtension> {
    let decl = decl?;
    let mut refuse = |ctx: &mut Ctx<'_>, span: Range<usize>, message: &str, help: &str| {
        ctx.error(span, message, help);
        *ok = false;
    };
    if decl.index + 1 != cx.lay.pi {
        refuse(
            ctx,
            decl.span.clone(),
            "a wider length is the last header field, right before the payload",
            "move it before the payload: fields after it would move with it",
        );
    }
    let def = cx.def;
    let flagged = |b: &Option<toml::Spanned<bool>>| b.as_ref().is_some_and(|b| *b.get_ref());
    if !cx.first
        || cx.lay.els.iter().any(|e| e.def.is_none())
        || def.dispatch.is_none()
        || def.ack.is_some()
        || def.stuffing.is_some()
        || flagged(&def.truncate_zeros)
        || flagged(&def.bare_header)
        || cx.header_checks
    {
        refuse(
            ctx,
            decl.span.clone(),
            "a wider length needs the first frame format, serial, with `dispatch`",
            "it does not combine with header checks, `bare_header`, `ack`, `stuffing` or \
             `truncate_zeros`",
        );
    }
    let (base, adjust) = match cx.length {
        Length::Field { value, adjust } => (*value, *adjust),
        Length::Fixed(_) => {
            refuse(
                ctx,
                decl.extends.span(),
                "a wider length extends a length field, and the frame has none",
                "mark the frame's length field with `length_of`",
            );
            return None;
        }
    };
    let name = &values[base].name;
    if decl.extends.get_ref() != name {
        refuse(
            ctx,
            decl.extends.span(),
            &format!(
                "`{}` is not the frame's length field",
                decl.extends.get_ref()
            ),
            &format!("write `extends = \"{name}\"`"),
        );
    }
    let wide = &values[decl.value];
    let lay = cx.lay;
    let needed = (lay.header_len + lay.payload_max + lay.trailer_len) as i64 - adjust;
    if needed > 0 && needed as u64 > mask(wide.width) {
        refuse(
            ctx,
            decl.span.clone(),
            &format!(
                "the wider length has {} bits (at most {}), but the largest frame needs the value {needed}",
                wide.width,
                mask(wide.width)
            ),
            "use a wider type, or lower the payload's `max`",
        );
    }
    let marker = lower_marker(ctx, decl.marker, &values[base], &decl.span, ok)?;
    Some(LengthExtension {
        value: decl.value,
        marker,
        len: decl.size,
    })
}

/// Rule: a wider length has a `marker`, from 1 to the largest value of the length field.
fn lower_marker(
    ctx: &mut Ctx<'_>,
    marker: Option<&SInt>,
    base: &HeaderValue,
    span: &Range<usize>,
    ok: &mut bool,
) -> Option<u64> {
    let Some(marker) = marker else {
        ctx.error(
            span.clone(),
            "a wider length needs the `marker` that announces it",
            format!(
                "add `marker = N`, the value of `{}` that announces it (255 for MSP v1)",
                base.name
            ),
        );
        *ok = false;
        return None;
    };
    let value = *marker.get_ref();
    if value < 1 || value as u64 > mask(base.width) {
        ctx.error(
            marker.span(),
            format!("marker {value} does not fit `{}`", base.name),
            format!("a marker is from 1 to {}", mask(base.width)),
        );
        *ok = false;
        return None;
    }
    Some(value as u64)
}
