//! Rules for a check inside a payload: a struct field that holds a check value over a run of
//! earlier fields of its struct (the inner CRC-8 of a CRSF command frame), with constant bytes
//! it covers first (`prefix`) folded into a CRC's initial value.

use toml::Spanned;

use super::super::checksum::{crc_of, resolve_algorithm};
use super::super::names::{parse_byte_order, to_snake};
use super::super::{Ctx, text};
use crate::diag::did_you_mean;
use crate::ir::{Algorithm, ByteOrder, Field, FieldKind, PayloadCheck};
use crate::spec::model::{FieldDef, SStr, StructDef};

/// Rule: a check field takes `name`, `check`, `over`, and optionally `prefix` (bytes, with a
/// CRC only), `byte_order` and `doc`; its algorithm resolves as a frame check's does. The
/// fields it covers are resolved by [`resolve_check_runs`] once the struct's fields are known.
pub(super) fn lower_check_field(
    ctx: &mut Ctx<'_>,
    f: &Spanned<FieldDef>,
    name: &SStr,
    struct_name: &str,
    endian: ByteOrder,
    offset: usize,
) -> Option<Field> {
    let d = f.get_ref();
    let alg_name = d.check.as_ref()?;
    if d.ty.is_some()
        || d.count.is_some()
        || d.max.is_some()
        || d.size.is_some()
        || d.repeat.is_some()
        || d.optional.is_some()
        || d.bits.is_some()
        || d.packed.is_some()
        || d.scale.is_some()
        || d.offset.is_some()
        || d.unit.is_some()
    {
        ctx.error(
            f.span(),
            format!("check field `{}` takes only `name`, `check`, `over`, `prefix`, `byte_order` and `doc`", name.get_ref()),
            "remove the other keys: a check's type is its algorithm's",
        );
    }
    if d.over.is_none() {
        ctx.error(
            alg_name.span(),
            format!("check field `{}` has no `over`", name.get_ref()),
            "add `over = \"first..last\"`, the run of earlier fields of this struct it covers",
        );
    }
    let endian = match &d.byte_order {
        Some(o) => parse_byte_order(ctx, o).unwrap_or(endian),
        None => endian,
    };
    let (algorithm, mut naming) = resolve_algorithm(ctx, alg_name)?;
    let prefix = lower_prefix(ctx, d, &algorithm)?;
    let algorithm = fold_prefix(algorithm, &prefix);
    if !prefix.is_empty() {
        // The parameters differ from the named CRC's: printed as they are.
        naming.crc_constant = None;
    }
    naming.table_static = Some(format!(
        "{}_{}_TABLE",
        to_snake(struct_name).to_uppercase(),
        name.get_ref().to_uppercase()
    ));
    Some(Field {
        name: name.get_ref().clone(),
        doc: text(&d.doc),
        offset,
        size: algorithm.width(),
        kind: FieldKind::Check(PayloadCheck {
            algorithm,
            naming,
            first: 0,
            last: 0,
            covered: String::new(),
            prefix,
            endian,
        }),
        unit: String::new(),
    })
}

/// Rule: `prefix` is a list of bytes, and only a CRC takes one (a CRC can start from the
/// register the bytes leave; a sum has no initial value to fold them into).
fn lower_prefix(ctx: &mut Ctx<'_>, d: &FieldDef, algorithm: &Algorithm) -> Option<Vec<u8>> {
    let Some(p) = &d.prefix else {
        return Some(Vec::new());
    };
    let is_crc = matches!(
        algorithm,
        Algorithm::Crc8(_) | Algorithm::Crc16(_) | Algorithm::Crc32(_) | Algorithm::Crc64(_)
    );
    if !is_crc {
        ctx.error(
            p.span(),
            "`prefix` applies to CRC checks",
            "remove `prefix`, or use a CRC: its initial register takes the prefix bytes",
        );
        return None;
    }
    let mut out = Vec::new();
    for b in p.get_ref() {
        match u8::try_from(*b.get_ref()) {
            Ok(v) => out.push(v),
            Err(_) => {
                ctx.error(
                    b.span(),
                    format!("{} is not a byte", b.get_ref()),
                    "prefix bytes are 0 to 255",
                );
                return None;
            }
        }
    }
    Some(out)
}

