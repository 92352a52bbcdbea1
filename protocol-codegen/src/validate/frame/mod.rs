//! Rules for frame formats: the layout's elements (sync, header fields and their bits, payload,
//! checks, trailers), offsets, the length field and what it counts, what each check covers,
//! and the dispatch key.

use toml::Spanned;

mod elements;
mod options;

use elements::{byte_list, check_element_keys};
use options::lower_transport;

use super::checksum::resolve_algorithm;
use super::names::{check_snake_name, parse_byte_order, parse_prim};
use super::types::{Enums, Structs, fit, lower_bits, mask};
use super::{Ctx, text};
use crate::diag::did_you_mean;
use crate::ir::{
    Algorithm, CAN_PREFIX_LEN, Check, Element, Endian, Frame, HeaderValue, Length, Pos, Prim, Role,
    Scalar, Trailer, Transport,
};
use crate::spec::model::{ElementDef, FrameDef, SStr};

/// Rule: a spec has at least one frame format, each with a snake_case name.
pub(crate) fn lower_frames(ctx: &mut Ctx<'_>, structs: &Structs, enums: &Enums) -> Vec<Frame> {
    let spec = ctx.spec;
    if spec.frames.is_empty() {
        ctx.error(
            spec.protocol.span(),
            "the spec has no frame format",
            "add a `[frames.NAME]` table with a `layout = [...]`; see docs/spec-format.md",
        );
    }
    let mut out = Vec::new();
    for (name, def) in &spec.frames {
        check_snake_name(ctx, name, "frame name");
        if let Some(f) = lower_frame(ctx, name, def.get_ref(), structs, enums) {
            out.push(f);
        }
    }
    out
}

/// What one layout element is, once classified.
enum Kind {
    Sync(Vec<u8>),
    /// A header word: indices of its values in `values`.
    Word(Scalar, Vec<usize>),
    Payload,
    Check(usize),
    Trailer(usize),
}

struct El<'s> {
    name: String,
    /// `None` for the virtual `can_id` and `dlc` of a CAN frame.
    def: Option<&'s Spanned<ElementDef>>,
    kind: Kind,
    size: usize,
}

