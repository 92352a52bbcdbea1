//! Rustdoc text for generated items: the spec's own documentation plus layout tables (offset,
//! size, field, type, byte order, unit). Text only; no tokens besides `#[doc]` attributes.

#[cfg(feature = "rust")]
use proc_macro2::TokenStream;
#[cfg(feature = "rust")]
use quote::quote;

use crate::ir::{
    Algorithm, BitMember, BitOrder, ByteOrder, Check, Field, FieldKind, Frame, Pos, Prim, Protocol,
    Role, Struct, ValueType,
};

/// `#[doc = "..."]` attributes, one per line (so rustdoc and prettyplease keep the layout).
#[cfg(feature = "rust")]
pub fn doc_attrs(text: &str) -> TokenStream {
    let lines: Vec<String> = if text.trim().is_empty() {
        Vec::new()
    } else {
        text.lines()
            .map(|l| format!(" {}", plain_brackets(l)).trim_end().to_string())
            .collect()
    };
    quote!(#(#[doc = #lines])*)
}

/// `line` with each bracketed run that rustdoc would take for a link to an item escaped
/// (`value[float]` -> `value\[float\]`): a spec's text is prose, and its brackets (array
/// indices, C types) are no paths. The generated docs' own links stay links: they name their
/// item in backticks (`` [`dispatch`] ``), and Markdown links are followed by `(` or `[`.
/// Code spans are left as they are (an escape would show there).
#[cfg(feature = "rust")]
fn plain_brackets(line: &str) -> String {
    line.split('`')
        .enumerate()
        .map(|(i, part)| {
            if i % 2 == 0 {
                prose_urls(&prose_brackets(part))
            } else {
                part.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("`")
}

/// `line` with each bare URL in angle brackets (`<https://...>`), as rustdoc links one: a
/// spec's text names its sources as plain text.
#[cfg(feature = "rust")]
fn prose_urls(line: &str) -> String {
    let mut out = String::with_capacity(line.len());
    let mut rest = line;
    while let Some(at) = ["https://", "http://"]
        .iter()
        .filter_map(|scheme| rest.find(scheme))
        .min()
    {
        let before = &rest[..at];
        out.push_str(before);
        let url_and_more = &rest[at..];
        let end = url_and_more
            .find(|c: char| c.is_whitespace() || c == '>' || c == ')')
            .unwrap_or(url_and_more.len());
        // A sentence's full stop or comma after the URL is not part of it.
        let url = url_and_more[..end].trim_end_matches(['.', ',', ';', ':']);
        // Not already in angle brackets, nor a Markdown link's target.
        let bare = !before.ends_with('<') && !before.ends_with("](");
        if bare {
            out.push('<');
            out.push_str(url);
            out.push('>');
        } else {
            out.push_str(url);
        }
        rest = &url_and_more[url.len()..];
    }
    out.push_str(rest);
    out
}

/// [`plain_brackets`] of a run of text outside code spans.
#[cfg(feature = "rust")]
fn prose_brackets(line: &str) -> String {
    let mut out = String::with_capacity(line.len());
    let mut rest = line;
    while let Some(open) = rest.find('[') {
        out.push_str(&rest[..open]);
        let after = &rest[open + 1..];
        let Some(close) = after.find(']') else {
            out.push_str(&rest[open..]);
            return out;
        };
        let inner = &after[..close];
        let next = after[close + 1..].chars().next();
        // Already escaped (`\[`), a link, or a link's text.
        let escaped = rest[..open].ends_with('\\');
        let link = escaped || inner.starts_with('`') || matches!(next, Some('(' | '[' | ':'));
        if link || inner.contains('[') {
            out.push('[');
            rest = after;
            continue;
        }
        out.push_str("\\[");
        out.push_str(inner);
        out.push_str("\\]");
        rest = &after[close + 1..];
    }
    out.push_str(rest);
    out
}

fn order_name(e: ByteOrder, size: usize) -> &'static str {
    if size <= 1 {
        "-"
    } else {
        match e {
            ByteOrder::Little => "little",
            ByteOrder::Big => "big",
        }
    }
}

/// What the docs say of one field kind: its type, its byte order (or bit order), the name
/// cell of the wire table when the kind names more than the field, and whether the offsets
/// of the fields after it count from its end (its size varies).
struct KindDoc {
    ty: String,
    order: &'static str,
    name: Option<String>,
    moves_offsets: bool,
}

impl KindDoc {
    fn of(ty: String, order: &'static str) -> KindDoc {
        KindDoc {
            ty,
            order,
            name: None,
            moves_offsets: false,
        }
    }

    /// Of a kind whose size varies.
    fn varying(ty: String) -> KindDoc {
        KindDoc {
            moves_offsets: true,
            ..KindDoc::of(ty, "-")
        }
    }
}

/// The docs of field `f` of kind `kind` (the field's, or what an optional field holds): the
/// one place the docs match on a field's kind.
fn kind_doc(p: &Protocol, f: &Field, kind: &FieldKind) -> KindDoc {
    match kind {
        FieldKind::Padding => KindDoc {
            name: Some("*(padding)*".to_string()),
            ..KindDoc::of("padding".into(), "-")
        },
        FieldKind::Bytes {
            max,
            size_from,
            text,
        } => {
            let what = if *text { "text" } else { "bytes" };
            KindDoc::varying(match size_from {
                None => format!("{what}, the rest (up to {max})"),
                Some(n) if *text => format!("text, `{n}` bytes (up to {max})"),
                Some(n) => format!("bytes, `{n}` of them (up to {max})"),
            })
        }
        FieldKind::Group { elem, max } => KindDoc::varying(format!(
            "`{}` repeated to the end (up to {max})",
            p.structs[*elem].name
        )),
        FieldKind::Optional(inner) => {
            let inner = kind_doc(p, f, inner);
            KindDoc::of(format!("optional {}", inner.ty), inner.order)
        }
        // Present or not, it moves the fields after it.
        FieldKind::When { kind, mask, bit } => {
            let inner = kind_doc(p, f, kind);
            KindDoc {
                moves_offsets: true,
                ..KindDoc::of(
                    format!("{} if bit {bit} of `{mask}` is set", inner.ty),
                    inner.order,
                )
            }
        }
        FieldKind::Packed {
            count,
            bits,
            scale,
            order,
            ..
        } => {
            let ty = match scale {
                None => format!("[u{bits}; {count}] packed"),
                Some(s) => {
                    let off = if s.offset != 0.0 {
                        format!(" + {}", s.offset)
                    } else {
                        String::new()
                    };
                    format!("[u{bits} × {}{off}; {count}] packed", s.factor)
                }
            };
            let order = match order {
                BitOrder::LsbFirst => "LSB first",
                BitOrder::MsbFirst => "MSB first",
            };
            KindDoc::of(ty, order)
        }
        FieldKind::Bits { word, members } => {
            let mut names: Vec<String> = members.iter().map(member_name).collect();
            // Bits above the members that no member keeps are reserved-zero.
            let used: u32 = members.iter().map(|m| m.width).sum();
            let bits = 8 * word.prim.size() as u32;
            if used < bits {
                names.push(format!("bits {used}..{bits} reserved, zero"));
            }
            KindDoc {
                name: Some(names.join(", ")),
                ..KindDoc::of(
                    format!("{} bits", word.prim.spec_name()),
                    order_name(word.endian, word.prim.size()),
                )
            }
        }
        FieldKind::BitStream { members } => {
            let names: Vec<String> = members.iter().map(member_name).collect();
            let bits: u32 = members.iter().map(|m| m.width).sum();
            let size = f.size as u32 * 8;
            let zero = if bits < size {
                format!(", bits {bits}..{size} zero")
            } else {
                String::new()
            };
            KindDoc {
                name: Some(format!("{}{zero}", names.join(", "))),
                ..KindDoc::of(format!("bit stream of {bits} bits"), "MSB first")
            }
        }
        FieldKind::NulText { max } => {
            KindDoc::varying(format!("NUL-terminated text (up to {max} bytes)"))
        }
        FieldKind::Array {
            ty,
            max,
            size_from,
            by_mask,
        } => {
            let elem = value_doc(p, ty, None);
            // Brackets escaped: rustdoc would read `[i24]` as a link.
            let ty = match size_from {
                None => format!("\\[{}\\] to the end (up to {max})", elem.ty),
                Some(n) if *by_mask => {
                    format!("\\[{}\\], one per bit set in `{n}` (up to {max})", elem.ty)
                }
                Some(n) => format!("\\[{}\\], `{n}` of them (up to {max})", elem.ty),
            };
            KindDoc {
                order: elem.order,
                ..KindDoc::varying(ty)
            }
        }
        FieldKind::Check(c) => {
            let prefix = if c.prefix.is_empty() {
                String::new()
            } else {
                let bytes: Vec<String> = c.prefix.iter().map(|b| format!("{b:#04x}")).collect();
                format!(", after {}", bytes.join(" "))
            };
            KindDoc::of(
                format!("check `{}` over {}{prefix}", c.naming.display, c.covered),
                order_name(c.endian, f.size),
            )
        }
        FieldKind::Value { ty, count } => value_doc(p, ty, *count),
    }
}

/// A bit member as a field's docs name it: its bits, and whether it is signed or scaled.
fn member_name(m: &BitMember) -> String {
    let mut what = format!("bits {}..{}", m.shift, m.shift + m.width);
    if m.is_signed() {
        what.push_str(", signed");
    }
    if let Some(s) = &m.scale {
        what.push_str(&format!(", × {}", s.factor));
        if s.offset != 0.0 {
            what.push_str(&format!(" + {}", s.offset));
        }
    }
    if !m.unit.is_empty() {
        what.push_str(&format!(", {}", m.unit));
    }
    format!("`{}` ({what})", m.name)
}

/// The docs of a value field ([`FieldKind::Value`]), or of an array's element.
fn value_doc(p: &Protocol, ty: &ValueType, count: Option<usize>) -> KindDoc {
    let (base, order) = match ty {
        // An inverted bool says so: its type alone would read as the usual one.
        ValueType::Scalar {
            scalar,
            scale: None,
        } if scalar.prim == Prim::BoolInverted => ("bool, 0 is true".to_string(), "-"),
        ValueType::Scalar {
            scalar,
            scale: None,
        } => (
            scalar.prim.spec_name().to_string(),
            order_name(scalar.endian, scalar.prim.size()),
        ),
        ValueType::Scalar {
            scalar,
            scale: Some(s),
        } => {
            let off = if s.offset != 0.0 {
                format!(" + {}", s.offset)
            } else {
                String::new()
            };
            (
                format!("{} × {}{off}", scalar.prim.spec_name(), s.factor),
                order_name(scalar.endian, scalar.prim.size()),
            )
        }
        ValueType::Struct(i) => (format!("`{}`", p.structs[*i].name), "-"),
        ValueType::Enum(i, s) => (
            format!("`{}` ({})", p.enums[*i].name, s.prim.spec_name()),
            order_name(s.endian, s.prim.size()),
        ),
        ValueType::Text(n) => (format!("`char[{n}]` (NUL-padded text)"), "-"),
    };
    match count {
        Some(n) => KindDoc::of(format!("[{base}; {n}]"), order),
        None => KindDoc::of(base, order),
    }
}

/// `1 byte`, `n bytes`.
pub fn bytes(n: usize) -> String {
    if n == 1 {
        "1 byte".into()
    } else {
        format!("{n} bytes")
    }
}

/// `` `A` ``, `` `A` and `B` ``, `` `A`, `B` and `C` ``.
fn name_list(names: &[&str]) -> String {
    let quoted: Vec<String> = names.iter().map(|n| format!("`{n}`")).collect();
    match quoted.split_last() {
        None => String::new(),
        Some((last, [])) => last.clone(),
        Some((last, rest)) => format!("{} and {last}", rest.join(", ")),
    }
}

/// The first sentence of an undocumented struct's doc: what carries it.
fn struct_summary(p: &Protocol, s: &Struct) -> String {
    let index = p.structs.iter().position(|x| x.name == s.name);
    let carriers: Vec<&str> = p
        .commands
        .iter()
        .filter(|c| c.payloads.iter().any(|&x| x.is_some() && x == index))
        .map(|c| c.name.as_str())
        .collect();
    if !carriers.is_empty() {
        return format!("The payload of {}.", name_list(&carriers));
    }
    let holders: Vec<&str> = p
        .structs
        .iter()
        .filter(|outer| {
            outer.fields.iter().any(|f| match &f.kind {
                FieldKind::Value {
                    ty: ValueType::Struct(i),
                    ..
                }
                | FieldKind::Group { elem: i, .. } => Some(*i) == index,
                _ => false,
            })
        })
        .map(|outer| outer.name.as_str())
        .collect();
    if !holders.is_empty() {
        return format!("A part of {}.", name_list(&holders));
    }
    format!("`{}`, a struct of the spec.", s.name)
}

/// The doc of a struct: its spec text (or a summary saying what carries it) and a table of
/// its wire layout.
pub fn struct_doc(p: &Protocol, s: &Struct) -> String {
    let mut out = if s.doc.trim().is_empty() {
        struct_summary(p, s)
    } else {
        s.doc.clone()
    };
    out.push_str(&format!("\n\nWire layout, {}:\n\n| offset | size | field | type | byte order | unit |\n|---:|---:|---|---|---|---|\n", bytes(s.size)));
    // After a field of variable size, offsets count from its end (its largest size's end
    // would be a wrong offset for most payloads).
    let mut after: Option<(&str, usize)> = None;
    for f in &s.fields {
        let offset = match after {
            None => f.offset.to_string(),
            Some((name, end)) => format!("`{name}` end + {}", f.offset - end),
        };
        let doc = kind_doc(p, f, &f.kind);
        if doc.moves_offsets {
            after = Some((&f.name, f.offset + f.size));
        }
        let name = doc.name.unwrap_or_else(|| format!("`{}`", f.name));
        let unit = if f.unit.is_empty() {
            "-".to_string()
        } else {
            f.unit.clone()
        };
        out.push_str(&format!(
            "| {} | {} | {} | {} | {} | {} |\n",
            offset, f.size, name, doc.ty, doc.order, unit
        ));
    }
    for c in &s.carries {
        out.push_str(&format!(
            "\n`{}` carries a packet: the payload of the command whose id `{}` holds, in the direction of the frame around it.\n",
            s.fields[c.field].name, s.fields[c.key].name
        ));
    }
    out
}

/// The marker and the name of the length field that announce a frame's wider length.
fn wide_length_text(f: &Frame) -> (u64, &str) {
    let base = match f.length {
        crate::ir::Length::Field { value, .. } => f.values[value].name.as_str(),
        crate::ir::Length::Fixed(_) => "",
    };
    (f.length_extension.as_ref().map_or(0, |e| e.marker), base)
}

fn pos_text(pos: Pos) -> String {
    match pos {
        Pos::Start(n) => n.to_string(),
        Pos::End(n) => format!("end − {n}"),
    }
}

/// Text for a check's algorithm, with the per-command byte it folds in.
pub fn algorithm_text(c: &Check) -> String {
    let text = algorithm_name_text(c);
    match &c.extra {
        Some(_) => format!("{text}, then the command's `check_extra` byte"),
        None => text,
    }
}

fn algorithm_name_text(c: &Check) -> String {
    let n = &c.naming;
    macro_rules! crc {
        ($spec:expr) => {{
            let p = &$spec.params;
            if n.custom {
                format!(
                    "custom CRC `{}`: width {}, poly {:#x}, init {:#x}, refin {}, refout {}, xorout {:#x}, check {:#x}",
                    n.display, p.width, p.poly, p.init, p.refin, p.refout, p.xorout, p.check
                )
            } else {
                format!("{} (catalogue CRC, check {:#x})", n.display.to_uppercase(), p.check)
            }
        }};
    }
    let sum = |text: String| {
        if n.custom {
            format!("custom sum `{}`: {text}", n.display)
        } else {
            text
        }
    };
    match &c.algorithm {
        Algorithm::Sum8 => sum("sum of the bytes modulo 256".into()),
        Algorithm::SumMod255 => sum("sum of the bytes modulo 255".into()),
        Algorithm::Xor8 => "XOR of the bytes".into(),
        Algorithm::Sum {
            width,
            init,
            xorout,
        } => {
            let seed = match init {
                0 => String::new(),
                init => format!(" from {init:#x}"),
            };
            let modulus = 1u32 << (8 * u32::from(*width));
            match xorout {
                0 => sum(format!("sum of the bytes{seed} modulo {modulus}")),
                xorout => sum(format!(
                    "sum of the bytes{seed} modulo {modulus}, xored with {xorout:#x}"
                )),
            }
        }
        Algorithm::Xor { init } => sum(format!("XOR of the bytes from {init:#x}")),
        Algorithm::Fletcher16 => {
            "Fletcher-16: sums A (of the bytes) and B (of the As) modulo 255, stored as B << 8 | A"
                .into()
        }
        Algorithm::Fletcher16Mod256 => {
            "Fletcher sums A (of the bytes) and B (of the As) modulo 256, stored as B << 8 | A"
                .into()
        }
        Algorithm::Crc8(s) => crc!(s),
        Algorithm::Crc16(s) => crc!(s),
        Algorithm::Crc32(s) => crc!(s),
        Algorithm::Crc64(s) => crc!(s),
    }
}

/// The doc of the generated module: the spec's text, its version, the first frame format's
/// table, the command table and the RAM of each stream decoder.
pub fn module_doc(p: &Protocol) -> String {
    let mut doc = p.doc.clone();
    if !p.version.is_empty() {
        doc.push_str(&format!("\n\nSpec version: {}.", p.version));
    }
    if let Some(f) = p.frames.first() {
        doc.push_str("\n\n");
        doc.push_str(&frame_doc(f));
    }
    for d in &p.directions {
        if let Some(f) = &d.frame {
            doc.push_str(&format!(
                "\nAs {}s lay the `{}` frame format out (`{}`):\n\n",
                d.name, f.name, f.names.layout_static
            ));
            doc.push_str(&frame_doc(f));
        }
    }
    if !p.commands.is_empty() {
        doc.push('\n');
        doc.push_str(&commands_doc(p));
    }
    let serial: Vec<&Frame> = p
        .frames
        .iter()
        .filter(|f| f.transport == crate::ir::Transport::Serial)
        .collect();
    if !serial.is_empty() {
        doc.push_str("\nRAM of a stream decoder (it never uses the heap):\n\n");
        for f in serial {
            doc.push_str(&format!(
                "- [`{1}`]({0}::{1}): {2}\n",
                p.name,
                f.names.decoder,
                decoder_ram(f)
            ));
        }
    }
    doc
}

/// What a frame format's stream decoder takes in RAM, buffer and state, on a microcontroller
/// (32-bit pointers, as thumbv7em) and on a 64-bit host: the runtime's own sizing.
pub fn decoder_ram(f: &Frame) -> String {
    let mcu = protocol_runtime::decoder::decoder_ram(f.max_len(), 4);
    let host = protocol_runtime::decoder::decoder_ram(f.max_len(), 8);
    format!(
        "{} bytes on a 32-bit microcontroller (a buffer of {} and {} of state), {} on a 64-bit \
         host ({} and {}).",
        mcu.buffer + mcu.state,
        mcu.buffer,
        mcu.state,
        host.buffer + host.state,
        host.buffer,
        host.state
    )
}

/// The command table: id, name (a link to its `Command` variant), payload per direction and
/// the first line of the command's doc.
///
/// Links name the module: rustdoc resolves the outer doc of a module in its parent's scope.
fn commands_doc(p: &Protocol) -> String {
    let m = &p.name;
    // An empty direction (sorted last) carries no command's payload: no column.
    let dirs: Vec<&str> = p
        .directions
        .iter()
        .filter(|d| !d.empty)
        .map(|d| d.name.as_str())
        .collect();
    let payload_heads = if dirs.is_empty() {
        "payload".to_string()
    } else {
        dirs.join(" | ")
    };
    let columns = dirs.len().max(1);
    let mut out = format!(
        "| id | command | {payload_heads} | doc |\n|---|---|{}---|\n",
        "---|".repeat(columns)
    );
    for c in &p.commands {
        let ids: Vec<String> = c.id.iter().map(|v| format!("{v:#04x}")).collect();
        let payloads: Vec<String> = c
            .payloads
            .iter()
            .take(columns)
            .map(|x| {
                x.map_or("-".into(), |i| {
                    format!("[`{0}`]({m}::{0})", p.structs[i].name)
                })
            })
            .collect();
        let summary = c.doc.lines().next().unwrap_or("");
        let row = format!(
            "| {} | [`{}`]({m}::Command::{}) | {} | {summary}",
            ids.join(", "),
            c.name,
            c.rust_name,
            payloads.join(" | ")
        );
        out.push_str(row.trim_end());
        out.push_str(" |\n");
    }
    out
}

/// Bytes as code spans: `` `C8` `EA` ``.
fn hex_list(bytes: &[u8]) -> String {
    bytes
        .iter()
        .map(|x| format!("`{x:02X}`"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// The doc of a frame format: a table of its elements.
pub fn frame_doc(f: &Frame) -> String {
    let mut out = String::new();
    if !f.doc.is_empty() {
        out.push_str(&f.doc);
        out.push_str("\n\n");
    }
    out.push_str(&format!(
        "Frame `{}`: {} to {} bytes (header {}, payload {} to {}, trailer {}).\n\n| offset | size | element | type | meaning |\n|---|---:|---|---|---|\n",
        f.name,
        f.min_len(),
        f.max_len(),
        f.header_len,
        f.payload_min,
        f.payload_max,
        f.trailer_len
    ));
    for e in &f.elements {
        match e {
            crate::ir::Element::Sync(b) => out.push_str(&format!(
                "| 0 | {} | sync | bytes | {} |\n",
                b.len(),
                hex_list(b)
            )),
            crate::ir::Element::Word {
                name,
                at,
                scalar,
                values,
            } => {
                let offset = pos_text(*at);
                let meaning = values
                    .iter()
                    .map(|&i| {
                        let v = &f.values[i];
                        let bits = if v.width as usize == scalar.prim.size() * 8 {
                            String::new()
                        } else {
                            format!("bits {}..{} ", v.shift, v.shift + v.width)
                        };
                        let role = match &v.role {
                            Role::User { .. } if i == 0 && !f.sync_set.is_empty() => {
                                format!(": the sync, one of {}", hex_list(&f.sync_set))
                            }
                            Role::User { .. } => String::new(),
                            Role::Length => match &f.length {
                                crate::ir::Length::Field { adjust, .. } => {
                                    format!(": length, total frame = value + {adjust}")
                                }
                                crate::ir::Length::Fixed(_) => ": length".into(),
                            },
                            Role::Dispatch => ": command id".into(),
                            Role::Const(c) => format!(": always {c:#x}"),
                            Role::Ack(v) => format!(": {v} in acknowledgements"),
                            Role::Flag => {
                                let name = f.flag_trailer.as_ref().map_or("", |t| t.name.as_str());
                                format!(": set when `{name}` is present")
                            }
                            Role::WideLength => {
                                let (marker, base) = wide_length_text(f);
                                format!(": the length, present when `{base}` is {marker}")
                            }
                        };
                        format!("{bits}`{}`{role}", v.name)
                    })
                    .collect::<Vec<_>>()
                    .join("; ");
                out.push_str(&format!(
                    "| {offset} | {} | `{name}` | {} {} | {meaning} |\n",
                    scalar.prim.size(),
                    scalar.prim.spec_name(),
                    order_name(scalar.endian, scalar.prim.size())
                ));
            }
            crate::ir::Element::Payload => out.push_str(&format!(
                "| {} | {}..={} | payload | bytes | the command's struct |\n",
                f.header_len, f.payload_min, f.payload_max
            )),
            crate::ir::Element::Check(i) => {
                let c = &f.checks[*i];
                out.push_str(&format!(
                    "| {} | {} | `{}` | check | {} over bytes {} .. {} |\n",
                    pos_text(c.at),
                    c.size,
                    c.name,
                    algorithm_text(c),
                    pos_text(c.from),
                    pos_text(c.to)
                ));
            }
            crate::ir::Element::Trailer(i) => {
                let t = &f.trailers[*i];
                out.push_str(&format!(
                    "| {} | {} | `{}` | bytes | {} |\n",
                    pos_text(t.at),
                    t.bytes.len(),
                    t.name,
                    t.bytes
                        .iter()
                        .map(|x| format!("`{x:02X}`"))
                        .collect::<Vec<_>>()
                        .join(" ")
                ));
            }
            crate::ir::Element::FlagTrailer => {
                if let Some(t) = &f.flag_trailer {
                    let flag = &f.values[t.flag].name;
                    out.push_str(&format!(
                        "| end | {} | `{}` | bytes | present when `{flag}` is set, after everything else; carried, not verified |\n",
                        t.len, t.name
                    ));
                }
            }
        }
    }
    out
}
