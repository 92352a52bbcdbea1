//! Rules for frame formats. `lower_frame` runs them in order over a `Draft`: each layout
//! element is lowered on its own (`elements`, `header`), then, once the payload's place is
//! known, the offsets and the length rule (`length`), what each check covers (`checks`), the
//! dispatch key, acknowledgements and bare headers (`ack`), and the settings outside the
//! layout (`options`). A rule that fails records its error and the frame is dropped at the
//! end, so every rule of a frame still reports.

mod ack;
mod can_id;
mod checks;
mod conditional;
mod counter;
mod directed;
mod elements;
mod escape;
mod header;
mod length;
mod link;
mod options;

use toml::Spanned;

use super::names::{check_snake_name, pascal_case};
use super::types::{Enums, Structs};
use super::{Ctx, text};
use crate::ir::{
    Check, Element, Frame, FrameNames, FrameSizeNames, HeaderValue, PacketKind, Pos, Scalar,
    Trailer, Transport,
};
use crate::spec::model::{ElementDef, FrameDef, SStr};
use length::Layout;

pub(crate) use directed::attach_own_layouts;
pub(crate) use link::lower_link;

/// The frame formats, and the first format as each direction with fields of its own lays it
/// out (`(direction, frame)`, in the order of `[directions]`).
pub(crate) type Lowered = (Vec<Frame>, Vec<(String, Frame)>);

/// Rule: a spec has at least one frame format, each with a snake_case name.
pub(crate) fn lower_frames(ctx: &mut Ctx<'_>, structs: &Structs, enums: &Enums) -> Lowered {
    let spec = ctx.spec;
    if spec.frames.is_empty() {
        ctx.error(
            spec.protocol.span(),
            "the spec has no frame format",
            "add a `[frames.NAME]` table with a `layout = [...]`; see docs/spec-format.md",
        );
    }
    let mut out = Vec::new();
    let mut own = Vec::new();
    for (i, (name, def)) in spec.frames.iter().enumerate() {
        check_snake_name(ctx, name, "frame name");
        directed::check_first_format(ctx, def.get_ref(), i == 0);
        // A field of one direction that breaks its rules is not lowered at all: the format's
        // own layout would report what the field's rule says once.
        if i == 0 && !directed::check_directed(ctx, def.get_ref()) {
            continue;
        }
        let f = lower_frame(ctx, name, i == 0, def.get_ref(), structs, enums, None);
        if i == 0 {
            own = directed::lower_directed(ctx, name, def.get_ref(), structs, enums, f.is_some());
        }
        out.extend(f);
    }
    (out, own)
}

/// What one layout element is, once classified.
enum Kind {
    Sync(Vec<u8>),
    /// A header word: indices of its values in `values`.
    Word(Scalar, Vec<usize>),
    Payload,
    Check(usize),
    Trailer(usize),
    /// The flag trailer (`optional`): no bytes at a fixed place.
    Optional,
}

/// One layout element, lowered.
struct El<'s> {
    name: String,
    /// `None` for the virtual `can_id` and `dlc` of a CAN frame.
    def: Option<&'s Spanned<ElementDef>>,
    kind: Kind,
    size: usize,
}

/// A frame format while its element rules run: the elements lowered so far and the values,
/// checks and trailers they declare. Positions are placeholders until the payload's place is
/// known (`Layout`).
struct Draft<'s> {
    transport: Transport,
    els: Vec<El<'s>>,
    values: Vec<HeaderValue>,
    /// Each check with the index of its element.
    checks: Vec<(Check, usize)>,
    trailers: Vec<Trailer>,
    /// The payload element: its index, smallest and largest size.
    payload: Option<(usize, usize, usize)>,
    /// The length field: its value index and what it counts.
    length_decl: Option<(usize, &'s SStr)>,
    /// An element could not be lowered, so offsets after it are unknown.
    broken: bool,
    /// The values of a field that is the sync (`one_of`), once lowered.
    sync_set: Option<Vec<u8>>,
    /// The flag trailer (`optional`) as declared, once lowered.
    optional: Option<conditional::OptionalDecl<'s>>,
}

impl Draft<'_> {
    /// A frame of `transport` before its first element.
    fn new(transport: Transport) -> Self {
        Draft {
            transport,
            els: Vec::new(),
            values: Vec::new(),
            checks: Vec::new(),
            trailers: Vec::new(),
            payload: None,
            length_decl: None,
            broken: false,
            sync_set: None,
            optional: None,
        }
    }
}

