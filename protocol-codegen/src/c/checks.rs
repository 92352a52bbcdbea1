//! The check algorithms in C: one `static` function per check of the frame format, printed
//! from the IR's [`Algorithm`] as it is. A CRC is computed bitwise when the spec asks for no
//! table, else with one 256-entry table computed here from the CRC's parameters (a spec's
//! 16-table slicing is a speed choice of the Rust engine; the C code keeps one table).
//!
//! Every check function has one shape, `int pfx_check_<name>(p, n, &value)`: 1 with the check
//! value of `p[0..n]`, or 0 when it has none. Only a check that folds in a per-command byte
//! (the IR's [`CheckExtra`], MAVLink's CRC_EXTRA) can have none: its key, read from the
//! covered bytes, may name no command (the runtime's `Extra::compute` gives `None` then, and
//! a decoder rejects the candidate as a bad check).

use crate::ir::{Algorithm, CheckExtra, CrcTable, Field, FieldKind, Protocol, Struct};
use protocol_runtime::checksum::CrcSpec;

use super::names::{Fx, Names, mask, snake, u64_lit, unsigned_of};
use super::template::fill;

/// The check functions (`pfx_check_<name>`, the format's prefix), one per check of each
/// frame format.
pub fn checks(p: &Protocol, n: &Names) -> String {
    let mut out = String::from("/* ---- Checks ---- */\n\n");
    for (fi, f) in p.frames.iter().enumerate() {
        let x = Fx::new(p, fi);
        for c in &f.checks {
            let name = format!("{}check_{}", x.lo, c.name);
            out.push_str(&format!("/* {} */\n", c.naming.display));
            out.push_str(&check_fn(n, &name, &c.algorithm, c.extra.as_ref()));
            out.push('\n');
        }
    }
    out
}

