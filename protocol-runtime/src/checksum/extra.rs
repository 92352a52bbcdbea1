//! A CRC that folds in one more byte after the bytes it covers, the byte picked by a key read
//! from those bytes: [`Extra`] (MAVLink's CRC_EXTRA, one byte per message id).
//!
//! This module owns looking the byte up and folding it in. Which key field and which table
//! come from the spec is validation's business; where the check sits is the layout's.
//!
//! The byte of a small key is read from a table indexed by the key ([`Extra::direct`], built
//! in a `const` by [`direct_table`]): one load, where a binary search of the pairs costs a
//! branch per halving that the keys of a mixed stream mispredict. Larger keys (MAVLink's
//! ids from 256 on) are searched among the sorted pairs ([`Extra::bytes`]).

use super::{Checksum, CrcImpl};
use crate::layout::WordField;

/// A CRC over the covered bytes, then one byte that the value of `key` picks from `bytes`.
///
/// A key without a byte cannot be verified: [`Checksum::compute_prefix`] gives `None` for it
/// (a decoder rejects the candidate as a bad check and resumes its search at the next byte),
/// and [`Checksum::compute`], which encoders call for the keys they know, gives the CRC of
/// the covered bytes alone.
///
/// ```
/// use protocol_runtime::checksum::{Checksum, CrcImpl, Extra};
/// use protocol_runtime::layout::{ByteOrder, Pos, WordField};
///
/// static CRC: crc::Crc<u16, crc::Table<1>> = crc::Crc::<u16, crc::Table<1>>::new(&crc::CRC_16_MCRF4XX);
/// // MAVLink v1: the CRC covers LEN..payload; the message id is its fifth byte.
/// static EXTRA: Extra<'static> = Extra {
///     crc: Checksum::Crc16(CrcImpl::Table1(&CRC)),
///     key: WordField { at: Pos::Start(4), size: 1, order: ByteOrder::Little, shift: 0, width: 8 },
///     direct: &[],
///     bytes: &[(0, 50)],
/// };
/// let check = Checksum::Extra(&EXTRA);
/// // HEARTBEAT (id 0, CRC_EXTRA 50): `FE 09 4E 01 01 00 00 00 00 00 02 03 51 04 03 1C 7F`.
/// let covered = [0x09, 0x4E, 0x01, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x02, 0x03, 0x51, 0x04, 0x03];
/// assert_eq!(check.compute_prefix(&covered, covered.len()), Some(0x7F1C));
/// let mut unknown = covered;
/// unknown[4] = 7;
/// assert_eq!(check.compute_prefix(&unknown, unknown.len()), None);
/// ```
#[derive(Debug, Clone, Copy)]
pub struct Extra<'a> {
    /// The CRC (any other checksum folds no byte).
    pub crc: Checksum<'a>,
    /// Where the key sits, from the first covered byte.
    pub key: WordField,
    /// The bytes of the keys below `direct.len()`, indexed by key: `0x100 | byte` for a key
    /// with a byte, 0 for one without ([`direct_table`] builds it from pairs).
    pub direct: &'a [u16],
    /// `(key, byte)` pairs of the keys from `direct.len()` on, sorted by key.
    pub bytes: &'a [(u32, u8)],
}

/// The [`Extra::direct`] table of `N` entries for `(key, byte)` pairs whose keys are below `N`
/// (a pair with a larger key is left out: it belongs in [`Extra::bytes`]). Evaluated in a
/// `const`, so that generated code prints the pairs and not the table.
///
/// ```
/// use protocol_runtime::checksum::direct_table;
///
/// const DIRECT: [u16; 4] = direct_table(&[(0, 50), (3, 0), (300, 7)]);
/// assert_eq!(DIRECT, [0x100 | 50, 0, 0, 0x100]);
/// ```
#[must_use]
pub const fn direct_table<const N: usize>(pairs: &[(u32, u8)]) -> [u16; N] {
    let mut table = [0u16; N];
    fill_direct(&mut table, pairs);
    table
}

/// Writes the entry of each pair whose key is below `table.len()` into `table` (as
/// [`direct_table`], into a table whose length is known at run time: the run-time codec's).
///
/// ```
/// use protocol_runtime::checksum::fill_direct;
///
/// let mut table = [0u16; 2];
/// fill_direct(&mut table, &[(1, 9), (2, 7)]);
/// assert_eq!(table, [0, 0x109]);
/// ```
// Each index is checked against the length it indexes (`i` against the pairs', the key
// against the table's), and `i` stays below the pairs' length, which a slice keeps below
// `usize::MAX`.
#[allow(clippy::indexing_slicing, clippy::arithmetic_side_effects)]
pub const fn fill_direct(table: &mut [u16], pairs: &[(u32, u8)]) {
    let mut i = 0;
    while i < pairs.len() {
        let (key, byte) = pairs[i];
        // Compared as `u64`, so that no key is cut short to fit a `usize`.
        if (key as u64) < (table.len() as u64) {
            table[key as usize] = 0x100 | byte as u16;
        }
        i += 1;
    }
}