#[allow(clippy::too_many_lines)]
fn lower_frame(
    ctx: &mut Ctx<'_>,
    fname: &SStr,
    def: &FrameDef,
    structs: &Structs,
    enums: &Enums,
) -> Option<Frame> {
    let mut els: Vec<El<'_>> = Vec::new();
    let mut values: Vec<HeaderValue> = Vec::new();
    let mut checks: Vec<(Check, usize)> = Vec::new();
    let mut trailers: Vec<Trailer> = Vec::new();
    let mut payload: Option<(usize, usize, usize)> = None; // (element index, min, max)
    let mut length_decl: Option<(usize, &SStr)> = None; // (value index, coverage)
    let layout = def.layout.get_ref();
    let mut broken = false;
    let transport = lower_transport(ctx, def);
    if let Transport::Can { extended } = transport {
        // The virtual prefix every CAN frame starts with: the id and the data length, so that
        // checks can cover them (the Scout CAN checksum does) and dispatch can name the id.
        let id_word = Scalar {
            prim: Prim::U32,
            endian: Endian::Big,
        };
        values.push(HeaderValue {
            name: "can_id".into(),
            doc: "The CAN identifier.".into(),
            at: Pos::Start(0),
            word: id_word,
            shift: 0,
            width: if extended { 29 } else { 11 },
            prim: Prim::U32,
            role: Role::User { addresses: false },
        });
        values.push(HeaderValue {
            name: "dlc".into(),
            doc: "The CAN data length code: number of data bytes.".into(),
            at: Pos::Start(4),
            word: Scalar {
                prim: Prim::U8,
                endian: Endian::Big,
            },
            shift: 0,
            width: 8,
            prim: Prim::U8,
            role: Role::Length,
        });
        els.push(El {
            name: "can_id".into(),
            def: None,
            size: 4,
            kind: Kind::Word(id_word, vec![0]),
        });
        els.push(El {
            name: "dlc".into(),
            def: None,
            size: 1,
            kind: Kind::Word(
                Scalar {
                    prim: Prim::U8,
                    endian: Endian::Big,
                },
                vec![1],
            ),
        });
    }

    for (i, el) in layout.iter().enumerate() {
        let Some(kind) = check_element_keys(ctx, el) else {
            broken = true;
            continue;
        };
        let d = el.get_ref();
        match kind {
            "sync" => {
                let bytes = byte_list(ctx, d.sync.as_ref()?, "sync");
                if matches!(transport, Transport::Can { .. }) {
                    ctx.error(
                        el.span(),
                        "a CAN frame has no sync bytes",
                        "remove the `sync` element: CAN delivers whole frames",
                    );
                } else if i != 0 {
                    ctx.error(el.span(), "sync bytes must be the first element of the layout", "move the `sync` element to the start; constant bytes after the payload are a `trailer`");
                    broken = true;
                }
                els.push(El {
                    name: "sync".into(),
                    def: Some(el),
                    size: bytes.len(),
                    kind: Kind::Sync(bytes),
                });
            }
            "field" => {
                let name = d.field.as_ref()?;
                check_snake_name(ctx, name, "field name");
                let after_payload = payload.is_some();
                if after_payload && (d.value.is_some() || d.length_of.is_some()) {
                    ctx.error(el.span(), "a field after the payload cannot be the length or a constant", "constant bytes after the payload are a `trailer = [...]`; the length field goes before the payload");
                }
                let Some(ty) = &d.ty else {
                    ctx.error(
                        el.span(),
                        format!("field `{}` has no `type`", name.get_ref()),
                        "add `type = \"u8\"` (or `u16be`, `u16le`, ...)",
                    );
                    broken = true;
                    continue;
                };
                let word = match parse_prim(ty.get_ref(), ctx.default_endian) {
                    Some(s) if s.prim.is_unsigned() => s,
                    Some(_) => {
                        ctx.error(ty.span(), format!("header field type `{}` is not an unsigned integer", ty.get_ref()), "header fields are `u8`, `u16le`, `u16be`, `u32le`, ... (use `bits` for flags)");
                        broken = true;
                        continue;
                    }
                    None => {
                        let known = ["u8", "u16le", "u16be", "u32le", "u32be", "u64le", "u64be"]
                            .map(String::from);
                        super::names::unknown_type(ctx, ty, &known, "a header field's type");
                        broken = true;
                        continue;
                    }
                };
                // The real position is set once the whole layout is known (fields after the
                // payload count back from the end).
                let placeholder = Pos::Start(0);
                let mut idx = Vec::new();
                let addresses = d.addresses.as_ref().is_some_and(|a| *a.get_ref());
                if let Some(bits) = &d.bits {
                    let members = lower_bits(ctx, bits.get_ref(), word.prim, enums, &|_| None);
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
                            length_decl_once(ctx, &mut length_decl, values.len(), cov);
                            Role::Length
                        } else {
                            Role::User { addresses }
                        };
                        idx.push(values.len());
                        values.push(HeaderValue {
                            name: m.name,
                            doc: m.doc,
                            at: placeholder,
                            word,
                            shift: m.shift,
                            width: m.width,
                            prim: if m.prim == Prim::Bool {
                                Prim::Bool
                            } else {
                                m.prim
                            },
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
                } else {
                    let role = if let Some(v) = &d.value {
                        if fit(*v.get_ref(), word.prim).is_none() {
                            ctx.error(
                                v.span(),
                                format!(
                                    "value {} does not fit in {}",
                                    v.get_ref(),
                                    word.prim.rust_name()
                                ),
                                "use a smaller value or a wider type",
                            );
                        }
                        Role::Const(*v.get_ref() as u64)
                    } else if let Some(cov) = &d.length_of {
                        length_decl_once(ctx, &mut length_decl, values.len(), cov);
                        Role::Length
                    } else {
                        Role::User { addresses }
                    };
                    idx.push(values.len());
                    let width = (word.prim.size() * 8) as u32;
                    values.push(HeaderValue {
                        name: name.get_ref().clone(),
                        doc: text(&d.doc),
                        at: placeholder,
                        word,
                        shift: 0,
                        width,
                        prim: word.prim,
                        role,
                    });
                }
                els.push(El {
                    name: name.get_ref().clone(),
                    def: Some(el),
                    size: word.prim.size(),
                    kind: Kind::Word(word, idx),
                });
            }
            "payload" => {
                let p = d.payload.as_ref()?;
                if payload.is_some() {
                    ctx.error(
                        el.span(),
                        "a frame has one payload",
                        "remove the second `payload` element",
                    );
                    continue;
                }
                let min = p.get_ref().min.as_ref().map_or(0, |m| *m.get_ref());
                let max = match &p.get_ref().max {
                    Some(m) => *m.get_ref(),
                    None => {
                        ctx.error(
                            p.span(),
                            "the payload needs a `max` size",
                            "write `payload = { max = N }`: decoders size their buffer from it",
                        );
                        broken = true;
                        min.max(0)
                    }
                };
                if min < 0 || max < min {
                    ctx.error(
                        p.span(),
                        format!("payload bounds {min}..={max} are not valid"),
                        "use 0 <= min <= max",
                    );
                    broken = true;
                }
                payload = Some((els.len(), min.max(0) as usize, max.max(0) as usize));
                els.push(El {
                    name: "payload".into(),
                    def: Some(el),
                    size: 0,
                    kind: Kind::Payload,
                });
            }
            "check" => {
                let alg_name = d.check.as_ref()?;
                let algorithm = resolve_algorithm(ctx, alg_name);
                let endian = match &d.byte_order {
                    Some(o) => parse_byte_order(ctx, o).unwrap_or(ctx.default_endian),
                    None => ctx.default_endian,
                };
                let name = d
                    .name
                    .as_ref()
                    .map_or_else(|| "checksum".to_string(), |n| n.get_ref().clone());
                if let Some(n) = &d.name {
                    check_snake_name(ctx, n, "check name");
                }
                let Some(algorithm) = algorithm else {
                    broken = true;
                    continue;
                };
                let size = algorithm_size(&algorithm);
                let ci = checks.len();
                checks.push((
                    Check {
                        name: name.clone(),
                        doc: text(&d.doc),
                        algorithm,
                        at: Pos::Start(0),
                        size,
                        endian,
                        from: Pos::Start(0),
                        to: Pos::Start(0),
                        header: payload.is_none(),
                    },
                    els.len(),
                ));
                els.push(El {
                    name,
                    def: Some(el),
                    size,
                    kind: Kind::Check(ci),
                });
            }
            _ => {
                let bytes = byte_list(ctx, d.trailer.as_ref()?, "trailer");
                if payload.is_none() {
                    ctx.error(el.span(), "a trailer comes after the payload", "constant bytes before the payload are a field with `value = ...`, or the sync");
                }
                let name = d
                    .name
                    .as_ref()
                    .map_or_else(|| "trailer".to_string(), |n| n.get_ref().clone());
                let ti = trailers.len();
                trailers.push(Trailer {
                    name: name.clone(),
                    doc: text(&d.doc),
                    at: Pos::Start(0),
                    bytes: bytes.clone(),
                });
                els.push(El {
                    name,
                    def: Some(el),
                    size: bytes.len(),
                    kind: Kind::Trailer(ti),
                });
            }
        }
    }

    // Rule: element names are unique within a frame (they are what `over` and `length_of` name).
    for (i, e) in els.iter().enumerate() {
        let Some(edef) = e.def else { continue };
        if els[..i].iter().any(|p| p.name == e.name) {
            let span = edef
                .get_ref()
                .field
                .as_ref()
                .or(edef.get_ref().name.as_ref())
                .map_or(edef.span(), Spanned::span);
            ctx.error(span, format!("two elements of frame `{}` are named `{}`", fname.get_ref(), e.name), "give every field, check and trailer its own name (checks and trailers take `name = \"...\"`)");
        }
    }

    // Rule: the first element of a serial frame is the sync.
    if transport == Transport::Serial
        && !matches!(els.first().map(|e| &e.kind), Some(Kind::Sync(_)))
        && !broken
    {
        ctx.error(def.layout.span(), format!("frame `{}` has no sync bytes", fname.get_ref()), "start the layout with `{ sync = [0xFF, 0xFF] }`: a stream decoder finds frames by their sync");
        broken = true;
    }
    let Some((pi, payload_min, payload_max)) = payload else {
        if !broken {
            ctx.error(
                def.layout.span(),
                format!("frame `{}` has no payload element", fname.get_ref()),
                "add `{ payload = { max = N } }` where the command's data goes",
            );
        }
        return None;
    };
    if broken {
        return None;
    }

    // Offsets: header elements from the start, trailer elements back from the end.
    let header_len: usize = els[..pi].iter().map(|e| e.size).sum();
    let trailer_len: usize = els[pi + 1..].iter().map(|e| e.size).sum();
    let start_of = |i: usize| -> Pos {
        if i <= pi {
            Pos::Start(els[..i].iter().map(|e| e.size).sum())
        } else {
            Pos::End(els[i..].iter().map(|e| e.size).sum())
        }
    };
    let end_of = |i: usize| -> Pos {
        if i < pi {
            Pos::Start(els[..=i].iter().map(|e| e.size).sum())
        } else {
            Pos::End(els[i + 1..].iter().map(|e| e.size).sum())
        }
    };
    let find = |ctx: &mut Ctx<'_>, n: &str, span: std::ops::Range<usize>| -> Option<usize> {
        let found = els.iter().position(|e| e.name == n);
        if found.is_none() {
            let help = match did_you_mean(n, els.iter().map(|e| e.name.as_str())) {
                Some(b) => format!("did you mean `{b}`?"),
                None => format!(
                    "name elements of this layout: {}",
                    els.iter()
                        .map(|e| format!("`{}`", e.name))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            };
            ctx.error(
                span,
                format!("frame `{}` has no element `{n}`", fname.get_ref()),
                help,
            );
        }
        found
    };
    // Parse "a..b", "a" or "frame" into element indices (inclusive); "frame" is `None`.
    let parse_range = |ctx: &mut Ctx<'_>, s: &SStr| -> Option<Option<(usize, usize)>> {
        let v = s.get_ref().trim();
        if v == "frame" {
            return Some(None);
        }
        let (a, b) = v.split_once("..").unwrap_or((v, v));
        let ia = find(ctx, a.trim(), s.span())?;
        let ib = find(ctx, b.trim(), s.span())?;
        if ia > ib {
            ctx.error(
                s.span(),
                format!("range `{v}` runs backwards"),
                format!(
                    "write the earlier element first: `{}..{}`",
                    b.trim(),
                    a.trim()
                ),
            );
            return None;
        }
        Some(Some((ia, ib)))
    };

    let mut ok = true;
    // Every word's position: header words from the start, words after the payload from the end.
    for (i, e) in els.iter().enumerate() {
        if let Kind::Word(_, idx) = &e.kind {
            for &vi in idx {
                values[vi].at = start_of(i);
            }
        }
    }
    if let Transport::Can { .. } = transport {
        // Rule: a CAN frame's length is its DLC, and it carries at most 8 data bytes.
        if let Some((_, cov)) = length_decl {
            ctx.error(
                cov.span(),
                "a CAN frame's length is its DLC",
                "remove `length_of`: the data length of a CAN frame comes with the frame",
            );
            return None;
        }
        let data_max = header_len - CAN_PREFIX_LEN + payload_max + trailer_len;
        if data_max > 8 {
            ctx.error(def.layout.span(), format!("frame `{}` needs up to {data_max} data bytes, but a CAN frame carries at most 8", fname.get_ref()), "shrink the payload's `max` or the fields around it");
            return None;
        }
    }
    // Rule: the length field covers a contiguous run of elements that includes the payload; the
    // total length is the field's value plus the bytes outside that run.
    let length = match length_decl {
        None if matches!(transport, Transport::Can { .. }) => Length::Field {
            value: 1,
            adjust: CAN_PREFIX_LEN as i64,
        },
        None if payload_min == payload_max => Length::Fixed(header_len + payload_max + trailer_len),
        None => {
            ctx.error(def.layout.span(), format!("frame `{}` has no length field, but its payload size varies", fname.get_ref()), "mark the field that holds the length with `length_of = \"...\"`, or set the payload's `min` equal to its `max`");
            return None;
        }
        Some((vi, cov)) => match parse_range(ctx, cov) {
            None => return None,
            Some(range) => {
                let (ia, ib) = range.unwrap_or((0, els.len() - 1));
                if ia > pi || ib < pi {
                    ctx.error(cov.span(), format!("the length field counts `{}`, which does not include the payload", cov.get_ref()), "a length field must count the payload (e.g. `\"payload\"`, `\"command..payload\"` or `\"frame\"`)");
                    return None;
                }
                let before = match start_of(ia) {
                    Pos::Start(n) | Pos::End(n) => n,
                };
                let after = match end_of(ib) {
                    Pos::Start(n) => header_len + trailer_len - n,
                    Pos::End(n) => n,
                };
                let adjust = (before + after) as i64;
                let v = &values[vi];
                let field_max = mask(v.width);
                let needed = (header_len + payload_max + trailer_len) as i64 - adjust;
                if needed > 0 && needed as u64 > field_max {
                    ctx.error(cov.span(), format!("the length field has {} bits (at most {field_max}), but the largest frame needs the value {needed}", v.width), "use a wider length field, or lower the payload's `max`");
                    ok = false;
                }
                if (header_len + payload_min + trailer_len) as i64 - adjust < 0 {
                    ctx.error(
                        cov.span(),
                        "the length field would count a negative number of bytes",
                        "check what `length_of` covers",
                    );
                    ok = false;
                }
                Length::Field { value: vi, adjust }
            }
        },
    };
    // Rule: a check covers bytes before it (`frame` means all of them), never its own bytes, and
    // a check inside the header covers only header bytes.
    for (check, ei) in &mut checks {
        let Some(edef) = els[*ei].def else { continue };
        let d = edef.get_ref();
        let at = start_of(*ei);
        let over = d.over.as_ref();
        let range = match over {
            None => {
                ctx.error(edef.span(), format!("check `{}` does not say what it covers", check.name), "add `over = \"frame\"` (every byte before the check) or `over = \"first..last\"`");
                ok = false;
                continue;
            }
            Some(s) => match parse_range(ctx, s) {
                None => {
                    ok = false;
                    continue;
                }
                Some(r) => r,
            },
        };
        let (from, to) = match range {
            None => (Pos::Start(0), at),
            Some((ia, ib)) => {
                if ia <= *ei && *ei <= ib {
                    ctx.error(over.map_or(0..0, Spanned::span), format!("check `{}` covers its own bytes", check.name), "a check covers bytes before it: end the range at the element before the check");
                    ok = false;
                    continue;
                }
                if ib > *ei {
                    ctx.error(
                        over.map_or(0..0, Spanned::span),
                        format!("check `{}` covers bytes after it", check.name),
                        "cover only elements before the check",
                    );
                    ok = false;
                    continue;
                }
                (start_of(ia), end_of(ib))
            }
        };
        check.at = at;
        check.from = from;
        check.to = to;
    }
    for (t, e) in trailers
        .iter_mut()
        .zip(els.iter().filter(|e| matches!(e.kind, Kind::Trailer(_))))
    {
        let i = els.iter().position(|x| std::ptr::eq(x, e)).unwrap_or(0);
        t.at = start_of(i);
    }

    // Rule: the dispatch key names header fields that are not the length or a constant.
    let mut dispatch = Vec::new();
    if let Some(keys) = &def.dispatch {
        for k in keys.get_ref() {
            match values.iter().position(|v| &v.name == k.get_ref()) {
                Some(vi) if matches!(values[vi].at, Pos::End(_)) => {
                    ctx.error(
                        k.span(),
                        format!(
                            "`{}` comes after the payload, so it cannot be a dispatch key",
                            k.get_ref()
                        ),
                        "dispatch on a header field",
                    );
                    ok = false;
                }
                Some(vi) => match values[vi].role {
                    Role::User { .. } => {
                        values[vi].role = Role::Dispatch;
                        dispatch.push(vi);
                    }
                    _ => {
                        ctx.error(
                            k.span(),
                            format!(
                                "`{}` cannot be a dispatch key: it is the length or a constant",
                                k.get_ref()
                            ),
                            "dispatch on a field that holds the command id",
                        );
                        ok = false;
                    }
                },
                None => {
                    let help =
                        match did_you_mean(k.get_ref(), values.iter().map(|v| v.name.as_str())) {
                            Some(b) => format!("did you mean `{b}`?"),
                            None => "name a header field of this frame".to_string(),
                        };
                    ctx.error(
                        k.span(),
                        format!(
                            "frame `{}` has no header field `{}`",
                            fname.get_ref(),
                            k.get_ref()
                        ),
                        help,
                    );
                    ok = false;
                }
            }
        }
    }

    // Rule: an acknowledgement flag is a one-bit header value set by the sender; the dispatch
    // fields, absent from acknowledgements, are the last header fields before the payload.
    let mut ack = None;
    if let Some(a) = &def.ack {
        let a_def = a.get_ref();
        match values.iter().position(|v| &v.name == a_def.field.get_ref()) {
            None => {
                ctx.error(
                    a_def.field.span(),
                    format!(
                        "frame `{}` has no header field `{}`",
                        fname.get_ref(),
                        a_def.field.get_ref()
                    ),
                    "name the one-bit flag that marks acknowledgements",
                );
                ok = false;
            }
            Some(vi) if values[vi].width != 1 || !matches!(values[vi].role, Role::User { .. }) => {
                ctx.error(
                    a_def.field.span(),
                    format!(
                        "`{}` is not a one-bit field set by the sender",
                        a_def.field.get_ref()
                    ),
                    "the acknowledgement flag is a one-bit member of a header field's `bits`",
                );
                ok = false;
            }
            Some(vi) => {
                let equals = *a_def.equals.get_ref();
                if !(0..=1).contains(&equals) {
                    ctx.error(
                        a_def.equals.span(),
                        "a one-bit flag equals 0 or 1",
                        "write `equals = 1` (or 0)",
                    );
                    ok = false;
                }
                // The dispatch words must sit right before the payload.
                let mut ack_header_len = header_len;
                let mut i = pi;
                let mut words = 0;
                while i > 0 {
                    match &els[i - 1].kind {
                        Kind::Word(_, idx)
                            if idx.iter().all(|v| dispatch.contains(v)) && !idx.is_empty() =>
                        {
                            ack_header_len -= els[i - 1].size;
                            words += idx.len();
                            i -= 1;
                        }
                        _ => break,
                    }
                }
                if dispatch.is_empty() || words != dispatch.len() {
                    ctx.error(a.span(), "acknowledgements need the dispatch fields to be the last header fields before the payload", "move the dispatch fields right before the `payload` element (acknowledgements are the frames without them)");
                    ok = false;
                }
                values[vi].role = Role::Ack(equals.clamp(0, 1) as u64);
                ack = Some((vi, ack_header_len));
            }
        }
    }
    // Rule: a bare header needs a length field (its value says the frame is the header alone).
    let bare_len = match &def.bare_header {
        Some(b) if *b.get_ref() => {
            if !matches!(length, Length::Field { .. }) {
                ctx.error(
                    b.span(),
                    "a bare header needs a length field",
                    "only a frame whose length field can say \"header only\" may be a bare header",
                );
                ok = false;
            }
            Some(ack.map_or(header_len, |(_, n)| n))
        }
        _ => None,
    };
    // Rule: stuffing names a non-empty pattern of bytes and a byte to insert.
    let stuffing = def.stuffing.as_ref().and_then(|st| {
        let d = st.get_ref();
        let after = byte_list(ctx, &d.after, "the stuffing pattern");
        match u8::try_from(*d.insert.get_ref()) {
            Ok(insert) if !after.is_empty() => Some((after, insert)),
            Ok(_) => None,
            Err(_) => {
                ctx.error(
                    d.insert.span(),
                    format!("{} is not a byte", d.insert.get_ref()),
                    "use a value from 0x00 to 0xFF",
                );
                None
            }
        }
    });
    // Rule: a frame format without a dispatch key may name the struct every frame carries; it
    // must fit the payload's bounds.
    let message = match &def.message {
        None => None,
        Some(m) if !dispatch.is_empty() || def.dispatch.is_some() => {
            ctx.error(
                m.span(),
                "a frame format has either a dispatch key or one `message`",
                "remove `dispatch` (every frame carries this struct) or `message`",
            );
            ok = false;
            None
        }
        Some(m) => match structs.by_name.get(m.get_ref()) {
            Some(&i) => {
                let st = &structs.structs[i];
                if st.min_size < payload_min || st.min_size > payload_max || (st.size < payload_min)
                {
                    ctx.error(m.span(), format!("struct `{}` takes {} to {} bytes, but frame `{}` carries {payload_min} to {payload_max}", st.name, st.min_size, st.size, fname.get_ref()), "make the payload bounds and the struct agree");
                    ok = false;
                }
                Some(i)
            }
            None => {
                let help = match did_you_mean(
                    m.get_ref(),
                    structs.structs.iter().map(|s| s.name.as_str()),
                ) {
                    Some(b) => format!("did you mean `{b}`?"),
                    None => "declare it as `[structs.NAME]`".to_string(),
                };
                ctx.error(m.span(), format!("unknown struct `{}`", m.get_ref()), help);
                ok = false;
                None
            }
        },
    };
    if !ok {
        // The commands cannot be checked against a frame whose layout is broken.
        return None;
    }
    let elements = els
        .iter()
        .map(|e| match &e.kind {
            Kind::Sync(b) => Element::Sync(b.clone()),
            Kind::Word(s, idx) => Element::Word {
                name: e.name.clone(),
                at: idx.first().map_or(Pos::Start(0), |&i| values[i].at),
                scalar: *s,
                values: idx.clone(),
            },
            Kind::Payload => Element::Payload,
            Kind::Check(i) => Element::Check(*i),
            Kind::Trailer(i) => Element::Trailer(*i),
        })
        .collect();
    let sync = match &els[0].kind {
        Kind::Sync(b) => b.clone(),
        _ => Vec::new(),
    };
    let mut ordered: Vec<Check> = checks
        .iter()
        .filter(|(c, _)| c.header)
        .map(|(c, _)| c.clone())
        .collect();
    ordered.extend(
        checks
            .iter()
            .filter(|(c, _)| !c.header)
            .map(|(c, _)| c.clone()),
    );
    // Element::Check indices refer to spec order; keep `checks` in spec order when no header
    // check follows a frame check (always true: header checks precede the payload).
    Some(Frame {
        name: fname.get_ref().clone(),
        transport,
        doc: text(&def.doc),
        sync,
        header_len,
        trailer_len,
        payload_min,
        payload_max,
        values,
        length,
        dispatch,
        checks: ordered,
        trailers,
        elements,
        ack,
        bare_len,
        stuffing,
        message,
    })
}

fn length_decl_once<'s>(
    ctx: &mut Ctx<'_>,
    slot: &mut Option<(usize, &'s SStr)>,
    value: usize,
    cov: &'s SStr,
) {
    if slot.is_some() {
        ctx.error(
            cov.span(),
            "a frame has one length field",
            "remove `length_of` from all but one field",
        );
    } else {
        *slot = Some((value, cov));
    }
}

/// Bytes of a check value.
pub(crate) fn algorithm_size(a: &Algorithm) -> usize {
    match a {
        Algorithm::Sum { .. } | Algorithm::Xor => 1,
        Algorithm::Crc(p) => usize::from(p.width / 8),
    }
}
