//! Frame check algorithms: byte sums (plain, complemented, 16-bit), xor, Fletcher sums, and
//! CRCs.
//!
//! This module owns computing a check value over a byte range ([`Checksum::compute`],
//! [`Checksum::compute_prefix`]), its size on the wire ([`Checksum::width`]), and the
//! table-free description of an algorithm that an IR holds ([`Algorithm`]). Which bytes a
//! check covers and where its value is stored is the frame layout's business
//! ([`crate::layout::Check`]).
//!
//! # CRC tables
//!
//! A CRC is built in a `static` or `const` from a [`crc::Algorithm`] and wrapped in a
//! [`CrcImpl`] that names its table size, which trades memory for speed:
//!
//! | implementation | tables | bytes for `u8` / `u16` / `u32` / `u64` | speed on 50-byte frames |
//! | --- | --- | --- | --- |
//! | [`CrcImpl::NoTable`] (`crc::NoTable`) | none | 0 | slowest (bit by bit) |
//! | [`CrcImpl::Table1`] (`crc::Table<1>`) | 256 entries | 256 / 512 / 1 Ki / 2 Ki | 3-5x slower |
//! | [`CrcImpl::Table16`] ([`Slicing16`]) | 16 × 256 entries | 4 / 8 / 16 / 32 Ki | fastest |
//!
//! Firmware short of flash picks `NoTable` or `Table1` (the `crc` crate's); hosts pick
//! `Table16`, this crate's [`Slicing16`], which has no byte-wise loop at all (the `crc` crate's
//! `Table<16>` finishes with one over the last `n % 16` bytes). A spec that names no table gets
//! [`TargetCrc`]: `Table16` where pointers are 64 bits, `Table1` elsewhere.
//!
//! On x86-64 hosts, the `clmul` feature in a build for a CPU with carry-less multiplication
//! (`-C target-cpu=native`, or `-C target-feature=+pclmulqdq`) has [`Slicing16`] fold reflected
//! CRCs of up to 32 bits over more than 8 bytes 16 bytes at a time with `pclmulqdq`
//! ([`Slicing16::uses_clmul`]): the referee's decoder then executes 150 instructions per frame
//! instead of 268.5 (`benches/count.sh`).
//! The tables stay for the CRCs that are not reflected or are wider, and for checks of at most
//! 8 bytes. The `unsafe` of the intrinsic is the `safe_arch` crate's. The decoder's module docs
//! list this and the crate's other
//! [target and build switches](crate::decoder#target-and-build-switches).
//!
//! ```
//! use protocol_runtime::checksum::{Checksum, CrcImpl, Slicing16};
//!
//! static CRC: Slicing16<u16> = Slicing16::<u16>::new(&crc::CRC_16_UMTS);
//! let check = Checksum::Crc16(CrcImpl::Table16(&CRC));
//! assert_eq!(check.width(), 2);
//! assert_eq!(check.compute(b"123456789"), 0xFEE8);
//! // The same over the first 9 bytes of a longer input.
//! assert_eq!(check.compute_prefix(b"123456789 and more", 9), Some(0xFEE8));
//! assert_eq!(Checksum::SumMod255.compute(b"123456789"), 0xDE);
//! ```

use core::fmt;

mod algorithm;
mod bitwise;
mod clmul;
mod declared;
mod extra;
#[cfg(feature = "crc-fast")]
mod fast;
mod fletcher;
mod slicing;
mod sum;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_declared;
#[cfg(test)]
mod tests_direct;
#[cfg(test)]
mod tests_extra;
#[cfg(test)]
mod tests_seeds;
#[cfg(test)]
mod tests_target;
#[cfg(test)]
mod tests_then;

pub use algorithm::{Algorithm, CrcSpec, CrcTable};
pub use bitwise::Bitwise;
pub use extra::{Extra, direct_table, fill_direct};
pub use slicing::Slicing16;

