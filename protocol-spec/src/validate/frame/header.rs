//! Rules for header fields: the virtual CAN prefix, a field's word type, and the values a field
//! holds (the whole word, or its `bits` members) with what each is for (a constant, the
//! length, or a value the sender sets).

use toml::Spanned;

use super::super::names::{check_snake_name, parse_prim, unknown_type};
use super::super::types::{Enums, MemberSite, fit, lower_bits, mask};
use super::super::{Ctx, text};
use super::elements::byte_list;
use super::{Draft, El, Kind, can_id};
use crate::ir::{ByteOrder, HeaderValue, Pos, Prim, Role, Scalar, Transport};
use crate::spec::model::{BitDef, ElementDef, FrameDef, SStr};

/// The virtual prefix every CAN frame starts with: the id and the data length, so that checks
/// can cover them (the Scout CAN checksum does) and dispatch can name the id.
/// With `can_id_bits` the identifier is its members, each a header value of its own.
pub(super) fn push_can_prefix(
    ctx: &mut Ctx<'_>,
    draft: &mut Draft<'_>,
    def: &FrameDef,
    enums: &Enums,
) {
    let Transport::Can { extended } = draft.transport else {
        return;
    };
    let id_word = Scalar {
        prim: Prim::U32,
        endian: ByteOrder::Big,
    };
    let dlc_word = Scalar {
        prim: Prim::U8,
        endian: ByteOrder::Big,
    };
    let id_values = if let Some(bits) = &def.can_id_bits {
        can_id::lower_id_members(
            ctx,
            &mut draft.values,
            bits,
            id_word,
            draft.transport,
            enums,
        )
    } else {
        draft.values.push(HeaderValue {
            name: "can_id".into(),
            doc: "The CAN identifier.".into(),
            at: Pos::Start(0),
            word: id_word,
            shift: 0,
            width: if extended { 29 } else { 11 },
            prim: Prim::U32,
            role: Role::User { addresses: false },
        });
        vec![draft.values.len() - 1]
    };
    let dlc_value = draft.values.len();
    draft.values.push(HeaderValue {
        name: "dlc".into(),
        doc: "The CAN data length code: number of data bytes.".into(),
        at: Pos::Start(4),
        word: dlc_word,
        shift: 0,
        width: 8,
        prim: Prim::U8,
        role: Role::Length,
    });
    draft.els.push(El {
        name: "can_id".into(),
        def: None,
        size: 4,
        kind: Kind::Word(id_word, id_values),
    });
    draft.els.push(El {
        name: "dlc".into(),
        def: None,
        size: 1,
        kind: Kind::Word(dlc_word, vec![dlc_value]),
    });
}

/// Rule: a header field has a snake_case name and an unsigned integer `type`; after the
/// payload it can be neither the length nor a constant.
pub(super) fn lower_field_element<'s>(
    ctx: &mut Ctx<'_>,
    draft: &mut Draft<'s>,
    el: &'s Spanned<ElementDef>,
    enums: &Enums,
) -> Option<()> {
    let d = el.get_ref();
    let name = d.field.as_ref()?;
    check_snake_name(ctx, name, "field name");
    if draft.payload.is_some() && (d.value.is_some() || d.length_of.is_some()) {
        ctx.error(el.span(), "a field after the payload cannot be the length or a constant", "constant bytes after the payload are a `trailer = [...]`; the length field goes before the payload");
    }
    let Some(ty) = &d.ty else {
        ctx.error(
            el.span(),
            format!("field `{}` has no `type`", name.get_ref()),
            "add `type = \"u8\"` (or `u16be`, `u16le`, ...)",
        );
        draft.broken = true;
        return Some(());
    };
    let Some(word) = lower_header_word(ctx, ty) else {
        draft.broken = true;
        return Some(());
    };
    if let Some(set) = &d.one_of {
        lower_sync_set(ctx, draft, el, set, word);
    }
    let idx = if let Some(bits) = &d.bits {
        check_member_constants_in_header(ctx, draft, name, bits.get_ref());
        check_member_length_in_header(ctx, draft, name, bits.get_ref());
        lower_member_values(ctx, draft, el, word, enums)
    } else {
        vec![lower_whole_value(ctx, draft, name, d, word)]
    };
    draft.els.push(El {
        name: name.get_ref().clone(),
        def: Some(el),
        size: word.prim.size(),
        kind: Kind::Word(word, idx),
    });
    Some(())
}

