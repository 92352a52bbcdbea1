//! The spec-text fuzzer's dictionary (`fuzz/spec.dict`, passed with `-dict=spec.dict`) names
//! every key of the spec format: libFuzzer splices its entries into inputs, so a key missing from
//! it is one the fuzzer reaches only by guessing its letters, and the rules behind that key go
//! untested. The keys are read from the JSON Schema generated from the serde model, so a key
//! added to the model fails here until the dictionary has it.

use std::collections::BTreeSet;
use std::path::Path;

use protocol_spec::spec::schema::json_schema;

/// Every property name in a JSON Schema, at any depth.
fn property_names(value: &serde_json::Value, out: &mut BTreeSet<String>) {
    match value {
        serde_json::Value::Object(map) => {
            if let Some(serde_json::Value::Object(properties)) = map.get("properties") {
                out.extend(properties.keys().cloned());
            }
            for child in map.values() {
                property_names(child, out);
            }
        }
        serde_json::Value::Array(items) => {
            for child in items {
                property_names(child, out);
            }
        }
        _ => {}
    }
}

/// The entries of a libFuzzer dictionary: each non-comment line is a quoted string.
fn dictionary_entries(text: &str) -> BTreeSet<String> {
    text.lines()
        .map(str::trim)
        .filter(|line| !line.is_empty() && !line.starts_with('#'))
        .map(|line| {
            line.strip_prefix('"')
                .and_then(|l| l.strip_suffix('"'))
                .unwrap_or_else(|| panic!("a dictionary line is one quoted string: {line}"))
                .to_string()
        })
        .collect()
}

#[test]
fn the_spec_fuzzer_dictionary_names_every_key_of_the_format() {
    let schema: serde_json::Value =
        serde_json::from_str(&json_schema()).expect("the generated schema is JSON");
    let mut keys = BTreeSet::new();
    property_names(&schema, &mut keys);
    // Table headers and element keys alike: the model has dozens; a handful means the walk
    // found the wrong part of the schema.
    assert!(keys.len() > 50, "the schema names {} keys", keys.len());

    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz/spec.dict");
    let text = std::fs::read_to_string(&path).expect("fuzz/spec.dict");
    let entries = dictionary_entries(&text);
    let missing: Vec<&String> = keys.difference(&entries).collect();
    assert!(
        missing.is_empty(),
        "fuzz/spec.dict lacks these keys of the spec format: {missing:?}"
    );
}
