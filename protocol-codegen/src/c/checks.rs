//! The check algorithms in C: one `static` function per check of the frame format, printed
//! from the IR's [`Algorithm`] as it is. A CRC is computed bitwise when the spec asks for no
//! table, else with one 256-entry table computed here from the CRC's parameters (a spec's
//! 16-table slicing is a speed choice of the Rust engine; the C code keeps one table).

use std::fmt::Write as _;

use crate::ir::{Algorithm, CrcTable, Protocol};

use super::names::{Names, unsigned_of};

/// The check functions (`pfx_check_<name>`), one per check of the first frame format.
pub fn checks(p: &Protocol, n: &Names) -> String {
    let mut out = String::from("/* ---- Checks ---- */\n\n");
    for c in &p.frames[0].checks {
        let name = format!("{}check_{}", n.lo, c.name);
        let _ = writeln!(out, "/* {} */", c.naming.display);
        out.push_str(&algorithm(&name, &c.algorithm));
        out.push('\n');
    }
    out
}

/// A CRC's parameters, widened to 64 bits.
struct Crc {
    width: u32,
    poly: u64,
    init: u64,
    refin: bool,
    refout: bool,
    xorout: u64,
    table: CrcTable,
}

fn algorithm(name: &str, a: &Algorithm) -> String {
    let body = |ty: &str, text: &str| {
        format!(
            "static uint64_t {name}(const uint8_t *p, size_t n)\n{{\n    {ty} s = 0;\n    size_t i;\n    for (i = 0; i < n; i++) {{\n{text}    }}\n"
        )
    };
    match a {
        Algorithm::Sum8 => {
            body("uint8_t", "        s = (uint8_t)(s + p[i]);\n") + "    return s;\n}\n"
        }
        Algorithm::SumMod255 => {
            body("uint32_t", "        s = (s + p[i]) % 255u;\n") + "    return s;\n}\n"
        }
        Algorithm::Xor8 => {
            body("uint8_t", "        s = (uint8_t)(s ^ p[i]);\n") + "    return s;\n}\n"
        }
        Algorithm::Sum { width, xorout } => {
            let mask = if *width == 1 { 0xFF } else { 0xFFFF };
            body("uint64_t", "        s += p[i];\n")
                + &format!("    return (s ^ {xorout:#x}u) & {mask:#x}u;\n}}\n")
        }
        Algorithm::Fletcher16 => fletcher(name, "% 255u"),
        Algorithm::Fletcher16Mod256 => fletcher(name, "& 0xFFu"),
        Algorithm::Crc8(c) => crc(
            name,
            &widen(
                c.params.width,
                c.params.poly.into(),
                c.params.init.into(),
                c.params.refin,
                c.params.refout,
                c.params.xorout.into(),
                c.table,
            ),
        ),
        Algorithm::Crc16(c) => crc(
            name,
            &widen(
                c.params.width,
                c.params.poly.into(),
                c.params.init.into(),
                c.params.refin,
                c.params.refout,
                c.params.xorout.into(),
                c.table,
            ),
        ),
        Algorithm::Crc32(c) => crc(
            name,
            &widen(
                c.params.width,
                c.params.poly.into(),
                c.params.init.into(),
                c.params.refin,
                c.params.refout,
                c.params.xorout.into(),
                c.table,
            ),
        ),
        Algorithm::Crc64(c) => crc(
            name,
            &widen(
                c.params.width,
                c.params.poly,
                c.params.init,
                c.params.refin,
                c.params.refout,
                c.params.xorout,
                c.table,
            ),
        ),
    }
}

#[allow(clippy::too_many_arguments)]
fn widen(
    width: u8,
    poly: u64,
    init: u64,
    refin: bool,
    refout: bool,
    xorout: u64,
    table: CrcTable,
) -> Crc {
    Crc {
        width: u32::from(width),
        poly,
        init,
        refin,
        refout,
        xorout,
        table,
    }
}

/// A Fletcher-16 sum, its two running sums reduced by `reduce` after every byte (the same
/// value as the runtime's reduction per block).
fn fletcher(name: &str, reduce: &str) -> String {
    format!(
        "static uint64_t {name}(const uint8_t *p, size_t n)\n{{\n    uint32_t a = 0, b = 0;\n    size_t i;\n    for (i = 0; i < n; i++) {{\n        a = (a + p[i]) {reduce};\n        b = (b + a) {reduce};\n    }}\n    return ((uint64_t)b << 8) | a;\n}}\n"
    )
}

