//! The link-quality chart of the report: bad checks, other rejections and skipped bytes per
//! window of offsets. The windows are counted while the capture is decoded, so the page of a
//! long capture keeps sixty counters, not its items.

use std::fmt::Write as _;

use protocol_runtime::Reject;

/// Windows of the link-quality chart.
const WINDOWS: usize = 60;

/// Per window of offsets: (bad checks, other rejections, skipped bytes).
pub(super) struct Windows {
    /// Bytes per window.
    size: usize,
    /// Bytes of the whole capture.
    total: usize,
    counts: Vec<[u64; 3]>,
}

impl Windows {
    /// The windows of a capture of `total` bytes, all counts zero.
    pub(super) fn new(total: usize) -> Self {
        let size = total.div_ceil(WINDOWS).max(1);
        Self {
            size,
            total,
            counts: vec![[0; 3]; total.div_ceil(size).max(1)],
        }
    }

    fn at(&mut self, offset: usize) -> &mut [u64; 3] {
        let last = self.counts.len() - 1;
        &mut self.counts[(offset / self.size).min(last)]
    }

    /// Per window: (bad checks, other rejections, skipped bytes).
    #[cfg(test)]
    pub(super) fn counts(&self) -> &[[u64; 3]] {
        &self.counts
    }

    /// Counts a rejected candidate at `offset`: a failed check or another rejection.
    pub(super) fn rejected(&mut self, offset: usize, reason: Reject) {
        let k = usize::from(!matches!(
            reason,
            Reject::BadChecksum | Reject::BadHeaderCheck
        ));
        self.at(offset)[k] += 1;
    }

    /// Counts a run of `len` skipped bytes at `offset`: a run may cross windows, and each
    /// gets its share.
    pub(super) fn skipped(&mut self, offset: usize, len: usize) {
        let (mut at, end) = (offset, offset + len);
        while at < end {
            let stop = ((at / self.size + 1) * self.size).min(end).max(at + 1);
            self.at(at)[2] += (stop - at) as u64;
            at = stop;
        }
    }
}

/// The link-quality chart: per window, bars of bad checks, other rejections and skipped bytes
/// (each series scaled to its own maximum, labelled with it).
pub(super) fn chart(windows: &Windows, out: &mut String) {
    let (size, w, total) = (windows.size, &windows.counts, windows.total);
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