/// Rule: a bit member of a field after the payload holds no constant. The decoder verifies
/// constants in the header, before it knows where the payload ends; a `value` on a member of a
/// field that follows the payload would be resolved against the wrong bytes, so it is refused
/// rather than accepted and left unchecked.
fn check_member_constants_in_header(
    ctx: &mut Ctx<'_>,
    draft: &Draft<'_>,
    field: &SStr,
    members: &[Spanned<BitDef>],
) {
    if draft.payload.is_none() {
        return;
    }
    for value in members.iter().filter_map(|m| m.get_ref().value.as_ref()) {
        ctx.error(
            value.span(),
            format!(
                "`value` on a member of `{}`, which follows the payload: a constant is checked only in the header",
                field.get_ref()
            ),
            format!(
                "move `{}` before the payload, or drop `value` and check the bits in the application",
                field.get_ref()
            ),
        );
    }
}

/// Rule: a bit member of a field after the payload is not the length. The decoder reads the
/// length in the header to find where the frame ends, so a length member after the payload
/// could never be read; the whole field's `length_of` there is refused by the field's rule.
fn check_member_length_in_header(
    ctx: &mut Ctx<'_>,
    draft: &Draft<'_>,
    field: &SStr,
    members: &[Spanned<BitDef>],
) {
    if draft.payload.is_none() {
        return;
    }
    for cov in members
        .iter()
        .filter_map(|m| m.get_ref().length_of.as_ref())
    {
        ctx.error(
            cov.span(),
            format!(
                "`length_of` on a member of `{}`, which follows the payload: the length is read only in the header",
                field.get_ref()
            ),
            format!(
                "move `{}` before the payload: the decoder needs the length to find the end of the frame",
                field.get_ref()
            ),
        );
    }
}

/// Rule: a field with `one_of` is the frame's sync taken from a set of values: the first element
/// of a serial frame's layout, a `u8`, without `value`, `length_of` or `bits`, its values
/// distinct bytes. The decoder searches for any of them; the matched one is the field's value,
/// which the sender sets (a CRSF device address).
fn lower_sync_set(
    ctx: &mut Ctx<'_>,
    draft: &mut Draft<'_>,
    el: &Spanned<ElementDef>,
    set: &Spanned<Vec<Spanned<i64>>>,
    word: Scalar,
) {
    let d = el.get_ref();
    let bytes = byte_list(ctx, set, "one_of");
    let fix = "a field that is the sync is `{ field = \"address\", type = \"u8\", one_of = [0xC8, 0xEA] }`, the first element of a serial frame";
    if matches!(draft.transport, Transport::Can { .. }) {
        ctx.error(
            set.span(),
            "a CAN frame has no sync",
            "remove `one_of`: CAN delivers whole frames",
        );
    } else if !draft.els.is_empty() {
        ctx.error(
            set.span(),
            "a field with `one_of` is the sync: it must be the first element of the layout",
            fix,
        );
    } else if word.prim != Prim::U8 {
        ctx.error(
            set.span(),
            "a field with `one_of` is the sync: its type is `u8`",
            fix,
        );
    } else if d.value.is_some() || d.length_of.is_some() || d.bits.is_some() {
        ctx.error(
            set.span(),
            "a field with `one_of` takes no `value`, `length_of` or `bits`",
            fix,
        );
    } else if let Some(twice) = set.get_ref().iter().enumerate().find_map(|(i, b)| {
        let earlier = &set.get_ref()[..i];
        earlier
            .iter()
            .any(|e| e.get_ref() == b.get_ref())
            .then_some(b)
    }) {
        ctx.error(
            twice.span(),
            format!("value {:#04X} appears twice in `one_of`", twice.get_ref()),
            "list each value once",
        );
    } else if !bytes.is_empty() {
        draft.sync_set = Some(bytes);
        return;
    }
    draft.broken = true;
}

/// Rule: a header field's type is an unsigned integer (flags are `bits` of one).
fn lower_header_word(ctx: &mut Ctx<'_>, ty: &SStr) -> Option<Scalar> {
    match parse_prim(ty.get_ref(), ctx.default_endian) {
        Some(s) if s.prim.is_unsigned() => Some(s),
        Some(_) => {
            ctx.error(
                ty.span(),
                format!(
                    "header field type `{}` is not an unsigned integer",
                    ty.get_ref()
                ),
                "header fields are `u8`, `u16le`, `u16be`, `u32le`, ... (use `bits` for flags)",
            );
            None
        }
        None => {
            let known =
                ["u8", "u16le", "u16be", "u32le", "u32be", "u64le", "u64be"].map(String::from);
            unknown_type(ctx, ty, &known, "a header field's type");
            None
        }
    }
}

