//! Signals: the numeric values of a capture's decoded frames as series over the capture, for the
//! report's plots. Series are chosen by name ([`names`]: `--plot`) or by default (the scaled
//! fields, those with a scale or a unit, of the most frequent commands), and decimated to a
//! bounded number of points per series (the minimum and the maximum of each of
//! [`BUCKETS`] equal stretches of the capture), so that a large capture gives a page of
//! bounded size. [`section`] writes the page's part; the plotter itself is `plot.js`.
//!
//! The frames come from [`crate::export::decode_capture`], so a series holds exactly the
//! values `protocol decode --format json` prints. Their position is the frame's index among
//! the capture's frames: a file of raw bytes has no receive times.

pub mod names;
pub mod section;

use crate::export::Record;
use crate::export::csv::flatten;
use names::{Catalogue, Kind, Refusal, Selector};

/// Series plotted without `--plot`, at most.
pub const DEFAULT_SERIES: usize = 6;
/// Series plotted with `--plot`, at most (a path without an index may name many elements).
pub const MAX_SERIES: usize = 24;
/// Stretches of the capture a long series is decimated into: two points (its minimum and its
/// maximum) each.
pub const BUCKETS: usize = 1500;

/// One plotted value over the capture.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// `COMMAND.payload.x`: the key of its frames and the column.
    pub name: String,
    /// The spec's unit (empty when none).
    pub unit: String,
    /// (frame index, value), in capture order; decimated when `samples` exceeds its length.
    pub points: Vec<(u64, f64)>,
    /// Values in the capture.
    pub samples: usize,
}

impl Series {
    /// Whether the series shows fewer points than the capture has values.
    pub fn decimated(&self) -> bool {
        self.samples > self.points.len()
    }
}

/// What was chosen to plot, and what was left out.
#[derive(Debug, Clone, Default)]
pub struct Plot {
    /// The series, in the order chosen.
    pub series: Vec<Series>,
    /// Series that matched but were not plotted (beyond the bound).
    pub left_out: Vec<String>,
    /// Names given that no frame of the capture carries.
    pub absent: Vec<String>,
    /// Whether the series are the default choice.
    pub default: bool,
}

/// A name of `--plot` that selects nothing: its place in the argument and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BadName {
    /// Byte range of the name in the joined `--plot` argument.
    pub at: std::ops::Range<usize>,
    /// The name.
    pub name: String,
    /// Why.
    pub refusal: Refusal,
}

/// Reads `--plot`'s names (comma-separated; the argument may be given several times, joined
/// with commas) against the spec's columns.
///
/// # Errors
/// Every name that selects nothing, with its place in `arg`.
pub fn parse(cat: &Catalogue, arg: &str) -> Result<Vec<(String, Selector)>, Vec<BadName>> {
    let mut ok = Vec::new();
    let mut bad = Vec::new();
    let mut at = 0;
    for part in arg.split(',') {
        let name = part.trim();
        let start = at + (part.len() - part.trim_start().len());
        at += part.len() + 1;
        if name.is_empty() {
            continue;
        }
        match names::select(cat, name) {
            Ok(s) => ok.push((name.to_string(), s)),
            Err(refusal) => bad.push(BadName {
                at: start..start + name.len(),
                name: name.to_string(),
                refusal,
            }),
        }
    }
    if bad.is_empty() { Ok(ok) } else { Err(bad) }
}

