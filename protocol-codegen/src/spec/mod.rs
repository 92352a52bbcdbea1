//! Loading a spec: TOML text to the [`model`] that mirrors it, with every shape error (TOML
//! syntax, unknown key, wrong value type, missing key) reported with its span.
//!
//! serde stops at the first error of a document, so after each shape error the offending
//! entry is removed from the parsed tree and deserialization runs again: one run of the loader
//! reports every unknown key and ill-typed value of the file, not only the first.

pub mod model;
pub mod schema;

use std::ops::Range;

use serde::Deserialize;
use toml::Spanned;
use toml::de::{DeTable, DeValue};

use crate::diag::{Diagnostics, did_you_mean};
use crate::source::SpecSource;

pub use model::SpecFile;

/// Most shape errors reported from one file before giving up.
const MAX_SHAPE_ERRORS: usize = 64;

/// Parse and deserialize a spec.
///
/// Returns `None` when the text is not TOML or a required key is missing. After shape errors
/// that could be repaired by dropping the offending entry (an unknown key, an ill-typed value),
/// it returns the repaired model so that validation can report the remaining errors too; the
/// caller knows from `diags` that the spec is invalid, and the spans of those errors let it drop
/// follow-up errors about the entries that were dropped.
pub fn load_spec(source: &SpecSource, diags: &mut Diagnostics) -> Option<SpecFile> {
    let (tree, syntax_errors) = DeTable::parse_recoverable(&source.text);
    if !syntax_errors.is_empty() {
        // Only the first: the parser's recovery turns one missing bracket into a cascade.
        for e in syntax_errors.into_iter().take(1) {
            let span = e.span().unwrap_or(0..0);
            diags
                .error(span, format!("invalid TOML: {}", first_line(e.message())))
                .help("fix the TOML syntax; see docs/spec-format.md for the shape of a spec");
        }
        return None;
    }
    let mut tree = tree;
    let mut reported: Vec<Range<usize>> = Vec::new();
    for _ in 0..MAX_SHAPE_ERRORS {
        let de = toml::de::Deserializer::from(tree.clone());
        match SpecFile::deserialize(de) {
            Ok(spec) => return Some(spec),
            Err(e) => {
                let span = e.span().unwrap_or(0..0);
                // A key dropped to repair an ill-typed value is then "missing": that is the
                // same mistake, already reported.
                let repaired = e.message().starts_with("missing field")
                    && reported
                        .iter()
                        .any(|r: &Range<usize>| span.start <= r.start && r.end <= span.end);
                if repaired {
                    return None;
                }
                reported.push(span.clone());
                report_shape_error(diags, span.clone(), e.message());
                if !remove_span(&mut tree, &span) {
                    return None;
                }
            }
        }
    }
    None
}

/// Turn a serde/toml message into a located diagnostic with a useful help line.
fn report_shape_error(diags: &mut Diagnostics, span: Range<usize>, message: &str) {
    let message = first_line(message);
    if let Some(rest) = message.strip_prefix("unknown field `") {
        let name = rest.split('`').next().unwrap_or("");
        let expected: Vec<&str> = rest.split('`').skip(2).step_by(2).collect();
        let d = diags.error(span, format!("unknown key `{name}`"));
        match did_you_mean(name, expected.iter().copied()) {
            Some(best) => d.help(format!("did you mean `{best}`?")),
            None if expected.is_empty() => d.help("this table takes no keys"),
            None => d.help(format!(
                "the keys allowed here are {}",
                expected
                    .iter()
                    .map(|k| format!("`{k}`"))
                    .collect::<Vec<_>>()
                    .join(", ")
            )),
        };
    } else if let Some(rest) = message.strip_prefix("missing field `") {
        let name = rest.split('`').next().unwrap_or("");
        diags
            .error(span, format!("missing key `{name}`"))
            .help(format!("add `{name} = ...`; see docs/spec-format.md"));
    } else if message.contains("did not match any variant of untagged enum ConstantDef") {
        diags
            .error(
                span,
                "expected an integer, or a table `{ value = ..., doc = \"...\" }`",
            )
            .help("write `NAME = 12` or `NAME = { value = 12, doc = \"...\" }`");
    } else if message.contains("did not match any variant of untagged enum IdDef") {
        diags
            .error(span, "expected an integer id, or an array of integers")
            .help("write `id = 0x01`, or `id = [0x02, 0x01]` for a two-field dispatch key");
    } else if message.contains("did not match any variant of untagged enum CountDef") {
        diags
            .error(span, "expected an integer count, or the name of a constant")
            .help("write `count = 8` or `count = \"SERVO_COUNT\"`");
    } else if let Some(rest) = message.strip_prefix("invalid type: ") {
        diags
            .error(span, format!("wrong type of value: {rest}"))
            .help("see docs/spec-format.md for the type each key takes");
    } else {
        diags
            .error(span, message.to_string())
            .help("see docs/spec-format.md");
    }
}

fn first_line(message: &str) -> &str {
    message.lines().next().unwrap_or("").trim()
}

/// Remove the table entry or array element whose key or value has exactly this span.
fn remove_span(table: &mut Spanned<DeTable<'_>>, span: &Range<usize>) -> bool {
    remove_in_table(table.get_mut(), span)
}

fn remove_in_table(table: &mut DeTable<'_>, span: &Range<usize>) -> bool {
    let key = table
        .iter()
        .find(|(k, v)| k.span() == *span || v.span() == *span)
        .map(|(k, _)| k.get_ref().to_string());
    if let Some(key) = key {
        table.remove(key.as_str());
        return true;
    }
    table
        .iter_mut()
        .any(|(_, v)| remove_in_value(v.get_mut(), span))
}

fn remove_in_value(value: &mut DeValue<'_>, span: &Range<usize>) -> bool {
    match value {
        DeValue::Table(t) => remove_in_table(t, span),
        DeValue::Array(items) => {
            if let Some(i) = items.iter().position(|v| v.span() == *span) {
                // Replace rather than remove, so sibling positions stay meaningful.
                let mut kept: Vec<Spanned<DeValue<'_>>> = Vec::new();
                for (j, v) in items.iter().enumerate() {
                    if j != i {
                        kept.push(v.clone());
                    }
                }
                *items = kept.into_iter().collect();
                return true;
            }
            items.iter_mut().any(|v| remove_in_value(v.get_mut(), span))
        }
        _ => false,
    }
}
