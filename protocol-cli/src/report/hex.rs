//! The hex view of the report: the first [`HEX_VIEW_MAX`] bytes of the capture, every item a
//! block, a frame's fields outlined with their names and values.

use std::fmt::Write as _;

use super::{Entry, HEX_VIEW_MAX, esc};
use crate::session::reject_name;

fn hex_bytes(data: &[u8], from: usize, to: usize, out: &mut String) {
    for b in data.get(from..to).unwrap_or_default() {
        let _ = write!(out, "<i>{b:02x}</i>");
    }
}

/// The hex view: every entry a block; a frame's spans outlined, with their name and value.
pub(super) fn hex_view(data: &[u8], entries: &[Entry], out: &mut String) {
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
