//! Rules for checksum algorithms: built-in sums, the `crc` catalogue by name or alias, and the
//! custom algorithms of `[checksums]` (CRCs verified against their declared check value, and
//! sums of a width with a final xor). What comes out is the runtime's own
//! [`Algorithm`](crate::ir::Algorithm): no backend translates it.

use super::catalog::{ALIASES, catalog, display_name};
use super::{Ctx, text};
use crate::diag::did_you_mean;
use crate::ir::{Algorithm, CheckNaming, CrcSpec, CrcTable};
use crate::spec::model::{ChecksumDef, CrcDef, SStr, SumDef, XorDef};
use toml::Spanned;

/// Built-in algorithms that are not CRCs: (spelling, description).
pub const BUILTINS: &[(&str, &str)] = &[
    ("sum8", "sum of the bytes modulo 256"),
    ("sum-mod-256", "sum of the bytes modulo 256"),
    ("sum-mod-255", "sum of the bytes modulo 255"),
    ("sum16", "sum of the bytes modulo 65536"),
    ("xor8", "XOR of the bytes"),
    (
        "fletcher-16",
        "Fletcher-16: two running sums modulo 255, stored as one 16-bit value B << 8 | A",
    ),
    (
        "fletcher-16-mod-256",
        "Fletcher's two running sums modulo 256 (u-blox UBX's CK_A, CK_B), stored as one 16-bit value B << 8 | A",
    ),
];

fn builtin(name: &str) -> Option<Algorithm> {
    match name {
        "sum8" | "sum-mod-256" => Some(Algorithm::Sum8),
        "sum-mod-255" => Some(Algorithm::SumMod255),
        "sum16" => Some(Algorithm::Sum {
            width: 2,
            init: 0,
            xorout: 0,
        }),
        "xor8" => Some(Algorithm::Xor8),
        "fletcher-16" => Some(Algorithm::Fletcher16),
        "fletcher-16-mod-256" => Some(Algorithm::Fletcher16Mod256),
        _ => None,
    }
}

fn normalize(s: &str) -> String {
    s.chars()
        .filter(|c| c.is_ascii_alphanumeric())
        .map(|c| c.to_ascii_lowercase())
        .collect()
}

fn naming(display: String, custom: bool, crc_constant: Option<String>) -> CheckNaming {
    CheckNaming {
        display,
        custom,
        crc_constant,
        table_static: None,
        extra_static: None,
    }
}

/// The catalogue CRC a name (a constant name or an alias, in any of the spellings
/// `crc-16-umts`, `CRC-16/UMTS`, `CRC_16_UMTS`) names: (constant, algorithm).
fn catalogue_crc(name: &str) -> Option<(&'static str, Algorithm)> {
    let wanted = normalize(name);
    let constant = ALIASES
        .iter()
        .find(|(alias, _)| normalize(alias) == wanted)
        .map(|(_, constant)| *constant);
    catalog()
        .into_iter()
        .find(|e| match constant {
            Some(c) => e.constant == c,
            None => normalize(e.constant) == wanted,
        })
        .map(|e| (e.constant, e.algorithm))
}

/// Rule: a check names a built-in sum, a CRC of the `crc` catalogue by its constant name or an
/// alias users know it by (spelled `crc-16-umts`, `CRC-16/UMTS` or `CRC_16_UMTS`), or an entry
/// of `[checksums]`. A misspelled name is answered with the closest name, aliases first.
pub(crate) fn resolve_algorithm(
    ctx: &mut Ctx<'_>,
    name: &SStr,
) -> Option<(Algorithm, CheckNaming)> {
    let n = name.get_ref();
    if let Some(a) = builtin(n) {
        return Some((a, naming(n.clone(), false, None)));
    }
    let spec = ctx.spec;
    if let Some((key, def)) = spec.checksums.iter().find(|(k, _)| k.get_ref() == n) {
        let algorithm = lower_custom(ctx, key, def)?;
        return Some((algorithm, naming(key.get_ref().clone(), true, None)));
    }
    if let Some((constant, algorithm)) = catalogue_crc(n) {
        let shown = naming(display_name(constant), false, Some(constant.to_string()));
        return Some((algorithm, shown));
    }
    let mut known: Vec<String> = ALIASES.iter().map(|(a, _)| display_name(a)).collect();
    known.extend(BUILTINS.iter().map(|(b, _)| (*b).to_string()));
    known.extend(catalog().iter().map(|e| display_name(e.constant)));
    known.extend(spec.checksums.keys().map(|k| k.get_ref().clone()));
    let help = match did_you_mean(n, known.iter().map(String::as_str)) {
        Some(best) => format!("did you mean `{best}`?"),
        None => "use `sum8`, `sum-mod-255`, `sum16`, `xor8`, `fletcher-16`, a CRC of the crc catalogue such as `crc-16-umts` or `crc-32`, or define one under `[checksums.NAME]`".to_string(),
    };
    ctx.error(
        name.span(),
        format!("unknown checksum algorithm `{n}`"),
        help,
    );
    None
}

