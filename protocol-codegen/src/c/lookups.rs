//! The source's functions on a spec's names: whether raw bits name an enum's variant
//! (`<enum>_known`), and the spec name of a variant, a command and a direction (`_name`).

use crate::ir::{Enum, Protocol};

use super::names::{Names, mask, u64_lit};
use super::template::fill;

/// The functions of every enum, then `command_name` and `direction_name`.
pub fn lookups(p: &Protocol, n: &Names) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let mut out = String::from("/* ---- Names ---- */\n\n");
    for e in &p.enums {
        enum_fns(n, e, &mut out);
    }
    out.push_str(&switch(
        &fill!("const char *${lo}command_name(${lo}command command)", lo),
        "command",
        p.commands
            .iter()
            .map(|c| (format!("{up}{}", c.name), format!("\"{}\"", c.name))),
        "NULL",
    ));
    if !p.directions.is_empty() {
        out.push_str(&switch(
            &fill!(
                "const char *${lo}direction_name(${lo}direction direction)",
                lo
            ),
            "direction",
            p.directions.iter().map(|d| {
                (
                    format!("{up}{}", d.name.to_uppercase()),
                    format!("\"{}\"", d.name),
                )
            }),
            "NULL",
        ));
    }
    out
}

/// `<enum>_known` and `<enum>_name`: the variants by their bits in the enum's width.
fn enum_fns(n: &Names, e: &Enum, out: &mut String) {
    let (ty, up) = (n.ty(&e.name), &n.up);
    let m = mask(8 * e.prim.size() as u32);
    let head = fill!(
        r"
/* Whether raw bits (the enum's width) name a variant. */
${up}UNUSED static int ${ty}_known(uint64_t bits)",
        up,
        ty
    );
    let cases = e
        .variants
        .iter()
        .map(|v| (u64_lit(v.value & m), "1".into()));
    out.push_str(&switch(&head, "bits", cases, "0"));
    let cases = e
        .variants
        .iter()
        .map(|v| (u64_lit(v.value & m), format!("\"{}\"", v.name)));
    out.push_str(&switch(
        &fill!("const char *${ty}_name(${ty} value)", ty),
        &format!("(uint64_t)value & {}", u64_lit(m)),
        cases,
        "NULL",
    ));
}

/// A function whose body is one switch over `selector`: `case LABEL: return VALUE;` per
/// case, `default` otherwise.
fn switch(
    head: &str,
    selector: &str,
    cases: impl Iterator<Item = (String, String)>,
    default: &str,
) -> String {
    let mut out = fill!(
        r"
${head}
{
    switch (${selector}) {
",
        head,
        selector
    );
    for (label, value) in cases {
        out.push_str(&fill!(
            "    case ${label}: return ${value};\n",
            label,
            value
        ));
    }
    out.push_str(&fill!(
        r"
    default: return ${default};
    }
}

",
        default
    ));
    out
}
