//! Slicing-by-16 CRCs without a byte-wise loop: [`Slicing16`].
//!
//! This module owns the fast table-driven CRC and which of its inputs go to a faster path built
//! beside it (the `crc-fast` crate from 128 bytes on, the carry-less folding of `clmul.rs` from
//! 9 bytes on, each where its feature is on); which CRC a check uses and the smaller table
//! choices (`crc::NoTable`, `crc::Table<1>`) are the parent module's business.
//!
//! We do not use the `crc` crate's `Table<16>`: it runs a byte-wise loop over the last
//! `n % 16` bytes, and a loop whose trip count follows the frame length mispredicts its exit
//! about once per frame, since the length changes from one frame to the next (see
//! BENCHMARKS.md). Here the leading `n % 16` bytes are one zero-padded 16-byte block and
//! everything after them whole blocks.
//!
//! # How
//!
//! The register is kept as the `crc` crate keeps it: in the low `width` bits when the input is
//! reflected (`refin`, the register shifts right), in the high `width` bits otherwise (it
//! shifts left). A CRC register update is linear, so the register after a 16-byte block `b`
//! from register `r` is the xor, over the block's bytes, of `T[15 - i][b[i] ^ r[i]]`, where
//! `r[i]` are the register's bytes in the order they meet the input (little-endian when
//! reflected, big-endian otherwise; zero past the register's size) and `T[k][v]` is the
//! register after the byte `v` then `k` zero bytes, from a zero register.
//!
//! Leading zero bytes leave a zero register zero, so a first block of `lead` bytes (1..=16) is
//! read as `16 - lead` zero bytes then those bytes. The initial register is folded into the
//! first `lead` bytes; when the register is wider than `lead` bytes, the part that does not
//! meet an input byte is what the register still holds after them, shifted by `lead` bytes.

use core::fmt;

/// Bytes per block, and number of tables.
const BLOCK: usize = 16;

/// A slicing-by-16 CRC: sixteen 256-entry tables of `W`, built at compile time from a
/// `crc` crate [`Algorithm`](crc::Algorithm), computing exactly what
/// `crc::Crc::<W, crc::NoTable>::new(alg).checksum(data)` computes, for any width from 1 to
/// the bits of `W` and any `refin`/`refout`.
///
/// Its size is 16 × 256 × `size_of::<W>()` bytes plus a few words: 4 KiB (`u8`), 8 KiB
/// (`u16`), 16 KiB (`u32`), 32 KiB (`u64`).
///
/// With the `clmul` feature, in a build for an x86-64 CPU with `pclmulqdq`, a reflected CRC of
/// up to 32 bits over more than 8 bytes is folded with carry-less multiplication instead
/// ([`uses_clmul`](Self::uses_clmul)); the value is the same.
///
/// ```
/// use protocol_runtime::checksum::Slicing16;
///
/// static CRC: Slicing16<u16> = Slicing16::<u16>::new(&crc::CRC_16_UMTS);
/// assert_eq!(CRC.checksum(b"123456789"), 0xFEE8);
/// // The CRC of the first 9 bytes; the bytes after them are read but do not count.
/// assert_eq!(CRC.checksum_prefix(b"123456789 and more", 9), 0xFEE8);
/// ```
#[derive(Clone)]
pub struct Slicing16<W: crc::Width> {
    /// `tables[k][v]`: the register after the byte `v` then `k` zero bytes, from zero.
    tables: [[W; 256]; BLOCK],
    /// The parameters, held by value: a CRC built at run time from a loaded spec borrows
    /// nothing that must outlive it.
    algorithm: crc::Algorithm<W>,
    /// The initial register, aligned as the tables are.
    init: W,
    /// Whether the input is reflected (the register shifts right).
    reflect: bool,
    /// Whether the register is reversed at the end (`refin != refout`).
    reverse: bool,
    /// Bits the (possibly reversed) register is shifted right at the end: the unused low bits
    /// of a register kept in the high bits.
    shift: u32,
    xorout: W,
    /// The `crc-fast` algorithm that computes this CRC, if that crate catalogues it.
    #[cfg(feature = "crc-fast")]
    fast: Option<super::fast::CrcAlgorithm>,
    /// The carry-less folding of a reflected CRC (the `clmul` feature, in a build for a CPU
    /// with `pclmulqdq`); always `None`, and no bytes, otherwise.
    folding: Option<super::clmul::Folding>,
    /// Where the compiler does not optimise (cfg `protocol_opt0`, the runtime's build script),
    /// what the public methods call to compute with the tables: the computation is then
    /// linked only where a `Slicing16` of its width is built. A [`CrcImpl`](super::CrcImpl)
    /// matches every table size of every width, and at opt-level 0 nothing folds that match:
    /// called directly, every width's slicing code lands in any firmware that checks a frame
    /// (about 20 KB of the HFLink debug firmware's `.text`, whose spec has no CRC at all;
    /// `docs/performance.md`). Optimised builds call the computation directly, where a
    /// constant layout keeps only what the spec uses.
    #[cfg(protocol_opt0)]
    run: fn(&Self, &[u8], usize, Run) -> W,
}