/// Rule: a header field without `bits` is one value: a constant (`value`, which fits the
/// word), the length (`length_of`), or a value the sender sets. Its position is placed once
/// the whole layout is known (fields after the payload count back from the end).
fn lower_whole_value<'s>(
    ctx: &mut Ctx<'_>,
    draft: &mut Draft<'s>,
    name: &SStr,
    d: &'s ElementDef,
    word: Scalar,
) -> usize {
    let role = if let Some(v) = &d.value {
        if fit(*v.get_ref(), word.prim).is_none() {
            ctx.error(
                v.span(),
                format!(
                    "value {} does not fit in {}",
                    v.get_ref(),
                    word.prim.spec_name()
                ),
                "use a smaller value or a wider type",
            );
        }
        Role::Const(*v.get_ref() as u64)
    } else if let Some(cov) = &d.length_of {
        check_one_length_field(ctx, draft, cov);
        Role::Length
    } else if d.extends.is_some() {
        Role::WideLength
    } else {
        Role::User {
            addresses: d.addresses.as_ref().is_some_and(|a| *a.get_ref()),
        }
    };
    draft.values.push(HeaderValue {
        name: name.get_ref().clone(),
        doc: text(&d.doc),
        at: Pos::Start(0),
        word,
        shift: 0,
        width: (word.prim.size() * 8) as u32,
        prim: word.prim,
        role,
    });
    draft.values.len() - 1
}

/// Rule: the members of a header field's `bits` follow the bit-member rules; a member is a
/// constant (`value`, which fits its bits), the length (`length_of`), or a value the sender
/// sets; the field itself then carries neither `value` nor `length_of`.
fn lower_member_values<'s>(
    ctx: &mut Ctx<'_>,
    draft: &mut Draft<'s>,
    el: &'s Spanned<ElementDef>,
    word: Scalar,
    enums: &Enums,
) -> Vec<usize> {
    let d = el.get_ref();
    let Some(bits) = &d.bits else {
        return Vec::new();
    };
    let addresses = d.addresses.as_ref().is_some_and(|a| *a.get_ref());
    let word_bits = (word.prim.size() * 8) as u32;
    let members = lower_bits(
        ctx,
        bits.get_ref(),
        word_bits,
        MemberSite::Header,
        enums,
        &|_| None,
    );
    let mut idx = Vec::new();
    for (m, bdef) in members.into_iter().zip(bits.get_ref()) {
        let b = bdef.get_ref();
        let role = if let Some(v) = &b.value {
            if *v.get_ref() < 0 || (*v.get_ref() as u64) > mask(m.width) {
                ctx.error(
                    v.span(),
                    format!(
                        "value {} does not fit in `{}` ({} bit{})",
                        v.get_ref(),
                        m.name,
                        m.width,
                        if m.width == 1 { "" } else { "s" }
                    ),
                    "use a smaller value or more bits",
                );
            }
            Role::Const(*v.get_ref() as u64)
        } else if let Some(cov) = &b.length_of {
            check_one_length_field(ctx, draft, cov);
            Role::Length
        } else {
            Role::User { addresses }
        };
        idx.push(draft.values.len());
        draft.values.push(HeaderValue {
            name: m.name,
            doc: m.doc,
            at: Pos::Start(0),
            word,
            shift: m.shift,
            width: m.width,
            prim: m.prim,
            role,
        });
    }
    if d.value.is_some() || d.length_of.is_some() {
        ctx.error(
            el.span(),
            "a field with `bits` puts `value` and `length_of` on its members",
            "move the key into the member it is about",
        );
    }
    idx
}

/// Rule: a frame has one length field. The next value pushed is the one `cov` belongs to.
fn check_one_length_field<'s>(ctx: &mut Ctx<'_>, draft: &mut Draft<'s>, cov: &'s SStr) {
    if draft.length_decl.is_some() {
        ctx.error(
            cov.span(),
            "a frame has one length field",
            "remove `length_of` from all but one field",
        );
    } else {
        draft.length_decl = Some((draft.values.len(), cov));
    }
}
