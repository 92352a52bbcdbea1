//! The committed JSON Schema (`docs/spec.schema.json`, used by editors through `.taplo.toml`)
//! is the one generated from the serde model, and it agrees with the loader: every bundled spec
//! and feature fixture validates against it, and an invalid fixture fails the schema exactly
//! when the loader finds a shape error in it (an unknown key, a wrong value type, a missing key).
//!
//! Regenerate the committed schema with
//! `UPDATE_SCHEMA=1 cargo test -p protocol-spec --test it -- schema::`.

use std::path::{Path, PathBuf};

use protocol_spec::diag::{Diagnostics, render_all};
use protocol_spec::source::SpecSource;
use protocol_spec::spec::{load_spec, schema::json_schema};

const REGENERATE: &str = "UPDATE_SCHEMA=1 cargo test -p protocol-spec --test it -- schema::";

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("workspace root")
        .to_path_buf()
}

fn schema_path() -> PathBuf {
    repo().join("docs").join("spec.schema.json")
}

/// The `.toml` files of a directory, sorted, as (path shown in messages, text).
fn tomls(dir: &Path, shown: &str) -> Vec<(String, String)> {
    let mut out: Vec<(String, String)> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .map(|p| {
            let name = p.file_name().and_then(|n| n.to_str()).expect("utf-8 name");
            (
                format!("{shown}/{name}"),
                std::fs::read_to_string(&p).expect("toml file"),
            )
        })
        .collect();
    out.sort();
    out
}

fn validator() -> jsonschema::Validator {
    let schema: serde_json::Value =
        serde_json::from_str(&json_schema()).expect("the generated schema is JSON");
    jsonschema::validator_for(&schema).expect("the generated schema is a valid JSON Schema")
}

/// Schema errors of a TOML document, one line each (empty: it validates).
fn schema_errors(validator: &jsonschema::Validator, text: &str) -> Vec<String> {
    let value: serde_json::Value = toml::from_str(text).expect("TOML");
    validator
        .iter_errors(&value)
        .map(|e| format!("at `{}`: {e}", e.instance_path()))
        .collect()
}

#[test]
fn committed_schema_is_the_generated_one() {
    let generated = json_schema();
    let path = schema_path();
    if std::env::var_os("UPDATE_SCHEMA").is_some() {
        std::fs::write(&path, &generated).expect("write docs/spec.schema.json");
        return;
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == generated,
        "docs/spec.schema.json is stale or missing: it differs from the schema generated from \
         protocol-spec/src/spec/model.rs. Regenerate it with `{REGENERATE}` and commit it."
    );
}

#[test]
fn every_bundled_spec_and_feature_fixture_validates() {
    let validator = validator();
    let mut files = tomls(&repo().join("specs"), "specs");
    let bundled = files.len();
    files.extend(tomls(
        &repo().join("protocol-codegen/tests/features"),
        "protocol-codegen/tests/features",
    ));
    assert!(bundled >= 2, "specs/ holds {bundled} specs");
    for (path, text) in &files {
        let errors = schema_errors(&validator, text);
        assert!(
            errors.is_empty(),
            "{path} does not validate against docs/spec.schema.json:\n{}",
            errors.join("\n")
        );
    }
}

#[test]
fn invalid_fixtures_fail_the_schema_exactly_when_their_shape_is_wrong() {
    let validator = validator();
    let (mut unknown_keys, mut shape_errors, mut shape_valid) = (0, 0, 0);
    for (path, text) in tomls(
        &repo().join("protocol-codegen/tests/invalid"),
        "tests/invalid",
    ) {
        if toml::from_str::<toml::Table>(&text).is_err() {
            continue; // not TOML at all: nothing for a schema to say
        }
        let source = SpecSource::new(path.clone(), text.clone());
        let mut diags = Diagnostics::new();
        let loaded = load_spec(&source, &mut diags).is_some();
        let shape_ok = loaded && diags.is_empty();
        let errors = schema_errors(&validator, &text);
        let rendered = render_all(&diags.into_sorted(), &source);
        if rendered.contains("error: unknown key") {
            unknown_keys += 1;
        }
        if shape_ok {
            shape_valid += 1;
            assert!(
                errors.is_empty(),
                "{path} has a valid shape (its mistakes are found by validation), but the \
                 schema rejects it:\n{}",
                errors.join("\n")
            );
        } else {
            shape_errors += 1;
            assert!(
                !errors.is_empty(),
                "the loader rejects the shape of {path}, but the schema accepts it:\n{rendered}"
            );
        }
    }
    // Both sides of the comparison must be exercised, or the test proves nothing.
    assert!(
        shape_errors >= 5 && shape_valid >= 40,
        "{shape_errors} fixtures with shape errors, {shape_valid} without"
    );
    assert!(
        unknown_keys >= 2,
        "expected fixtures with unknown keys (unknown_key.toml, unknown_table.toml), found {unknown_keys}"
    );
}