/// What a [`Slicing16`]'s public methods ask of its computation through its `run` pointer.
#[cfg(protocol_opt0)]
#[derive(Clone, Copy)]
enum Run {
    /// [`Slicing16::checksum_prefix`].
    Prefix,
    /// [`Slicing16::checksum_written`].
    Written,
    /// [`Slicing16::checksum_prefix_then`] of this byte.
    PrefixThen(u8),
    /// [`Slicing16::checksum_written_then`] of this byte.
    WrittenThen(u8),
}

impl<W: crc::Width> Slicing16<W> {
    /// The parameters of the CRC.
    #[inline]
    pub const fn algorithm(&self) -> &crc::Algorithm<W> {
        &self.algorithm
    }
}

impl<W: crc::Width + fmt::Debug> fmt::Debug for Slicing16<W> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Slicing16")
            .field("algorithm", &self.algorithm)
            .finish_non_exhaustive()
    }
}

/// Checks of at most this many bytes are computed byte by byte
/// ([`Slicing16::checksum_prefix`]).
const SHORT: usize = 8;

macro_rules! slicing16_width {
    ($($w:ty => $fast:ident),*) => {$(
        impl Slicing16<$w> {
            #[doc = concat!("The tables of `alg`, a CRC of 1 to ", stringify!($w), "::BITS bits.")]
            ///
            /// Meant for a `static` or `const` initialiser (the tables are then built by the
            /// compiler); at run time it takes a few microseconds. A width outside that range
            /// gives meaningless values, never a panic.
            #[must_use]
            pub const fn new(alg: &crc::Algorithm<$w>) -> Self {
                let pad = <$w>::BITS.saturating_sub(alg.width as u32);
                let (poly, init) = if alg.refin {
                    (
                        shr_or_zero!($w, alg.poly.reverse_bits(), pad),
                        shr_or_zero!($w, alg.init.reverse_bits(), pad),
                    )
                } else {
                    (shl_or_zero!($w, alg.poly, pad), shl_or_zero!($w, alg.init, pad))
                };
                Slicing16 {
                    tables: slicing16_tables!($w, poly, alg.refin),
                    algorithm: *alg,
                    init,
                    reflect: alg.refin,
                    reverse: alg.refin != alg.refout,
                    shift: if alg.refout { 0 } else { pad },
                    xorout: alg.xorout,
                    #[cfg(feature = "crc-fast")]
                    fast: super::fast::$fast(alg),
                    folding: if alg.refin {
                        super::clmul::Folding::new(poly as u64, alg.width)
                    } else {
                        None
                    },
                    #[cfg(protocol_opt0)]
                    run: Self::run,
                }
            }

            /// What the public methods compute, reached through the `run` pointer where the
            /// compiler does not optimise.
            #[cfg(protocol_opt0)]
            fn run(&self, data: &[u8], n: usize, ask: Run) -> $w {
                match ask {
                    Run::Prefix => self.checksum_with::<true>(data, n),
                    Run::Written => self.checksum_with::<false>(data, n),
                    Run::PrefixThen(byte) => self.then(self.checksum_with::<true>(data, n), byte),
                    Run::WrittenThen(byte) => {
                        self.then(self.checksum_with::<false>(data, n), byte)
                    }
                }
            }

            /// Whether the CRCs of 128 bytes or more are computed by the `crc-fast` crate (the
            /// `crc-fast` feature, and a CRC that crate catalogues).
            #[inline]
            pub const fn uses_crc_fast(&self) -> bool {
                #[cfg(feature = "crc-fast")]
                {
                    self.fast.is_some()
                }
                #[cfg(not(feature = "crc-fast"))]
                {
                    false
                }
            }

            /// Whether the CRCs of more than 8 bytes are folded with carry-less multiplication
            /// (the `clmul` feature in a build for a CPU with `pclmulqdq`, and a reflected CRC
            /// of up to 32 bits).
            #[inline]
            pub const fn uses_clmul(&self) -> bool {
                self.folding.is_some()
            }

            /// The CRC of `data`.
            #[inline]
            pub fn checksum(&self, data: &[u8]) -> $w {
                self.checksum_prefix(data, data.len())
            }

            /// The CRC of `data[..n]`; `data` may run past `n` (the bytes after `n` are read,
            /// to load the first block whole, but never change the result). If `data` is
            /// shorter than `n`, the CRC of all of `data`.
            ///
            /// Always inlined: a frame's header check covers a constant number of bytes, and
            /// inlined with it the leading block's zero bytes fold away (a 4-byte header CRC
            /// costs four lookups, not sixteen).
            #[cfg_attr(not(protocol_opt0), inline(always))]
            pub fn checksum_prefix(&self, data: &[u8], n: usize) -> $w {
                #[cfg(protocol_opt0)]
                {
                    (self.run)(self, data, n, Run::Prefix)
                }
                #[cfg(not(protocol_opt0))]
                {
                    self.checksum_with::<true>(data, n)
                }
            }

            /// The CRC of `data`, bytes the caller has just written (an encoder's frame),
            /// without the carry-less folding even where it is built in
            /// ([`uses_clmul`](Self::uses_clmul)): the tables read the bytes one at a time,
            /// loads that the processor serves from the pending stores, while the folding's
            /// 16-byte loads of bytes stored a few at a time wait for the stores to reach the
            /// cache (a store-forwarding stall per block).
            #[cfg_attr(not(protocol_opt0), inline(always))]
            pub fn checksum_written(&self, data: &[u8]) -> $w {
                #[cfg(protocol_opt0)]
                {
                    (self.run)(self, data, data.len(), Run::Written)
                }
                #[cfg(not(protocol_opt0))]
                {
                    self.checksum_with::<false>(data, data.len())
                }
            }

            /// The CRC of `data[..n]` then one more byte, `byte` (as
            /// [`checksum_prefix`](Self::checksum_prefix) of those bytes one after the other):
            /// the covered bytes by the fast path (blocks, the carry-less folding or the
            /// `crc-fast` crate where built in), then one table step ([`then`](Self::then)).
            #[cfg_attr(not(protocol_opt0), inline(always))]
            pub fn checksum_prefix_then(&self, data: &[u8], n: usize, byte: u8) -> $w {
                #[cfg(protocol_opt0)]
                {
                    (self.run)(self, data, n, Run::PrefixThen(byte))
                }
                #[cfg(not(protocol_opt0))]
                {
                    self.then(self.checksum_prefix(data, n), byte)
                }
            }

            /// [`checksum_prefix_then`](Self::checksum_prefix_then) of all of `data`, bytes the
            /// caller has just written (the tables only, as
            /// [`checksum_written`](Self::checksum_written)).
            #[cfg_attr(not(protocol_opt0), inline(always))]
            pub fn checksum_written_then(&self, data: &[u8], byte: u8) -> $w {
                #[cfg(protocol_opt0)]
                {
                    (self.run)(self, data, data.len(), Run::WrittenThen(byte))
                }
                #[cfg(not(protocol_opt0))]
                {
                    self.then(self.checksum_written(data), byte)
                }
            }

            /// The CRC of some bytes whose CRC is `crc`, then `byte`: the finalisation undone
            /// (it is a bijection: the xor, the shift of a register kept in the high bits,
            /// whose low bits are zero, and the reversal), one step of table 0, and the
            /// finalisation again. A byte appended costs one lookup, whatever computed `crc`.
            ///
            /// ```
            /// use protocol_runtime::checksum::Slicing16;
            ///
            /// static CRC: Slicing16<u16> = Slicing16::<u16>::new(&crc::CRC_16_MCRF4XX);
            /// assert_eq!(CRC.then(CRC.checksum(b"12345678"), b'9'), CRC.checksum(b"123456789"));
            /// ```
            #[cfg_attr(not(protocol_opt0), inline(always))]
            pub fn then(&self, crc: $w, byte: u8) -> $w {
                let aligned = (crc ^ self.xorout).checked_shl(self.shift).unwrap_or(0);
                let register = if self.reverse { aligned.reverse_bits() } else { aligned };
                let register = if self.reflect {
                    // The low byte meets the input; the rest moves down a byte.
                    let index = (register as u8) ^ byte;
                    register.checked_shr(8).unwrap_or(0) ^ self.entry(0, index)
                } else {
                    // The high byte meets the input; the rest moves up a byte.
                    let index = (register.checked_shr(<$w>::BITS - 8).unwrap_or(0) as u8) ^ byte;
                    register.checked_shl(8).unwrap_or(0) ^ self.entry(0, index)
                };
                let register = if self.reverse { register.reverse_bits() } else { register };
                register.checked_shr(self.shift).unwrap_or(0) ^ self.xorout
            }

            /// [`checksum_prefix`](Self::checksum_prefix), folded with carry-less
            /// multiplication where the build has it and `FOLD` asks for it.
            #[cfg_attr(not(protocol_opt0), inline(always))]
            fn checksum_with<const FOLD: bool>(&self, data: &[u8], n: usize) -> $w {
                let n = n.min(data.len());
                #[cfg(feature = "crc-fast")]
                if let (Some(fast), true) = (self.fast, n >= super::fast::FAST_FROM) {
                    // The catalogued CRC, as wide as `$w`.
                    return crc_fast::checksum(fast, data.get(..n).unwrap_or(data)) as $w;
                }
                let register = if self.reflect {
                    self.register::<true, FOLD>(data, n)
                } else {
                    self.register::<false, FOLD>(data, n)
                };
                let register = if self.reverse { register.reverse_bits() } else { register };
                register.checked_shr(self.shift).unwrap_or(0) ^ self.xorout
            }

            /// The register after `data[..n]` (`n <= data.len()`), before finalisation.
            #[cfg_attr(not(protocol_opt0), inline(always))]
            fn register<const REFLECT: bool, const FOLD: bool>(&self, data: &[u8], n: usize) -> $w {
                if n <= SHORT {
                    return self.short_register::<REFLECT>(data, n);
                }
                if let (true, true, Some(folding)) = (REFLECT, FOLD, &self.folding) {
                    // The register in the low `width` bits, as the tables keep it.
                    return folding.register(data, n, self.init as u64) as $w;
                }
                // (`n <= data.len()`, the caller's bound: said once, so that the compiler drops
                // the fallback of every slice below.)
                let Some(covered) = data.get(..n) else {
                    return 0;
                };
                // The leading bytes: 1..=16 of them, so that whole blocks follow. (Written so
                // that the compiler sees both bounds: the shift below needs no test of its
                // range.)
                let lead = (n.wrapping_sub(1) & (BLOCK - 1)).wrapping_add(1);
                let first = match data.first_chunk::<BLOCK>() {
                    Some(block) => *block,
                    None => {
                        // Only when all of `data` is shorter than a block.
                        let mut block = [0u8; BLOCK];
                        if let (Some(dst), Some(src)) = (block.get_mut(..n), data.get(..n)) {
                            dst.copy_from_slice(src);
                        }
                        block
                    }
                };
                // Big-endian, input byte `i` sits at bits `8 * (15 - i)`: shifting right by
                // `16 - lead` bytes moves the leading bytes to the end of the block, zeros in
                // front, and drops what `first` held past them.
                let pad = ((!n.wrapping_sub(1) & (BLOCK - 1)) as u32).wrapping_mul(8);
                let aligned = (u128::from_be_bytes(first) ^ Self::spread::<REFLECT>(self.init))
                    .checked_shr(pad)
                    .unwrap_or(0);
                let kept_bits = (lead as u32).wrapping_mul(8);
                let kept = if REFLECT {
                    self.init.checked_shr(kept_bits)
                } else {
                    self.init.checked_shl(kept_bits)
                };
                let mut register = self.block::<REFLECT>(&aligned.to_be_bytes(), 0)
                    ^ kept.unwrap_or(0);
                let rest = covered.get(lead..).unwrap_or_default();
                for block in rest.chunks_exact(BLOCK) {
                    if let Some(block) = block.first_chunk::<BLOCK>() {
                        register = self.block::<REFLECT>(block, register);
                    }
                }
                register
            }

            /// [`register`](Self::register) of at most [`SHORT`] bytes (a header check),
            /// byte by byte: one lookup per byte, the initial register folded into the first
            /// ones. With `n` a constant (a header's span) this is straight-line code over
            /// single-byte loads, which the compiler takes from the stores of an encoder that
            /// has just written the header; a whole-block read of freshly written bytes stalls
            /// on store forwarding.
            #[cfg_attr(not(protocol_opt0), inline(always))]
            fn short_register<const REFLECT: bool>(&self, data: &[u8], n: usize) -> $w {
                let init = if REFLECT {
                    self.init.to_le_bytes()
                } else {
                    self.init.to_be_bytes()
                };
                let mut acc: $w = 0;
                for i in 0..n.min(data.len()) {
                    let byte = data.get(i).copied().unwrap_or(0);
                    let index = byte ^ init.get(i).copied().unwrap_or(0);
                    acc ^= self.entry(n.wrapping_sub(1).wrapping_sub(i), index);
                }
                let kept_bits = (n as u32).wrapping_mul(8);
                let kept = if REFLECT {
                    self.init.checked_shr(kept_bits)
                } else {
                    self.init.checked_shl(kept_bits)
                };
                acc ^ kept.unwrap_or(0)
            }

            /// What a byte of value `index` with `after` more bytes behind it adds to the
            /// register: table `after`'s entry (slicing-by-16 looks up every byte of a block at
            /// once, each in the table of its distance to the block's end).
            #[cfg_attr(not(protocol_opt0), inline(always))]
            fn entry(&self, after: usize, index: u8) -> $w {
                self.tables
                    .get(after)
                    .and_then(|table| table.get(usize::from(index)))
                    .copied()
                    .unwrap_or(0)
            }

            /// The register's bytes in input order, at the start of a big-endian block.
            #[cfg_attr(not(protocol_opt0), inline(always))]
            fn spread<const REFLECT: bool>(register: $w) -> u128 {
                let ordered = if REFLECT { register.swap_bytes() } else { register };
                u128::from(ordered) << (u128::BITS - <$w>::BITS)
            }

            /// The register after the 16 bytes of `block` fed into `register`.
            ///
            /// The register is folded into the block's first bytes byte by byte, with the
            /// block read straight from the input: the register is what each block waits for,
            /// and folding it into a 128-bit copy of the block first put a store and reloads of
            /// the copy on that path.
            #[cfg_attr(not(protocol_opt0), inline(always))]
            fn block<const REFLECT: bool>(&self, block: &[u8; BLOCK], register: $w) -> $w {
                let folded = if REFLECT {
                    register.to_le_bytes()
                } else {
                    register.to_be_bytes()
                };
                let lookup = |k: usize, index: u8| self.entry(BLOCK.wrapping_sub(1).wrapping_sub(k), index);
                let byte = |k: usize| block.get(k).copied().unwrap_or(0);
                // Loops over indices, not zipped iterators (here and in `short_register`): in a
                // large caller (the benchmark binary) the compiler leaves `Zip::next` out of
                // line, a call per byte through memory.
                //
                // The bytes the register is not folded into first: their lookups do not wait
                // for the register, so only the last few xors below do.
                let mut acc: $w = 0;
                for k in folded.len()..BLOCK {
                    acc ^= lookup(k, byte(k));
                }
                for k in 0..folded.len() {
                    let r = folded.get(k).copied().unwrap_or(0);
                    acc ^= lookup(k, byte(k) ^ r);
                }
                acc
            }
        }
    )*};
}