/// How an algorithm is printed: its state, what one byte does to it, and its value.
struct Parts {
    /// Declarations of the state, initialised.
    state: String,
    /// A table the steps use, printed before the function.
    table: String,
    /// The statements one byte `b` (a C expression) runs, inside the loop over the bytes.
    step: Box<dyn Fn(&str) -> String>,
    /// Statements after the last byte, before `value`.
    finish: String,
    /// The check value, a `uint64_t` expression.
    value: String,
    /// Whether a folded-in byte goes through `step` (a CRC; a sum folds nothing, as the
    /// runtime's `Extra::fold` does).
    folds: bool,
    /// For a sum reduced modulo 255: the bytes `step` may add to the state without reducing
    /// it (the state then stays below 2^32), and the statement that reduces it. The bytes are
    /// summed in blocks of that many, reduced once per block instead of once per byte: the
    /// same value, since a reduction modulo 255 may come at any point of the sum.
    block: Option<(usize, &'static str)>,
    /// For a plain sum in blocks: the statement that adds four bytes from `p[i]` at once
    /// (fewer loop turns per byte).
    four: Option<&'static str>,
}

/// The check functions of the checks inside payload structs (`pfx_pcheck_<struct>_<field>`),
/// the runtime's `field::verify_check` and `field::put_check` compute them over the covered
/// fields' bytes (a constant prefix is folded into a CRC's initial value by the IR).
pub fn payload_checks(p: &Protocol, n: &Names) -> String {
    let mut out = String::new();
    for s in &p.structs {
        for f in &s.fields {
            if let FieldKind::Check(c) = &f.kind {
                let (what, field, covered) = (&c.naming.display, &f.name, &c.covered);
                let name = &s.name;
                out.push_str(&fill!(
                    "/* ${what}: `${field}` of struct `${name}` over ${covered} */\n",
                    what,
                    field,
                    name,
                    covered
                ));
                out.push_str(&check_fn(
                    n,
                    &payload_check_name(n, s, f),
                    &c.algorithm,
                    None,
                ));
                out.push('\n');
            }
        }
    }
    out
}

/// The C function of a check inside a payload struct.
pub fn payload_check_name(n: &Names, s: &Struct, f: &Field) -> String {
    format!("{}pcheck_{}_{}", n.lo, snake(&s.name), f.name)
}

/// One check function: the per-command byte looked up (a check that folds one in), the
/// bytes stepped through the algorithm, the byte folded in, the value.
fn check_fn(n: &Names, name: &str, algorithm: &Algorithm, extra: Option<&CheckExtra>) -> String {
    let parts = parts(name, algorithm);
    let mut body = extra.map_or(String::new(), |x| extra_lookup(n, x));
    body.push_str(&bytes_loop(&parts));
    if extra.is_some() && parts.folds {
        // The loop body's statements, one level out.
        for line in (parts.step)("extra").lines() {
            body.push_str(line.strip_prefix("    ").unwrap_or(line));
            body.push('\n');
        }
    }
    let Parts {
        table,
        state,
        finish,
        value,
        ..
    } = parts;
    fill!(
        r"
${table}static int ${name}(const uint8_t *p, size_t n, uint64_t *out)
{
${state}    size_t i;
${body}${finish}    *out = ${value};
    return 1;
}
",
        table,
        name,
        state,
        body,
        finish,
        value
    )
}

/// The loop over the bytes `p[0..n]`: one step per byte, or for a sum in blocks, a block's
/// steps (four bytes at a time where the sum has a statement for it) then its reduction.
fn bytes_loop(parts: &Parts) -> String {
    let Some((block, reduce)) = parts.block else {
        let step = (parts.step)("p[i]");
        return fill!(
            r"
    for (i = 0; i < n; i++) {
${step}    }
",
            step
        );
    };
    let four = parts.four.map_or(String::new(), |four| {
        fill!(
            r"
        for (; stop - i >= 4u; i += 4u) {
            ${four}
        }
",
            four
        )
    });
    let step: String = (parts.step)("p[i]")
        .lines()
        .map(|line| format!("    {line}\n"))
        .collect();
    fill!(
        r"
    for (i = 0; i < n;) {
        size_t stop = n - i > ${block}u ? i + ${block}u : n;
${four}        for (; i < stop; i++) {
${step}        }
        ${reduce}
    }
",
        block,
        four,
        step,
        reduce
    )
}

/// The byte the key in the covered bytes picks (`uint8_t extra`), or `return 0` for a key
/// without one.
fn extra_lookup(n: &Names, x: &CheckExtra) -> String {
    let (from_end, at) = match x.key.at {
        crate::ir::Pos::Start(a) => (0, a),
        crate::ir::Pos::End(a) => (1, a),
    };
    let (lo, size, shift, width) = (&n.lo, x.key.size, x.key.shift, x.key.width);
    let big = u8::from(x.key.order == crate::ir::ByteOrder::Big);
    let mut out = fill!(
        r"
    uint64_t key = 0;
    uint8_t extra;
    if (!${lo}field(p, n, ${from_end}, ${at}u, ${size}u, ${big}, ${shift}u, ${width}u, &key)) return 0;
    switch (key) {
",
        lo,
        from_end,
        at,
        size,
        big,
        shift,
        width
    );
    for (key, byte) in &x.bytes {
        out.push_str(&fill!(
            "    case ${key}u: extra = ${byte}u; break;\n",
            key,
            byte
        ));
    }
    out.push_str(&fill!(
        r"
    default: return 0;
    }
"
    ));
    out
}

fn parts(name: &str, a: &Algorithm) -> Parts {
    let sum = |ty: &str, step: &'static str, value: String| Parts {
        state: fill!("    ${ty} s = 0;\n", ty),
        table: String::new(),
        step: Box::new(move |b| format!("        {}\n", step.replace("BYTE", b))),
        finish: String::new(),
        value,
        folds: false,
        block: None,
        four: None,
    };
    match a {
        Algorithm::Sum8 => sum("uint8_t", "s = (uint8_t)(s + BYTE);", "s".into()),
        // Below 255 at a block's start, plus at most 255 per byte: 65,536 bytes keep the sum
        // below 2^24.
        Algorithm::SumMod255 => Parts {
            block: Some((65_536, "s %= 255u;")),
            four: Some("s += (uint32_t)p[i] + p[i + 1] + p[i + 2] + p[i + 3];"),
            ..sum("uint32_t", "s += BYTE;", "s".into())
        },
        Algorithm::Xor8 => sum("uint8_t", "s = (uint8_t)(s ^ BYTE);", "s".into()),
        Algorithm::Sum {
            width,
            init,
            xorout,
        } => {
            let mask = if *width == 1 { 0xFF } else { 0xFFFF };
            Parts {
                state: format!("    uint64_t s = {init:#x}u;\n"),
                ..sum(
                    "uint64_t",
                    "s += BYTE;",
                    format!("(s ^ {xorout:#x}u) & {mask:#x}u"),
                )
            }
        }
        Algorithm::Xor { init } => Parts {
            state: format!("    uint8_t s = {init:#x}u;\n"),
            ..sum("uint8_t", "s = (uint8_t)(s ^ BYTE);", "s".into())
        },
        Algorithm::Fletcher16 => fletcher("% 255u"),
        Algorithm::Fletcher16Mod256 => fletcher("& 0xFFu"),
        Algorithm::Crc8(c) => crc(name, &Crc::of(c)),
        Algorithm::Crc16(c) => crc(name, &Crc::of(c)),
        Algorithm::Crc32(c) => crc(name, &Crc::of(c)),
        Algorithm::Crc64(c) => crc(name, &Crc::of(c)),
    }
}

