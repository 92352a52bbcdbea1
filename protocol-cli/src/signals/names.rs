//! The names a signal can be chosen by, read from the spec: every header value and payload
//! field of every command (or of a frame format without commands), with its unit and whether
//! it is a number; how a name given to `--plot` matches the columns of a decoded frame; and
//! the close names an unknown one is answered with.
//!
//! A column is a value's path in the frame's JSON object, as the CSV export names it
//! (`payload.x`, `payload.voltages[3]`, `header.sender`). A name is `COMMAND.PATH` (that
//! command's column) or `PATH` alone (that column of every command that has it); a path
//! without an index (`payload.voltages`) stands for all of its elements.

use protocol_spec::ir::{FieldKind, Prim, Protocol, Role, Struct, ValueType};

/// What a column holds, as far as a plot cares.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A number; `scaled` when the spec gives it a scale or a unit.
    Number {
        /// Scaled, or with a unit: a physical value, plotted by default.
        scaled: bool,
    },
    /// `true` or `false`, plotted as 1 and 0.
    Flag,
    /// Names or text (an enum, `char[N]`, bytes): nothing to plot.
    Named,
}

/// One column of a command's frames, without its indices.
#[derive(Debug, Clone, PartialEq)]
pub struct Column {
    /// `payload.x`, `payload.servos.position`, `header.sender`.
    pub shape: String,
    /// The spec's unit (empty when none).
    pub unit: String,
    /// What it holds.
    pub kind: Kind,
}

/// The columns of every key: a command's name, or a frame format's for frames without one
/// (the keys of [`crate::export::Record::key`]).
#[derive(Debug, Clone, Default)]
pub struct Catalogue {
    /// (key, its columns in spec order).
    pub keys: Vec<(String, Vec<Column>)>,
}

impl Catalogue {
    /// Every column of the spec `p`.
    pub fn of(p: &Protocol) -> Self {
        let mut header = Vec::new();
        for f in &p.frames {
            for v in f
                .values
                .iter()
                .filter(|v| matches!(v.role, Role::User { .. }))
            {
                let kind = if v.prim == Prim::Bool {
                    Kind::Flag
                } else {
                    Kind::Number { scaled: false }
                };
                push(&mut header, format!("header.{}", v.name), "", kind);
            }
        }
        let mut keys = Vec::new();
        for c in &p.commands {
            let mut cols = header.clone();
            for si in c.payloads.iter().flatten() {
                walk(p, &p.structs[*si], "payload", &mut cols);
            }
            keys.push((c.name.clone(), cols));
        }
        // Frames that carry one struct without a command: a format's, or a direction's.
        for f in &p.frames {
            let structs = f
                .message
                .into_iter()
                .chain(p.directions.iter().filter_map(|d| d.message.map(|m| m.0)));
            let mut cols = header.clone();
            let mut any = false;
            for si in structs {
                walk(p, &p.structs[si], "payload", &mut cols);
                any = true;
            }
            if any {
                keys.push((f.name.clone(), cols));
            }
        }
        Catalogue { keys }
    }

    /// The columns of `key`.
    pub fn columns(&self, key: &str) -> &[Column] {
        self.keys
            .iter()
            .find(|(k, _)| k == key)
            .map_or(&[], |(_, c)| c.as_slice())
    }

    /// Every name a selector may be written as: `COMMAND.PATH`, then each `PATH` once.
    pub fn names(&self) -> Vec<String> {
        let mut out: Vec<String> = Vec::new();
        for (key, cols) in &self.keys {
            out.extend(cols.iter().map(|c| format!("{key}.{}", c.shape)));
        }
        for (_, cols) in &self.keys {
            for c in cols {
                if !out.contains(&c.shape) {
                    out.push(c.shape.clone());
                }
            }
        }
        out
    }
}

fn push(cols: &mut Vec<Column>, shape: String, unit: &str, kind: Kind) {
    if !cols.iter().any(|c| c.shape == shape) {
        cols.push(Column {
            shape,
            unit: unit.to_string(),
            kind,
        });
    }
}

/// The columns of struct `s` under `prefix`, nested structs and groups walked.
fn walk(p: &Protocol, s: &Struct, prefix: &str, cols: &mut Vec<Column>) {
    for f in &s.fields {
        field(
            p,
            &f.kind,
            &format!("{prefix}.{}", f.name),
            &f.unit,
            prefix,
            cols,
        );
    }
}