/// Lower one frame format (`first`: the spec's first, default one) as the frames of
/// `direction` lay it out (`None`: without the fields of one direction): the element rules,
/// then the rules over the whole layout. `None` when any rule failed (its error is recorded).
fn lower_frame(
    ctx: &mut Ctx<'_>,
    fname: &SStr,
    first: bool,
    def: &FrameDef,
    structs: &Structs,
    enums: &Enums,
    direction: Option<&str>,
) -> Option<Frame> {
    let transport = options::lower_transport(ctx, def);
    let mut draft = Draft::new(transport);
    can_id::check_members_placement(ctx, def, first);
    header::push_can_prefix(ctx, &mut draft, def, enums);
    let layout = def.layout.get_ref().iter();
    let own = layout.filter(|el| directed::in_direction(el.get_ref(), direction));
    for (i, el) in own.enumerate() {
        elements::lower_element(ctx, &mut draft, i, el, enums)?;
    }
    can_id::check_member_names(ctx, def, &draft);
    elements::check_unique_names(ctx, fname, &draft.els);
    elements::check_serial_sync(ctx, fname, def, &mut draft);
    let extension = conditional::find_extension(ctx, &mut draft);
    let Some((pi, payload_min, payload_max)) = draft.payload else {
        if !draft.broken {
            ctx.error(
                def.layout.span(),
                format!("frame `{}` has no payload element", fname.get_ref()),
                "add `{ payload = { max = N } }` where the command's data goes",
            );
        }
        return None;
    };
    if draft.broken {
        return None;
    }
    let Draft {
        els,
        mut values,
        mut checks,
        mut trailers,
        length_decl,
        sync_set,
        optional,
        ..
    } = draft;
    let sync_set = sync_set.unwrap_or_default();
    let lay = Layout::new(fname, &els, pi, payload_min, payload_max);
    lay.place_values(&mut values);
    length::check_can_length(ctx, def, &lay, transport, length_decl)?;
    let mut ok = true;
    let length = length::lower_length(ctx, def, &lay, transport, length_decl, &values, &mut ok)?;
    let runs = checks::lower_coverage(ctx, &lay, &mut checks, &mut ok);
    checks::check_coverage_order(ctx, &lay, &checks, &runs, &mut ok);
    checks::place_trailers(&lay, &mut trailers);
    let dispatch = ack::lower_dispatch(ctx, fname, def, &mut values, &mut ok);
    checks::lower_extra_keys(ctx, &lay, &mut checks, &values, &dispatch, &mut ok);
    let ack = ack::lower_ack(ctx, fname, def, &lay, &mut values, &dispatch, &mut ok);
    ack::check_ack_extra(ctx, fname, def, &checks, &mut ok);
    let bare_len = ack::lower_bare_header(ctx, def, &length, lay.header_len, ack, &mut ok);
    checks::check_bare_header(ctx, &lay, &checks, bare_len.is_some(), &mut ok);
    let stuffing = options::lower_stuffing(ctx, def);
    let escape = escape::lower_escape(ctx, def, &els, &trailers, transport, &mut ok);
    let truncate_zeros = options::lower_truncate_zeros(ctx, def, first, transport, &mut ok);
    let message = options::lower_message(ctx, fname, def, &dispatch, structs, &lay, &mut ok);
    let cx = conditional::Context {
        def,
        lay: &lay,
        first,
        length: &length,
        header_checks: checks.iter().any(|(c, _)| c.header),
    };
    let flag_trailer = conditional::lower_flag_trailer(ctx, &cx, optional, &mut values, &mut ok);
    let length_extension = conditional::lower_extension(ctx, &cx, extension, &values, &mut ok);
    let counter = counter::lower_counter(ctx, def, &values, &mut ok);
    if !ok {
        // The commands cannot be checked against a frame whose layout is broken.
        return None;
    }
    let sync = match &els[0].kind {
        Kind::Sync(b) => b.clone(),
        _ => Vec::new(),
    };
    let names = lower_names(fname.get_ref(), first, direction, &values);
    let (checks, check_order) = order_checks(checks);
    let checks = name_tables(checks, &names);
    Some(Frame {
        name: fname.get_ref().clone(),
        names,
        transport,
        doc: text(&def.doc),
        decide_len: length::lower_decide_len(
            sync.len() + usize::from(!sync_set.is_empty()),
            &values,
            &length,
            flag_trailer.as_ref(),
            &checks,
        ),
        sync,
        sync_set,
        header_len: lay.header_len,
        trailer_len: lay.trailer_len,
        payload_min,
        payload_max,
        elements: lower_elements(&els, &values, &check_order),
        values,
        length,
        dispatch,
        checks,
        trailers,
        ack,
        bare_len,
        stuffing,
        escape,
        truncate_zeros,
        message,
        packet: PacketKind::None,
        extensions: def.extensions.as_ref().is_none_or(|e| *e.get_ref()),
        direction: None,
        commands: Vec::new(),
        flag_trailer,
        length_extension,
        counter,
        payload_origin: String::new(),
    })
}

/// The `static` each CRC's table lives in (the frame's const prefix, the check's name,
/// `_TABLE`), and the `static` of a per-command extra (`_EXTRA`); unique, since element names
/// are.
fn name_tables(mut checks: Vec<Check>, names: &FrameNames) -> Vec<Check> {
    for c in &mut checks {
        if c.algorithm.crc_table().is_some() {
            let name = format!("{}{}_TABLE", names.const_prefix, c.name);
            c.naming.table_static = Some(name.to_ascii_uppercase());
        }
        if c.extra.is_some() {
            let name = format!("{}{}_EXTRA", names.const_prefix, c.name);
            c.naming.extra_static = Some(name.to_ascii_uppercase());
        }
    }
    checks
}

