//! Canonical payloads: random values of a spec's payload structs, written as the generated
//! encoder writes them (padding zero, booleans 0 or 1, unused bits zero, enum values that exist,
//! scaled values inside their clamp range, byte counts that match the fields that state them),
//! so that decoding them and encoding the result gives the same bytes.

use std::collections::HashMap;

use protocol_codegen::ir;

use super::Source;
use super::model::Model;

impl Model {
    /// Appends the canonical bytes of a random value of struct `s`, keeping variable parts
    /// (bytes, groups, optional fields) within about `budget` bytes.
    pub fn canonical_struct(
        &self,
        src: &mut impl Source,
        s: usize,
        budget: usize,
        ctx: &mut Ctx,
        out: &mut Vec<u8>,
    ) {
        self.size_limits(s, &mut ctx.limits);
        // Where each field starts and ends in `out`, for the checks over them.
        let mut spans: Vec<(usize, usize)> = Vec::new();
        for field in &self.ir.structs[s].fields {
            let start = out.len();
            match &field.kind {
                ir::FieldKind::Check(c) => {
                    let covered = &out[spans[c.first].0..spans[c.last].1];
                    let value = check_value(&c.algorithm, covered);
                    let scalar = ir::Scalar {
                        prim: match field.size {
                            1 => ir::Prim::U8,
                            2 => ir::Prim::U16,
                            4 => ir::Prim::U32,
                            _ => ir::Prim::U64,
                        },
                        endian: c.endian,
                    };
                    put_uint(out, scalar, value);
                }
                kind => self.canonical_field(src, field, kind, budget, ctx, out),
            }
            spans.push((start, out.len()));
        }
    }

    /// Records, for every field that gives a byte count (`size = "field"`), the most bytes it
    /// may count.
    fn size_limits(&self, s: usize, limits: &mut HashMap<String, u64>) {
        for field in &self.ir.structs[s].fields {
            match &field.kind {
                ir::FieldKind::Bytes {
                    max,
                    size_from: Some(name),
                    ..
                }
                | ir::FieldKind::Array {
                    max,
                    size_from: Some(name),
                    ..
                } => {
                    let limit = limits.entry(name.clone()).or_insert(u64::MAX);
                    *limit = (*limit).min(*max as u64);
                }
                ir::FieldKind::Group { elem, .. } => self.size_limits(*elem, limits),
                _ => {}
            }
        }
    }