/// The series of `records` that `chosen` selects (in the order of the names, then of the
/// columns' first appearance), or by default the scaled columns of the most frequent keys.
pub fn pick(cat: &Catalogue, records: &[Record], chosen: Option<&[(String, Selector)]>) -> Plot {
    let mut plot = Plot {
        default: chosen.is_none(),
        ..Plot::default()
    };
    let selectors: Vec<(String, Selector)> = match chosen {
        Some(c) => c.to_vec(),
        None => default_selectors(cat, records),
    };
    let bound = if chosen.is_some() {
        MAX_SERIES
    } else {
        DEFAULT_SERIES
    };
    let mut all: Vec<(usize, Series)> = Vec::new();
    for (index, record) in records.iter().enumerate() {
        let key = record.key();
        for (path, cell) in flatten(&record.value) {
            if !(path.starts_with("header.") || path.starts_with("payload.")) {
                continue;
            }
            let Some(rank) = selectors.iter().position(|(_, s)| s.matches(key, &path)) else {
                continue;
            };
            let Some(y) = number(&cell) else { continue };
            let name = format!("{key}.{path}");
            let at = match all.iter().position(|(_, s)| s.name == name) {
                Some(at) => at,
                None => {
                    let unit = cat
                        .columns(key)
                        .iter()
                        .find(|c| c.shape == names::shape(&path))
                        .map(|c| c.unit.clone())
                        .unwrap_or_default();
                    all.push((
                        rank,
                        Series {
                            name,
                            unit,
                            points: Vec::new(),
                            samples: 0,
                        },
                    ));
                    all.len() - 1
                }
            };
            all[at].1.points.push((index as u64, y));
        }
    }
    // Stable: within a name, columns stay in order of first appearance.
    all.sort_by_key(|(rank, _)| *rank);
    for (rank, (name, _)) in selectors.iter().enumerate() {
        if chosen.is_some() && !all.iter().any(|(r, _)| *r == rank) {
            plot.absent.push(name.clone());
        }
    }
    for (_, mut s) in all {
        if plot.series.len() == bound {
            plot.left_out.push(s.name);
            continue;
        }
        s.samples = s.points.len();
        s.points = decimate(&s.points, BUCKETS);
        plot.series.push(s);
    }
    plot
}

/// A cell as a number: a JSON number, or a flag as 1 or 0 (non-finite floats, printed as
/// text, are left out).
fn number(cell: &str) -> Option<f64> {
    match cell {
        "true" => Some(1.0),
        "false" => Some(0.0),
        c => c.parse::<f64>().ok().filter(|v| v.is_finite()),
    }
}

/// The scaled columns of the keys of `records`, most frequent key first.
fn default_selectors(cat: &Catalogue, records: &[Record]) -> Vec<(String, Selector)> {
    let mut counts: Vec<(&str, usize)> = Vec::new();
    for r in records {
        match counts.iter_mut().find(|(k, _)| *k == r.key()) {
            Some((_, n)) => *n += 1,
            None => counts.push((r.key(), 1)),
        }
    }
    counts.sort_by_key(|c| std::cmp::Reverse(c.1));
    let mut out = Vec::new();
    for (key, _) in counts {
        for c in cat.columns(key) {
            if c.kind == (Kind::Number { scaled: true }) {
                let selector = Selector {
                    key: Some(key.to_string()),
                    path: c.shape.clone(),
                };
                out.push((format!("{key}.{}", c.shape), selector));
            }
        }
    }
    out
}

/// `points` (in order of position) cut into `buckets` equal stretches of positions, each
/// giving its smallest and its largest value in the order they came; all of them when there
/// are no more than two a bucket. The extremes of every stretch survive, so a spike or a
/// dropout still shows at any width.
pub fn decimate(points: &[(u64, f64)], buckets: usize) -> Vec<(u64, f64)> {
    if points.len() <= 2 * buckets {
        return points.to_vec();
    }
    let (first, last) = (points[0].0, points[points.len() - 1].0);
    let span = (last - first + 1) as f64;
    let bucket_of = |x: u64| (((x - first) as f64 / span) * buckets as f64) as usize;
    let mut out = Vec::with_capacity(2 * buckets);
    let mut start = 0;
    while start < points.len() {
        let b = bucket_of(points[start].0);
        let mut end = start;
        let (mut lo, mut hi) = (start, start);
        while end < points.len() && bucket_of(points[end].0) == b {
            if points[end].1 < points[lo].1 {
                lo = end;
            }
            if points[end].1 > points[hi].1 {
                hi = end;
            }
            end += 1;
        }
        out.push(points[lo.min(hi)]);
        if lo != hi {
            out.push(points[lo.max(hi)]);
        }
        start = end;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimation_keeps_each_stretchs_extremes_in_order() {
        let points: Vec<(u64, f64)> = (0..10_000u64)
            .map(|i| (i, if i == 4321 { 99.0 } else { (i % 7) as f64 }))
            .collect();
        let d = decimate(&points, 100);
        assert!(d.len() <= 200, "{} points", d.len());
        assert!(d.windows(2).all(|w| w[0].0 < w[1].0), "in order");
        assert!(d.contains(&(4321, 99.0)), "the spike survives");
        assert_eq!(d.iter().map(|p| p.1).fold(f64::MAX, f64::min), 0.0);
        assert_eq!(decimate(&points[..150], 100), points[..150].to_vec());
    }
}
