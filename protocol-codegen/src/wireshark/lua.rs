//! Lua literals of the runtime's vocabulary: strings, byte lists, positions, word fields and
//! check algorithms, as the dissector's tables hold them. One function per kind of value.

use std::fmt::Write as _;

use crate::ir::{Algorithm, ByteOrder, Pos, WordField};

/// A Lua string literal (double-quoted, with `\` and `"` escaped and control bytes as `\ddd`).
pub fn string(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + 2);
    out.push('"');
    for b in text.bytes() {
        match b {
            b'"' => out.push_str("\\\""),
            b'\\' => out.push_str("\\\\"),
            0x20..=0x7e => out.push(b as char),
            other => {
                let _ = write!(out, "\\{other:03}");
            }
        }
    }
    out.push('"');
    out
}

/// `{ 0xFF, 0xFF }`.
pub fn bytes(bytes: &[u8]) -> String {
    let items: Vec<String> = bytes.iter().map(|b| format!("0x{b:02X}")).collect();
    format!("{{ {} }}", items.join(", "))
}

/// `{ s = 4 }` from the start, `{ e = 2 }` back from the end.
pub fn pos(p: Pos) -> String {
    match p {
        Pos::Start(n) => format!("{{ s = {n} }}"),
        Pos::End(n) => format!("{{ e = {n} }}"),
    }
}

/// `"le"` or `"be"`.
pub fn order(o: ByteOrder) -> &'static str {
    match o {
        ByteOrder::Little => "\"le\"",
        ByteOrder::Big => "\"be\"",
    }
}

/// A word field: where, how many bytes, which bits.
pub fn word(w: WordField) -> String {
    format!(
        "{{ at = {}, size = {}, order = {}, shift = {}, width = {} }}",
        pos(w.at),
        w.size,
        order(w.order),
        w.shift,
        w.width
    )
}

/// A check algorithm as the dissector's `compute` runs it; `None` for a CRC wider than the
/// 32 bits Lua's `bit32` computes.
pub fn algorithm(a: &Algorithm) -> Option<String> {
    let crc = |width: u8, poly: u64, init: u64, refin: bool, refout: bool, xorout: u64| {
        format!(
            "{{ kind = \"crc\", width = {width}, poly = 0x{poly:X}, init = 0x{init:X}, \
             refin = {refin}, refout = {refout}, xorout = 0x{xorout:X} }}"
        )
    };
    Some(match a {
        Algorithm::Sum8 => "{ kind = \"sum8\" }".to_string(),
        Algorithm::SumMod255 => "{ kind = \"sum_mod_255\" }".to_string(),
        Algorithm::Xor8 => "{ kind = \"xor8\" }".to_string(),
        Algorithm::Sum {
            width,
            init,
            xorout,
        } => {
            // A sum without a seed prints as it always has (its `init` is 0 in the dissector).
            let seed = match init {
                0 => String::new(),
                init => format!(", init = 0x{init:X}"),
            };
            format!("{{ kind = \"sum\", width = {width}{seed}, xorout = 0x{xorout:X} }}")
        }
        Algorithm::Xor { init } => format!("{{ kind = \"xor8\", init = 0x{init:X} }}"),
        Algorithm::Fletcher16 => "{ kind = \"fletcher16\" }".to_string(),
        Algorithm::Fletcher16Mod256 => "{ kind = \"fletcher16_mod256\" }".to_string(),
        Algorithm::Crc8(c) => {
            let p = &c.params;
            let (poly, init, xorout) = (p.poly.into(), p.init.into(), p.xorout.into());
            crc(p.width, poly, init, p.refin, p.refout, xorout)
        }
        Algorithm::Crc16(c) => {
            let p = &c.params;
            let (poly, init, xorout) = (p.poly.into(), p.init.into(), p.xorout.into());
            crc(p.width, poly, init, p.refin, p.refout, xorout)
        }
        Algorithm::Crc32(c) => {
            let p = &c.params;
            let (poly, init, xorout) = (p.poly.into(), p.init.into(), p.xorout.into());
            crc(p.width, poly, init, p.refin, p.refout, xorout)
        }
        // Every CRC of more than 32 bits is a `Crc64` (the narrowest register that holds it).
        Algorithm::Crc64(_) => return None,
    })
}

#[cfg(test)]
mod tests {
    #[test]
    fn strings_are_escaped() {
        assert_eq!(super::string("a\"b\\c\n"), "\"a\\\"b\\\\c\\010\"");
    }
}