    fn canonical_field(
        &self,
        src: &mut impl Source,
        field: &ir::Field,
        kind: &ir::FieldKind,
        budget: usize,
        ctx: &mut Ctx,
        out: &mut Vec<u8>,
    ) {
        let room = budget.saturating_sub(out.len());
        match kind {
            ir::FieldKind::Padding => out.resize(out.len() + field.size, 0),
            ir::FieldKind::Value { ty, count } => {
                for _ in 0..count.unwrap_or(1) {
                    let limit = ctx.limits.get(&field.name).copied();
                    let value = self.canonical_value(src, ty, limit, out);
                    ctx.values.insert(field.name.clone(), value);
                }
            }
            ir::FieldKind::Bits { word, members } => {
                let mut bits = 0u64;
                for m in members {
                    let value = match (m.enum_index, m.prim) {
                        (Some(e), _) => self.enum_value(src, e, m.width),
                        (None, ir::Prim::Bool) => src.below(2),
                        (None, _) => src.next_u64() & mask(m.width),
                    };
                    bits |= (value & mask(m.width)) << m.shift;
                }
                put_uint(out, *word, bits);
            }
            ir::FieldKind::BitStream { members } => {
                // Random bits per member (a signed member's bits are its two's complement, a
                // scaled member's its raw value); the bits after the last member stay 0, as
                // the encoder writes them.
                let mut bytes = vec![0u8; field.size];
                for m in members {
                    let value = match (m.enum_index, m.prim) {
                        (Some(e), _) => self.enum_value(src, e, m.width),
                        (None, ir::Prim::Bool) => src.below(2),
                        (None, _) => src.next_u64() & mask(m.width),
                    };
                    protocol_kit::bitstream::set_stream(
                        &mut bytes,
                        m.shift as usize,
                        m.width,
                        value,
                    )
                    .expect("the member fits its bits");
                }
                out.extend(bytes);
            }
            ir::FieldKind::Packed {
                count, bits, order, ..
            } => {
                // Random elements (scaled ones as raw values: clamping is for `Value` fields
                // of the specs this generator serves); the bits after the last element stay 0,
                // as the encoder writes them.
                let mut bytes = vec![0u8; field.size];
                for i in 0..*count {
                    let raw = src.next_u64() & mask(*bits);
                    protocol_kit::packed::set_packed(&mut bytes, i, *bits, *order, raw)
                        .expect("the element fits its bits");
                }
                out.extend(bytes);
            }
            // Any bytes are text too: a text without a terminator keeps them as they are.
            ir::FieldKind::Bytes { max, size_from, .. } => {
                let n = match size_from {
                    Some(name) => ctx.values.get(name).copied().unwrap_or(0) as usize,
                    None => src.len((*max).min(room)),
                };
                let mut bytes = src.bytes(n);
                // Often hold the sync bytes or the stuffing pattern: what a weak decoder or
                // encoder gets wrong.
                let f = self.frame();
                let pattern = match &f.stuffing {
                    Some((after, _)) if src.one_in(2) => after.as_slice(),
                    _ => &f.sync,
                };
                if src.one_in(3) && n >= pattern.len() {
                    let at = src.below((n - pattern.len() + 1) as u64) as usize;
                    bytes[at..at + pattern.len()].copy_from_slice(pattern);
                }
                out.extend(bytes);
            }
            ir::FieldKind::Group { elem, max } => {
                for _ in 0..src.len(*max) {
                    let before = out.len();
                    self.canonical_struct(src, *elem, budget, ctx, out);
                    if out.len() > budget {
                        out.truncate(before);
                        break;
                    }
                }
            }
            ir::FieldKind::Array {
                ty,
                max,
                size_from,
                by_mask,
            } => {
                let stated = |name: &String| ctx.values.get(name).copied().unwrap_or(0);
                let n = match size_from {
                    Some(name) if *by_mask => stated(name).count_ones() as usize,
                    Some(name) => stated(name) as usize,
                    None => src.len(*max).min(room / (field.size / max).max(1)),
                };
                for _ in 0..n {
                    self.canonical_value(src, ty, None, out);
                }
            }
            // Any bytes but NUL, then the NUL.
            ir::FieldKind::NulText { max } => {
                let n = src.len((*max).min(room));
                out.extend((0..n).map(|_| (src.next_u64() as u8).max(1)));
                out.push(0);
            }
            // Written by `canonical_struct`, which knows the covered bytes.
            ir::FieldKind::Check(_) => {}
            // Present exactly when the mask's bit is set, as the encoder requires.
            ir::FieldKind::When { kind, mask, bit } => {
                let bits = ctx.values.get(mask).copied().unwrap_or(0);
                if protocol_kit::field::mask_bit(bits, *bit) {
                    self.canonical_field(src, field, kind, budget, ctx, out);
                }
            }
            ir::FieldKind::Optional(inner) => {
                if src.one_in(2) {
                    let before = out.len();
                    self.canonical_field(src, field, inner, budget, ctx, out);
                    if out.len() > budget {
                        out.truncate(before);
                    }
                }
            }
        }
    }

    /// Appends one canonical value; returns its raw bits (for fields other fields refer to).
    fn canonical_value(
        &self,
        src: &mut impl Source,
        ty: &ir::ValueType,
        limit: Option<u64>,
        out: &mut Vec<u8>,
    ) -> u64 {
        match ty {
            ir::ValueType::Struct(s) => {
                self.canonical_struct(src, *s, usize::MAX, &mut Ctx::default(), out);
                0
            }
            ir::ValueType::Enum(e, scalar) => {
                let value = self.enum_value(src, *e, 8 * scalar.prim.size() as u32);
                put_uint(out, *scalar, value);
                value
            }
            // Every byte string is a text that encodes back to itself.
            ir::ValueType::Text(n) => {
                out.extend((0..*n).map(|_| src.next_u64() as u8));
                0
            }
            ir::ValueType::Scalar { scalar, scale } => {
                let mut value = match (scalar.prim, limit) {
                    (prim, _) if prim.is_bool() => src.below(2),
                    (_, Some(limit)) => src.below(limit.saturating_add(1)),
                    _ => src.next_u64(),
                };
                // A NaN's payload may change through a scaled float's arithmetic (a signaling
                // NaN is quieted): not canonical.
                while scale.is_some() && is_nan(scalar.prim, value) {
                    value = src.next_u64();
                }
                // A scaled value outside its clamp range is not canonical: the encoder clamps it.
                if let Some(scale) = scale {
                    let mut tries = 0;
                    while !in_clamp(scale, scalar.prim, value) {
                        tries += 1;
                        value = if tries < 16 {
                            src.next_u64()
                        } else {
                            clamp_midpoint(scale)
                        };
                    }
                }
                put_uint(out, *scalar, value);
                value & mask(8 * scalar.prim.size() as u32)
            }
        }
    }

