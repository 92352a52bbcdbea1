//! Rules for checksum algorithms: built-in sums, the `crc` catalogue by name, and custom CRCs
//! of `[checksums]` verified against their declared check value.

use super::catalog::{catalog, display_name};
use super::{Ctx, text};
use crate::diag::did_you_mean;
use crate::ir::{Algorithm, CrcParams};
use crate::spec::model::{ChecksumDef, SStr};
use toml::Spanned;

/// Built-in algorithms that are not CRCs: (spelling, algorithm, description).
pub const BUILTINS: &[(&str, &str)] = &[
    ("sum8", "sum of the bytes modulo 256"),
    ("sum-mod-256", "sum of the bytes modulo 256"),
    ("sum-mod-255", "sum of the bytes modulo 255"),
    ("xor8", "XOR of the bytes"),
];

fn builtin(name: &str) -> Option<Algorithm> {
    match name {
        "sum8" | "sum-mod-256" => Some(Algorithm::Sum { modulus: 256 }),
        "sum-mod-255" => Some(Algorithm::Sum { modulus: 255 }),
        "xor8" => Some(Algorithm::Xor),
        _ => None,
    }
}

fn normalize(s: &str) -> String {
    s.chars()
        .filter(|c| c.is_ascii_alphanumeric())
        .map(|c| c.to_ascii_lowercase())
        .collect()
}

/// Rule: a check names a built-in sum, a CRC of the `crc` catalogue (spelled `crc-16-umts`,
/// `CRC-16/UMTS` or `CRC_16_UMTS`), or an entry of `[checksums]`.
pub(crate) fn resolve_algorithm(ctx: &mut Ctx<'_>, name: &SStr) -> Option<Algorithm> {
    let n = name.get_ref();
    if let Some(a) = builtin(n) {
        return Some(a);
    }
    let spec = ctx.spec;
    if let Some((key, def)) = spec.checksums.iter().find(|(k, _)| k.get_ref() == n) {
        return lower_custom(ctx, key, def);
    }
    let wanted = normalize(n);
    if let Some((_, params)) = catalog().into_iter().find(|(c, _)| normalize(c) == wanted) {
        return Some(Algorithm::Crc(params));
    }
    let mut known: Vec<String> = BUILTINS.iter().map(|(b, _)| (*b).to_string()).collect();
    known.extend(catalog().iter().map(|(c, _)| display_name(c)));
    known.extend(spec.checksums.keys().map(|k| k.get_ref().clone()));
    let help = match did_you_mean(n, known.iter().map(String::as_str)) {
        Some(best) => format!("did you mean `{best}`?"),
        None => "use `sum8`, `sum-mod-255`, `xor8`, a CRC of the crc catalogue such as `crc-16-umts`, or define one under `[checksums.NAME]`".to_string(),
    };
    ctx.error(
        name.span(),
        format!("unknown checksum algorithm `{n}`"),
        help,
    );
    None
}

/// Rule: a custom checksum has `crc` parameters with a width of 8, 16, 32 or 64; poly, init and
/// xorout fit that width; the declared `check` equals the CRC of "123456789" computed from the
/// parameters; `table` is 0, 1 or 16.
fn lower_custom(ctx: &mut Ctx<'_>, key: &SStr, def: &Spanned<ChecksumDef>) -> Option<Algorithm> {
    let d = def.get_ref();
    let Some(crc) = &d.crc else {
        ctx.error(def.span(), format!("checksum `{}` has no `crc` parameters", key.get_ref()), "add `crc = { width = 16, poly = 0x1021, init = 0xFFFF, refin = false, refout = false, xorout = 0, check = 0x29B1 }`");
        return None;
    };
    let c = crc.get_ref();
    let width = *c.width.get_ref();
    if ![8, 16, 32, 64].contains(&width) {
        ctx.error(
            c.width.span(),
            format!("CRC width {width} cannot be stored in whole bytes"),
            "use a width of 8, 16, 32 or 64",
        );
        return None;
    }
    let max = if width == 64 {
        u64::MAX
    } else {
        (1u64 << width) - 1
    };
    let mut ok = true;
    for (what, v) in [
        ("poly", &c.poly),
        ("init", &c.init),
        ("xorout", &c.xorout),
        ("check", &c.check),
    ] {
        if *v.get_ref() < 0 || (*v.get_ref() as u64) > max {
            ctx.error(
                v.span(),
                format!("`{what}` {:#x} does not fit in {width} bits", v.get_ref()),
                format!("use a value from 0 to {max:#x}"),
            );
            ok = false;
        }
    }
    let table = match &d.table {
        None => 16,
        Some(t) if [0, 1, 16].contains(t.get_ref()) => *t.get_ref() as u8,
        Some(t) => {
            ctx.error(
                t.span(),
                format!("table size {} is not offered", t.get_ref()),
                "use 0 (no table, smallest), 1 (256 entries) or 16 (slicing-by-16, fastest)",
            );
            16
        }
    };
    if !ok {
        return None;
    }
    let params = CrcParams {
        catalog: None,
        display: key.get_ref().clone(),
        width: width as u8,
        poly: *c.poly.get_ref() as u64,
        init: *c.init.get_ref() as u64,
        refin: *c.refin.get_ref(),
        refout: *c.refout.get_ref(),
        xorout: *c.xorout.get_ref() as u64,
        check: *c.check.get_ref() as u64,
        residue: 0,
        table,
    };
    let actual = crc_of(&params, b"123456789");
    if actual != params.check {
        ctx.error(
            c.check.span(),
            format!("custom CRC `{}` declares check {:#x}, but its parameters give {actual:#x}", key.get_ref(), params.check),
            "fix the parameters or the check value; for a reflected CRC, `init` is the un-reflected register value (a C table that starts at R uses init = reflect(R))",
        );
        return None;
    }
    let _ = text(&d.doc);
    Some(Algorithm::Crc(params))
}

/// Compute a CRC with the `crc` crate (the same code the generated decoders run), its
/// parameters interned ([`crate::layout::crc_algorithm16`] and its siblings).
pub fn crc_of(p: &CrcParams, data: &[u8]) -> u64 {
    use crate::layout::{crc_algorithm8, crc_algorithm16, crc_algorithm32, crc_algorithm64};
    use crc::{Crc, NoTable};
    match p.width {
        8 => u64::from(Crc::<u8, NoTable>::new(crc_algorithm8(p)).checksum(data)),
        16 => u64::from(Crc::<u16, NoTable>::new(crc_algorithm16(p)).checksum(data)),
        32 => u64::from(Crc::<u32, NoTable>::new(crc_algorithm32(p)).checksum(data)),
        _ => Crc::<u64, NoTable>::new(crc_algorithm64(p)).checksum(data),
    }
}