/// `$x >> $n`, zero when `$n` is the width or more (`checked_shr` in a `const fn`).
macro_rules! shr_or_zero {
    ($w:ty, $x:expr, $n:expr) => {
        match <$w>::checked_shr($x, $n) {
            Some(v) => v,
            None => 0,
        }
    };
}

/// `$x << $n`, zero when `$n` is the width or more.
macro_rules! shl_or_zero {
    ($w:ty, $x:expr, $n:expr) => {
        match <$w>::checked_shl($x, $n) {
            Some(v) => v,
            None => 0,
        }
    };
}

/// The sixteen tables of the aligned polynomial `$poly` (reflected when `$reflect`).
macro_rules! slicing16_tables {
    ($w:ty, $poly:expr, $reflect:expr) => {{
        // Indexing and the loop counters only run in a `const` initialiser or in `new`, with
        // every index a counter bounded by the array it indexes: an index out of bounds would
        // fail to compile (const) or could not happen (run time).
        #[allow(clippy::indexing_slicing, clippy::arithmetic_side_effects)]
        const fn build(poly: $w, reflect: bool) -> [[$w; 256]; BLOCK] {
            const TOP: $w = 1 << (<$w>::BITS - 1);
            let mut tables = [[0; 256]; BLOCK];
            // Table 0: one byte, bit by bit.
            let mut v = 0;
            while v < 256 {
                let mut r: $w = if reflect {
                    v as $w
                } else {
                    shl_or_zero!($w, v as $w, <$w>::BITS - 8)
                };
                let mut bit = 0;
                while bit < 8 {
                    r = if reflect {
                        if r & 1 != 0 { (r >> 1) ^ poly } else { r >> 1 }
                    } else if r & TOP != 0 {
                        (r << 1) ^ poly
                    } else {
                        r << 1
                    };
                    bit += 1;
                }
                tables[0][v] = r;
                v += 1;
            }
            // Table k: table k - 1 followed by one zero byte.
            let mut k = 1;
            while k < BLOCK {
                let mut v = 0;
                while v < 256 {
                    let prev = tables[k - 1][v];
                    tables[k][v] = if reflect {
                        shr_or_zero!($w, prev, 8) ^ tables[0][(prev & 0xFF) as usize]
                    } else {
                        shl_or_zero!($w, prev, 8) ^ tables[0][(prev >> (<$w>::BITS - 8)) as usize]
                    };
                    v += 1;
                }
                k += 1;
            }
            tables
        }
        build($poly, $reflect)
    }};
}

slicing16_width!(u8 => crc8, u16 => crc16, u32 => crc32, u64 => crc64);