/// The CRC that gives, over some bytes, what `a` gives over `prefix` then those bytes: the
/// same parameters from the register `prefix` leaves (its `check` recomputed to match). Any
/// other algorithm, or an empty prefix, is returned unchanged.
pub(crate) fn fold_prefix(a: Algorithm, prefix: &[u8]) -> Algorithm {
    macro_rules! fold {
        ($spec:expr, $w:ty, $variant:ident) => {{
            let mut spec = $spec;
            let p = spec.params;
            // Undo the final XOR and the output reflection: the register after the prefix.
            let mut register = (crc_of(&a, prefix).unwrap_or(0) as $w) ^ p.xorout;
            // Reflection over the CRC's width (a CRC-24 sits in the low 24 bits of a `u32`).
            let reflect = |v: $w| v.reverse_bits() >> (<$w>::BITS - u32::from(p.width));
            if p.refin != p.refout {
                register = reflect(register);
            }
            // The crate reflects a reflected CRC's `init` before it starts.
            spec.params.init = if p.refin { reflect(register) } else { register };
            let folded = Algorithm::$variant(spec);
            spec.params.check = crc_of(&folded, b"123456789").unwrap_or(0) as $w;
            Algorithm::$variant(spec)
        }};
    }
    if prefix.is_empty() {
        return a;
    }
    match a {
        Algorithm::Crc8(s) => fold!(s, u8, Crc8),
        Algorithm::Crc16(s) => fold!(s, u16, Crc16),
        Algorithm::Crc32(s) => fold!(s, u32, Crc32),
        Algorithm::Crc64(s) => fold!(s, u64, Crc64),
        other => other,
    }
}

