//! The encoder workload: a million frames written one after the other into a reused buffer.
//!
//! The buffer is 64 KiB and the writer wraps around to its start when the next frame would not
//! fit, so that the benchmark times encoding, not the bandwidth to main memory (a million
//! 28-byte frames would be 28 MB). The values change with every frame, so nothing is constant
//! folded. The encoders themselves are [`crate::generated`]'s and [`crate::hand`]'s.

/// Frames per iteration.
pub const FRAMES: u32 = 1_000_000;
/// Bytes of the reused output buffer.
pub const BUFFER: usize = 64 << 10;
/// Room a frame needs before the writer wraps (larger than any frame encoded here).
const ROOM: usize = 64;

/// The `SystemInfo` of frame `i`.
#[inline]
pub fn system_info(i: u32) -> [f32; 5] {
    [
        i as f32 * 0.01,
        40.0 + (i % 8) as f32,
        0.25,
        12.3,
        (i % 100) as f32,
    ]
}

/// The `GameRobotPos` of frame `i`.
#[inline]
pub fn robot_pos(i: u32) -> [f32; 4] {
    [i as f32 * 0.001, 2.5, 0.0, (i % 360) as f32]
}

/// Encodes `frames` frames with `encode(buffer_rest, i) -> bytes written` into `buf`, wrapping
/// around; returns the bytes written in all.
#[inline]
pub fn encode_wrapping<E: FnMut(&mut [u8], u32) -> usize>(
    buf: &mut [u8],
    frames: u32,
    mut encode: E,
) -> usize {
    let mut at = 0;
    let mut total = 0;
    for i in 0..frames {
        if at + ROOM > buf.len() {
            at = 0;
        }
        let n = encode(&mut buf[at..], i);
        at += n;
        total += n;
    }
    total
}

/// Encodes `frames` frames one after the other into a new vector (to compare encoders).
pub fn encode_all<E: FnMut(&mut [u8], u32) -> usize>(frames: u32, mut encode: E) -> Vec<u8> {
    let mut out = Vec::new();
    let mut frame = [0u8; ROOM];
    for i in 0..frames {
        let n = encode(&mut frame, i);
        out.extend_from_slice(&frame[..n]);
    }
    out
}
