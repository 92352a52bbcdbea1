//! C text with named holes: a template is the C it prints, with `${name}` where a value of
//! the spec goes (`${lo}decode`, `${size}u`). C never writes `$`, so a hole cannot be mistaken
//! for C, and braces stay single. [`fill!`] fills one; the loops over a spec's items stay Rust.

use std::fmt::{Display, Write as _};

/// Fills the `${name}` holes of a C template with `name = value` pairs (`name` alone: the
/// variable of that name), as `format!` does, without doubling C's braces.
///
/// A template that starts with a line break drops it, so that a template in a raw string
/// begins on the line after its opening quote, at the C's own indentation. A line that ends
/// with a backslash goes on at the next line's first non-blank character, as C splices such
/// lines: a long C line is written on several, and printed on one.
macro_rules! fill {
    (@value $name:ident) => {
        $name
    };
    (@value $name:ident $value:expr) => {
        $value
    };
    ($template:expr $(, $name:ident $(= $value:expr)?)* $(,)?) => {
        $crate::c::template::fill_holes(
            $template,
            &[$((
                stringify!($name),
                &$crate::c::template::fill!(@value $name $($value)?) as &dyn ::std::fmt::Display,
            )),*],
        )
    };
}
pub(crate) use fill;

/// The template with every hole filled. A hole without a value, or a value no hole takes, is
/// a mistake of the printer (every template is printed by the tests), not of the spec.
pub fn fill_holes(template: &str, values: &[(&str, &dyn Display)]) -> String {
    let template = template.strip_prefix('\n').unwrap_or(template);
    let template = splice(template);
    let mut out = String::with_capacity(template.len() + 64);
    let mut used = vec![false; values.len()];
    let mut rest = template.as_str();
    while let Some(at) = rest.find("${") {
        out.push_str(&rest[..at]);
        let hole = &rest[at + 2..];
        let Some(end) = hole.find('}') else {
            panic!("internal error: an unclosed `${{` in a C template")
        };
        let name = &hole[..end];
        let Some(k) = values.iter().position(|(n, _)| *n == name) else {
            panic!("internal error: the C template's hole `${{{name}}}` has no value")
        };
        used[k] = true;
        let _ = write!(out, "{}", values[k].1);
        rest = &hole[end + 1..];
    }
    out.push_str(rest);
    if let Some(k) = used.iter().position(|u| !u) {
        panic!(
            "internal error: the C template has no hole `${{{}}}`",
            values[k].0
        );
    }
    out
}

/// The template's lines that end with a backslash joined to the next, its indentation dropped.
fn splice(template: &str) -> String {
    let mut out = String::with_capacity(template.len());
    let mut rest = template;
    while let Some(at) = rest.find("\\\n") {
        out.push_str(&rest[..at]);
        rest = rest[at + 2..].trim_start_matches(' ');
    }
    out.push_str(rest);
    out
}

#[cfg(test)]
mod tests {
    #[test]
    fn holes_are_filled_and_braces_kept() {
        let lo = "hflink_";
        let text = fill!(
            r"
int ${lo}decode(void)
{
    return ${n};
}
",
            lo,
            n = 3
        );
        assert_eq!(text, "int hflink_decode(void)\n{\n    return 3;\n}\n");
    }

    #[test]
    fn a_line_ending_in_a_backslash_goes_on_at_the_next() {
        let text = fill!(
            r"
    if (a || \
        b) return ${e};
",
            e = 1
        );
        assert_eq!(text, "    if (a || b) return 1;\n");
    }

    #[test]
    #[should_panic(expected = "has no value")]
    fn a_hole_without_value_is_a_printer_mistake() {
        let _ = fill!("${lo}x");
    }

    #[test]
    #[should_panic(expected = "has no hole")]
    fn a_value_without_hole_is_a_printer_mistake() {
        let _ = fill!("x", lo = 1);
    }
}