/// The packet type of each frame format, once the directions are known: the first frame
/// format has one when it has a dispatch key, and then so do the other serial frame formats
/// that carry one `message` and, in a spec without directions, the other CAN frame formats.
/// A first (and only) serial frame format that carries one `message` has its packet too (a
/// link whose frames have no command, as SBUS).
pub(crate) fn lower_packets(frames: &mut [Frame], directions: bool, commands: usize) {
    let Some(first) = frames.first_mut() else {
        return;
    };
    if first.dispatch.is_empty() {
        if let (Transport::Serial, Some(si), 1) = (first.transport, first.message, frames.len()) {
            frames[0].packet = PacketKind::Message(si);
        }
        return;
    }
    frames[0].packet = PacketKind::Command;
    frames[0].commands = (0..commands).collect();
    for f in frames.iter_mut().skip(1) {
        f.packet = match (f.transport, f.message) {
            (Transport::Serial, Some(si)) => PacketKind::Message(si),
            (Transport::Can { .. }, _) if !directions => PacketKind::Can,
            _ => PacketKind::None,
        };
    }
}

/// The Rust names of a frame format's items: plain for the first frame format, prefixed with
/// the frame's name for the others (so two frame formats never define the same item). The
/// first format as a direction with fields of its own lays it out has its statics and consts
/// prefixed with the direction's name (`RESPONSE_LAYOUT`, `wire::RESPONSE_LENGTH`) and shares
/// the format's `Header` and `Packet`, which hold every direction's values.
fn lower_names(
    name: &str,
    first: bool,
    direction: Option<&str>,
    values: &[HeaderValue],
) -> FrameNames {
    if let Some(d) = direction {
        let mut names = lower_names(d, false, None, values);
        names.header = "Header".to_string();
        names.packet = "Packet".to_string();
        return names;
    }
    let pascal = pascal_case(name);
    let item = |plain: &str| {
        if first {
            plain.to_string()
        } else {
            format!("{pascal}{plain}")
        }
    };
    let prefix = if first {
        String::new()
    } else {
        format!("{}_", name.to_ascii_uppercase())
    };
    let constant = |plain: &str| format!("{prefix}{plain}").to_ascii_uppercase();
    FrameNames {
        header: item("Header"),
        packet: item("Packet"),
        layout: item("Layout"),
        decoder: item("Decoder"),
        decoder_fn: if first {
            "decoder".to_string()
        } else {
            format!("{name}_decoder")
        },
        layout_static: constant("LAYOUT"),
        rules_static: constant("RULES"),
        sizes: FrameSizeNames {
            max_frame_len: constant("MAX_FRAME_LEN"),
            min_frame_len: constant("MIN_FRAME_LEN"),
            max_payload_len: constant("MAX_PAYLOAD_LEN"),
            min_payload_len: constant("MIN_PAYLOAD_LEN"),
            header_len: constant("HEADER_LEN"),
            trailer_len: constant("TRAILER_LEN"),
            decoder_buffer_len: constant("DECODER_BUFFER_LEN"),
        },
        wire: values.iter().map(|v| constant(&v.name)).collect(),
        const_prefix: prefix,
        pascal,
    }
}

/// The wire elements in order, for docs and diagrams; `check_order` gives each check's index
/// (in spec order) its place in [`Frame::checks`].
fn lower_elements(els: &[El<'_>], values: &[HeaderValue], check_order: &[usize]) -> Vec<Element> {
    els.iter()
        .map(|e| match &e.kind {
            Kind::Sync(b) => Element::Sync(b.clone()),
            Kind::Word(s, idx) => Element::Word {
                name: e.name.clone(),
                at: idx.first().map_or(Pos::Start(0), |&i| values[i].at),
                scalar: *s,
                values: idx.clone(),
            },
            Kind::Payload => Element::Payload,
            Kind::Check(i) => Element::Check(check_order[*i]),
            Kind::Trailer(i) => Element::Trailer(*i),
            Kind::Optional => Element::FlagTrailer,
        })
        .collect()
}

/// Checks in the order they are verified: header checks first, then frame checks, each in
/// spec order; and for each check in spec order, its place in that order (a check before the
/// payload that covers the payload is a frame check, so a header check may follow it in the
/// layout).
fn order_checks(checks: Vec<(Check, usize)>) -> (Vec<Check>, Vec<usize>) {
    let mut indices: Vec<usize> = (0..checks.len()).collect();
    indices.sort_by_key(|&i| !checks[i].0.header);
    let mut place = vec![0; checks.len()];
    for (p, &i) in indices.iter().enumerate() {
        place[i] = p;
    }
    let mut slots: Vec<Option<Check>> = checks.into_iter().map(|(c, _)| Some(c)).collect();
    let ordered = indices.iter().filter_map(|&i| slots[i].take()).collect();
    (ordered, place)
}
