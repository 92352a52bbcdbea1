//! The names decoded values carry, made once per interpreter: each struct field's name (and
//! the names it takes in its struct's object, a bit field's members), each header value's and
//! each flag trailer's, as shared text that a decoded [`Fields`](crate::Fields) holds without
//! copying it.
//!
//! This module owns only that table; which names a field takes is the payload module's rule
//! (`keys`), and the table is indexed as the IR is (struct, then field; frame, then header
//! value).

use std::sync::Arc;

use protocol_spec::ir::{Field, Protocol};

/// The names of one struct field.
pub(crate) struct FieldNames {
    /// The field's own name.
    pub name: Arc<str>,
    /// The names it takes in its struct's object, in order (its bit members' names, its name,
    /// or none for padding and checks).
    pub keys: Vec<Arc<str>>,
}

impl FieldNames {
    fn new(f: &Field) -> Self {
        let name: Arc<str> = Arc::from(f.name.as_str());
        let keys = crate::payload::keys(f)
            .into_iter()
            .map(|k| {
                if k == f.name {
                    Arc::clone(&name)
                } else {
                    Arc::from(k)
                }
            })
            .collect();
        FieldNames { name, keys }
    }
}

/// Every name a decoded value of a protocol carries.
pub(crate) struct Names {
    /// Per struct, per field.
    structs: Vec<Vec<FieldNames>>,
    /// Per frame format, per header value.
    values: Vec<Vec<Arc<str>>>,
    /// Per frame format, its flag trailer's name.
    trailers: Vec<Option<Arc<str>>>,
    /// Per direction, the header values' names of its own layout of the first frame format
    /// (`None`: it has none).
    own: Vec<Option<Vec<Arc<str>>>>,
}

impl Names {
    /// The names of `p`.
    pub fn new(p: &Protocol) -> Self {
        Names {
            structs: p
                .structs
                .iter()
                .map(|s| s.fields.iter().map(FieldNames::new).collect())
                .collect(),
            values: p
                .frames
                .iter()
                .map(|f| {
                    f.values
                        .iter()
                        .map(|v| Arc::from(v.name.as_str()))
                        .collect()
                })
                .collect(),
            trailers: p
                .frames
                .iter()
                .map(|f| f.flag_trailer.as_ref().map(|t| Arc::from(t.name.as_str())))
                .collect(),
            own: p
                .directions
                .iter()
                .map(|d| {
                    let f = d.frame.as_ref()?;
                    Some(
                        f.values
                            .iter()
                            .map(|v| Arc::from(v.name.as_str()))
                            .collect(),
                    )
                })
                .collect(),
        }
    }

    /// The names of the fields of struct `si`, by field index.
    pub fn fields(&self, si: usize) -> &[FieldNames] {
        &self.structs[si]
    }

    /// The name of header value `vi` of frame format `fi` as the frames of `direction` lay it
    /// out ([`Protocol::frame_in`](protocol_spec::ir::Protocol::frame_in)).
    pub fn value(&self, fi: usize, direction: Option<usize>, vi: usize) -> &Arc<str> {
        let own = direction
            .filter(|_| fi == 0)
            .and_then(|d| self.own.get(d)?.as_ref());
        match own {
            Some(names) => &names[vi],
            None => &self.values[fi][vi],
        }
    }

    /// The name of the flag trailer of frame format `fi`.
    pub fn trailer(&self, fi: usize) -> Option<&Arc<str>> {
        self.trailers[fi].as_ref()
    }
}
