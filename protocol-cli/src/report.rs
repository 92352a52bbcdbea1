//! `protocol report`: one self-contained HTML page about a capture (no network: inline CSS,
//! SVG and script). Link statistics, frames per command, the signals (drawn by
//! [`crate::signals`]), link quality per window of offsets (bad checks, other rejections,
//! skipped bytes) as an SVG chart, and a hex view in which every frame's fields are outlined
//! and named on hover, errors highlighted.
//!
//! This module decodes and renders; reading the files is the command's.

use std::fmt::Write as _;

use protocol_dynamic::{Codec, DecodeIssue, Decoded, Item, Value};
use protocol_runtime::{FrameLayout, Reject, Stats};
use protocol_spec::ir::{Element, FieldKind, Frame, Pos, Protocol};

use crate::counter::Counters;
use crate::session::reject_name;

/// Bytes of the capture the hex view shows at most (the statistics cover all of it).
pub const HEX_VIEW_MAX: usize = 64 * 1024;
/// Windows of the link-quality chart.
const WINDOWS: usize = 60;

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
    entries: Vec<Entry>,
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
        entries: Vec::new(),
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
                    (name, None, spans(p, frame, &layout, bytes, Some(d)))
                }
                Err(e) => {
                    c.undecoded += 1;
                    (
                        None,
                        Some(issue_text(e)),
                        spans(p, frame, &layout, bytes, None),
                    )
                }
            };
            c.entries.push(Entry::Frame {
                offset: offset as usize,
                len: bytes.len(),
                command,
                issue,
                spans,
            });
        }
        Item::Rejected { offset, reason } => c.entries.push(Entry::Rejected {
            offset: offset as usize,
            reason,
        }),
        Item::Skipped { offset, len } => c.entries.push(Entry::Skipped {
            offset: offset as usize,
            len,
        }),
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
    let hex_of = |from: usize, to: usize| {
        bytes
            .get(from..to)
            .map(protocol_dynamic::hex)
            .unwrap_or_default()
    };
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
                let fields = decoded.and_then(|d| {
                    let s = match d.command {
                        Some(ci) => (*p.commands[ci].payloads.get(d.direction.unwrap_or(0))?)?,
                        None => carried(p, d)?,
                    };
                    Some((&p.structs[s], &d.payload))
                });
                match fields {
                    Some((s, payload)) if !s.fields.is_empty() => {
                        let last = s.fields.len() - 1;
                        for (i, field) in s.fields.iter().enumerate() {
                            let from = start + field.offset;
                            let to = if i == last {
                                end
                            } else {
                                (from + field.size).min(end)
                            };
                            let (name, value) = match (&field.kind, payload) {
                                (FieldKind::Padding, _) => ("padding".into(), hex_of(from, to)),
                                (
                                    FieldKind::Bits { members, .. }
                                    | FieldKind::BitStream { members },
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
                                _ => (field.name.clone(), hex_of(from, to)),
                            };
                            push(from, to, name, value);
                        }
                    }
                    _ => push(start, end, "payload".into(), hex_of(start, end)),
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

/// Per window of offsets: (bad checks, other rejections, skipped bytes).
fn windows(entries: &[Entry], total: usize) -> (usize, Vec<[u64; 3]>) {
    let size = total.div_ceil(WINDOWS).max(1);
    let mut w = vec![[0u64; 3]; total.div_ceil(size).max(1)];
    let last = w.len() - 1;
    for e in entries {
        match e {
            Entry::Rejected { offset, reason } => {
                let k = usize::from(!matches!(
                    reason,
                    Reject::BadChecksum | Reject::BadHeaderCheck
                ));
                w[(offset / size).min(last)][k] += 1;
            }
            Entry::Skipped { offset, len } => {
                // A run of skipped bytes may cross windows: each gets its share.
                let (mut at, end) = (*offset, offset + len);
                while at < end {
                    let i = (at / size).min(last);
                    let stop = ((i + 1) * size).min(end).max(at + 1);
                    w[i][2] += (stop - at) as u64;
                    at = stop;
                }
            }
            Entry::Frame { .. } => {}
        }
    }
    (size, w)
}

/// The link-quality chart: per window, bars of bad checks, other rejections and skipped bytes
/// (each series scaled to its own maximum, labelled with it).
fn chart(entries: &[Entry], total: usize, out: &mut String) {
    let (size, w) = windows(entries, total);
    let (width, row, gap) = (900.0, 60.0, 18.0);
    let names = ["bad checks", "other rejections", "skipped bytes"];
    let classes = ["check", "reject", "skip"];
    let height = 3.0 * (row + gap) + 20.0;
    let bar = width / w.len() as f64;
    let _ = write!(
        out,
        "<svg id=\"quality\" xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {} {height}\" role=\"img\" aria-label=\"link quality per window of {size} bytes\">",
        width + 160.0
    );
    for (k, name) in names.iter().enumerate() {
        let max = w.iter().map(|x| x[k]).max().unwrap_or(0).max(1);
        let top = k as f64 * (row + gap) + gap;
        let _ = write!(
            out,
            "<text x=\"{}\" y=\"{}\" class=\"label\">{name} (max {max})</text><line x1=\"0\" x2=\"{width}\" y1=\"{}\" y2=\"{}\" class=\"axis\"/>",
            width + 8.0,
            top + row / 2.0,
            top + row,
            top + row
        );
        for (i, x) in w.iter().enumerate() {
            if x[k] == 0 {
                continue;
            }
            let h = row * x[k] as f64 / max as f64;
            let _ = write!(
                out,
                "<rect class=\"bar {}\" data-window=\"{i}\" data-offset=\"{}\" x=\"{:.1}\" y=\"{:.1}\" width=\"{:.1}\" height=\"{h:.1}\"><title>offsets {}..{}: {} {name}</title></rect>",
                classes[k],
                i * size,
                i as f64 * bar,
                top + row - h,
                (bar - 1.0).max(1.0),
                i * size,
                ((i + 1) * size).min(total),
                x[k]
            );
        }
    }
    let _ = write!(
        out,
        "<text x=\"0\" y=\"{}\" class=\"label\">offset 0</text><text x=\"{width}\" y=\"{}\" class=\"label\" text-anchor=\"end\">{total}</text></svg>",
        height - 2.0,
        height - 2.0
    );
}

fn hex_bytes(data: &[u8], from: usize, to: usize, out: &mut String) {
    for b in data.get(from..to).unwrap_or_default() {
        let _ = write!(out, "<i>{b:02x}</i>");
    }
}

/// The hex view: every entry a block; a frame's spans outlined, with their name and value.
fn hex_view(data: &[u8], entries: &[Entry], out: &mut String) {
    out.push_str("<div id=\"hex\">");
    for e in entries {
        let start = match e {
            Entry::Frame { offset, .. }
            | Entry::Rejected { offset, .. }
            | Entry::Skipped { offset, .. } => *offset,
        };
        if start >= HEX_VIEW_MAX {
            break;
        }
        match e {
            Entry::Frame {
                offset,
                len,
                command,
                issue,
                spans,
            } => {
                let label = command.clone().unwrap_or_else(|| "(no command)".into());
                let class = if issue.is_some() {
                    "frame bad"
                } else {
                    "frame"
                };
                let _ = write!(
                    out,
                    "<div class=\"{class}\" id=\"at{offset}\" data-offset=\"{offset}\" data-command=\"{}\" title=\"{}\"><b>{offset}</b><span class=\"cmd\">{}</span>",
                    esc(&label),
                    esc(issue.as_deref().unwrap_or(&label)),
                    esc(&label)
                );
                let mut at = 0;
                for s in spans {
                    if s.from > at {
                        hex_bytes(data, offset + at, offset + s.from, out);
                    }
                    let _ = write!(
                        out,
                        "<span class=\"field\" data-name=\"{}\" data-value=\"{}\" title=\"{}: {}\">",
                        esc(&s.name),
                        esc(&s.value),
                        esc(&s.name),
                        esc(&s.value)
                    );
                    hex_bytes(data, offset + s.from, offset + s.to, out);
                    out.push_str("</span>");
                    at = s.to;
                }
                hex_bytes(data, offset + at, offset + len, out);
                out.push_str("</div>");
            }
            Entry::Rejected { offset, reason } => {
                let _ = write!(
                    out,
                    "<div class=\"rejected\" id=\"at{offset}\" data-offset=\"{offset}\" title=\"{}: a candidate frame rejected; the search resumes at the next byte\"><b>{offset}</b><span class=\"cmd\">{}</span>",
                    reject_name(*reason),
                    reject_name(*reason)
                );
                hex_bytes(data, *offset, offset + 1, out);
                out.push_str("</div>");
            }
            Entry::Skipped { offset, len } => {
                let _ = write!(
                    out,
                    "<div class=\"skipped\" id=\"at{offset}\" data-offset=\"{offset}\" title=\"{len} bytes in no frame\"><b>{offset}</b><span class=\"cmd\">skipped</span>"
                );
                hex_bytes(data, *offset, offset + len, out);
                out.push_str("</div>");
            }
        }
    }
    if data.len() > HEX_VIEW_MAX {
        let _ = write!(
            out,
            "<p class=\"note\">The hex view ends at offset {HEX_VIEW_MAX}; the statistics and the chart cover all {} bytes.</p>",
            data.len()
        );
    }
    out.push_str("</div>");
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
    let frames = capture
        .entries
        .iter()
        .filter(|e| matches!(e, Entry::Frame { .. }))
        .count();
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
    chart(&capture.entries, data.len(), &mut out);
    out.push_str("<h2>Bytes</h2><p>Every frame's fields are outlined; hover one for its name and value. Rejected candidates are red, skipped bytes grey, frames without a message of the spec orange. A click on a bar of the chart scrolls here.</p>");
    hex_view(data, &capture.entries, &mut out);
    let _ = writeln!(
        out,
        "<div id=\"tip\"></div><script>{SCRIPT}</script></body></html>"
    );
    Some(out)
}
