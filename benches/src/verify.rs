//! Running a decoder over a workload and comparing what it returns with the ground truth. The
//! benchmark calls these before timing anything, so a fast wrong decoder is never reported.

use std::fmt;

use crate::workload::Workload;
use crate::{ChunkDecoder, run};

/// Every frame a decoder returned, kept for comparison.
#[derive(Debug, Default, Clone, PartialEq, Eq)]
pub struct Output {
    /// The bytes of the frames, one after the other.
    pub bytes: Vec<u8>,
    /// The length of each frame.
    pub lengths: Vec<usize>,
}

impl Output {
    /// Number of frames.
    pub fn frames(&self) -> usize {
        self.lengths.len()
    }

    /// Each frame's bytes.
    pub fn iter(&self) -> impl Iterator<Item = &[u8]> {
        self.lengths.iter().scan(0, |at, &len| {
            let frame = &self.bytes[*at..*at + len];
            *at += len;
            Some(frame)
        })
    }
}

/// Feeds `stream` to `decoder` in chunks of `chunk` bytes and keeps every frame.
pub fn collect<D: ChunkDecoder>(decoder: &mut D, stream: &[u8], chunk: usize) -> Output {
    let mut out = Output::default();
    run(decoder, stream, chunk, &mut |frame: &[u8]| {
        out.bytes.extend_from_slice(frame);
        out.lengths.push(frame.len());
    });
    out
}

/// The timed work: feeds `stream` and counts the frames and their bytes (a frame is only looked
/// at through its length, the same for every decoder).
#[inline]
pub fn count<D: ChunkDecoder>(decoder: &mut D, stream: &[u8], chunk: usize) -> (usize, usize) {
    let (mut frames, mut bytes) = (0usize, 0usize);
    run(decoder, stream, chunk, &mut |frame: &[u8]| {
        frames += 1;
        bytes += frame.len();
    });
    (frames, bytes)
}

/// How a decoder's frames differ from the ground truth.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Loss {
    /// Ground-truth frames it did not return.
    pub lost: usize,
    /// Frames it returned that are not in the ground truth (at that place).
    pub extra: usize,
}

impl fmt::Display for Loss {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} lost, {} extra", self.lost, self.extra)
    }
}

/// Checks that `out` holds exactly the frames of `w`'s ground truth, in order.
///
/// # Errors
///
/// A description of the first difference.
pub fn exact(w: &Workload, out: &Output) -> Result<(), String> {
    if out.frames() != w.frames.len() {
        let loss = compare(w, out);
        return Err(format!(
            "{}: {} frames instead of {} ({loss})",
            w.name(),
            out.frames(),
            w.frames.len()
        ));
    }
    for (i, (got, want)) in out.iter().zip(&w.frames).enumerate() {
        if got != &w.stream[want.clone()] {
            return Err(format!(
                "{}: frame {i} (at {}) differs",
                w.name(),
                want.start
            ));
        }
    }
    Ok(())
}

/// Matches `out`'s frames against the ground truth in order (a frame matches the next
/// ground-truth frame with the same bytes within the following 64) and counts the differences.
pub fn compare(w: &Workload, out: &Output) -> Loss {
    let mut loss = Loss::default();
    let mut next = 0;
    for got in out.iter() {
        let window = next..(next + 64).min(w.frames.len());
        match window
            .clone()
            .find(|&i| &w.stream[w.frames[i].clone()] == got)
        {
            Some(i) => {
                loss.lost += i - next;
                next = i + 1;
            }
            None => loss.extra += 1,
        }
    }
    loss.lost += w.frames.len() - next;
    loss
}
