//! Cursors over payload bytes ([`Reader`], [`Writer`]) and words at fixed positions of a frame
//! ([`read_uint`], [`write_uint`], [`WordField`](crate::layout::WordField)).
//!
//! This module owns every primitive read and write of the runtime: numbers of each width and
//! byte order, raw byte runs, and bit fields inside a word. Nothing here panics or indexes
//! without a check: a short input is
//! [`DecodeError::Truncated`](crate::DecodeError::Truncated), a short buffer
//! [`EncodeError::BufferTooSmall`](crate::EncodeError::BufferTooSmall), a position outside the
//! frame `None`. The cursors are the hot path of generated payload code, so every method is
//! `#[inline]` and reads fixed-size chunks with `split_first_chunk`. What the bytes mean
//! (structs, enums, scaling) is generated code's business.
//!
//! ```
//! use protocol_runtime::{Reader, Writer};
//!
//! let mut buf = [0u8; 7];
//! let mut w = Writer::new(&mut buf);
//! w.put_u16_be(0x0102)?;
//! w.put_f32_le(1.5)?;
//! w.put_bool(true)?;
//! assert_eq!(w.remaining(), 0);
//!
//! let mut r = Reader::new(&buf);
//! assert_eq!(r.u16_be()?, 0x0102);
//! assert_eq!(r.f32_le()?, 1.5);
//! assert!(r.bool()?);
//! r.finish()?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod half;
mod int24;
mod reader;
mod wide_int;
mod word;
mod writer;

pub use half::{f16_to_f32, f32_to_f16, fit_f16};
pub use int24::{fit_i24, fit_u24};
pub use reader::Reader;
pub use wide_int::{fit_signed, fit_unsigned};
pub use word::{read_uint, write_uint};
pub use writer::Writer;

#[cfg(test)]
#[allow(clippy::indexing_slicing, clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::error::{DecodeError, EncodeError};

    #[test]
    fn every_number_round_trips_in_both_orders() {
        let mut buf = [0u8; 2 * (2 + 2 + 4 + 4 + 8 + 8 + 4 + 8) + 3];
        let mut w = Writer::new(&mut buf);
        w.put_u8(0xAB).unwrap();
        w.put_i8(-5).unwrap();
        w.put_bool(true).unwrap();
        w.put_u16_le(0x1234).unwrap();
        w.put_u16_be(0x1234).unwrap();
        w.put_i16_le(-2).unwrap();
        w.put_i16_be(-2).unwrap();
        w.put_u32_le(0xDEAD_BEEF).unwrap();
        w.put_u32_be(0xDEAD_BEEF).unwrap();
        w.put_i32_le(-7).unwrap();
        w.put_i32_be(-7).unwrap();
        w.put_u64_le(0x0102_0304_0506_0708).unwrap();
        w.put_u64_be(0x0102_0304_0506_0708).unwrap();
        w.put_i64_le(i64::MIN).unwrap();
        w.put_i64_be(i64::MIN).unwrap();
        w.put_f32_le(-1.25).unwrap();
        w.put_f32_be(-1.25).unwrap();
        w.put_f64_le(core::f64::consts::PI).unwrap();
        w.put_f64_be(core::f64::consts::PI).unwrap();
        assert_eq!(w.remaining(), 0);
        assert_eq!(&buf[3..7], &[0x34, 0x12, 0x12, 0x34]);

        let mut r = Reader::new(&buf);
        assert_eq!(r.u8().unwrap(), 0xAB);
        assert_eq!(r.i8().unwrap(), -5);
        assert!(r.bool().unwrap());
        assert_eq!(r.u16_le().unwrap(), 0x1234);
        assert_eq!(r.u16_be().unwrap(), 0x1234);
        assert_eq!(r.i16_le().unwrap(), -2);
        assert_eq!(r.i16_be().unwrap(), -2);
        assert_eq!(r.u32_le().unwrap(), 0xDEAD_BEEF);
        assert_eq!(r.u32_be().unwrap(), 0xDEAD_BEEF);
        assert_eq!(r.i32_le().unwrap(), -7);
        assert_eq!(r.i32_be().unwrap(), -7);
        assert_eq!(r.u64_le().unwrap(), 0x0102_0304_0506_0708);
        assert_eq!(r.u64_be().unwrap(), 0x0102_0304_0506_0708);
        assert_eq!(r.i64_le().unwrap(), i64::MIN);
        assert_eq!(r.i64_be().unwrap(), i64::MIN);
        assert_eq!(r.f32_le().unwrap(), -1.25);
        assert_eq!(r.f32_be().unwrap(), -1.25);
        assert_eq!(r.f64_le().unwrap(), core::f64::consts::PI);
        assert_eq!(r.f64_be().unwrap(), core::f64::consts::PI);
        r.finish().unwrap();
    }

    #[test]
    fn short_reads_fail_without_advancing() {
        let mut r = Reader::new(&[1, 2, 3]);
        assert_eq!(
            r.u32_be(),
            Err(DecodeError::Truncated {
                needed: 4,
                available: 3
            })
        );
        assert_eq!(
            r.take(4),
            Err(DecodeError::Truncated {
                needed: 4,
                available: 3
            })
        );
        assert_eq!(
            r.skip(usize::MAX),
            Err(DecodeError::Truncated {
                needed: usize::MAX,
                available: 3
            })
        );
        assert_eq!(r.position(), 0);
        assert_eq!(r.take(2).unwrap(), &[1, 2]);
        assert_eq!(r.rest(), &[3]);
        assert_eq!(
            r.clone().finish(),
            Err(DecodeError::PayloadLength {
                expected: 2,
                actual: 3
            })
        );
        assert_eq!(r.bytes::<1>().unwrap(), [3]);
        assert_eq!(r.bytes::<0>().unwrap(), []);
        r.finish().unwrap();
    }

    #[test]
    fn short_writes_fail_without_writing() {
        let mut buf = [9u8; 3];
        let mut w = Writer::new(&mut buf);
        w.put_u8(1).unwrap();
        assert_eq!(
            w.put_u32_le(0),
            Err(EncodeError::BufferTooSmall {
                needed: 5,
                available: 3
            })
        );
        assert_eq!(
            w.put_bytes(&[0; 3]),
            Err(EncodeError::BufferTooSmall {
                needed: 4,
                available: 3
            })
        );
        assert_eq!(
            w.zeros(usize::MAX),
            Err(EncodeError::BufferTooSmall {
                needed: usize::MAX,
                available: 3
            })
        );
        assert_eq!(w.position(), 1);
        w.put_bytes(&[7]).unwrap();
        w.zeros(1).unwrap();
        assert_eq!(
            w.put_bool(false),
            Err(EncodeError::BufferTooSmall {
                needed: 4,
                available: 3
            })
        );
        assert_eq!(buf, [1, 7, 0]);
    }
}
