//! What a check computes, as a value: [`Algorithm`].
//!
//! This module owns the description of a check algorithm that a spec's validation decides and
//! every backend takes as it is: the expansion prints it as a [`Checksum`] constant with its
//! table in a `static`, and the run-time codec builds the same [`Checksum`] from it with tables
//! it owns. Computing a check is [`Checksum`]'s business; an [`Algorithm`] holds no table, so
//! it is a plain value (`Copy`, comparable, owned by an IR).

use super::Checksum;

/// A check algorithm, without tables.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Algorithm {
    /// [`Checksum::Sum8`].
    Sum8,
    /// [`Checksum::SumMod255`].
    SumMod255,
    /// [`Checksum::Xor8`].
    Xor8,
    /// [`Checksum::Sum`]: the sum of `init` and the bytes modulo 2^(8 × `width`), xored with
    /// `xorout`.
    Sum {
        /// Bytes of the stored value: 1 or 2.
        width: u8,
        /// The value the sum starts from (a seed).
        init: u16,
        /// Xored into the sum (all ones: the one's complement).
        xorout: u16,
    },
    /// [`Checksum::Xor`]: the XOR of the bytes, starting from `init`.
    Xor {
        /// The value the XOR starts from (a seed).
        init: u8,
    },
    /// [`Checksum::Fletcher16`].
    Fletcher16,
    /// [`Checksum::Fletcher16Mod256`].
    Fletcher16Mod256,
    /// An 8-bit CRC.
    Crc8(CrcSpec<u8>),
    /// A 16-bit CRC.
    Crc16(CrcSpec<u16>),
    /// A 32-bit CRC.
    Crc32(CrcSpec<u32>),
    /// A 64-bit CRC.
    Crc64(CrcSpec<u64>),
}

/// A CRC: its parameters as the [`crc`] crate takes them, and the table it is computed with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CrcSpec<W: crc::Width> {
    /// The parameters (Rocksoft model).
    pub params: crc::Algorithm<W>,
    /// The table size.
    pub table: CrcTable,
}

/// The table a CRC is computed with (see the [module docs](super) for the trade-off).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum CrcTable {
    /// [`CrcImpl::NoTable`](super::CrcImpl::NoTable).
    NoTable,
    /// [`CrcImpl::Table1`](super::CrcImpl::Table1).
    Table1,
    /// [`CrcImpl::Table16`](super::CrcImpl::Table16).
    Table16,
    /// Chosen by the target the code is built for ([`TargetCrc`](super::TargetCrc)):
    /// [`Table16`](Self::Table16) where pointers are 64 bits (a host: speed first), else
    /// [`Table1`](Self::Table1) (a microcontroller: flash first). What a spec that names no
    /// `table` gets.
    ByTarget,
}

impl CrcTable {
    /// Number of 256-entry tables: 0, 1 or 16 (for [`ByTarget`](Self::ByTarget), on the
    /// target this is built for).
    #[inline]
    pub const fn lanes(self) -> usize {
        match self.on_this_target() {
            CrcTable::NoTable => 0,
            CrcTable::Table1 | CrcTable::ByTarget => 1,
            CrcTable::Table16 => 16,
        }
    }

    /// The table size on the target this is built for: [`ByTarget`](Self::ByTarget) resolved
    /// (a run-time codec builds its tables with it), any other unchanged.
    #[inline]
    #[must_use]
    pub const fn on_this_target(self) -> CrcTable {
        match self {
            CrcTable::ByTarget if super::TARGET_TABLE16 => CrcTable::Table16,
            CrcTable::ByTarget => CrcTable::Table1,
            other => other,
        }
    }
}

impl Algorithm {
    /// Bytes of the stored check value (as [`Checksum::width`]).
    ///
    /// ```
    /// use protocol_runtime::checksum::{Algorithm, CrcSpec, CrcTable};
    ///
    /// assert_eq!(Algorithm::Fletcher16Mod256.width(), 2);
    /// assert_eq!(Algorithm::Sum { width: 2, init: 0, xorout: 0xFFFF }.width(), 2);
    /// // A CRC takes the fewest whole bytes that hold its width: a CRC-24 three.
    /// let crc24 = Algorithm::Crc32(CrcSpec { params: crc::CRC_24_OPENPGP, table: CrcTable::Table1 });
    /// assert_eq!(crc24.width(), 3);
    /// ```
    #[inline]
    pub const fn width(&self) -> usize {
        match self {
            Algorithm::Sum8 | Algorithm::SumMod255 | Algorithm::Xor8 | Algorithm::Xor { .. } => 1,
            Algorithm::Sum { width, .. } => *width as usize,
            Algorithm::Fletcher16 | Algorithm::Fletcher16Mod256 => 2,
            Algorithm::Crc8(c) => super::crc_bytes(c.params.width),
            Algorithm::Crc16(c) => super::crc_bytes(c.params.width),
            Algorithm::Crc32(c) => super::crc_bytes(c.params.width),
            Algorithm::Crc64(c) => super::crc_bytes(c.params.width),
        }
    }

    /// The [`Checksum`] of an algorithm that needs no table; `None` for a CRC, whose table
    /// the caller builds (a `static` in generated code, an owned object in the run-time
    /// codec).
    ///
    /// ```
    /// use protocol_runtime::checksum::Algorithm;
    ///
    /// let dynamixel = Algorithm::Sum { width: 1, init: 0, xorout: 0xFF }.tableless().unwrap();
    /// assert_eq!(dynamixel.compute(&[0x01, 0x02, 0x01]), 0xFB);
    /// ```
    #[inline]
    pub const fn tableless(&self) -> Option<Checksum<'static>> {
        Some(match *self {
            Algorithm::Sum8 => Checksum::Sum8,
            Algorithm::SumMod255 => Checksum::SumMod255,
            Algorithm::Xor8 => Checksum::Xor8,
            Algorithm::Sum {
                width,
                init,
                xorout,
            } => Checksum::Sum {
                width,
                init,
                xorout,
            },
            Algorithm::Xor { init } => Checksum::Xor { init },
            Algorithm::Fletcher16 => Checksum::Fletcher16,
            Algorithm::Fletcher16Mod256 => Checksum::Fletcher16Mod256,
            Algorithm::Crc8(_)
            | Algorithm::Crc16(_)
            | Algorithm::Crc32(_)
            | Algorithm::Crc64(_) => {
                return None;
            }
        })
    }

    /// The table of a CRC; `None` for the other algorithms.
    #[inline]
    pub const fn crc_table(&self) -> Option<CrcTable> {
        match self {
            Algorithm::Crc8(c) => Some(c.table),
            Algorithm::Crc16(c) => Some(c.table),
            Algorithm::Crc32(c) => Some(c.table),
            Algorithm::Crc64(c) => Some(c.table),
            _ => None,
        }
    }
}