impl Extra<'_> {
    /// The byte of the key the covered bytes `data` hold, if it has one.
    ///
    /// One load from [`direct`](Self::direct) for a key below its length, else a binary
    /// search of [`bytes`](Self::bytes): O(log n) in the number of larger keys.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub fn byte(&self, data: &[u8]) -> Option<u8> {
        let key = self.key.read(data)?;
        if let Some(&entry) = usize::try_from(key).ok().and_then(|k| self.direct.get(k)) {
            // The high byte marks a key with a byte; the low one is the byte.
            return (entry >> 8 != 0).then_some(entry as u8);
        }
        let key = u32::try_from(key).ok()?;
        let at = self.bytes.binary_search_by_key(&key, |&(k, _)| k).ok()?;
        self.bytes.get(at).map(|&(_, b)| b)
    }

    /// The CRC of `data`, then `byte`.
    #[inline]
    pub fn fold(&self, data: &[u8], byte: u8) -> u64 {
        self.fold_prefix(data, data.len(), byte)
    }

    /// The CRC of `data[..n]`, then `byte`; `data` may run past `n` (as in
    /// [`Checksum::compute_prefix`], the bytes after `n` let a block be read whole).
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub fn fold_prefix(&self, data: &[u8], n: usize, byte: u8) -> u64 {
        match &self.crc {
            Checksum::Crc8(c) => u64::from(c.checksum_prefix_then(data, n, byte)),
            Checksum::Crc16(c) => u64::from(c.checksum_prefix_then(data, n, byte)),
            Checksum::Crc32(c) => u64::from(c.checksum_prefix_then(data, n, byte)),
            Checksum::Crc64(c) => c.checksum_prefix_then(data, n, byte),
            other => other.compute(data.get(..n).unwrap_or(data)),
        }
    }

    /// [`fold`](Self::fold) of bytes the caller has just written (an encoder's frame):
    /// the same value, with a CRC's tables even in a build with the carry-less folding.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub fn fold_written(&self, data: &[u8], byte: u8) -> u64 {
        match &self.crc {
            Checksum::Crc8(c) => u64::from(c.checksum_written_then(data, byte)),
            Checksum::Crc16(c) => u64::from(c.checksum_written_then(data, byte)),
            Checksum::Crc32(c) => u64::from(c.checksum_written_then(data, byte)),
            Checksum::Crc64(c) => c.checksum_written_then(data, byte),
            other => other.compute(data),
        }
    }

    /// The check value of `data`: `None` when its key has no byte.
    #[inline]
    pub fn compute(&self, data: &[u8]) -> Option<u64> {
        Some(self.fold(data, self.byte(data)?))
    }

    /// The check value of `data[..n]`: `None` when `data` is shorter than `n` or the key of
    /// `data[..n]` has no byte.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub fn compute_prefix(&self, data: &[u8], n: usize) -> Option<u64> {
        let byte = self.byte(data.get(..n)?)?;
        Some(self.fold_prefix(data, n, byte))
    }
}

macro_rules! checksum_then {
    ($($w:ty),*) => {$(
        impl CrcImpl<'_, $w> {
            #[doc = concat!("The CRC of `data[..n]` then `byte`, as a `", stringify!($w), "`;")]
            /// `data` may run past `n`.
            ///
            /// A [`CrcImpl::Table16`] computes the covered bytes as
            /// [`checksum_prefix`](Self::checksum_prefix) does (blocks, or the carry-less
            /// folding where built in) and appends the byte with one table step
            /// ([`Slicing16::then`](super::Slicing16::then)); the one-table and table-free
            /// CRCs run the `crc` crate's streaming digest.
            #[cfg_attr(not(protocol_opt0), inline(always))]
            pub fn checksum_prefix_then(&self, data: &[u8], n: usize, byte: u8) -> $w {
                let covered = data.get(..n).unwrap_or(data);
                match self {
                    CrcImpl::NoTable(c) => {
                        let mut d = c.digest();
                        d.update(covered);
                        d.update(&[byte]);
                        d.finalize()
                    }
                    CrcImpl::Table1(c) => {
                        let mut d = c.digest();
                        d.update(covered);
                        d.update(&[byte]);
                        d.finalize()
                    }
                    CrcImpl::Table16(c) => c.checksum_prefix_then(data, n, byte),
                }
            }

            #[doc = concat!("The CRC of `data` then `byte`, as a `", stringify!($w), "`.")]
            #[inline]
            pub fn checksum_then(&self, data: &[u8], byte: u8) -> $w {
                self.checksum_prefix_then(data, data.len(), byte)
            }

            /// [`checksum_then`](Self::checksum_then) of bytes the caller has just written:
            /// never with the carry-less folding ([`Slicing16::checksum_written`](super::Slicing16::checksum_written)).
            #[cfg_attr(not(protocol_opt0), inline(always))]
            pub fn checksum_written_then(&self, data: &[u8], byte: u8) -> $w {
                match self {
                    CrcImpl::Table16(c) => c.checksum_written_then(data, byte),
                    other => other.checksum_then(data, byte),
                }
            }
        }
    )*};
}
checksum_then!(u8, u16, u32, u64);
