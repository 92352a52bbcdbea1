//! A spec's frame formats as runtime [`FrameLayout`] and [`PacketRules`] values, built from the
//! same lowerings the generated `LAYOUT` and `RULES` statics are printed from ([`lower_layout`],
//! [`lower_rules`]), so the interpreter and generated code run the same engine and the same
//! packet rules on the same description.
//!
//! This module owns the CRC objects a layout's checks borrow ([`CrcStore`]: the codec owns it,
//! its layouts borrow it, parameters included) and the per-frame slices of constants and checks, and
//! of the packet rules' key fields and direction tests ([`FrameParts`]); a check with a
//! per-command byte owns its CRC and byte table ([`OwnedExtra`]), so that dropping a codec frees
//! all it built. A check's algorithm is the IR's runtime [`Algorithm`], executed as it is;
//! which bytes a check covers and how a frame is verified or sealed is the runtime's business,
//! and so is every packet rule.

use protocol_runtime::checksum::{CheckObject, Checksum, CrcImpl, Extra, Slicing16, fill_direct};
use protocol_runtime::layout::{Check, Constant, FrameLayout, WordField};
use protocol_runtime::rules::{DirectionTest, PacketRules};
use protocol_spec::ir::{self, Algorithm, CrcSpec};
pub use protocol_spec::layout::word_field;
use protocol_spec::layout::{self, LayoutPlan, lower_layout};
use protocol_spec::rules::{RulesPlan, lower_rules};

/// A CRC object of one width: sixteen tables ([`Slicing16`]), whatever table size the spec
/// chose.
///
/// Why not the spec's choice: a spec's `table` trades a microcontroller's flash for speed, and
/// this codec runs on hosts, where `by-target` is sixteen tables anyway; and the `crc` crate's
/// one-table and table-free CRCs take `&'static` parameters, which a spec loaded at run time
/// could only give by keeping every parameter set it met for the life of the process.
/// [`Slicing16`] holds its parameters by value, so dropping the codec frees all of it. Every
/// table size computes the same value (the runtime's tests check them against each other).
struct Tables<W: crc::Width>(Box<Slicing16<W>>);

impl<W: crc::Width> Tables<W> {
    fn as_impl(&self) -> CrcImpl<'_, W> {
        CrcImpl::Table16(&self.0)
    }
}

macro_rules! tables {
    ($($w:ty),*) => {$(
        impl From<&CrcSpec<$w>> for Tables<$w> {
            fn from(spec: &CrcSpec<$w>) -> Self {
                Tables(Box::new(Slicing16::<$w>::new(&spec.params)))
            }
        }
    )*};
}
tables!(u8, u16, u32, u64);

/// The CRC object of one check.
enum CrcObject {
    W8(Tables<u8>),
    W16(Tables<u16>),
    W32(Tables<u32>),
    W64(Tables<u64>),
}

impl CrcObject {
    /// The CRC object of a CRC algorithm; `None` for the other algorithms.
    fn new(a: &Algorithm) -> Option<Self> {
        Some(match a {
            Algorithm::Crc8(spec) => CrcObject::W8(spec.into()),
            Algorithm::Crc16(spec) => CrcObject::W16(spec.into()),
            Algorithm::Crc32(spec) => CrcObject::W32(spec.into()),
            Algorithm::Crc64(spec) => CrcObject::W64(spec.into()),
            _ => return None,
        })
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

/// A check with a per-command byte, owning what the runtime's [`Extra`] borrows (its CRC and
/// its byte table), run by the engine as a [`Checksum::Object`].
///
/// Why an object and not an [`Extra`] held beside the CRC objects: a layout's check borrows
/// its [`Extra`], which borrows the CRC, so a codec that owned both the [`Extra`] and what it
/// borrows would borrow from itself. Building the [`Extra`] view on each call costs a few
/// stores, and the codec frees the tables with itself (generated code keeps its `static`
/// [`Extra`] and never runs this).
struct OwnedExtra {
    crc: CrcObject,
    key: WordField,
    direct: Box<[u16]>,
    bytes: Box<[(u32, u8)]>,
}

impl OwnedExtra {
    /// The owned parts of `extra`; `None` for an algorithm other than a CRC (validation
    /// allows an extra byte on CRCs only).
    fn new(algorithm: &Algorithm, extra: &ir::CheckExtra) -> Option<Self> {
        Some(OwnedExtra {
            crc: CrcObject::new(algorithm)?,
            key: extra.key,
            direct: direct_entries(extra),
            bytes: extra.searched_pairs().into(),
        })
    }

    /// The runtime's [`Extra`], borrowing this object's parts.
    fn view(&self) -> Extra<'_> {
        Extra {
            crc: self.crc.checksum(),
            key: self.key,
            direct: &self.direct,
            bytes: &self.bytes,
        }
    }
}

/// The direct table of `extra`, as generated code's `direct_table` builds it.
fn direct_entries(extra: &ir::CheckExtra) -> Box<[u16]> {
    let mut table = vec![0u16; extra.direct];
    fill_direct(&mut table, extra.direct_pairs());
    table.into_boxed_slice()
}

/// Prints as the [`Checksum::Extra`] of generated code, so that a layout prints alike from
/// either.
impl std::fmt::Debug for OwnedExtra {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        Checksum::Extra(&self.view()).fmt(f)
    }
}

