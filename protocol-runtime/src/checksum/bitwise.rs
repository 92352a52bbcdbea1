//! A CRC computed bit by bit from parameters it holds by value: [`Bitwise`].
//!
//! This module owns the CRC that needs neither a table nor parameters that live for the whole
//! program. The `crc` crate's `Crc::new` takes `&'static` parameters, which generated code has
//! (its `static` algorithms) and a spec loaded at run time does not: a run-time codec or a
//! spec's validation that computed a custom CRC with that crate would have to keep every
//! parameter set it ever met for the rest of the process. [`Bitwise`] computes the same value
//! with no table, and the run-time codec's tables are [`Slicing16`](super::Slicing16)s, which
//! also hold their parameters by value.

use core::fmt;

use super::CheckObject;

/// A CRC of any width from 1 to the bits of `W`, computed bit by bit, without a table, from
/// parameters it owns: exactly what `crc::Crc::<W, crc::NoTable>::new(alg).checksum(data)`
/// computes.
///
/// ```
/// use protocol_runtime::checksum::{Bitwise, Checksum};
///
/// let params = crc::Algorithm { init: 0x1D0F, ..crc::CRC_16_IBM_3740 };
/// let crc = Bitwise::<u16>::new(&params);
/// // CRC-16/IBM-3740 from another initial value is CRC-16/SPI-FUJITSU.
/// assert_eq!(crc.checksum(b"123456789"), crc::CRC_16_SPI_FUJITSU.check);
/// // As a check the engine runs: a check object two bytes wide.
/// let check = Checksum::Object { width: 2, check: &crc };
/// assert_eq!(check.compute(b"123456789"), 0xE5CC);
/// ```
#[derive(Clone, Copy)]
pub struct Bitwise<W: crc::Width> {
    algorithm: crc::Algorithm<W>,
}

impl<W: crc::Width + Copy> Bitwise<W> {
    /// The CRC of `alg`'s parameters (copied).
    #[must_use]
    pub const fn new(alg: &crc::Algorithm<W>) -> Self {
        Bitwise { algorithm: *alg }
    }

    /// The parameters of the CRC.
    #[must_use]
    pub const fn algorithm(&self) -> &crc::Algorithm<W> {
        &self.algorithm
    }
}

impl<W: crc::Width + fmt::Debug> fmt::Debug for Bitwise<W> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_tuple("Bitwise").field(&self.algorithm).finish()
    }
}

macro_rules! bitwise_width {
    ($($w:ty),*) => {$(
        impl Bitwise<$w> {
            /// The CRC of `data`.
            ///
            /// The register is kept as [`Slicing16`](super::Slicing16) keeps it: in the low
            /// `width` bits when the input is reflected (it shifts right, and the polynomial
            /// and initial value are reflected), in the high `width` bits otherwise (it shifts
            /// left). A width outside `1..=BITS` gives a meaningless value, never a panic.
            #[must_use]
            pub fn checksum(&self, data: &[u8]) -> $w {
                let a = &self.algorithm;
                let pad = <$w>::BITS.saturating_sub(u32::from(a.width));
                let mut register: $w;
                if a.refin {
                    let poly = a.poly.reverse_bits().checked_shr(pad).unwrap_or(0);
                    register = a.init.reverse_bits().checked_shr(pad).unwrap_or(0);
                    for &byte in data {
                        register ^= <$w>::from(byte);
                        for _ in 0..8 {
                            let low = register & 1 != 0;
                            register >>= 1;
                            if low {
                                register ^= poly;
                            }
                        }
                    }
                } else {
                    let poly = a.poly.checked_shl(pad).unwrap_or(0);
                    register = a.init.checked_shl(pad).unwrap_or(0);
                    for &byte in data {
                        register ^= <$w>::from(byte).checked_shl(<$w>::BITS - 8).unwrap_or(0);
                        for _ in 0..8 {
                            let high = register.leading_zeros() == 0;
                            register <<= 1;
                            if high {
                                register ^= poly;
                            }
                        }
                    }
                    // Down to the low `width` bits, where the reflected register already is.
                    register = register.checked_shr(pad).unwrap_or(0);
                }
                if a.refin != a.refout {
                    register = register.reverse_bits().checked_shr(pad).unwrap_or(0);
                }
                register ^ a.xorout
            }
        }

        impl CheckObject for Bitwise<$w> {
            fn compute(&self, data: &[u8]) -> u64 {
                u64::from(self.checksum(data))
            }

            fn compute_prefix(&self, data: &[u8], n: usize) -> Option<u64> {
                Some(u64::from(self.checksum(data.get(..n).unwrap_or(data))))
            }
        }
    )*};
}
bitwise_width!(u8, u16, u32, u64);
