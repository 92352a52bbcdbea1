//! `protocol report`: one self-contained HTML page about a capture (no network: inline CSS,
//! SVG and script). Link statistics, frames per command, the signals (drawn by
//! [`crate::signals`]), link quality per window of offsets (bad checks, other rejections,
//! skipped bytes) as an SVG chart (`chart`), and a hex view (`hex`) in which every frame's
//! fields are outlined and named on hover, errors highlighted.
//!
//! This module decodes and renders; reading the files is the command's. What the page keeps of
//! a capture is bounded: counters for the whole of it, items for the bytes the hex view shows.

mod chart;
mod hex;
#[cfg(test)]
mod tests;

use std::fmt::Write as _;

use protocol_dynamic::{Codec, DecodeIssue, Decoded, Item, Value};
use protocol_runtime::{FrameLayout, Reject, Stats};
use protocol_spec::ir::{Element, FieldKind, Frame, Pos, Protocol};

use crate::counter::Counters;
use chart::Windows;

/// Bytes of the capture the hex view shows at most (the statistics cover all of it).
pub const HEX_VIEW_MAX: usize = 64 * 1024;

/// A named byte range inside a frame, for the hex view.
struct Span {
    from: usize,
    to: usize,
    name: String,
    value: String,
}

/// One item of the capture, as the page shows it.
enum Entry {
    Frame {
        offset: usize,
        len: usize,
        command: Option<String>,
        issue: Option<String>,
        spans: Vec<Span>,
    },
    Rejected {
        offset: usize,
        reason: Reject,
    },
    Skipped {
        offset: usize,
        len: usize,
    },
}

/// What the page reports, decoded once.
struct Capture {
    /// The items the hex view shows (those that start before [`HEX_VIEW_MAX`]).
    shown: Vec<Entry>,
    /// Frames accepted in the whole capture.
    frames: usize,
    windows: Windows,
    stats: Stats,
    per_command: Vec<(usize, usize)>,
    undecoded: usize,
    counters: Counters,
}

fn decode(codec: &Codec<'_>, format: usize, data: &[u8]) -> Option<Capture> {
    let p = codec.protocol();
    let frame = p.frames.get(format)?;
    let layout = codec.layout(format)?;
    let mut stream = codec.stream(format)?;
    let mut capture = Capture {
        shown: Vec::new(),
        frames: 0,
        windows: Windows::new(data.len()),
        stats: Stats::default(),
        per_command: vec![(0, 0); p.commands.len()],
        undecoded: 0,
        counters: Counters::default(),
    };
    let mut input = data;
    let take = |item: Item<'_>, c: &mut Capture| match item {
        Item::Frame {
            offset,
            bytes,
            decoded,
        } => {
            c.frames += 1;
            let offset = offset as usize;
            let shown = offset < HEX_VIEW_MAX;
            // The hex view names the fields of the frames it shows; the others are counted.
            let spans_of = |d| {
                if shown {
                    spans(p, frame, &layout, bytes, d)
                } else {
                    Vec::new()
                }
            };
            let (command, issue, spans) = match &decoded {
                Ok(d) => {
                    c.counters.observe(p, d);
                    if let Some((n, b)) = d.command.and_then(|i| c.per_command.get_mut(i)) {
                        *n += 1;
                        *b += bytes.len();
                    }
                    // A frame without a command is labelled by the struct it carries (a
                    // status packet of a direction given to the decoder), as `decode` shows it.
                    let name = match d.command {
                        Some(i) => Some(p.commands[i].name.clone()),
                        None => carried(p, d).map(|si| format!("({})", p.structs[si].name)),
                    };
                    (name, None, spans_of(Some(d)))
                }
                Err(e) => {
                    c.undecoded += 1;
                    (None, Some(issue_text(e)), spans_of(None))
                }
            };
            if shown {
                c.shown.push(Entry::Frame {
                    offset,
                    len: bytes.len(),
                    command,
                    issue,
                    spans,
                });
            }
        }
        Item::Rejected { offset, reason } => {
            let offset = offset as usize;
            c.windows.rejected(offset, reason);
            if offset < HEX_VIEW_MAX {
                c.shown.push(Entry::Rejected { offset, reason });
            }
        }
        Item::Skipped { offset, len } => {
            let offset = offset as usize;
            c.windows.skipped(offset, len);
            if offset < HEX_VIEW_MAX {
                c.shown.push(Entry::Skipped { offset, len });
            }
        }
    };
    while let Some(item) = stream.next_item(&mut input) {
        take(item, &mut capture);
    }
    while let Some(item) = stream.flush_item() {
        take(item, &mut capture);
    }
    capture.stats = *stream.stats();
    Some(capture)
}

