//! Signals: the numeric values of a capture's decoded frames as series over the capture, for the
//! report's plots. Series are chosen by name ([`names`]: `--plot`) or by default (the scaled
//! fields, those with a scale or a unit, of the most frequent commands), and decimated to a
//! bounded number of points per series (the minimum and the maximum of each of
//! [`BUCKETS`] equal stretches of the capture), so that a large capture gives a page of
//! bounded size. [`section`] writes the page's part; the plotter itself is `plot.js`.
//!
//! The frames come from [`crate::export::each_frame`], one at a time into a [`Collector`], so
//! a series holds exactly the values `protocol decode --format json` prints. Their position is the frame's index among
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

/// A series being gathered: the selector that took it, its key's place in the counts.
struct Gathered {
    rank: usize,
    key: usize,
    series: Series,
}

/// Gathers the series of a capture one decoded frame at a time ([`Collector::add`]), so that a
/// long capture is never held decoded whole; [`Collector::finish`] chooses, bounds and
/// decimates them.
pub struct Collector<'c> {
    cat: &'c Catalogue,
    /// The names given, or by default every scaled column of every key.
    selectors: Vec<(String, Selector)>,
    chosen: bool,
    /// Frames per key, in order of first appearance.
    counts: Vec<(String, usize)>,
    /// The series, in order of first appearance.
    all: Vec<Gathered>,
    frames: u64,
}

impl<'c> Collector<'c> {
    /// Gathers what `chosen` selects, or by default the scaled columns of every key (the most
    /// frequent keys' are plotted).
    pub fn new(cat: &'c Catalogue, chosen: Option<&[(String, Selector)]>) -> Self {
        Collector {
            cat,
            selectors: chosen.map_or_else(|| scaled_selectors(cat), <[_]>::to_vec),
            chosen: chosen.is_some(),
            counts: Vec::new(),
            all: Vec::new(),
            frames: 0,
        }
    }

    /// Adds the values of the capture's next frame.
    pub fn add(&mut self, record: &Record) {
        let index = self.frames;
        self.frames += 1;
        let key = record.key();
        let k = match self.counts.iter().position(|(x, _)| x == key) {
            Some(k) => k,
            None => {
                self.counts.push((key.to_string(), 0));
                self.counts.len() - 1
            }
        };
        self.counts[k].1 += 1;
        for (path, cell) in flatten(&record.value) {
            if !(path.starts_with("header.") || path.starts_with("payload.")) {
                continue;
            }
            let shape = names::shape(&path);
            let selected = (self.selectors.iter()).position(|(_, s)| s.matches(key, &path, &shape));
            let (Some(rank), Some(y)) = (selected, number(&cell)) else {
                continue;
            };
            let name = format!("{key}.{path}");
            let at = match self.all.iter().position(|g| g.series.name == name) {
                Some(at) => at,
                None => {
                    let unit = self
                        .cat
                        .columns(key)
                        .iter()
                        .find(|c| c.shape == shape)
                        .map(|c| c.unit.clone())
                        .unwrap_or_default();
                    let series = Series {
                        name,
                        unit,
                        points: Vec::new(),
                        samples: 0,
                    };
                    self.all.push(Gathered {
                        rank,
                        key: k,
                        series,
                    });
                    self.all.len() - 1
                }
            };
            self.all[at].series.points.push((index, y));
        }
    }

    /// The plot: the series in the order of the names given (then of first appearance), or by
    /// default those of the most frequent keys first; at most [`MAX_SERIES`] or
    /// [`DEFAULT_SERIES`] of them, each decimated to at most `2 * BUCKETS` points.
    pub fn finish(self) -> Plot {
        let mut plot = Plot {
            default: !self.chosen,
            ..Plot::default()
        };
        let mut all = self.all;
        let counts = &self.counts;
        // Stable sorts: within a rank, columns stay in order of first appearance.
        if self.chosen {
            all.sort_by_key(|g| g.rank);
            for (rank, (name, _)) in self.selectors.iter().enumerate() {
                if !all.iter().any(|g| g.rank == rank) {
                    plot.absent.push(name.clone());
                }
            }
        } else {
            all.sort_by_key(|g| (std::cmp::Reverse(counts[g.key].1), g.rank));
        }
        let bound = if self.chosen {
            MAX_SERIES
        } else {
            DEFAULT_SERIES
        };
        for Gathered { mut series, .. } in all {
            if plot.series.len() == bound {
                plot.left_out.push(series.name);
                continue;
            }
            series.samples = series.points.len();
            series.points = decimate(&series.points, BUCKETS);
            plot.series.push(series);
        }
        plot
    }
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

/// Every scaled column of every key, in the spec's order.
fn scaled_selectors(cat: &Catalogue) -> Vec<(String, Selector)> {
    let mut out = Vec::new();
    for (key, columns) in &cat.keys {
        for c in columns {
            if c.kind == (Kind::Number { scaled: true }) {
                let selector = Selector {
                    key: Some(key.clone()),
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
