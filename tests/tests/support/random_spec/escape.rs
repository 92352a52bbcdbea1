//! The random spec's byte escaping between flags (`escape`): the escape byte, the reserved
//! bytes and their substitutes, in either of the two forms the language takes.

use super::Spec;

impl Spec {
    /// The `escape` of a format whose flag is `flag`: an escape byte, and the reserved bytes
    /// (the flag, the escape byte, and up to two others, a zero often among them, as payloads
    /// hold many) with their substitutes, as a mask (`xor` with `bytes`) or a table (`map`).
    /// No substitute is the flag, and no two are the same.
    pub(super) fn escape_rule(&mut self, flag: u8) -> String {
        self.feature("escape");
        let mut side = self.side();
        let escape = loop {
            let b = side.below(256) as u8;
            if b != flag {
                break b;
            }
        };
        let mut reserved = vec![flag, escape];
        for _ in 0..side.below(3) {
            let b = if side.one_in(2) {
                0
            } else {
                side.below(256) as u8
            };
            if !reserved.contains(&b) {
                reserved.push(b);
            }
        }
        let hex = |b: &u8| format!("{b:#04X}");
        if side.one_in(2) {
            // A mask that sends no reserved byte as the flag.
            let xor = loop {
                let m = side.range(1, 255) as u8;
                if reserved.iter().all(|&b| b ^ m != flag) {
                    break m;
                }
            };
            let bytes: Vec<String> = reserved.iter().map(hex).collect();
            return format!(
                "{{ flag = {}, escape = {}, xor = {xor:#04X}, bytes = [{}] }}",
                hex(&flag),
                hex(&escape),
                bytes.join(", ")
            );
        }
        self.feature("escape-map");
        let mut subs: Vec<u8> = Vec::new();
        while subs.len() < reserved.len() {
            let b = side.below(256) as u8;
            if b != flag && !subs.contains(&b) {
                subs.push(b);
            }
        }
        let pairs: Vec<String> = reserved
            .iter()
            .zip(&subs)
            .map(|(r, s)| format!("[{}, {}]", hex(r), hex(s)))
            .collect();
        format!(
            "{{ flag = {}, escape = {}, map = [{}] }}",
            hex(&flag),
            hex(&escape),
            pairs.join(", ")
        )
    }
}