fn issue_text(e: &DecodeIssue) -> String {
    e.to_string()
}

fn resolve(pos: Pos, len: usize) -> usize {
    match pos {
        Pos::Start(n) => n,
        Pos::End(n) => len.saturating_sub(n),
    }
}

fn value_text(v: &Value) -> String {
    serde_json::to_string(v).unwrap_or_default()
}

/// The struct a frame without a command carries: its direction's message (a status packet), or
/// its format's.
fn carried(p: &Protocol, d: &Decoded) -> Option<usize> {
    if d.command.is_some() || d.ack {
        return None;
    }
    d.direction
        .and_then(|di| p.directions.get(di))
        .and_then(|x| x.message)
        .map(|(si, _)| si)
        .or(p.frames.get(d.format)?.message)
}

/// The named byte ranges of a frame: header elements, payload fields, checks, trailers.
fn spans(
    p: &Protocol,
    f: &Frame,
    layout: &FrameLayout<'_>,
    bytes: &[u8],
    decoded: Option<&Decoded>,
) -> Vec<Span> {
    // Checks and trailers sit back from the end of the frame without its flag trailer.
    let flagged = layout.flag_trailer_len(bytes);
    let len = bytes.len() - flagged.min(bytes.len());
    let header_len = f.header_len + layout.extension_len(bytes);
    let hex_of = |from: usize, to: usize| hex_of(bytes, from, to);
    let mut out = Vec::new();
    let mut push = |from: usize, to: usize, name: String, value: String| {
        if from < to && to <= len {
            out.push(Span {
                from,
                to,
                name,
                value,
            });
        }
    };
    for e in &f.elements {
        match e {
            Element::Sync(s) => push(0, s.len(), "sync".into(), hex_of(0, s.len())),
            Element::Word {
                name, at, scalar, ..
            } => {
                let from = resolve(*at, len);
                let to = from + scalar.prim.size();
                let value = decoded
                    .and_then(|d| d.header.get(name))
                    .map_or_else(|| hex_of(from, to), value_text);
                push(from, to, name.clone(), value);
            }
            Element::Payload => {
                let (start, end) = (header_len, len.saturating_sub(f.trailer_len));
                for (from, to, name, value) in payload_spans(p, decoded, bytes, start, end) {
                    push(from, to, name, value);
                }
            }
            Element::Check(i) => {
                let c = &f.checks[*i];
                let from = resolve(c.at, len);
                push(
                    from,
                    from + c.size,
                    c.name.clone(),
                    hex_of(from, from + c.size),
                );
            }
            Element::Trailer(i) => {
                let t = &f.trailers[*i];
                let from = resolve(t.at, len);
                push(
                    from,
                    from + t.bytes.len(),
                    t.name.clone(),
                    hex_of(from, from + t.bytes.len()),
                );
            }
            Element::FlagTrailer => {
                if let Some(t) = f.flag_trailer.as_ref().filter(|_| flagged > 0) {
                    push(
                        len,
                        len + flagged,
                        t.name.clone(),
                        hex_of(len, len + flagged),
                    );
                }
            }
        }
    }
    out.sort_by_key(|s| s.from);
    out
}

/// The bytes `from..to` of `bytes` in hex (empty where they lie outside).
fn hex_of(bytes: &[u8], from: usize, to: usize) -> String {
    bytes
        .get(from..to)
        .map(protocol_dynamic::hex)
        .unwrap_or_default()
}