impl CheckObject for OwnedExtra {
    fn compute(&self, data: &[u8]) -> u64 {
        Checksum::Extra(&self.view()).compute(data)
    }

    fn compute_prefix(&self, data: &[u8], n: usize) -> Option<u64> {
        Checksum::Extra(&self.view()).compute_prefix(data, n)
    }
}

/// What a check needs built: a CRC object, or a CRC with its per-command bytes.
enum Built {
    Crc(CrcObject),
    Extra(OwnedExtra),
}

/// The CRC objects of every check of every frame format of a spec, owned so that layouts can
/// borrow them.
pub struct CrcStore {
    /// `crcs[frame][check]`: what a check needs built, `None` for sums and xor.
    crcs: Vec<Vec<Option<Built>>>,
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
                    .map(|c| match &c.extra {
                        Some(extra) => OwnedExtra::new(&c.algorithm, extra).map(Built::Extra),
                        None => CrcObject::new(&c.algorithm).map(Built::Crc),
                    })
                    .collect()
            })
            .collect();
        CrcStore { crcs }
    }

    fn checksum(&self, frame: usize, check: usize, c: &ir::Check) -> Checksum<'_> {
        match self
            .crcs
            .get(frame)
            .and_then(|f| f.get(check))
            .and_then(Option::as_ref)
        {
            Some(Built::Crc(crc)) => crc.checksum(),
            Some(Built::Extra(extra)) => Checksum::Object {
                width: c.algorithm.width() as u8,
                check: extra,
            },
            // A sum or xor (a CRC's object was built from the same protocol).
            None => c.algorithm.tableless().unwrap_or(Checksum::Sum8),
        }
    }
}

/// The slices a [`FrameLayout`] and its [`PacketRules`] borrow, for one frame format.
pub struct FrameParts<'a> {
    plan: LayoutPlan<'a>,
    constants: Vec<Constant>,
    header_checks: Vec<Check<'a>>,
    frame_checks: Vec<Check<'a>>,
    rules: RulesPlan<'a>,
    key: Vec<WordField>,
    directions: Vec<DirectionTest>,
}

impl<'a> FrameParts<'a> {
    /// The parts of frame format `index` of protocol `p`, its CRCs borrowed from `store`.
    pub fn new(
        p: &'a ir::Protocol,
        index: usize,
        frame: &'a ir::Frame,
        store: &'a CrcStore,
    ) -> Self {
        let plan = lower_layout(frame);
        let rules = lower_rules(p, frame);
        let checks = |indices: &[usize]| -> Vec<Check<'a>> {
            indices
                .iter()
                .filter_map(|&i| {
                    let c = frame.checks.get(i)?;
                    Some(layout::check(c, store.checksum(index, i, c)))
                })
                .collect()
        };
        FrameParts {
            constants: plan.constants.iter().map(|&(_, c)| c).collect(),
            header_checks: checks(&plan.header_checks),
            frame_checks: checks(&plan.frame_checks),
            plan,
            key: rules.key_fields(),
            directions: rules.direction_tests(),
            rules,
        }
    }

    /// The layout, as generated code's `LAYOUT` static holds it.
    pub fn layout(&self) -> FrameLayout<'_> {
        self.plan
            .layout(&self.constants, &self.header_checks, &self.frame_checks)
    }

    /// `f` run on the packet rules, as generated code's `RULES` static holds them, their frame
    /// rules this format's [`layout`](Self::layout). A closure, since the rules borrow the
    /// layout, which borrows these parts.
    pub fn with_rules<R>(&self, f: impl FnOnce(&PacketRules<'_>) -> R) -> R {
        let layout = self.layout();
        f(&self.rules.rules(&layout, &self.key, &self.directions))
    }
}
