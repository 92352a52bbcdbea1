//! A spec's frame formats as runtime [`FrameLayout`] values: the same data the generated
//! `LAYOUT` statics hold (`protocol-codegen/src/codegen/frame.rs` emits them as tokens, this
//! module builds them as values), so the interpreter and generated code run the same engine on
//! the same description.
//!
//! This module owns the CRC objects a layout's checks borrow ([`CrcStore`]) and the per-frame
//! slices of checks, constants and markers ([`FrameParts`]). Which bytes a check covers and how
//! a frame is verified or sealed is the runtime's business.

use std::sync::Mutex;

use protocol_codegen::ir::{self, Algorithm, CrcParams, HeaderValue, Length, Role};
use protocol_runtime::checksum::{Checksum, CrcImpl, Slicing16};
use protocol_runtime::layout::{Check, Constant, FrameLayout, LengthRule, Marker, WordField};

/// Where a header value sits, as the runtime reads and writes it (the generated `wire::NAME`).
pub fn word_field(v: &HeaderValue) -> WordField {
    WordField {
        at: v.at,
        size: v.word.prim.size() as u8,
        order: v.word.endian,
        shift: v.shift as u8,
        width: v.width as u8,
    }
}

/// `crc::Crc::new` takes a `&'static crc::Algorithm`. A spec's parameters are only known at
/// run time, so each distinct parameter set is leaked once per process and reused: memory is
/// bounded by the number of distinct CRC algorithms, however many specs are loaded.
macro_rules! interned_algorithm {
    ($name:ident, $w:ty) => {
        fn $name(p: &CrcParams) -> &'static crc::Algorithm<$w> {
            static CACHE: Mutex<Vec<&'static crc::Algorithm<$w>>> = Mutex::new(Vec::new());
            // The parameters come from a checked IR and fit the width; `as` keeps their bits.
            let wanted = crc::Algorithm::<$w> {
                width: p.width,
                poly: p.poly as $w,
                init: p.init as $w,
                refin: p.refin,
                refout: p.refout,
                xorout: p.xorout as $w,
                check: p.check as $w,
                residue: p.residue as $w,
            };
            // A poisoned lock only means another thread panicked while pushing: the list is
            // still a list of valid algorithms.
            let mut cache = CACHE.lock().unwrap_or_else(|e| e.into_inner());
            let same = |a: &crc::Algorithm<$w>| {
                (
                    a.width, a.poly, a.init, a.refin, a.refout, a.xorout, a.check, a.residue,
                ) == (
                    wanted.width,
                    wanted.poly,
                    wanted.init,
                    wanted.refin,
                    wanted.refout,
                    wanted.xorout,
                    wanted.check,
                    wanted.residue,
                )
            };
            if let Some(found) = cache.iter().find(|a| same(a)) {
                return found;
            }
            let leaked: &'static crc::Algorithm<$w> = Box::leak(Box::new(wanted));
            cache.push(leaked);
            leaked
        }
    };
}

interned_algorithm!(algorithm8, u8);
interned_algorithm!(algorithm16, u16);
interned_algorithm!(algorithm32, u32);
interned_algorithm!(algorithm64, u64);

/// A CRC object of one width, with the table size the spec chose (as generated code builds):
/// the `crc` crate's for no table and one table, the runtime's [`Slicing16`] for sixteen.
enum Tables<W: crc::Width> {
    NoTable(Box<crc::Crc<W, crc::NoTable>>),
    Table1(Box<crc::Crc<W, crc::Table<1>>>),
    Table16(Box<Slicing16<W>>),
}

impl<W: crc::Width> Tables<W> {
    fn as_impl(&self) -> CrcImpl<'_, W> {
        match self {
            Tables::NoTable(c) => CrcImpl::NoTable(c),
            Tables::Table1(c) => CrcImpl::Table1(c),
            Tables::Table16(c) => CrcImpl::Table16(c),
        }
    }
}

macro_rules! tables {
    ($w:ty, $alg:expr, $table:expr) => {{
        let alg = $alg;
        match $table {
            0 => Tables::NoTable(Box::new(crc::Crc::<$w, crc::NoTable>::new(alg))),
            1 => Tables::Table1(Box::new(crc::Crc::<$w, crc::Table<1>>::new(alg))),
            _ => Tables::Table16(Box::new(Slicing16::<$w>::new(alg))),
        }
    }};
}

/// The CRC object of one check.
enum CrcObject {
    W8(Tables<u8>),
    W16(Tables<u16>),
    W32(Tables<u32>),
    W64(Tables<u64>),
}

