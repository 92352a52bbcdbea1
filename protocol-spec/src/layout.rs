//! The lowering of a frame format ([`ir::Frame`]) to the runtime's [`FrameLayout`], once.
//!
//! [`lower_layout`] turns what validation decided (the sync bytes, how many bytes the engine
//! needs before it knows a frame's length, the length bounds and rule, the constants, which
//! checks are header checks and which frame checks, the markers) into the runtime's own
//! values: the length rule, word fields, constants and markers. Two backends take its
//! result as it is: the expansion prints it as the `LAYOUT` static (`codegen::frame` in
//! `protocol-codegen`), and the run-time codec builds a [`FrameLayout`] value from it. What
//! stays to each is the one thing that differs: how a check's algorithm becomes a
//! [`Checksum`] (a `static` table in generated code, an object the codec owns).

use protocol_runtime::checksum::{Algorithm, Checksum};
use protocol_runtime::escape::Escape;
use protocol_runtime::layout::{
    Check, Constant, FlagTrailer, FrameLayout, LengthExtension, LengthRule, Marker, WordField,
};

use crate::ir::{self, HeaderValue, Length, Role};

/// A frame format as the runtime's [`FrameLayout`] holds it, with the checks still to be given
/// their [`Checksum`]s, and the header values its fields come from (so the expansion can name
/// them as `wire::NAME`).
#[derive(Debug, Clone, PartialEq)]
pub struct LayoutPlan<'f> {
    /// Bytes every frame starts with (after the byte of `sync_set`, if any).
    pub sync: &'f [u8],
    /// Bytes one of which every frame starts with: the first header value is the sync.
    pub sync_set: &'f [u8],
    /// Bytes the engine needs before it knows a frame's length and has verified its header.
    pub header_len: usize,
    /// Smallest valid total length.
    pub min_len: usize,
    /// Largest valid total length.
    pub max_len: usize,
    /// How the total length is known.
    pub length: LengthRule,
    /// The header value (index into [`ir::Frame::values`]) of the length rule's field.
    pub length_value: Option<usize>,
    /// Values that must hold, each with its header value (index into [`ir::Frame::values`]).
    pub constants: Vec<(usize, Constant)>,
    /// Checks verified before the length is trusted (indices into [`ir::Frame::checks`]).
    pub header_checks: Vec<usize>,
    /// Checks over the whole frame (indices into [`ir::Frame::checks`]), in order.
    pub frame_checks: Vec<usize>,
    /// Constant byte runs after the payload.
    pub markers: Vec<Marker<'f>>,
    /// The byte escaping between the frame's flags.
    pub escape: Option<Escape<'f>>,
}

/// Lowers a frame format to its layout plan.
pub fn lower_layout(f: &ir::Frame) -> LayoutPlan<'_> {
    let (length, length_value) = match &f.length {
        Length::Fixed(n) => (LengthRule::Fixed(*n), None),
        Length::Field { value, adjust } => {
            let field = word_field(&f.values[*value]);
            let adjust = *adjust;
            let trailer = f.flag_trailer.as_ref().map(|t| FlagTrailer {
                flag: word_field(&f.values[t.flag]),
                len: t.len,
            });
            let extension = f.length_extension.as_ref().map(|e| LengthExtension {
                marker: e.marker,
                wide: word_field(&f.values[e.value]),
                len: e.len,
            });
            let rule = match (f.bare_len, trailer, extension) {
                (Some(bare), ..) => LengthRule::FieldOrBare {
                    field,
                    adjust,
                    bare,
                },
                (None, None, None) => LengthRule::Field { field, adjust },
                (None, trailer, extension) => LengthRule::Conditional {
                    field,
                    adjust,
                    extension,
                    trailer,
                },
            };
            (rule, Some(*value))
        }
    };
    let constants = f
        .values
        .iter()
        .enumerate()
        .filter_map(|(i, v)| match v.role {
            Role::Const(value) => Some((
                i,
                Constant {
                    field: word_field(v),
                    value,
                },
            )),
            _ => None,
        })
        .collect();
    let (header_checks, frame_checks) = (0..f.checks.len()).partition(|&i| f.checks[i].header);
    let markers = f
        .trailers
        .iter()
        .map(|t| Marker {
            at: t.at,
            bytes: &t.bytes,
        })
        .collect();
    LayoutPlan {
        sync: &f.sync,
        sync_set: &f.sync_set,
        header_len: f.decide_len,
        min_len: f.min_len(),
        max_len: f.max_len(),
        length,
        length_value,
        constants,
        header_checks,
        frame_checks,
        markers,
        escape: f.escape.as_ref().map(|e| Escape {
            flag: e.flag,
            escape: e.escape,
            pairs: &e.pairs,
        }),
    }
}

impl LayoutPlan<'_> {
    /// The layout, with the constants and checks built from this plan.
    pub fn layout<'a>(
        &'a self,
        constants: &'a [Constant],
        header_checks: &'a [Check<'a>],
        frame_checks: &'a [Check<'a>],
    ) -> FrameLayout<'a> {
        FrameLayout {
            sync: self.sync,
            sync_set: self.sync_set,
            header_len: self.header_len,
            min_len: self.min_len,
            max_len: self.max_len,
            length: self.length,
            constants,
            header_checks,
            frame_checks,
            markers: &self.markers,
            escape: self.escape,
        }
    }
}

/// Whether `check` is computed with a CRC: one of the CRC algorithms, or any algorithm with a
/// per-command byte (the runtime's `Extra` holds a CRC).
fn is_crc(check: &ir::Check) -> bool {
    check.extra.is_some()
        || matches!(
            check.algorithm,
            Algorithm::Crc8(_) | Algorithm::Crc16(_) | Algorithm::Crc32(_) | Algorithm::Crc64(_)
        )
}

/// The runtime check of `check` (one of [`ir::Frame::checks`]), computed with `checksum`.
pub fn check<'c>(check: &ir::Check, checksum: Checksum<'c>) -> Check<'c> {
    Check {
        checksum,
        from: check.from,
        to: check.to,
        at: check.at,
        order: check.endian,
    }
}

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

/// The rule kinds a link's frame formats use, for the engine's paths that a layout known at
/// compile time leaves out (the runtime's `LayoutRef::ESCAPED`, `HEADER_DECIDED` and
/// `SEVERAL_FORMATS`): a kind none of the formats uses is not linked into a firmware, even
/// unoptimised.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RuleKinds {
    /// A format escapes its bytes between flags.
    pub escaped: bool,
    /// A format decides parts of its frames by header values ([`LengthRule::Conditional`]).
    pub header_decided: bool,
    /// The link's decoder finds the frames of more than one format.
    pub several_formats: bool,
    /// A format checks with a CRC (of any width, with or without a per-command byte).
    pub crc_checked: bool,
}

impl RuleKinds {
    /// The kinds of a decoder of `formats`' frames (the first, then the others it finds
    /// beside it).
    pub fn of_link<'f>(formats: impl IntoIterator<Item = &'f ir::Frame>) -> Self {
        formats
            .into_iter()
            .enumerate()
            .fold(RuleKinds::default(), |kinds, (i, f)| {
                let plan = lower_layout(f);
                RuleKinds {
                    escaped: kinds.escaped || plan.escape.is_some(),
                    header_decided: kinds.header_decided
                        || matches!(plan.length, LengthRule::Conditional { .. }),
                    several_formats: kinds.several_formats || i > 0,
                    crc_checked: kinds.crc_checked || f.checks.iter().any(is_crc),
                }
            })
    }
}