fn field(
    p: &Protocol,
    kind: &FieldKind,
    path: &str,
    unit: &str,
    owner: &str,
    cols: &mut Vec<Column>,
) {
    let scaled = |scale: bool| Kind::Number {
        scaled: scale || !unit.is_empty(),
    };
    match kind {
        FieldKind::Padding | FieldKind::Check(_) => {}
        FieldKind::Optional(inner) | FieldKind::When { kind: inner, .. } => {
            field(p, inner, path, unit, owner, cols)
        }
        FieldKind::Value { ty, .. } | FieldKind::Array { ty, .. } => match ty {
            ValueType::Scalar { scalar, scale } => {
                let kind = if scalar.prim.is_bool() {
                    Kind::Flag
                } else {
                    scaled(scale.is_some())
                };
                push(cols, path.to_string(), unit, kind);
            }
            ValueType::Struct(si) => walk(p, &p.structs[*si], path, cols),
            ValueType::Enum(..) | ValueType::Text(_) => {
                push(cols, path.to_string(), unit, Kind::Named)
            }
        },
        FieldKind::Group { elem, .. } => walk(p, &p.structs[*elem], path, cols),
        FieldKind::Packed { scale, .. } => {
            push(cols, path.to_string(), unit, scaled(scale.is_some()))
        }
        // Bit members are keys of the struct's own object, beside the other fields.
        FieldKind::Bits { members, .. } | FieldKind::BitStream { members } => {
            for m in members {
                let kind = match (m.enum_index, m.prim) {
                    (Some(_), _) => Kind::Named,
                    (None, Prim::Bool) => Kind::Flag,
                    (None, _) => Kind::Number {
                        scaled: m.scale.is_some(),
                    },
                };
                push(cols, format!("{owner}.{}", m.name), &m.unit, kind);
            }
        }
        FieldKind::Bytes { .. } | FieldKind::NulText { .. } => {
            push(cols, path.to_string(), unit, Kind::Named)
        }
    }
}

/// A column's path without its indices: `payload.servos[3].position` is
/// `payload.servos.position`.
pub fn shape(path: &str) -> String {
    let mut out = String::with_capacity(path.len());
    let mut depth = 0usize;
    for c in path.chars() {
        match c {
            '[' => depth += 1,
            ']' => depth = depth.saturating_sub(1),
            c if depth == 0 => out.push(c),
            _ => {}
        }
    }
    out
}

/// A name given to `--plot`, split.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Selector {
    /// The command (or format) it names, or `None` for every key with the path.
    pub key: Option<String>,
    /// The path: with indices it names one element, without them every element.
    pub path: String,
}

impl Selector {
    /// Whether column `path` (whose [`shape`] is `shape`) of a frame of `key` is selected.
    pub fn matches(&self, key: &str, path: &str, shape: &str) -> bool {
        if self.key.as_deref().is_some_and(|k| k != key) {
            return false;
        }
        if self.path.contains('[') {
            self.path == path
        } else {
            self.path == shape
        }
    }
}

/// Why a name selects nothing.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Refusal {
    /// No command of the spec has such a column.
    Unknown {
        /// Names of the spec closest to it, closest first.
        close: Vec<String>,
    },
    /// The column holds names or text.
    NotNumeric,
}

/// Reads one name of `--plot` against the spec's columns.
///
/// # Errors
/// [`Refusal::Unknown`] for a name no command has, with the closest names;
/// [`Refusal::NotNumeric`] for a column of names or text.
pub fn select(cat: &Catalogue, name: &str) -> Result<Selector, Refusal> {
    let split = name
        .split_once('.')
        .filter(|(head, _)| *head != "header" && *head != "payload");
    let (key, path) = match split {
        Some((k, p)) => (Some(k.to_string()), p.to_string()),
        None => (None, name.to_string()),
    };
    let wanted = shape(&path);
    let found: Vec<&Column> = cat
        .keys
        .iter()
        .filter(|(k, _)| key.as_deref().is_none_or(|x| x == k))
        .flat_map(|(_, cols)| cols.iter().filter(|c| c.shape == wanted))
        .collect();
    if found.is_empty() {
        return Err(Refusal::Unknown {
            close: close_names(cat, name),
        });
    }
    if found.iter().all(|c| c.kind == Kind::Named) {
        return Err(Refusal::NotNumeric);
    }
    Ok(Selector { key, path })
}

/// The spec's names most like `name`: those ending in the same field, and those a few edits
/// away, closest first, at most six.
fn close_names(cat: &Catalogue, name: &str) -> Vec<String> {
    let wanted = shape(name).to_lowercase();
    let last = wanted.rsplit('.').next().unwrap_or("");
    let mut scored: Vec<(usize, String)> = cat
        .names()
        .into_iter()
        .filter_map(|n| {
            let lower = n.to_lowercase();
            let d = strsim::levenshtein(&wanted, &lower);
            let same_field = !last.is_empty() && lower.rsplit('.').next() == Some(last);
            let near = d <= (wanted.len() / 3).max(2);
            (same_field || near).then_some((if same_field { d.min(1) } else { d }, n))
        })
        .collect();
    scored.sort_by(|a, b| a.0.cmp(&b.0).then_with(|| a.1.len().cmp(&b.1.len())));
    scored.into_iter().take(6).map(|(_, n)| n).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shapes_drop_indices() {
        assert_eq!(
            shape("payload.servos[3].position"),
            "payload.servos.position"
        );
        assert_eq!(shape("payload.v[10]"), "payload.v");
        assert_eq!(shape("header.sender"), "header.sender");
    }

    #[test]
    fn a_selector_with_an_index_names_one_element() {
        let one = Selector {
            key: Some("STATUS".into()),
            path: "payload.v[1]".into(),
        };
        assert!(one.matches("STATUS", "payload.v[1]", "payload.v"));
        assert!(!one.matches("STATUS", "payload.v[0]", "payload.v"));
        assert!(!one.matches("OTHER", "payload.v[1]", "payload.v"));
        let all = Selector {
            key: None,
            path: "payload.v".into(),
        };
        assert!(all.matches("STATUS", "payload.v[0]", "payload.v"));
        assert!(all.matches("OTHER", "payload.v[7]", "payload.v"));
    }
}