/// A Fletcher-16 sum, its two running sums reduced by `reduce` after every byte (the same
/// value as the runtime's reduction per block).
fn fletcher(reduce: &'static str) -> Parts {
    Parts {
        state: "    uint32_t a = 0, b = 0;\n".into(),
        table: String::new(),
        step: Box::new(move |byte| {
            fill!(
                r"
        a = (a + ${byte}) ${reduce};
        b = (b + a) ${reduce};
",
                byte,
                reduce
            )
        }),
        finish: String::new(),
        value: "((uint64_t)b << 8) | a".into(),
        folds: false,
        block: None,
        four: None,
    }
}

/// A CRC's parameters, widened to 64 bits, with the register the C code shifts: the CRC's
/// own width, except for a CRC of fewer than 8 bits that is not reflected, which runs in an
/// 8-bit register with its polynomial and initial value moved to the top (as the `crc` crate
/// computes it), so that a byte always fits the register.
struct Crc {
    /// Bits of the register the steps shift: `width`, or 8.
    width: u32,
    /// Bits of the CRC: the register is shifted right by `width - crc_width` at the end.
    crc_width: u32,
    poly: u64,
    init: u64,
    refin: bool,
    refout: bool,
    xorout: u64,
    table: CrcTable,
}

impl Crc {
    fn of<W: crc::Width + Copy + Into<u64>>(c: &CrcSpec<W>) -> Crc {
        let crc_width = u32::from(c.params.width);
        let pad = if c.params.refin {
            0
        } else {
            8u32.saturating_sub(crc_width)
        };
        let (poly, init): (u64, u64) = (c.params.poly.into(), c.params.init.into());
        Crc {
            width: crc_width + pad,
            crc_width,
            poly: poly << pad,
            init: init << pad,
            refin: c.params.refin,
            refout: c.params.refout,
            xorout: c.params.xorout.into(),
            table: c.table,
        }
    }