/// Rule: a custom checksum is one of a CRC (`crc = {...}`), a sum (`sum = {...}`) or a XOR
/// (`xor = {...}`); `table` applies to a CRC only.
fn lower_custom(ctx: &mut Ctx<'_>, key: &SStr, def: &Spanned<ChecksumDef>) -> Option<Algorithm> {
    let d = def.get_ref();
    let _ = text(&d.doc);
    let kinds = [
        d.crc.as_ref().map(Spanned::span),
        d.sum.as_ref().map(Spanned::span),
        d.xor.as_ref().map(Spanned::span),
    ];
    if let Some(second) = kinds.iter().flatten().nth(1) {
        ctx.error(
            second.clone(),
            format!(
                "checksum `{}` has more than one of `crc`, `sum` and `xor`",
                key.get_ref()
            ),
            "keep one: a custom checksum is a CRC, a sum or a XOR",
        );
        return None;
    }
    // A table with neither parameters is answered by the missing parameters alone.
    if let (None, Some(t), true) = (&d.crc, &d.table, d.sum.is_some() || d.xor.is_some()) {
        let kind = if d.xor.is_some() { "a XOR" } else { "a sum" };
        ctx.error(
            t.span(),
            format!("checksum `{}` is {kind}: it has no table", key.get_ref()),
            "remove `table` (it sizes a CRC's lookup table)",
        );
    }
    match (&d.crc, &d.sum, &d.xor) {
        (Some(crc), ..) => lower_custom_crc(ctx, key, crc, d.table.as_ref()),
        (_, Some(sum), _) => lower_custom_sum(ctx, sum),
        (.., Some(xor)) => lower_custom_xor(ctx, xor),
        (None, None, None) => {
            ctx.error(def.span(), format!("checksum `{}` has no `crc`, `sum` or `xor` parameters", key.get_ref()), "add `crc = { width = 16, poly = 0x1021, init = 0xFFFF, refin = false, refout = false, xorout = 0, check = 0x29B1 }`, `sum = { width = 8, xorout = 0xFF }` for a complemented sum, or `xor = { init = 0xFF }` for a XOR from a constant");
            None
        }
    }
}

/// Rule: a custom XOR starts from an `init` of 0 to 255 (it is 8 bits wide).
fn lower_custom_xor(ctx: &mut Ctx<'_>, xor: &Spanned<XorDef>) -> Option<Algorithm> {
    let init = &xor.get_ref().init;
    match u8::try_from(*init.get_ref()) {
        Ok(init) => Some(Algorithm::Xor { init }),
        Err(_) => {
            ctx.error(
                init.span(),
                format!("`init` {:#x} does not fit in 8 bits", init.get_ref()),
                "a XOR checksum is one byte: use a value from 0 to 0xff",
            );
            None
        }
    }
}

/// Rule: a custom sum has a width of 8 or 16 bits, and its `init` (the value it starts from)
/// and `xorout` (all ones for the one's complement), both 0 by default, fit that width.
fn lower_custom_sum(ctx: &mut Ctx<'_>, sum: &Spanned<SumDef>) -> Option<Algorithm> {
    let s = sum.get_ref();
    let width = *s.width.get_ref();
    if width != 8 && width != 16 {
        ctx.error(
            s.width.span(),
            format!("sum width {width} is not offered"),
            "use a width of 8 (a sum modulo 256) or 16 (a sum modulo 65536)",
        );
        return None;
    }
    let max = (1i64 << width) - 1;
    let mut fits = |what: &str, v: &Option<Spanned<i64>>, help: &str| match v {
        None => Some(0),
        Some(x) if (0..=max).contains(x.get_ref()) => Some(*x.get_ref() as u16),
        Some(x) => {
            ctx.error(
                x.span(),
                format!("`{what}` {:#x} does not fit in {width} bits", x.get_ref()),
                format!("use a value from 0 to {max:#x}{help}"),
            );
            None
        }
    };
    let init = fits("init", &s.init, " (the value the sum starts from)");
    let xorout = fits(
        "xorout",
        &s.xorout,
        &format!(" ({max:#x} stores the one's complement of the sum)"),
    );
    Some(Algorithm::Sum {
        width: (width / 8) as u8,
        init: init?,
        xorout: xorout?,
    })
}