/// The payload's spans, `start..end` of the frame: one per field of the struct the frame
/// carries (bit members together, the last field to the end), or the payload whole when it
/// was not decoded.
fn payload_spans(
    p: &Protocol,
    decoded: Option<&Decoded>,
    bytes: &[u8],
    start: usize,
    end: usize,
) -> Vec<(usize, usize, String, String)> {
    let fields = decoded.and_then(|d| {
        let s = match d.command {
            Some(ci) => (*p.commands[ci].payloads.get(d.direction.unwrap_or(0))?)?,
            None => carried(p, d)?,
        };
        Some((&p.structs[s], &d.payload))
    });
    let Some((s, payload)) = fields.filter(|(s, _)| !s.fields.is_empty()) else {
        return vec![(start, end, "payload".into(), hex_of(bytes, start, end))];
    };
    let last = s.fields.len() - 1;
    let mut out = Vec::with_capacity(s.fields.len());
    for (i, field) in s.fields.iter().enumerate() {
        let from = start + field.offset;
        let to = if i == last {
            end
        } else {
            (from + field.size).min(end)
        };
        let (name, value) = match (&field.kind, payload) {
            (FieldKind::Padding, _) => ("padding".into(), hex_of(bytes, from, to)),
            (
                FieldKind::Bits { members, .. } | FieldKind::BitStream { members },
                Value::Struct(v),
            ) => (
                members
                    .iter()
                    .map(|m| m.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", "),
                members
                    .iter()
                    .map(|m| {
                        let x = v.get(&m.name).map(value_text);
                        format!("{}={}", m.name, x.unwrap_or_default())
                    })
                    .collect::<Vec<_>>()
                    .join(" "),
            ),
            (_, Value::Struct(v)) => (
                field.name.clone(),
                v.get(&field.name).map(value_text).unwrap_or_default(),
            ),
            _ => (field.name.clone(), hex_of(bytes, from, to)),
        };
        out.push((from, to, name, value));
    }
    out
}

