//! The report's "Signals" section: the chosen series as JSON in the page, with a panel per unit,
//! the notes a reader needs (what the axis is, what was decimated or left out), and the
//! plotter (`plot.js`, `plot.css`: canvas drawing, zoom and hover, no third-party code).

use std::fmt::Write as _;

use serde_json::{Value, json};

use super::{BUCKETS, DEFAULT_SERIES, MAX_SERIES, Plot};
use crate::report::esc;

/// The plotter: reads the page's JSON, draws one canvas per panel.
const SCRIPT: &str = include_str!("plot.js");
/// The plotter's style.
pub const STYLE: &str = include_str!("plot.css");

/// Series colours, distinct on white and from each other (the page's colour of series `i` is
/// `COLOURS[i % len]`).
pub const COLOURS: [&str; 8] = [
    "#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf",
];

/// The JSON the plotter draws: panels (one per unit, in order of first series) and series.
pub fn data(plot: &Plot) -> Value {
    let mut units: Vec<&str> = Vec::new();
    let series: Vec<Value> = plot
        .series
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let panel = units.iter().position(|u| *u == s.unit).unwrap_or_else(|| {
                units.push(&s.unit);
                units.len() - 1
            });
            json!({
                "name": s.name,
                "unit": s.unit,
                "color": COLOURS[i % COLOURS.len()],
                "panel": panel,
                "samples": s.samples,
                "x": s.points.iter().map(|p| p.0).collect::<Vec<_>>(),
                "y": s.points.iter().map(|p| p.1).collect::<Vec<_>>(),
            })
        })
        .collect();
    json!({
        "axis": "frame index",
        "panels": units.iter().map(|u| json!({"unit": u})).collect::<Vec<_>>(),
        "series": series,
    })
}

/// Writes the section: heading, notes, the panels' container, the data and the plotter. The
/// page opened at `#signals-section` shows this section alone (`plot.css`), for a link or a
/// screenshot of the signals.
pub fn write(plot: &Plot, out: &mut String) {
    out.push_str("<section id=\"signals-section\"><h2>Signals</h2>");
    if plot.series.is_empty() {
        let why = if plot.default {
            "No field of the capture's commands has a scale or a unit, so none is plotted by default."
        } else {
            "No frame of the capture carries the fields given to <code>--plot</code>."
        };
        let _ = write!(
            out,
            "<p class=\"note\" id=\"signals-none\">{why} Choose fields with <code>protocol report --plot COMMAND.payload.FIELD,...</code>.</p></section>"
        );
        return;
    }
    let how = if plot.default {
        "The scaled fields (with a scale or a unit) of the most frequent commands; choose others with <code>--plot</code>."
    } else {
        "The fields given to <code>--plot</code>."
    };
    let _ = write!(
        out,
        "<p>{how} One panel per unit, over the frame index (a file of raw bytes has no receive times). Drag across a panel or turn the wheel to zoom, double-click or <i>Reset zoom</i> to see it all; hover for the nearest value.</p>"
    );
    let decimated: Vec<String> = plot
        .series
        .iter()
        .filter(|s| s.decimated())
        .map(|s| format!("{} ({} values)", esc(&s.name), s.samples))
        .collect();
    if !decimated.is_empty() {
        let _ = write!(
            out,
            "<p class=\"note\" id=\"decimated\">Decimated: {}. Each series shows the smallest and the largest value of each of {BUCKETS} equal stretches of the capture, and the plot draws the smallest and largest of each pixel column, so that spikes stay visible at any zoom.</p>",
            decimated.join(", ")
        );
    }
    let bound = if plot.default {
        format!("at most {DEFAULT_SERIES} series by default")
    } else {
        format!("at most {MAX_SERIES} series")
    };
    for (what, names) in [
        (format!("Not plotted ({bound})"), &plot.left_out),
        ("No frame of the capture carries".to_string(), &plot.absent),
    ] {
        if !names.is_empty() {
            let mut list: Vec<String> = names.iter().take(12).map(|n| esc(n)).collect();
            if names.len() > 12 {
                list.push(format!("and {} more", names.len() - 12));
            }
            let _ = write!(out, "<p class=\"note\">{what}: {}.</p>", list.join(", "));
        }
    }
    // `<` is escaped inside the JSON so that no `</script>` can end the element early.
    let json = data(plot).to_string().replace('<', "\\u003c");
    let _ = write!(
        out,
        "<div id=\"signals\"><div class=\"plot-bar\"><button type=\"button\" id=\"plot-reset\">Reset zoom</button><span id=\"plot-range\"></span></div><div id=\"plot-panels\"></div><div id=\"plot-tip\"></div><ul id=\"plot-errors\"></ul></div><script type=\"application/json\" id=\"signal-data\">{json}</script><script>{SCRIPT}</script></section>"
    );
}