    /// The C type of the register: the fewest whole bytes that hold it.
    fn ty(&self) -> &'static str {
        unsigned_of(self.width.div_ceil(8) as usize)
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
fn crc(name: &str, c: &Crc) -> Parts {
    let ty = c.ty();
    let w = c.width;
    let init = if c.refin { reflect(c.init, w) } else { c.init };
    let mut state = format!("    {ty} r = ({ty}){init:#x}u;\n");
    let mut table = String::new();
    let step = match c.table {
        CrcTable::NoTable => {
            state.push_str("    int k;\n");
            bitwise_step(c)
        }
        _ => {
            table = crc_table(name, ty, c);
            table_step(name, c)
        }
    };
    let mut finish = match w - c.crc_width {
        0 => String::new(),
        pad => fill!("    r = (${ty})(r >> ${pad});\n", ty, pad),
    };
    let w = c.crc_width;
    if c.refin != c.refout {
        finish.push_str(&fill!(
            r"
    {
        ${ty} o = 0;
        int j;
        for (j = 0; j < ${w}; j++) {
            o = (${ty})(o | (((r >> j) & 1u) << (${w} - 1 - j)));
        }
        r = o;
    }
",
            ty,
            w
        ));
    }
    let (xorout, mask) = (format!("{:#x}", c.xorout), u64_lit(mask(w)));
    Parts {
        state,
        table,
        step,
        finish,
        value: fill!(
            "(uint64_t)(r ^ (${ty})${xorout}u) & ${mask}",
            ty,
            xorout,
            mask
        ),
        folds: true,
        block: None,
        four: None,
    }
}

/// The step of a CRC without table: the byte into the register, then eight shifts.
fn bitwise_step(c: &Crc) -> Box<dyn Fn(&str) -> String> {
    let ty = c.ty();
    if c.refin {
        let poly = format!("{:#x}", reflect(c.poly, c.width));
        return Box::new(move |b| {
            fill!(
                r"
        r ^= ${b};
        for (k = 0; k < 8; k++) {
            r = (r & 1u) ? ((${ty})(r >> 1) ^ (${ty})${poly}u) : (${ty})(r >> 1);
        }
",
                b,
                ty,
                poly
            )
        });
    }
    let (poly, low, top) = (format!("{:#x}", c.poly), c.width - 8, c.width - 1);
    Box::new(move |b| {
        fill!(
            r"
        r ^= (${ty})((uint64_t)${b} << ${low});
        for (k = 0; k < 8; k++) {
            r = (r >> ${top}) & 1u ? (${ty})(((uint64_t)r << 1) ^ ${poly}u) : (${ty})((uint64_t)r << 1);
        }
",
            ty,
            b,
            low,
            top,
            poly
        )
    })
}

/// The step of a CRC with a table: one lookup per byte.
fn table_step(name: &str, c: &Crc) -> Box<dyn Fn(&str) -> String> {
    let ty = c.ty();
    // A reflected register of up to 8 bits takes its byte whole (`low` 0); a register that is
    // not reflected is at least 8 bits (`Crc::of`).
    let (name, refin, low) = (name.to_string(), c.refin, c.width.saturating_sub(8));
    Box::new(move |b| match (refin, low > 0) {
        (true, true) => fill!(
            "        r = (${ty})(${name}_table[(r ^ ${b}) & 0xFFu] ^ (r >> 8));\n",
            ty,
            name,
            b
        ),
        (false, true) => fill!(
            "        r = (${ty})(${name}_table[((r >> ${low}) ^ ${b}) & 0xFFu] ^ ((uint64_t)r << 8));\n",
            ty,
            name,
            low,
            b
        ),
        (_, false) => fill!("        r = ${name}_table[(r ^ ${b}) & 0xFFu];\n", name, b),
    })
}

/// The 256-entry table of a CRC, eight entries a line.
fn crc_table(name: &str, ty: &str, c: &Crc) -> String {
    let digits = c.width.div_ceil(4) as usize;
    let mut rows = String::new();
    for row in 0..32u64 {
        let cells: Vec<String> = (0..8)
            .map(|k| format!("{:#0w$x}u", entry(c, row * 8 + k), w = digits + 2))
            .collect();
        rows.push_str(&format!("    {},\n", cells.join(", ")));
    }
    fill!(
        r"
static const ${ty} ${name}_table[256] = {
${rows}};
",
        ty,
        name,
        rows
    )
}
