//! Lost and reordered frames, counted from a spec's frame counter (`counter = true` on a
//! header field: a sequence number the sender adds one to per frame, wrapping at the field's
//! width). Decode-side statistics only: no codec checks the counter.
//!
//! Each sender counts on its own: frames are grouped by frame format and by the values of the
//! frame's other user header fields (MAVLink's `sysid` and `compid`). Within a group, a frame
//! whose counter is `k` ahead of the last one (less than half the counter's range) follows
//! `k - 1` lost frames; one behind it (half the range or more) arrived late: it counts as
//! reordered and no longer as lost, and the last value stays; the same value again counts as
//! repeated.

use std::collections::HashMap;

use protocol_dynamic::Decoded;
use protocol_spec::ir::{Protocol, Role};

/// What the frame counters of a capture showed.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Counters {
    /// The last counter value of each group (frame format, the other header values).
    last: HashMap<(usize, String), u64>,
    /// Frames that carried a counter.
    pub counted: u64,
    /// Frames missing between counted frames.
    pub lost: u64,
    /// Frames that arrived after a later one.
    pub reordered: u64,
    /// Frames with the same counter as the one before them.
    pub repeated: u64,
}

impl Counters {
    /// Counts one decoded frame (a frame of a format without a counter is ignored).
    pub fn observe(&mut self, p: &Protocol, d: &Decoded) {
        let Some(f) = p.frames.get(d.format) else {
            return;
        };
        let Some(counter) = f.counter.and_then(|vi| f.values.get(vi)) else {
            return;
        };
        let Some(value) = d.header.get(&counter.name).and_then(|v| v.as_u64()) else {
            return;
        };
        let stream: Vec<String> = f
            .values
            .iter()
            .filter(|v| matches!(v.role, Role::User { .. }) && v.name != counter.name)
            .filter_map(|v| Some(format!("{}={:?}", v.name, d.header.get(&v.name)?)))
            .collect();
        self.step(d.format, stream.join(","), value, counter.width);
    }

    /// Counts one counter value `value` of `width` bits in group (`format`, `stream`).
    ///
    /// ```
    /// use protocol_cli::counter::Counters;
    /// let mut c = Counters::default();
    /// for (format, stream, value) in [(0, "", 254), (0, "", 255), (0, "", 2), (0, "", 1)] {
    ///     c.step(format, stream.to_string(), value, 8);
    /// }
    /// // 255 -> 2 wraps and skips 0 and 1; 1 then comes late: 0 alone is lost.
    /// assert_eq!((c.counted, c.lost, c.reordered, c.repeated), (4, 1, 1, 0));
    /// ```
    pub fn step(&mut self, format: usize, stream: String, value: u64, width: u32) {
        self.counted += 1;
        let range: u128 = 1u128 << width.min(64);
        let Some(last) = self.last.get_mut(&(format, stream.clone())) else {
            self.last.insert((format, stream), value);
            return;
        };
        // How far `value` is ahead of the last one, around the counter's range.
        let ahead = (u128::from(value) % range + range - u128::from(*last) % range) % range;
        if ahead == 0 {
            self.repeated += 1;
        } else if ahead < range / 2 {
            self.lost += u64::try_from(ahead - 1).unwrap_or(u64::MAX);
            *last = value;
        } else {
            // A late frame is one of those counted as lost when the frame after it came.
            self.reordered += 1;
            self.lost = self.lost.saturating_sub(1);
        }
    }

    /// The line `--stats` and the report show: `None` when no frame carried a counter.
    pub fn summary(&self) -> Option<String> {
        (self.counted > 0).then(|| {
            format!(
                "{} lost, {} reordered, {} repeated (of {} frames with a frame counter)",
                self.lost, self.reordered, self.repeated, self.counted
            )
        })
    }
}