/// Escapes text for HTML content and attribute values.
pub(crate) fn esc(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

fn percent(n: u64, total: u64) -> String {
    if total == 0 {
        "0.0%".into()
    } else {
        format!("{:.1}%", n as f64 * 100.0 / total as f64)
    }
}

const STYLE: &str = "body{font:14px/1.4 system-ui,sans-serif;margin:24px;color:#222}\
h1{font-size:20px}h2{font-size:16px;margin-top:28px}\
table{border-collapse:collapse}td,th{padding:2px 10px;border-bottom:1px solid #ddd;text-align:left}\
td.n{text-align:right;font-variant-numeric:tabular-nums}\
#quality{width:100%;max-width:1060px;height:auto}.axis{stroke:#999}.label{font-size:12px;fill:#444}\
.bar.check{fill:#d62728}.bar.reject{fill:#ff7f0e}.bar.skip{fill:#7f7f7f}.bar{cursor:pointer}\
#hex{font:12px/1.9 ui-monospace,monospace}#hex>div{display:block;margin:1px 0;padding:0 4px}\
#hex b{display:inline-block;width:64px;color:#888;font-weight:normal}\
#hex .cmd{display:inline-block;width:190px;color:#333}\
#hex i{font-style:normal;padding:0 2px}\
.field{outline:1px solid #1f77b4;border-radius:3px;margin:0 2px;background:#eef5fb}\
.field:hover{background:#1f77b4;color:#fff}\
.frame.bad{background:#fff1df}.rejected{background:#fde0e0;color:#a00}.skipped{color:#888;background:#f2f2f2}\
#tip{position:fixed;right:16px;bottom:16px;background:#222;color:#fff;padding:6px 10px;border-radius:4px;font:12px monospace;display:none}";

const SCRIPT: &str = "document.body.dataset.ready='1';var tip=document.getElementById('tip');\
document.getElementById('hex').addEventListener('mouseover',function(e){var f=e.target.closest('.field');\
if(!f){tip.style.display='none';return;}var fr=f.closest('.frame');\
tip.textContent=(fr?fr.dataset.command+' @'+fr.dataset.offset+': ':'')+f.dataset.name+' = '+f.dataset.value;tip.style.display='block';});\
document.getElementById('quality').addEventListener('click',function(e){var r=e.target.closest('rect');if(!r)return;\
var at=+r.dataset.offset,best=null;document.querySelectorAll('#hex>div').forEach(function(d){if(+d.dataset.offset<=at)best=d;});\
if(best)best.scrollIntoView({block:'center'});});";

/// The whole page for `data` decoded with frame format `format` of `codec`'s spec, with the
/// signals of `plot`; `name` titles it. `None` when the codec has no such format.
pub fn render(
    codec: &Codec<'_>,
    format: usize,
    data: &[u8],
    name: &str,
    plot: &crate::signals::Plot,
) -> Option<String> {
    let p = codec.protocol();
    let capture = decode(codec, format, data)?;
    let s = &capture.stats;
    let total = data.len() as u64;
    let frames = capture.frames;
    let mut out = String::new();
    let title = format!("{name}: {} capture", p.name);
    let _ = write!(
        out,
        "<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>{}</title><style>{STYLE}{}</style></head><body><h1>{}</h1>",
        esc(&title),
        crate::signals::section::STYLE,
        esc(&title)
    );
    let rejected = s.bad_checksum
        + s.bad_header_check
        + s.bad_length
        + s.bad_header
        + s.bad_trailer
        + s.truncated;
    let mut rows = vec![
        ("bytes", total.to_string()),
        (
            "frames accepted (framing and checks)",
            format!(
                "{frames} ({} bytes, {})",
                s.frame_bytes,
                percent(s.frame_bytes, total)
            ),
        ),
        (
            "of them without a message of the spec",
            capture.undecoded.to_string(),
        ),
        (
            "checksum failures",
            format!(
                "{} (frame checks {}, header checks {})",
                s.bad_checksum + s.bad_header_check,
                s.bad_checksum,
                s.bad_header_check
            ),
        ),
        ("length rejections", s.bad_length.to_string()),
        (
            "other rejections",
            format!(
                "bad header {}, bad trailer {}, truncated {}",
                s.bad_header, s.bad_trailer, s.truncated
            ),
        ),
        (
            "bytes skipped",
            format!(
                "{} ({}): {} in skipped runs, {rejected} the first bytes of rejected candidates",
                s.skipped_bytes,
                percent(s.skipped_bytes, total),
                s.skipped_bytes.saturating_sub(rejected)
            ),
        ),
    ];
    if let Some(counters) = capture.counters.summary() {
        rows.push(("frame counter", counters));
    }
    out.push_str("<h2>Link statistics</h2><table id=\"stats\">");
    for (k, v) in rows {
        let _ = write!(out, "<tr><th>{k}</th><td>{}</td></tr>", esc(&v));
    }
    out.push_str("</table><h2>Frames per command</h2><table id=\"commands\"><tr><th>command</th><th>frames</th><th>bytes</th></tr>");
    for (c, (n, b)) in p.commands.iter().zip(&capture.per_command) {
        if *n > 0 {
            let _ = write!(
                out,
                "<tr data-command=\"{}\"><td>{}</td><td class=\"n\">{n}</td><td class=\"n\">{b}</td></tr>",
                esc(&c.name),
                esc(&c.name)
            );
        }
    }
    out.push_str("</table>");
    crate::signals::section::write(plot, &mut out);
    out.push_str("<h2>Link quality over the capture</h2>");
    chart::chart(&capture.windows, &mut out);
    out.push_str("<h2>Bytes</h2><p>Every frame's fields are outlined; hover one for its name and value. Rejected candidates are red, skipped bytes grey, frames without a message of the spec orange. A click on a bar of the chart scrolls here.</p>");
    hex::hex_view(data, &capture.shown, &mut out);
    let _ = writeln!(
        out,
        "<div id=\"tip\"></div><script>{SCRIPT}</script></body></html>"
    );
    Some(out)
}
