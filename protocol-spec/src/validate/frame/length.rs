//! The layout once the payload's place is known: element offsets (header elements from the
//! start, elements after the payload back from the end), element names and ranges as `over`
//! and `length_of` write them, and the rules of the frame's length.

use std::ops::Range;

use super::super::Ctx;
use super::super::types::mask;
use super::{El, Kind};
use crate::diag::did_you_mean;
use crate::ir::{CAN_PREFIX_LEN, Check, FlagTrailer, HeaderValue, Length, Pos, Role, Transport};
use crate::spec::model::{FrameDef, SStr};

/// A frame's elements with the payload placed.
pub(super) struct Layout<'d, 's> {
    pub fname: &'d SStr,
    pub els: &'d [El<'s>],
    /// Index of the payload element.
    pub pi: usize,
    pub payload_min: usize,
    pub payload_max: usize,
    /// Bytes before the payload.
    pub header_len: usize,
    /// Bytes after the payload.
    pub trailer_len: usize,
}

impl<'d, 's> Layout<'d, 's> {
    pub fn new(
        fname: &'d SStr,
        els: &'d [El<'s>],
        pi: usize,
        payload_min: usize,
        payload_max: usize,
    ) -> Self {
        Layout {
            fname,
            els,
            pi,
            payload_min,
            payload_max,
            header_len: els[..pi].iter().map(|e| e.size).sum(),
            trailer_len: els[pi + 1..].iter().map(|e| e.size).sum(),
        }
    }

    /// Where element `i` starts.
    pub fn start_of(&self, i: usize) -> Pos {
        if i <= self.pi {
            Pos::Start(self.els[..i].iter().map(|e| e.size).sum())
        } else {
            Pos::End(self.els[i..].iter().map(|e| e.size).sum())
        }
    }

    /// Where element `i` ends (one past its last byte).
    pub fn end_of(&self, i: usize) -> Pos {
        if i < self.pi {
            Pos::Start(self.els[..=i].iter().map(|e| e.size).sum())
        } else {
            Pos::End(self.els[i + 1..].iter().map(|e| e.size).sum())
        }
    }

    /// Every word's values at the word's position.
    pub fn place_values(&self, values: &mut [HeaderValue]) {
        for (i, e) in self.els.iter().enumerate() {
            if let Kind::Word(_, idx) = &e.kind {
                for &vi in idx {
                    values[vi].at = self.start_of(i);
                }
            }
        }
    }

    /// Rule: `over` and `length_of` name elements of their frame.
    fn find(&self, ctx: &mut Ctx<'_>, n: &str, span: Range<usize>) -> Option<usize> {
        let found = self.els.iter().position(|e| e.name == n);
        if found.is_none() {
            let help = match did_you_mean(n, self.els.iter().map(|e| e.name.as_str())) {
                Some(b) => format!("did you mean `{b}`?"),
                None => format!(
                    "name elements of this layout: {}",
                    self.els
                        .iter()
                        .map(|e| format!("`{}`", e.name))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            };
            ctx.error(
                span,
                format!("frame `{}` has no element `{n}`", self.fname.get_ref()),
                help,
            );
        }
        found
    }

    /// Rule: a range is `"a..b"` (a before b), `"a"` or `"frame"`. Gives the element indices
    /// (inclusive), `None` for `"frame"`; the outer `None` is an error.
    pub fn parse_range(&self, ctx: &mut Ctx<'_>, s: &SStr) -> Option<Option<(usize, usize)>> {
        let v = s.get_ref().trim();
        if v == "frame" {
            return Some(None);
        }
        let (a, b) = v.split_once("..").unwrap_or((v, v));
        let ia = self.find(ctx, a.trim(), s.span())?;
        let ib = self.find(ctx, b.trim(), s.span())?;
        if ia > ib {
            ctx.error(
                s.span(),
                format!("range `{v}` runs backwards"),
                format!(
                    "write the earlier element first: `{}..{}`",
                    b.trim(),
                    a.trim()
                ),
            );
            return None;
        }
        Some(Some((ia, ib)))
    }
}

/// Rule: a CAN frame's length is its DLC (no `length_of`), and it carries at most 8 data
/// bytes. `None` when the rule fails.
pub(super) fn check_can_length(
    ctx: &mut Ctx<'_>,
    def: &FrameDef,
    lay: &Layout<'_, '_>,
    transport: Transport,
    length_decl: Option<(usize, &SStr)>,
) -> Option<()> {
    if !matches!(transport, Transport::Can { .. }) {
        return Some(());
    }
    if let Some((_, cov)) = length_decl {
        ctx.error(
            cov.span(),
            "a CAN frame's length is its DLC",
            "remove `length_of`: the data length of a CAN frame comes with the frame",
        );
        return None;
    }
    let data_max = lay.header_len - CAN_PREFIX_LEN + lay.payload_max + lay.trailer_len;
    if data_max > 8 {
        ctx.error(
            def.layout.span(),
            format!(
                "frame `{}` needs up to {data_max} data bytes, but a CAN frame carries at most 8",
                lay.fname.get_ref()
            ),
            "shrink the payload's `max` or the fields around it",
        );
        return None;
    }
    Some(())
}