/// Rule: a check's `over` names a run of fields of its struct before it, `"first..last"`
/// (first not after last) or `"field"`; a check is not inside a run another check covers
/// and is no field of a repeated element (checked where it repeats). Sets each check's run.
pub(super) fn resolve_check_runs(
    ctx: &mut Ctx<'_>,
    struct_name: &str,
    d: &StructDef,
    fields: &mut [Field],
) {
    for def in d.fields.get_ref() {
        let fd = def.get_ref();
        let (Some(over), Some(name)) = (&fd.over, &fd.name) else {
            if let (Some(over), None) = (&fd.over, &fd.check) {
                ctx.error(
                    over.span(),
                    "`over` applies to check fields",
                    "add `check = \"algorithm\"`, or remove `over`",
                );
            }
            continue;
        };
        if fd.check.is_none() {
            ctx.error(
                over.span(),
                "`over` applies to check fields",
                "add `check = \"algorithm\"`, or remove `over`",
            );
            continue;
        }
        let Some(at) = fields.iter().position(|f| &f.name == name.get_ref()) else {
            continue;
        };
        let before: Vec<&str> = fields[..at]
            .iter()
            .filter(|f| !f.name.is_empty())
            .map(|f| f.name.as_str())
            .collect();
        let text = over.get_ref();
        let (a, b) = text.split_once("..").unwrap_or((text, text));
        let find = |n: &str| fields[..at].iter().position(|f| f.name == n.trim());
        let (first, last) = match (find(a), find(b)) {
            (Some(first), Some(last)) if first <= last => (first, last),
            (Some(_), Some(_)) => {
                ctx.error(
                    over.span(),
                    format!("`{text}` starts after it ends"),
                    "name the first covered field first: `over = \"first..last\"`",
                );
                continue;
            }
            (x, _) => {
                let missing = if x.is_none() { a } else { b };
                let help = match did_you_mean(missing.trim(), before.iter().copied()) {
                    Some(best) => format!("did you mean `{best}`?"),
                    None => format!(
                        "a check covers fields of `{struct_name}` before it: {}",
                        before.join(", ")
                    ),
                };
                ctx.error(
                    over.span(),
                    format!(
                        "`{}` is no field of `{struct_name}` before check `{}`",
                        missing.trim(),
                        name.get_ref()
                    ),
                    help,
                );
                continue;
            }
        };
        if fields[first..=last]
            .iter()
            .any(|f| matches!(f.kind, FieldKind::Check(_)))
        {
            ctx.error(
                over.span(),
                format!("check `{}` covers another check", name.get_ref()),
                "cover the fields between the checks only",
            );
            continue;
        }
        let covered = if first == last {
            format!("`{}`", fields[first].name)
        } else {
            format!("`{}` to `{}`", fields[first].name, fields[last].name)
        };
        if let FieldKind::Check(c) = &mut fields[at].kind {
            c.first = first;
            c.last = last;
            c.covered = covered;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ir::{CrcSpec, CrcTable};

    fn spec<W: crc::Width>(params: crc::Algorithm<W>) -> CrcSpec<W> {
        CrcSpec {
            params,
            table: CrcTable::NoTable,
        }
    }

    #[test]
    fn a_folded_prefix_gives_the_crc_of_the_prefix_then_the_bytes() {
        let data = b"\xEC\xEA\x10\x01 and more bytes";
        let algorithms = [
            Algorithm::Crc8(spec(crc::CRC_8_DVB_S2)),
            Algorithm::Crc8(spec(crc::CRC_8_MAXIM_DOW)),
            Algorithm::Crc16(spec(crc::CRC_16_IBM_SDLC)),
            Algorithm::Crc16(spec(crc::CRC_16_XMODEM)),
            Algorithm::Crc32(spec(crc::CRC_32_ISO_HDLC)),
            Algorithm::Crc32(spec(crc::CRC_32_MPEG_2)),
            Algorithm::Crc64(spec(crc::CRC_64_XZ)),
            // Narrower than their registers, reflected or not, or reflected at the end only.
            Algorithm::Crc8(spec(crc::CRC_5_USB)),
            Algorithm::Crc8(spec(crc::CRC_7_MMC)),
            Algorithm::Crc16(spec(crc::CRC_12_UMTS)),
            Algorithm::Crc32(spec(crc::CRC_24_BLE)),
            Algorithm::Crc32(spec(crc::CRC_24_LTE_A)),
            Algorithm::Crc64(spec(crc::CRC_40_GSM)),
        ];
        for a in algorithms {
            for prefix in [&[0x32u8][..], b"\x00\xFF\x12"] {
                let mut whole = prefix.to_vec();
                whole.extend_from_slice(data);
                let folded = fold_prefix(a, prefix);
                assert_eq!(crc_of(&folded, data), crc_of(&a, &whole), "{a:?}");
                assert_eq!(crc_of(&folded, b""), crc_of(&a, prefix), "{a:?}");
            }
        }
    }

    #[test]
    fn the_crsf_command_crc_over_its_frame_type_gives_the_recorded_value() {
        // Poly 0xBA, init 0, no reflection: the inner CRC of CRSF command frames over type
        // 0x32 then EC EA 10 01 is 0x34 (tests/vectors/crsf.json, command_bind).
        let params = crc::Algorithm::<u8> {
            width: 8,
            poly: 0xBA,
            init: 0,
            refin: false,
            refout: false,
            xorout: 0,
            check: 0x20,
            residue: 0,
        };
        let folded = fold_prefix(Algorithm::Crc8(spec(params)), &[0x32]);
        assert_eq!(crc_of(&folded, &[0xEC, 0xEA, 0x10, 0x01]), Some(0x34));
    }
}