fn mask(width: u32) -> u64 {
    if width >= 64 {
        u64::MAX
    } else {
        (1u64 << width) - 1
    }
}

fn reflect(v: u64, width: u32) -> u64 {
    (0..width).fold(0, |acc, i| acc | (((v >> i) & 1) << (width - 1 - i)))
}

/// The table entry of byte `i`: the register after shifting the byte through it.
fn entry(c: &Crc, i: u64) -> u64 {
    if c.refin {
        let poly = reflect(c.poly, c.width);
        (0..8).fold(i, |r, _| if r & 1 != 0 { (r >> 1) ^ poly } else { r >> 1 })
    } else {
        let top = 1u64 << (c.width - 1);
        (0..8).fold(i << (c.width - 8), |r, _| {
            (if r & top != 0 {
                (r << 1) ^ c.poly
            } else {
                r << 1
            }) & mask(c.width)
        })
    }
}

/// A CRC by its Rocksoft parameters: the register starts at `init` (reflected for a
/// reflected input), each byte goes in low bit first (reflected) or high bit first, and the
/// result is reflected when `refout` differs from `refin`, then xored with `xorout`.
fn crc(name: &str, c: &Crc) -> String {
    let ty = unsigned_of((c.width / 8) as usize);
    let w = c.width;
    let m = mask(w);
    let init = if c.refin { reflect(c.init, w) } else { c.init };
    let mut out = String::new();
    let step = match (c.table, c.refin) {
        (CrcTable::NoTable, true) => format!(
            "        int k;\n        r ^= p[i];\n        for (k = 0; k < 8; k++) {{\n            r = (r & 1u) ? (({ty})(r >> 1) ^ ({ty}){:#x}u) : ({ty})(r >> 1);\n        }}\n",
            reflect(c.poly, w)
        ),
        (CrcTable::NoTable, false) => format!(
            "        int k;\n        r ^= ({ty})((uint64_t)p[i] << {});\n        for (k = 0; k < 8; k++) {{\n            r = (r >> {}) & 1u ? ({ty})(((uint64_t)r << 1) ^ {:#x}u) : ({ty})((uint64_t)r << 1);\n        }}\n",
            w - 8,
            w - 1,
            c.poly
        ),
        (_, true) => {
            table(&mut out, name, ty, c);
            let shifted = if w > 8 {
                "(r >> 8)".to_string()
            } else {
                "0u".into()
            };
            format!("        r = ({ty})({name}_table[(r ^ p[i]) & 0xFFu] ^ {shifted});\n")
        }
        (_, false) => {
            table(&mut out, name, ty, c);
            let shifted = if w > 8 {
                "((uint64_t)r << 8)".to_string()
            } else {
                "0u".into()
            };
            format!(
                "        r = ({ty})({name}_table[((r >> {}) ^ p[i]) & 0xFFu] ^ {shifted});\n",
                w - 8
            )
        }
    };
    let refout = if c.refin != c.refout {
        format!(
            "    {{\n        {ty} o = 0;\n        int k;\n        for (k = 0; k < {w}; k++) {{\n            o = ({ty})(o | (((r >> k) & 1u) << ({w} - 1 - k)));\n        }}\n        r = o;\n    }}\n"
        )
    } else {
        String::new()
    };
    let _ = write!(
        out,
        "static uint64_t {name}(const uint8_t *p, size_t n)\n{{\n    {ty} r = ({ty}){init:#x}u;\n    size_t i;\n    for (i = 0; i < n; i++) {{\n{step}    }}\n{refout}    return (uint64_t)(r ^ ({ty}){:#x}u) & {};\n}}\n",
        c.xorout,
        super::names::u64_lit(m)
    );
    out
}

fn table(out: &mut String, name: &str, ty: &str, c: &Crc) {
    let digits = (c.width / 4) as usize;
    let _ = writeln!(out, "static const {ty} {name}_table[256] = {{");
    for row in 0..32u64 {
        let cells: Vec<String> = (0..8)
            .map(|k| format!("{:#0w$x}u", entry(c, row * 8 + k), w = digits + 2))
            .collect();
        let _ = writeln!(out, "    {},", cells.join(", "));
    }
    out.push_str("};\n");
}
