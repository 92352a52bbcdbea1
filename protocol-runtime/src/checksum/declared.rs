//! A check computed as the layout type of its link declares the link's checks
//! ([`LayoutRef::CRC_CHECKED`]): where the type declares no CRC, only the sums, xors and
//! Fletcher checks are reached, so an unoptimised build (where a `match` over a `Checksum`
//! keeps every arm) links none of the CRCs.

use super::{Checksum, fletcher, sum};
use crate::layout::LayoutRef;

impl Checksum<'_> {
    /// [`compute_prefix`](Self::compute_prefix) on a link of layout type `L`: `None` for a
    /// CRC, a check with a per-command byte or a checksum object where `L` declares none.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub(crate) fn compute_prefix_of<L: LayoutRef>(&self, data: &[u8], n: usize) -> Option<u64> {
        if L::CRC_CHECKED {
            return self.compute_prefix(data, n);
        }
        // The arms of `compute_prefix` for these kinds.
        let covered = data.get(..n)?;
        Some(match self {
            Checksum::Sum8 => u64::from(sum::sum8_prefix(data, n)),
            Checksum::SumMod255 => u64::from(sum::sum_mod255_prefix(data, n)),
            Checksum::Xor8 => u64::from(sum::xor8_prefix(data, n)),
            Checksum::Xor { init } => u64::from(sum::xor8_prefix(data, n) ^ init),
            other => return other.compute_sum(covered),
        })
    }

    /// [`compute_written`](Self::compute_written) on a link of layout type `L`, as
    /// [`compute_prefix_of`](Self::compute_prefix_of).
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub(crate) fn compute_written_of<L: LayoutRef>(&self, data: &[u8]) -> Option<u64> {
        if L::CRC_CHECKED {
            Some(self.compute_written(data))
        } else {
            self.compute_sum(data)
        }
    }

    /// The check value of the sums, xors and Fletcher checks (the one list of them, which
    /// [`compute`](Self::compute) takes too); `None` for the other kinds.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub(crate) fn compute_sum(&self, data: &[u8]) -> Option<u64> {
        Some(match self {
            Checksum::Sum8 => u64::from(sum::sum8(data)),
            Checksum::SumMod255 => u64::from(sum::sum_mod255(data)),
            Checksum::Xor8 => u64::from(sum::xor8(data)),
            Checksum::Sum {
                width,
                init,
                xorout,
            } => sum::sum_xorout(data, *width, *init, *xorout),
            Checksum::Xor { init } => u64::from(sum::xor8(data) ^ init),
            Checksum::Fletcher16 => u64::from(fletcher::fletcher16(data)),
            Checksum::Fletcher16Mod256 => u64::from(fletcher::fletcher16_mod256(data)),
            _ => return None,
        })
    }
}