/// Rule: a CRC's `table` is 0, 1 or 16.
fn crc_table(ctx: &mut Ctx<'_>, t: &Spanned<i64>) -> Option<CrcTable> {
    match t.get_ref() {
        0 => Some(CrcTable::NoTable),
        1 => Some(CrcTable::Table1),
        16 => Some(CrcTable::Table16),
        other => {
            ctx.error(
                t.span(),
                format!("table size {other} is not offered"),
                "use 0 (no table, smallest), 1 (256 entries) or 16 (slicing-by-16, fastest)",
            );
            None
        }
    }
}

/// Rule: a check's `table` sizes the lookup table of a CRC (any CRC: of the catalogue, which
/// keeps its parameters, or of `[checksums]`, whose own `table` it overrides); it is 0, 1 or
/// 16, and a sum has none. Answers whether the table was set.
pub(crate) fn set_crc_table(
    ctx: &mut Ctx<'_>,
    t: &Spanned<i64>,
    algorithm: &mut Algorithm,
) -> bool {
    let Some(table) = crc_table(ctx, t) else {
        return false;
    };
    match algorithm {
        Algorithm::Crc8(s) => s.table = table,
        Algorithm::Crc16(s) => s.table = table,
        Algorithm::Crc32(s) => s.table = table,
        Algorithm::Crc64(s) => s.table = table,
        _ => {
            ctx.error(
                t.span(),
                "this check is not a CRC: it has no table",
                "remove `table` (it sizes a CRC's lookup table)",
            );
            return false;
        }
    }
    true
}

/// Rule: a custom CRC has a width of 1 to 64 bits (stored in the fewest whole bytes that hold
/// it: a CRC-24 in three); poly, init and xorout fit that width;
/// the declared `check` equals the CRC of "123456789" computed from the parameters; `table`
/// is 0, 1 or 16.
fn lower_custom_crc(
    ctx: &mut Ctx<'_>,
    key: &SStr,
    crc: &Spanned<CrcDef>,
    table: Option<&Spanned<i64>>,
) -> Option<Algorithm> {
    let c = crc.get_ref();
    let width = *c.width.get_ref();
    if !(1..=64).contains(&width) {
        ctx.error(
            c.width.span(),
            format!("CRC width {width} is not offered"),
            "use a width from 1 to 64 bits; the check is stored in the fewest whole bytes that hold it (a CRC-24 in 3)",
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
    let table = match table {
        None => CrcTable::ByTarget,
        Some(t) => crc_table(ctx, t).unwrap_or(CrcTable::ByTarget),
    };
    if !ok {
        return None;
    }
    // The values fit the width (checked above); `as` keeps their bits.
    let (poly, init, xorout, check) = (
        *c.poly.get_ref() as u64,
        *c.init.get_ref() as u64,
        *c.xorout.get_ref() as u64,
        *c.check.get_ref() as u64,
    );
    let (refin, refout) = (*c.refin.get_ref(), *c.refout.get_ref());
    macro_rules! spec {
        ($w:ty, $variant:ident) => {
            Algorithm::$variant(CrcSpec {
                params: crc::Algorithm::<$w> {
                    width: width as u8,
                    poly: poly as $w,
                    init: init as $w,
                    refin,
                    refout,
                    xorout: xorout as $w,
                    check: check as $w,
                    residue: 0,
                },
                table,
            })
        };
    }
    // The narrowest register that holds the width, as the `crc` crate's catalogue types its
    // CRCs (a CRC-24 is an `Algorithm<u32>`).
    let algorithm = match width {
        1..=8 => spec!(u8, Crc8),
        9..=16 => spec!(u16, Crc16),
        17..=32 => spec!(u32, Crc32),
        _ => spec!(u64, Crc64),
    };
    let actual = crc_of(&algorithm, b"123456789").unwrap_or(0);
    if actual != check {
        ctx.error(
            c.check.span(),
            format!("custom CRC `{}` declares check {check:#x}, but its parameters give {actual:#x}", key.get_ref()),
            "fix the parameters or the check value; for a reflected CRC, `init` is the un-reflected register value (a C table that starts at R uses init = reflect(R))",
        );
        return None;
    }
    Some(algorithm)
}

/// The CRC of `data` by the runtime's own code (its table-free [`Bitwise`] CRC, which holds
/// the parameters by value: validating a spec keeps nothing once it is done); `None` for an
/// algorithm that is not a CRC.
pub fn crc_of(a: &Algorithm, data: &[u8]) -> Option<u64> {
    use protocol_runtime::checksum::Bitwise;
    Some(match a {
        Algorithm::Crc8(c) => u64::from(Bitwise::<u8>::new(&c.params).checksum(data)),
        Algorithm::Crc16(c) => u64::from(Bitwise::<u16>::new(&c.params).checksum(data)),
        Algorithm::Crc32(c) => u64::from(Bitwise::<u32>::new(&c.params).checksum(data)),
        Algorithm::Crc64(c) => Bitwise::<u64>::new(&c.params).checksum(data),
        _ => return None,
    })
}
