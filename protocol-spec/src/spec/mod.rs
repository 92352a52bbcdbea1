//! Loading a spec: TOML text to the [`model`] that mirrors it, with every shape error (TOML
//! syntax, unknown key, wrong value type, missing key) reported with its span.
//!
//! serde stops at the first error of a document, so after each shape error the offending
//! entry is removed from the parsed tree and deserialization runs again: one run of the loader
//! reports every unknown key and ill-typed value of the file, not only the first.

pub mod model;
pub mod registers;
#[cfg(feature = "schema")]
pub mod schema;
pub mod session;
mod words;

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
    load_spec_repaired(source, diags).0
}

/// [`load_spec`], and the spans of the tables an ill-typed or unknown entry was dropped from:
/// an error validation then finds about such a table as a whole (a checksum whose `crc` was
/// dropped "has no parameters") follows from the shape error, and is not reported again.
pub fn load_spec_repaired(
    source: &SpecSource,
    diags: &mut Diagnostics,
) -> (Option<SpecFile>, Vec<Range<usize>>) {
    let mut repaired = Vec::new();
    let spec = load_into(source, diags, &mut repaired);
    (spec, repaired)
}

fn load_into(
    source: &SpecSource,
    diags: &mut Diagnostics,
    repaired_tables: &mut Vec<Range<usize>>,
) -> Option<SpecFile> {
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
                let key = key_of(tree.get_ref(), &span);
                // A key dropped to repair an ill-typed value is then "missing": that is the
                // same mistake, already reported.
                let repaired = e.message().starts_with("missing field")
                    && reported
                        .iter()
                        .any(|r| span.start <= r.start && r.end <= span.end);
                // Every element of one array written the same wrong way is one mistake.
                let again = key.as_ref().and_then(|k| k.array.clone()).is_some_and(|a| {
                    reported
                        .iter()
                        .any(|r| a.start <= r.start && r.end <= a.end)
                });
                reported.push(span.clone());
                let meant = if repaired || again {
                    None
                } else {
                    report_shape_error(diags, span.clone(), e.message(), key.as_ref())
                };
                // A misspelled key is read as the key it was meant to be, so that its table is
                // checked as written (a misspelled `values` would otherwise drop its enum).
                if let Some(meant) = meant
                    && rename_key(tree.get_mut(), &span, &meant)
                {
                    continue;
                }
                match remove_in_table(tree.get_mut(), &span) {
                    Removed::No => return None,
                    Removed::From(parent) => {
                        if repaired {
                            repaired_tables.push(span);
                        }
                        repaired_tables.extend(parent);
                    }
                }
            }
        }
    }
    None
}

/// Rename the key with exactly this span to `meant`, unless its table has that key already.
fn rename_key(table: &mut DeTable<'_>, span: &Range<usize>, meant: &str) -> bool {
    let found = table.keys().find(|k| k.span() == *span).cloned();
    if let Some(k) = found {
        if table.keys().any(|other| other.get_ref() == meant) {
            return false;
        }
        let Some(value) = table.remove(k.get_ref().as_ref()) else {
            return false;
        };
        table.insert(Spanned::new(k.span(), meant.to_string().into()), value);
        return true;
    }
    table.iter_mut().any(|(_, v)| match v.get_mut() {
        DeValue::Table(t) => rename_key(t, span, meant),
        DeValue::Array(items) => items.iter_mut().any(|i| match i.get_mut() {
            DeValue::Table(t) => rename_key(t, span, meant),
            _ => false,
        }),
        _ => false,
    })
}

/// Turn a serde/toml message into a located diagnostic with a useful help line, in the
/// spec's words (a table, an array, an integer), never a Rust type's.
fn report_shape_error(
    diags: &mut Diagnostics,
    span: Range<usize>,
    message: &str,
    key: Option<&KeyOf>,
) -> Option<String> {
    let message = first_line(message);
    if let Some(rest) = message.strip_prefix("unknown field `") {
        let name = rest.split('`').next().unwrap_or("");
        let expected: Vec<&str> = rest.split('`').skip(2).step_by(2).collect();
        let d = diags.error(span, format!("unknown key `{name}`"));
        let best = did_you_mean(name, expected.iter().copied());
        match best {
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
        return best.map(str::to_string);
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
    } else if let Some((message, help)) = words::wrong_value(message, key) {
        diags.error(span, message).help(help);
    } else {
        diags
            .error(span, message.to_string())
            .help("see docs/spec-format.md");
    }
    None
}

fn first_line(message: &str) -> &str {
    message.lines().next().unwrap_or("").trim()
}

/// Whether an entry was removed, and the span of the table value it was removed from (`None`
/// for the top level or an array).
enum Removed {
    No,
    From(Option<Range<usize>>),
}

/// Remove the table entry or array element whose key or value has exactly this span.
fn remove_in_table(table: &mut DeTable<'_>, span: &Range<usize>) -> Removed {
    let key = table
        .iter()
        .find(|(k, v)| k.span() == *span || v.span() == *span)
        .map(|(k, _)| k.get_ref().to_string());
    if let Some(key) = key {
        table.remove(key.as_str());
        return Removed::From(None);
    }
    for (_, v) in table.iter_mut() {
        let outer = v.span();
        match remove_in_value(v.get_mut(), span) {
            Removed::No => {}
            Removed::From(None) if matches!(v.get_ref(), DeValue::Table(_)) => {
                return Removed::From(Some(outer));
            }
            found => return found,
        }
    }
    Removed::No
}

fn remove_in_value(value: &mut DeValue<'_>, span: &Range<usize>) -> Removed {
    match value {
        DeValue::Table(t) => remove_in_table(t, span),
        DeValue::Array(items) => {
            if let Some(i) = items.iter().position(|v| v.span() == *span) {
                let mut kept: Vec<Spanned<DeValue<'_>>> = Vec::new();
                for (j, v) in items.iter().enumerate() {
                    if j != i {
                        kept.push(v.clone());
                    }
                }
                *items = kept.into_iter().collect();
                return Removed::From(None);
            }
            for v in items.iter_mut() {
                let outer = v.span();
                match remove_in_value(v.get_mut(), span) {
                    Removed::No => {}
                    Removed::From(None) if matches!(v.get_ref(), DeValue::Table(_)) => {
                        return Removed::From(Some(outer));
                    }
                    found => return found,
                }
            }
            Removed::No
        }
        _ => Removed::No,
    }
}

/// Where an ill-typed value sits: the key it is the value of, and whether it is an element of
/// that key's array rather than the whole value.
struct KeyOf {
    name: String,
    element: bool,
    /// The span of the array, for an element.
    array: Option<Range<usize>>,
}

fn key_of(table: &DeTable<'_>, span: &Range<usize>) -> Option<KeyOf> {
    for (k, v) in table.iter() {
        if v.span() == *span || k.span() == *span {
            return Some(KeyOf {
                name: k.get_ref().to_string(),
                element: false,
                array: None,
            });
        }
        if let Some(found) = key_in_value(k.get_ref(), v, span) {
            return Some(found);
        }
    }
    None
}

fn key_in_value(key: &str, value: &Spanned<DeValue<'_>>, span: &Range<usize>) -> Option<KeyOf> {
    match value.get_ref() {
        DeValue::Table(t) => key_of(t, span),
        DeValue::Array(items) => items.iter().find_map(|v| {
            if v.span() == *span {
                Some(KeyOf {
                    name: key.to_string(),
                    element: true,
                    array: Some(value.span()),
                })
            } else {
                key_in_value(key, v, span)
            }
        }),
        _ => None,
    }
}
