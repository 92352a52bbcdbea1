//! What the statements of every field kind in a struct's reader or writer share: the
//! direction of the walk, the value of a field that states a length, the context a repeated
//! struct is given, the checks of a count before it is written. Each kind's own statements are
//! its module's in `kinds`; one value's are `values`'.

use crate::ir::{Field, Struct};

use super::names::{self, Names};
use super::template::fill;

/// Which way a struct's walk goes: from the payload into the C struct, or back.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dir {
    Read,
    Write,
}

/// The C value of the unsigned integer field `name` that states a length, in struct `s`
/// being read or written through `this`: the struct's own field before it, or one of the
/// struct that repeats it (`ctx`, in the order of [`Struct::context`]).
pub(super) fn stated(s: &Struct, this: &str, name: &str) -> String {
    match s.context.iter().position(|c| c == name) {
        Some(j) => format!("ctx[{j}]"),
        None => format!("(uint64_t){this}->{}", names::field(name)),
    }
}

/// The context values a struct that repeats `elem` passes to its reader or writer: the
/// fields `elem.context` names, from `this` (or from the repeating struct's own context).
pub(super) fn context_args(s: &Struct, elem: &Struct, this: &str) -> String {
    if elem.context.is_empty() {
        return String::new();
    }
    let values: Vec<String> = elem.context.iter().map(|c| stated(s, this, c)).collect();
    format!(", (const uint64_t[]){{{}}}", values.join(", "))
}

/// Lines indented `levels` levels (four spaces each) more.
pub(super) fn indent(text: &str, levels: usize) -> String {
    let pad = "    ".repeat(levels);
    text.lines().map(|l| format!("{pad}{l}\n")).collect()
}

/// The flag of an optional field whose value is `here` (`out->ports` -> `out->ports_present`).
pub(super) fn optional_flag(here: &str, f: &Field) -> String {
    let base = here.rsplit_once("->").map_or("", |(b, _)| b);
    format!("{base}->{}_present", names::field(&f.name))
}

/// The checks of a count before its bytes or elements are written: at most `max`, and the
/// count a field states (the runtime's `field::check_stated_len`).
pub(super) fn count_fits(n: &Names, max: usize, stated: Option<&str>, here: &str) -> String {
    let up = &n.up;
    let mut out = fill!(
        "    if (${here}_len > ${max}u) return ${up}ERR_OUT_OF_RANGE;\n",
        here,
        max,
        up
    );
    if let Some(stated) = stated {
        out.push_str(&fill!(
            "    if ((uint64_t)${here}_len != ${stated}) return ${up}ERR_OUT_OF_RANGE;\n",
            here,
            stated,
            up
        ));
    }
    out
}
