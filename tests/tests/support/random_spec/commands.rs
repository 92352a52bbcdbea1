//! The random spec's `[directions]` (told by a header field, by an address set, or given to
//! the decoder, one carrying a struct) and `[commands]` (ids, payloads per direction, CAN
//! ids, a byte per command for a check with `extra`), as its [`Shape`](super::Shape) says.
//! The frame formats that carry them are `frames.rs`'s.

use std::fmt::Write as _;

use super::{Directions, Spec};

impl Spec {
    /// `[directions]` (and `[addresses]` for directions told by an address set); `key_len` is
    /// the size of the first format's dispatch key.
    pub(super) fn emit_directions(&mut self, key_len: usize) {
        let t = match self.shape.directions {
            Directions::None => return,
            Directions::Equals => {
                self.feature("directions-equals");
                let a = self.rng.below(128);
                let b = a + self.rng.range(1, 127);
                format!(
                    "request = {{ field = \"src\", equals = {a} }}\nresponse = {{ field = \"src\", equals = {b} }}\n"
                )
            }
            Directions::Addresses => {
                self.feature("directions-addresses");
                self.feature("addresses");
                let split = self.rng.range(1, 200);
                writeln!(
                    self.out,
                    "[addresses]\nhost = {{ range = [0, {}] }}\ndevice = {{ range = [{split}, 255] }}\n",
                    split - 1
                )
                .unwrap();
                "request = { field = \"src\", in = \"host\" }\nresponse = { field = \"src\", in = \"device\" }\n".to_string()
            }
            Directions::Given => {
                self.feature("directions-given");
                "request = { given = true }\nresponse = { given = true }\n".to_string()
            }
            Directions::GivenMessage => {
                self.feature("directions-given");
                // The struct takes the dispatch key's bytes: it is at least as large.
                let fits: Vec<String> = self
                    .payloads
                    .iter()
                    .filter(|p| p.min >= key_len)
                    .map(|p| p.name.clone())
                    .collect();
                if fits.is_empty() {
                    "request = { given = true }\nresponse = { given = true }\n".to_string()
                } else {
                    self.feature("directions-message");
                    let p = self.rng.pick(&fits).clone();
                    format!(
                        "request = {{ given = true }}\nresponse = {{ given = true, message = \"{p}\" }}\n"
                    )
                }
            }
        };
        writeln!(self.out, "[directions]\n{t}").unwrap();
    }

    /// `[commands]`: ids, payloads (per direction where the spec has directions), a CAN id
    /// for those the CAN format carries, a byte per command for a check with `extra`.
    pub(super) fn emit_commands(&mut self, wide_cmd: bool, can_max: Option<usize>) {
        writeln!(self.out, "[commands]").unwrap();
        let can_fits: Vec<String> = can_max
            .map(|m| {
                self.payloads_within(m)
                    .into_iter()
                    .map(|p| p.name)
                    .collect()
            })
            .unwrap_or_default();
        let mut id = self.rng.below(3);
        let mut can_id = self.rng.below(0x100);
        let can_step = if self.shape.can == Some(true) {
            0x10_0000
        } else {
            0x40
        };
        for c in 0..self.rng.range(1, 4) {
            let mut t = if self.shape.two_key {
                format!("C{c} = {{ id = [{}, {id}]", self.rng.below(3))
            } else {
                format!("C{c} = {{ id = {id}")
            };
            let mut carried = Vec::new();
            let payload = |s: &mut Spec| {
                (!s.rng.one_in(5)).then(|| {
                    s.payloads[s.rng.below(s.payloads.len() as u64) as usize]
                        .name
                        .clone()
                })
            };
            match self.shape.directions {
                Directions::None => {
                    if let Some(p) = payload(self) {
                        write!(t, ", payload = \"{p}\"").unwrap();
                        carried.push(p);
                    }
                }
                Directions::GivenMessage => {
                    if let Some(p) = payload(self) {
                        write!(t, ", request = \"{p}\"").unwrap();
                    }
                }
                _ => {
                    for key in ["request", "response"] {
                        if let Some(p) = payload(self) {
                            write!(t, ", {key} = \"{p}\"").unwrap();
                        }
                    }
                }
            }
            if can_max.is_some() && carried.iter().all(|p| can_fits.contains(p)) {
                write!(t, ", can_id = {can_id:#x}").unwrap();
                can_id += self.rng.range(1, can_step);
            }
            if self.shape.extra {
                write!(t, ", check_extra = {}", self.rng.below(256)).unwrap();
            }
            t.push_str(" }");
            writeln!(self.out, "{t}").unwrap();
            id += self.rng.range(1, if wide_cmd { 4000 } else { 40 });
        }
        self.out.push('\n');
    }
}
