//! The JSON Schema of the spec format, generated from the serde [`model`](super::model) so it
//! cannot drift from what the loader accepts. Editors with a TOML language server (taplo) use
//! the committed copy, `docs/spec.schema.json`, to complete and check keys while a spec is
//! written; `tests/it/schema.rs` fails when that copy is stale.
//!
//! The schema describes the *shape* of a spec (which keys exist where, and their value types),
//! exactly as deserialization checks it: an unknown key or an ill-typed value is a schema error.
//! What validation checks afterwards (names, references, sizes, ids) is not in the schema.

use schemars::Schema;
use schemars::generate::SchemaSettings;
use schemars::transform::{Transform, transform_subschemas};
use serde_json::{Map, Value};

use super::model::SpecFile;

/// The JSON Schema (draft 7, the draft TOML language servers support best) of a spec file,
/// pretty-printed, ending with a newline.
pub fn json_schema() -> String {
    let generated = SchemaSettings::draft07()
        .with_transform(NoNull)
        .into_generator()
        .into_root_schema_for::<SpecFile>();
    // Head the document with what a reader looks for first, then the generated keys in order.
    let mut root = Map::new();
    if let Some(meta) = generated.get("$schema") {
        root.insert("$schema".into(), meta.clone());
    }
    root.insert("title".into(), "protocol spec".into());
    root.insert(
        "description".into(),
        "A protocol spec (`specs/*.toml`): framing, checks, commands, payload structs and enums. \
         Every key is described in docs/spec-format.md."
            .into(),
    );
    for (key, value) in generated.as_object().into_iter().flatten() {
        if !root.contains_key(key) {
            root.insert(key.clone(), value.clone());
        }
    }
    format!("{:#}\n", Value::Object(root))
}

/// TOML has no null, so an absent optional key is simply missing: drop the `null` that schemars
/// allows for every `Option`, so editors do not offer `null` as a value.
#[derive(Clone, Copy)]
struct NoNull;

impl Transform for NoNull {
    fn transform(&mut self, schema: &mut Schema) {
        transform_subschemas(self, schema);
        let Some(obj) = schema.as_object_mut() else {
            return;
        };
        if let Some(Value::Array(types)) = obj.get_mut("type") {
            types.retain(|t| t != "null");
            if types.len() == 1 {
                let only = types.remove(0);
                obj.insert("type".into(), only);
            }
        }
        if let Some(Value::Array(alternatives)) = obj.get_mut("anyOf") {
            alternatives.retain(|a| a.get("type").and_then(Value::as_str) != Some("null"));
            if alternatives.len() == 1 && !obj.contains_key("allOf") {
                // `anyOf` of one is `allOf` of one: the conventional way to give a `$ref` a
                // description in draft 7, where siblings of `$ref` are ignored.
                if let Some(one) = obj.remove("anyOf") {
                    obj.insert("allOf".into(), one);
                }
            }
        }
    }
}