    /// A value of enum `e`: one of its variants, or (when unknown values are kept) any value.
    fn enum_value(&self, src: &mut impl Source, e: usize, width: u32) -> u64 {
        let en = &self.ir.enums[e];
        if en.unknown == ir::UnknownPolicy::Keep && src.one_in(4) || en.variants.is_empty() {
            return src.next_u64() & mask(width);
        }
        en.variants[src.below(en.variants.len() as u64) as usize].value
    }
}

/// The raw bits as a number of the wire type (sign-extended for signed types).
fn raw_number(prim: ir::Prim, raw: u64) -> f64 {
    let bits = 8 * prim.size() as u32;
    let raw = raw & mask(bits);
    if prim.is_signed() {
        let shift = 64 - bits;
        (((raw << shift) as i64) >> shift) as f64
    } else {
        raw as f64
    }
}

/// Whether `raw` is the bits of a NaN of the float type `prim` (never for other types).
fn is_nan(prim: ir::Prim, raw: u64) -> bool {
    match prim {
        ir::Prim::F16 => raw & 0x7C00 == 0x7C00 && raw & 0x3FF != 0,
        ir::Prim::F32 => f32::from_bits(raw as u32).is_nan(),
        ir::Prim::F64 => f64::from_bits(raw).is_nan(),
        _ => false,
    }
}

/// Whether the physical value of `raw`, as the decoder computes it, lies in the clamp range.
fn in_clamp(scale: &ir::Scale, prim: ir::Prim, raw: u64) -> bool {
    let Some((lo, hi)) = scale.clamp else {
        return true;
    };
    let physical = raw_number(prim, raw) * scale.factor + scale.offset;
    let physical = match scale.physical {
        ir::Prim::F32 => f64::from(physical as f32),
        _ => physical,
    };
    lo <= physical && physical <= hi
}

/// The raw value nearest the middle of the clamp range (two's complement bits).
fn clamp_midpoint(scale: &ir::Scale) -> u64 {
    let (lo, hi) = scale.clamp.unwrap_or((0.0, 0.0));
    (((lo + hi) / 2.0 - scale.offset) / scale.factor).round() as i64 as u64
}

/// Values of the fields generated so far, and bounds on the fields that count bytes.
#[derive(Debug, Default)]
pub struct Ctx {
    values: HashMap<String, u64>,
    limits: HashMap<String, u64>,
}

/// The check value of `bytes` by `a`, computed here with the `crc` crate (no table) or the
/// runtime's sums.
fn check_value(a: &ir::Algorithm, bytes: &[u8]) -> u64 {
    use super::oracle::params as intern;
    match a {
        ir::Algorithm::Crc8(c) => u64::from(crc::Crc::<u8>::new(intern(&c.params)).checksum(bytes)),
        ir::Algorithm::Crc16(c) => {
            u64::from(crc::Crc::<u16>::new(intern(&c.params)).checksum(bytes))
        }
        ir::Algorithm::Crc32(c) => {
            u64::from(crc::Crc::<u32>::new(intern(&c.params)).checksum(bytes))
        }
        ir::Algorithm::Crc64(c) => crc::Crc::<u64>::new(intern(&c.params)).checksum(bytes),
        sum => sum
            .tableless()
            .expect("a sum needs no table")
            .compute(bytes),
    }
}

/// The low `width` bits.
fn mask(width: u32) -> u64 {
    if width >= 64 {
        u64::MAX
    } else {
        (1u64 << width) - 1
    }
}

/// Appends the low bytes of `value` in the scalar's size and byte order.
fn put_uint(out: &mut Vec<u8>, scalar: ir::Scalar, value: u64) {
    let size = scalar.prim.size();
    let le = value.to_le_bytes();
    let bytes = &le[..size];
    match scalar.endian {
        ir::ByteOrder::Little => out.extend_from_slice(bytes),
        ir::ByteOrder::Big => out.extend(bytes.iter().rev()),
    }
}