/// A check algorithm.
#[derive(Clone, Copy)]
pub enum Checksum<'a> {
    /// Sum of the bytes modulo 256.
    Sum8,
    /// Sum of the bytes modulo 255 (a value in `0..=254`).
    SumMod255,
    /// Xor of the bytes.
    Xor8,
    /// The sum of `init` and the bytes modulo 2^(8 × `width`) (`width` 1 or 2; any other
    /// counts as 2), xored with `xorout`. All ones is the one's complement of the sum:
    /// `~sum & 0xFF` (Dynamixel Protocol 1.0), `0xFFFF - sum` (iBUS). `init` seeds the sum
    /// with a constant a link's documentation gives (0 for a plain sum).
    Sum {
        /// Bytes of the stored value: 1 or 2.
        width: u8,
        /// The value the sum starts from.
        init: u16,
        /// Xored into the sum.
        xorout: u16,
    },
    /// The XOR of the bytes, starting from `init` (a seed: [`Xor8`](Self::Xor8) is `init` 0).
    Xor {
        /// The value the XOR starts from.
        init: u8,
    },
    /// Fletcher-16: two running sums modulo 255 (`A` of the bytes, `B` of the successive
    /// `A`s), the value `B << 8 | A` (Fletcher, "An Arithmetic Checksum for Serial
    /// Transmissions", 1982; the 8-bit Fletcher of RFC 1146).
    Fletcher16,
    /// Fletcher's two running sums modulo 256, the value `B << 8 | A`: the pair u-blox UBX
    /// stores as `CK_A, CK_B` (a little-endian `u16`).
    Fletcher16Mod256,
    /// An 8-bit CRC.
    Crc8(CrcImpl<'a, u8>),
    /// A 16-bit CRC.
    Crc16(CrcImpl<'a, u16>),
    /// A 32-bit CRC.
    Crc32(CrcImpl<'a, u32>),
    /// A 64-bit CRC.
    Crc64(CrcImpl<'a, u64>),
    /// A CRC that folds in one more byte, picked by a key in the covered bytes ([`Extra`]).
    Extra(&'a Extra<'a>),
    /// A check computed by an object its user owns ([`CheckObject`]), `width` bytes wide.
    ///
    /// The run-time codec's check with a per-command byte: an [`Extra`] borrows its CRC and
    /// its byte table, and a layout borrows the [`Extra`], so a codec that builds all three
    /// from a spec would have to own a value that borrows from itself. It owns them in one
    /// object instead, which builds the [`Extra`] view on each call, and frees them when it
    /// is dropped. Generated code never names this variant: its statics, the size of a
    /// [`Checksum`] and the code a constant [`Checksum`] folds to stay as they are.
    Object {
        /// Bytes of the stored value.
        width: u8,
        /// What computes it.
        check: &'a dyn CheckObject,
    },
}

/// A check value computed by an object outside this crate, for [`Checksum::Object`]: a check
/// whose tables are built at run time and owned by their user. `Sync`, as a layout in a
/// `static` must be; its `Debug` is the [`Checksum`]'s, so that it can print as the
/// [`Checksum`] it computes like (the run-time codec's layouts print as generated code's).
///
/// ```
/// use protocol_runtime::checksum::{CheckObject, Checksum};
///
/// /// A byte sum xored with a byte known only at run time.
/// #[derive(Debug)]
/// struct Salted(u8);
///
/// impl CheckObject for Salted {
///     fn compute(&self, data: &[u8]) -> u64 {
///         Checksum::Sum8.compute(data) ^ u64::from(self.0)
///     }
///     fn compute_prefix(&self, data: &[u8], n: usize) -> Option<u64> {
///         Some(self.compute(data.get(..n)?))
///     }
/// }
///
/// let salted = Salted(0xA5);
/// let check = Checksum::Object { width: 1, check: &salted };
/// assert_eq!(check.width(), 1);
/// assert_eq!(check.compute(&[0x01, 0x02]), 0xA6);
/// assert_eq!(check.compute_prefix(&[0x01, 0x02, 0xFF], 2), Some(0xA6));
/// ```
pub trait CheckObject: Sync + fmt::Debug {
    /// The check value of `data`, as [`Checksum::compute`].
    fn compute(&self, data: &[u8]) -> u64;

    /// The check value of `data[..n]`, as [`Checksum::compute_prefix`] (`data` holds at least
    /// `n` bytes; `None` when the value cannot be computed, as an [`Extra`]'s unknown key).
    fn compute_prefix(&self, data: &[u8], n: usize) -> Option<u64>;
}

/// A CRC with its table size.
#[derive(Clone, Copy)]
pub enum CrcImpl<'a, W: crc::Width> {
    /// Bit by bit, no table (the [`crc`] crate's).
    NoTable(&'a crc::Crc<W, crc::NoTable>),
    /// One 256-entry table (the [`crc`] crate's).
    Table1(&'a crc::Crc<W, crc::Table<1>>),
    /// Slicing by 16: sixteen 256-entry tables, no byte-wise loop ([`Slicing16`]).
    Table16(&'a Slicing16<W>),
}

/// Whether [`TargetCrc`] is [`Slicing16`] (pointers of 64 bits) rather than one table.
pub const TARGET_TABLE16: bool = cfg!(target_pointer_width = "64");

/// The CRC tables of a check whose spec names no `table` ([`CrcTable::ByTarget`]): sixteen
/// ([`Slicing16`]) where pointers are 64 bits, where speed comes first; one 256-entry table
/// (`crc::Table<1>`) elsewhere, on microcontrollers, where flash does (sixteen tables of a
/// CRC-16 are 8 KiB). Both build in a `const` with `TargetCrc::<W>::new(&algorithm)`;
/// [`CrcImpl::by_target`] wraps either.
#[cfg(target_pointer_width = "64")]
pub type TargetCrc<W> = Slicing16<W>;
/// The CRC tables of a check whose spec names no `table` ([`CrcTable::ByTarget`]): sixteen
/// ([`Slicing16`]) where pointers are 64 bits, where speed comes first; one 256-entry table
/// (`crc::Table<1>`) elsewhere, on microcontrollers, where flash does (sixteen tables of a
/// CRC-16 are 8 KiB). Both build in a `const` with `TargetCrc::<W>::new(&algorithm)`;
/// [`CrcImpl::by_target`] wraps either.
#[cfg(not(target_pointer_width = "64"))]
pub type TargetCrc<W> = crc::Crc<W, crc::Table<1>>;

impl<'a, W: crc::Width> CrcImpl<'a, W> {
    /// The [`CrcImpl`] of a [`TargetCrc`]: [`CrcImpl::Table16`] or [`CrcImpl::Table1`].
    ///
    /// ```
    /// use protocol_runtime::checksum::{Checksum, CrcImpl, TargetCrc};
    ///
    /// static CRC: TargetCrc<u16> = TargetCrc::<u16>::new(&crc::CRC_16_MCRF4XX);
    /// let check = Checksum::Crc16(CrcImpl::by_target(&CRC));
    /// assert_eq!(check.compute(b"123456789"), 0x6F91);
    /// ```
    #[inline]
    #[must_use]
    pub const fn by_target(tables: &'a TargetCrc<W>) -> Self {
        #[cfg(target_pointer_width = "64")]
        {
            CrcImpl::Table16(tables)
        }
        #[cfg(not(target_pointer_width = "64"))]
        {
            CrcImpl::Table1(tables)
        }
    }
}

macro_rules! crc_impl_width {
    ($($w:ty),*) => {$(
        impl CrcImpl<'_, $w> {
            #[doc = concat!("The CRC of `data` as a `", stringify!($w), "`.")]
            #[cfg_attr(not(protocol_opt0), inline(always))]
            pub fn checksum(&self, data: &[u8]) -> $w {
                match self {
                    CrcImpl::NoTable(c) => c.checksum(data),
                    CrcImpl::Table1(c) => c.checksum(data),
                    CrcImpl::Table16(c) => c.checksum(data),
                }
            }

            #[doc = concat!("The CRC of `data` as a `", stringify!($w), "`, bytes just written:")]
            /// as [`checksum`](Self::checksum), but never with the carry-less folding
            /// ([`Slicing16::checksum_written`]).
            #[cfg_attr(not(protocol_opt0), inline(always))]
            pub fn checksum_written(&self, data: &[u8]) -> $w {
                match self {
                    CrcImpl::NoTable(c) => c.checksum(data),
                    CrcImpl::Table1(c) => c.checksum(data),
                    CrcImpl::Table16(c) => c.checksum_written(data),
                }
            }

            #[doc = concat!("The CRC of `data[..n]` as a `", stringify!($w), "`; `data` may")]
            /// run past `n` (bytes past `n` never change the result). If `data` is shorter
            /// than `n`, the CRC of all of `data`.
            #[cfg_attr(not(protocol_opt0), inline(always))]
            pub fn checksum_prefix(&self, data: &[u8], n: usize) -> $w {
                match self {
                    CrcImpl::NoTable(c) => c.checksum(data.get(..n).unwrap_or(data)),
                    CrcImpl::Table1(c) => c.checksum(data.get(..n).unwrap_or(data)),
                    CrcImpl::Table16(c) => c.checksum_prefix(data, n),
                }
            }
        }
    )*};
}
crc_impl_width!(u8, u16, u32, u64);

/// Bytes a CRC of `width` bits is stored in: the fewest whole bytes that hold it (a CRC-24 in
/// three, a CRC-5 in one).
///
/// ```
/// use protocol_runtime::checksum::crc_bytes;
///
/// assert_eq!(crc_bytes(24), 3);
/// assert_eq!(crc_bytes(5), 1);
/// assert_eq!(crc_bytes(40), 5);
/// ```
#[cfg_attr(not(protocol_opt0), inline(always))]
pub const fn crc_bytes(width: u8) -> usize {
    (width as usize).div_ceil(8)
}

impl<W: crc::Width> CrcImpl<'_, W> {
    /// The parameters of the CRC.
    #[inline]
    pub fn algorithm(&self) -> &crc::Algorithm<W> {
        match self {
            CrcImpl::NoTable(c) => c.algorithm,
            CrcImpl::Table1(c) => c.algorithm,
            CrcImpl::Table16(c) => c.algorithm(),
        }
    }

    /// Bytes the CRC is stored in ([`crc_bytes`] of its width). Read from the parameters the
    /// tables were built from: in a generated layout they are a constant, and this folds.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub const fn stored_bytes(&self) -> usize {
        crc_bytes(match self {
            CrcImpl::NoTable(c) => c.algorithm.width,
            CrcImpl::Table1(c) => c.algorithm.width,
            CrcImpl::Table16(c) => c.algorithm().width,
        })
    }

    /// Number of 256-entry tables: 0, 1 or 16.
    #[inline]
    pub const fn table_lanes(&self) -> usize {
        match self {
            CrcImpl::NoTable(_) => 0,
            CrcImpl::Table1(_) => 1,
            CrcImpl::Table16(_) => 16,
        }
    }
}

impl<W: crc::Width + fmt::Debug> fmt::Debug for CrcImpl<'_, W> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let name = match self {
            CrcImpl::NoTable(_) => "NoTable",
            CrcImpl::Table1(_) => "Table1",
            CrcImpl::Table16(_) => "Table16",
        };
        f.debug_tuple(name).field(self.algorithm()).finish()
    }
}

