//! Reading frames from byte sources: an `embedded-io` reader (UART drivers of embedded HALs,
//! behind the `embedded-io` feature) or a `std::io::Read` (serial ports, files, sockets, behind
//! the `std` feature). Both feed the one stream engine; frames reach a callback while they
//! borrow the decoder's buffer or the read buffer, so nothing is copied or allocated.

use crate::decoder::{Frame, StreamDecoder};
use crate::layout::LayoutRef;

/// Reads once from `reader` into `buf` and hands every complete frame to `sink`.
///
/// Returns the number of bytes read: 0 means end of input (the caller may then
/// [`flush`](StreamDecoder::flush) the decoder).
///
/// # Errors
///
/// The reader's error; the decoder keeps any partial frame for the next call.
#[cfg(feature = "embedded-io")]
pub fn read_frames<R: embedded_io::Read, L: LayoutRef, const N: usize>(
    reader: &mut R,
    decoder: &mut StreamDecoder<L, N>,
    buf: &mut [u8],
    sink: impl FnMut(Frame<'_>),
) -> Result<usize, R::Error> {
    let n = reader.read(buf)?;
    decoder.feed(buf.get(..n).unwrap_or(&[]), sink);
    Ok(n)
}

/// `read_frames` (the `embedded-io` reader) for a `std::io::Read` (a serial port, a file, a
/// socket).
///
/// # Errors
///
/// The reader's error (`Interrupted` is retried).
#[cfg(feature = "std")]
pub fn read_frames_std<R: std::io::Read, L: LayoutRef, const N: usize>(
    reader: &mut R,
    decoder: &mut StreamDecoder<L, N>,
    buf: &mut [u8],
    sink: impl FnMut(Frame<'_>),
) -> std::io::Result<usize> {
    let n = loop {
        match reader.read(buf) {
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            other => break other?,
        }
    };
    decoder.feed(buf.get(..n).unwrap_or(&[]), sink);
    Ok(n)
}

#[cfg(all(test, feature = "std"))]
// Tests may index and unwrap: a panic there is a failed test, not a runtime fault.
#[allow(
    clippy::indexing_slicing,
    clippy::arithmetic_side_effects,
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic
)]
mod tests {
    use super::*;
    use crate::Checksum;
    use crate::layout::{ByteOrder, Check, FrameLayout, LengthRule, Pos, WordField};

    static LAYOUT: FrameLayout<'static> = FrameLayout {
        sync: &[0xFF, 0xFF],
        sync_set: &[],
        header_len: 6,
        min_len: 8,
        max_len: 127,
        length: LengthRule::Field {
            field: WordField {
                at: Pos::Start(4),
                size: 2,
                order: ByteOrder::Big,
                shift: 0,
                width: 16,
            },
            adjust: 7,
        },
        constants: &[],
        header_checks: &[],
        frame_checks: &[Check {
            checksum: Checksum::SumMod255,
            from: Pos::Start(0),
            to: Pos::End(1),
            at: Pos::End(1),
            order: ByteOrder::Big,
        }],
        markers: &[],
        escape: None,
    };

    #[test]
    fn reads_frames_across_reads() {
        let frame = [0xFF, 0xFF, 0x11, 0x01, 0x00, 0x01, 0x00, 0x13];
        let stream = [&[0x42][..], &frame, &frame].concat();
        // A reader that returns 3 bytes at a time.
        struct Slow<'a>(&'a [u8]);
        impl std::io::Read for Slow<'_> {
            fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
                let n = self.0.len().min(3).min(buf.len());
                buf[..n].copy_from_slice(&self.0[..n]);
                self.0 = &self.0[n..];
                Ok(n)
            }
        }
        let mut reader = Slow(&stream);
        let mut decoder = StreamDecoder::<_, 128>::new(&LAYOUT);
        let mut buf = [0u8; 16];
        let mut frames = 0;
        while read_frames_std(&mut reader, &mut decoder, &mut buf, |f| {
            assert_eq!(f.bytes, &frame);
            frames += 1;
        })
        .expect("reads")
            > 0
        {}
        assert_eq!(frames, 2);
    }
}