/// Rule: a frame whose payload size varies has a length field (a CAN frame's is its DLC). The
/// length field covers a contiguous run of elements that includes the payload; the total
/// length is the field's value plus the bytes outside that run, and the field is wide enough
/// for the largest frame. `None` when the length cannot be known.
pub(super) fn lower_length(
    ctx: &mut Ctx<'_>,
    def: &FrameDef,
    lay: &Layout<'_, '_>,
    transport: Transport,
    length_decl: Option<(usize, &SStr)>,
    values: &[HeaderValue],
    ok: &mut bool,
) -> Option<Length> {
    let extended = lay
        .els
        .iter()
        .any(|e| e.def.is_some_and(|d| d.get_ref().extends.is_some()));
    let (header_len, trailer_len) = (lay.header_len, lay.trailer_len);
    let Some((vi, cov)) = length_decl else {
        return match transport {
            // The DLC: the one length value of a CAN frame (after the id or its members).
            Transport::Can { .. } => Some(Length::Field {
                value: values.iter().position(|v| v.role == Role::Length)?,
                adjust: CAN_PREFIX_LEN as i64,
            }),
            Transport::Serial if lay.payload_min == lay.payload_max => {
                Some(Length::Fixed(header_len + lay.payload_max + trailer_len))
            }
            Transport::Serial => {
                ctx.error(def.layout.span(), format!("frame `{}` has no length field, but its payload size varies", lay.fname.get_ref()), "mark the field that holds the length with `length_of = \"...\"`, or set the payload's `min` equal to its `max`");
                None
            }
        };
    };
    let range = lay.parse_range(ctx, cov)?;
    let (ia, ib) = range.unwrap_or((0, lay.els.len() - 1));
    if ia > lay.pi || ib < lay.pi {
        ctx.error(cov.span(), format!("the length field counts `{}`, which does not include the payload", cov.get_ref()), "a length field must count the payload (e.g. `\"payload\"`, `\"command..payload\"` or `\"frame\"`)");
        return None;
    }
    let before = match lay.start_of(ia) {
        Pos::Start(n) | Pos::End(n) => n,
    };
    let after = match lay.end_of(ib) {
        Pos::Start(n) => header_len + trailer_len - n,
        Pos::End(n) => n,
    };
    let adjust = (before + after) as i64;
    let v = &values[vi];
    let field_max = mask(v.width);
    let needed = (header_len + lay.payload_max + trailer_len) as i64 - adjust;
    // With a wider length, the field holds the counts below its marker (the wider length's
    // own rule checks the largest frame).
    if !extended && needed > 0 && needed as u64 > field_max {
        ctx.error(cov.span(), format!("the length field has {} bits (at most {field_max}), but the largest frame needs the value {needed}", v.width), "use a wider length field, or lower the payload's `max`");
        *ok = false;
    }
    if (header_len + lay.payload_min + trailer_len) as i64 - adjust < 0 {
        ctx.error(
            cov.span(),
            "the length field would count a negative number of bytes",
            "check what `length_of` covers",
        );
        *ok = false;
    }
    Some(Length::Field { value: vi, adjust })
}

/// Bytes a stream decoder needs before it knows a frame's length and has verified its header:
/// through the sync, the length field, the flag that announces optional bytes (it adds them to
/// the length), the constants and the header checks (fields after them, such as a command id,
/// are part of what the length counts).
pub(super) fn lower_decide_len(
    sync_len: usize,
    values: &[HeaderValue],
    length: &Length,
    flag_trailer: Option<&FlagTrailer>,
    checks: &[Check],
) -> usize {
    let word_end = |v: &HeaderValue| match v.at {
        Pos::Start(o) => o + v.word.prim.size(),
        Pos::End(_) => 0,
    };
    let length = match length {
        Length::Field { value, .. } => word_end(&values[*value]),
        Length::Fixed(_) => 0,
    };
    let flag = flag_trailer.map_or(0, |t| word_end(&values[t.flag]));
    let constants = values
        .iter()
        .filter(|v| matches!(v.role, Role::Const(_)))
        .map(word_end)
        .max()
        .unwrap_or(0);
    let checks = checks
        .iter()
        .filter(|c| c.header)
        .map(|c| match c.at {
            Pos::Start(o) => o + c.size,
            Pos::End(_) => 0,
        })
        .max()
        .unwrap_or(0);
    sync_len.max(length).max(flag).max(constants).max(checks)
}