impl fmt::Debug for Checksum<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Checksum::Sum8 => f.write_str("Sum8"),
            Checksum::SumMod255 => f.write_str("SumMod255"),
            Checksum::Xor8 => f.write_str("Xor8"),
            Checksum::Sum {
                width,
                init,
                xorout,
            } => f
                .debug_struct("Sum")
                .field("width", width)
                .field("init", init)
                .field("xorout", xorout)
                .finish(),
            Checksum::Xor { init } => f.debug_struct("Xor").field("init", init).finish(),
            Checksum::Fletcher16 => f.write_str("Fletcher16"),
            Checksum::Fletcher16Mod256 => f.write_str("Fletcher16Mod256"),
            Checksum::Crc8(c) => f.debug_tuple("Crc8").field(c).finish(),
            Checksum::Crc16(c) => f.debug_tuple("Crc16").field(c).finish(),
            Checksum::Crc32(c) => f.debug_tuple("Crc32").field(c).finish(),
            Checksum::Crc64(c) => f.debug_tuple("Crc64").field(c).finish(),
            Checksum::Extra(e) => f.debug_tuple("Extra").field(e).finish(),
            Checksum::Object { check, .. } => fmt::Debug::fmt(check, f),
        }
    }
}

// `compute` and `compute_prefix` (and `CrcImpl`'s `checksum` and `checksum_prefix`) are
// `#[inline(always)]` dispatchers over out-of-line per-algorithm functions: where the
// `Checksum` is a constant (a generated layout), only the algorithm it names is linked, which
// matters for firmware flash (at `opt-level = "s"` a plain `#[inline]` dispatcher stays out of
// line and links every table size of its width).
impl Checksum<'_> {
    /// Bytes of the stored check value: 1 for the 8-bit sums and xors, 2 for the 16-bit sums
    /// and the Fletcher pairs, and for a CRC the fewest whole bytes that hold its width
    /// ([`crc_bytes`]: 1 for a CRC-8, 3 for a CRC-24).
    ///
    /// Always inlined and not recursive: every check the engine verifies reads it, and where
    /// the `Checksum` is a constant it folds to a number. (The compiler does not inline a
    /// recursive function: a call per check and frame in the engine's scan, 24 instructions
    /// per referee frame in `benches/count.sh`.)
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub const fn width(&self) -> usize {
        match self {
            Checksum::Extra(e) => e.crc.width_of_crc(),
            other => other.width_of_crc(),
        }
    }

    /// [`width`](Self::width) of a checksum that is not an [`Extra`] (an [`Extra`] holds no
    /// other [`Extra`]: 0 for one).
    #[cfg_attr(not(protocol_opt0), inline(always))]
    const fn width_of_crc(&self) -> usize {
        match self {
            Checksum::Sum8 | Checksum::SumMod255 | Checksum::Xor8 | Checksum::Xor { .. } => 1,
            Checksum::Sum { width: 1, .. } => 1,
            Checksum::Sum { .. } => 2,
            Checksum::Fletcher16 | Checksum::Fletcher16Mod256 => 2,
            Checksum::Crc8(c) => c.stored_bytes(),
            Checksum::Crc16(c) => c.stored_bytes(),
            Checksum::Crc32(c) => c.stored_bytes(),
            Checksum::Crc64(c) => c.stored_bytes(),
            Checksum::Object { width, .. } => *width as usize,
            Checksum::Extra(_) => 0,
        }
    }

    /// The check value of `data`, in the low [`width`](Self::width) bytes of the result.
    ///
    /// ```
    /// use protocol_runtime::Checksum;
    ///
    /// assert_eq!(Checksum::Sum8.compute(&[0xFF, 0x02]), 0x01);
    /// assert_eq!(Checksum::Xor8.compute(&[0x0F, 0xF0]), 0xFF);
    /// ```
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub fn compute(&self, data: &[u8]) -> u64 {
        // The sums, xors and Fletcher checks are listed once, in `compute_sum`.
        if let Some(value) = self.compute_sum(data) {
            return value;
        }
        match self {
            Checksum::Crc8(c) => u64::from(c.checksum(data)),
            Checksum::Crc16(c) => u64::from(c.checksum(data)),
            Checksum::Crc32(c) => u64::from(c.checksum(data)),
            Checksum::Crc64(c) => c.checksum(data),
            Checksum::Extra(e) => match e.byte(data) {
                Some(byte) => e.fold(data, byte),
                None => e.crc.compute_plain(data),
            },
            Checksum::Object { check, .. } => check.compute(data),
            // `compute_sum` answered every other kind above.
            _ => 0,
        }
    }

    /// [`compute`](Self::compute) of bytes the caller has just written (an encoder's frame):
    /// the same value, with a CRC's tables even in a build with the carry-less folding
    /// ([`Slicing16::checksum_written`] says why).
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub fn compute_written(&self, data: &[u8]) -> u64 {
        match self {
            Checksum::Crc8(c) => u64::from(c.checksum_written(data)),
            Checksum::Crc16(c) => u64::from(c.checksum_written(data)),
            Checksum::Crc32(c) => u64::from(c.checksum_written(data)),
            Checksum::Crc64(c) => c.checksum_written(data),
            Checksum::Extra(e) => match e.byte(data) {
                Some(byte) => e.fold_written(data, byte),
                None => e.crc.compute_plain(data),
            },
            other => other.compute(data),
        }
    }

    /// [`compute`](Self::compute) of a checksum inside an [`Extra`] (0 for another
    /// [`Extra`], which it never holds).
    #[inline]
    fn compute_plain(&self, data: &[u8]) -> u64 {
        match self {
            Checksum::Extra(_) => 0,
            other => other.compute(data),
        }
    }

    /// The check value of `data[..n]`, in the low [`width`](Self::width) bytes of the result,
    /// or `None` if `data` is shorter than `n`.
    ///
    /// `data` may run past `n`, and bytes past `n` never change the result, but they let the
    /// computation read fixed-size blocks: the sums and xor read a whole 128-byte window under
    /// a mask when `data` holds 128 bytes and `n <= 128` (no loop or branch that follows `n`),
    /// and a [`CrcImpl::Table16`] CRC reads its first 16-byte block whole. A decoder passes the
    /// rest of its input from the candidate's start.
    ///
    /// ```
    /// use protocol_runtime::Checksum;
    ///
    /// let input = [0x01, 0x02, 0x03, 0xAA, 0xBB];
    /// assert_eq!(Checksum::Sum8.compute_prefix(&input, 3), Some(0x06));
    /// assert_eq!(Checksum::Sum8.compute_prefix(&input, 6), None);
    /// ```
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub fn compute_prefix(&self, data: &[u8], n: usize) -> Option<u64> {
        if data.len() < n {
            return None;
        }
        Some(match self {
            Checksum::Sum8 => u64::from(sum::sum8_prefix(data, n)),
            Checksum::SumMod255 => u64::from(sum::sum_mod255_prefix(data, n)),
            Checksum::Xor8 => u64::from(sum::xor8_prefix(data, n)),
            Checksum::Xor { init } => u64::from(sum::xor8_prefix(data, n) ^ init),
            Checksum::Sum { .. } | Checksum::Fletcher16 | Checksum::Fletcher16Mod256 => {
                self.compute(data.get(..n).unwrap_or(data))
            }
            Checksum::Crc8(c) => u64::from(c.checksum_prefix(data, n)),
            Checksum::Crc16(c) => u64::from(c.checksum_prefix(data, n)),
            Checksum::Crc32(c) => u64::from(c.checksum_prefix(data, n)),
            Checksum::Crc64(c) => c.checksum_prefix(data, n),
            Checksum::Extra(e) => return e.compute_prefix(data, n),
            Checksum::Object { check, .. } => return check.compute_prefix(data, n),
        })
    }
}