impl CrcObject {
    fn new(p: &CrcParams) -> Self {
        match p.width {
            8 => CrcObject::W8(tables!(u8, algorithm8(p), p.table)),
            16 => CrcObject::W16(tables!(u16, algorithm16(p), p.table)),
            32 => CrcObject::W32(tables!(u32, algorithm32(p), p.table)),
            _ => CrcObject::W64(tables!(u64, algorithm64(p), p.table)),
        }
    }

    fn checksum(&self) -> Checksum<'_> {
        match self {
            CrcObject::W8(t) => Checksum::Crc8(t.as_impl()),
            CrcObject::W16(t) => Checksum::Crc16(t.as_impl()),
            CrcObject::W32(t) => Checksum::Crc32(t.as_impl()),
            CrcObject::W64(t) => Checksum::Crc64(t.as_impl()),
        }
    }
}

/// The CRC objects of every check of every frame format of a spec, owned so that layouts can
/// borrow them.
pub struct CrcStore {
    /// `crcs[frame][check]`: the CRC of a check, `None` for sums and xor.
    crcs: Vec<Vec<Option<CrcObject>>>,
}

impl CrcStore {
    /// Builds the CRC objects of every check of `p`.
    pub fn new(p: &ir::Protocol) -> Self {
        let crcs = p
            .frames
            .iter()
            .map(|f| {
                f.checks
                    .iter()
                    .map(|c| match &c.algorithm {
                        Algorithm::Crc(params) => Some(CrcObject::new(params)),
                        Algorithm::Sum { .. } | Algorithm::Xor => None,
                    })
                    .collect()
            })
            .collect();
        CrcStore { crcs }
    }

    fn checksum(&self, frame: usize, check: usize, algorithm: &Algorithm) -> Checksum<'_> {
        match algorithm {
            Algorithm::Sum { modulus: 255 } => Checksum::SumMod255,
            Algorithm::Sum { .. } => Checksum::Sum8,
            Algorithm::Xor => Checksum::Xor8,
            Algorithm::Crc(_) => match self
                .crcs
                .get(frame)
                .and_then(|f| f.get(check))
                .and_then(Option::as_ref)
            {
                Some(crc) => crc.checksum(),
                // Unreachable: the store was built from the same protocol.
                None => Checksum::Sum8,
            },
        }
    }
}

/// The slices a [`FrameLayout`] borrows, for one frame format.
pub struct FrameParts<'a> {
    frame: &'a ir::Frame,
    length: LengthRule,
    constants: Vec<Constant>,
    header_checks: Vec<Check<'a>>,
    frame_checks: Vec<Check<'a>>,
    markers: Vec<Marker<'a>>,
}

impl<'a> FrameParts<'a> {
    /// The parts of frame format `index` of a protocol, its CRCs borrowed from `store`.
    pub fn new(frame: &'a ir::Frame, index: usize, store: &'a CrcStore) -> Self {
        let length = match &frame.length {
            Length::Fixed(n) => LengthRule::Fixed(*n),
            Length::Field { value, adjust } => match (frame.values.get(*value), frame.bare_len) {
                (Some(v), None) => LengthRule::Field {
                    field: word_field(v),
                    adjust: *adjust,
                },
                (Some(v), Some(bare)) => LengthRule::FieldOrBare {
                    field: word_field(v),
                    adjust: *adjust,
                    bare,
                },
                // Unreachable for a checked IR; a length that never fits rejects every frame.
                (None, _) => LengthRule::Fixed(0),
            },
        };
        let constants = frame
            .values
            .iter()
            .filter_map(|v| match v.role {
                Role::Const(value) => Some(Constant {
                    field: word_field(v),
                    value,
                }),
                _ => None,
            })
            .collect();
        let mut header_checks = Vec::new();
        let mut frame_checks = Vec::new();
        for (i, c) in frame.checks.iter().enumerate() {
            let check = Check {
                checksum: store.checksum(index, i, &c.algorithm),
                from: c.from,
                to: c.to,
                at: c.at,
                order: c.endian,
            };
            if c.header {
                header_checks.push(check);
            } else {
                frame_checks.push(check);
            }
        }
        let markers = frame
            .trailers
            .iter()
            .map(|t| Marker {
                at: t.at,
                bytes: &t.bytes,
            })
            .collect();
        FrameParts {
            frame,
            length,
            constants,
            header_checks,
            frame_checks,
            markers,
        }
    }

    /// The layout, as generated code's `LAYOUT` static holds it.
    pub fn layout(&self) -> FrameLayout<'_> {
        FrameLayout {
            sync: &self.frame.sync,
            // What the engine needs before the length is known and the header verified, as
            // generated code computes it (a command id after the length is not needed).
            header_len: self.frame.decide_len,
            min_len: self.frame.min_len(),
            max_len: self.frame.max_len(),
            length: self.length,
            constants: &self.constants,
            header_checks: &self.header_checks,
            frame_checks: &self.frame_checks,
            markers: &self.markers,
        }
    }
}
