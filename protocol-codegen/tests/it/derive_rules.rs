//! `#[derive(Payload)]` goes through the spec's validation: a mistake in a derive's attributes
//! or types gets the diagnostic (message and help) that the same mistake gets in a spec, and
//! every mistake of a derive is reported at once.

use protocol_codegen::derive::derive_payload;
use protocol_codegen::source::SpecSource;

/// The errors of a derive on `item`, each as its message (with the help the derive appends).
fn derive_errors(item: &str) -> Vec<String> {
    let input: syn::DeriveInput = syn::parse_str(item).expect("a Rust item");
    match derive_payload(&input) {
        Ok(_) => Vec::new(),
        Err(e) => e.into_iter().map(|e| e.to_string()).collect(),
    }
}

/// The errors of a spec whose one struct `S` has `fields` (TOML array items), each as the
/// derive renders a diagnostic: the message, then `= help:` and the help.
fn spec_errors(struct_keys: &str, fields: &str) -> Vec<String> {
    let text = format!(
        r#"[protocol]
name = "p"

[frames.f]
layout = [
  {{ sync = [0xAA] }},
  {{ field = "length", type = "u8", length_of = "payload" }},
  {{ field = "command", type = "u8" }},
  {{ payload = {{ max = 64 }} }},
  {{ check = "sum8", over = "frame" }},
]
dispatch = ["command"]

[commands]
C = {{ id = 1, payload = "S" }}

[structs.S]
{struct_keys}
fields = [
{fields}
]
"#
    );
    match protocol_codegen::compile(&SpecSource::new("s.toml", text)) {
        Ok(_) => Vec::new(),
        Err(diags) => diags
            .iter()
            .map(|d| match &d.help {
                Some(h) => format!("{}\n= help: {h}", d.message),
                None => d.message.clone(),
            })
            .collect(),
    }
}

/// Each mistake, written in a derive and in a spec: the same one diagnostic.
#[test]
fn a_derive_mistake_reads_as_the_same_mistake_in_a_spec() {
    let cases = [
        (
            "struct S { #[payload(pad_before = 0)] a: u8 }",
            "",
            "{ pad = 0 },\n{ name = \"a\", type = \"u8\" },",
        ),
        (
            "struct S { a: [u16; 0] }",
            "",
            "{ name = \"a\", type = \"u16\", count = 0 },",
        ),
        (
            "struct S { #[payload(scale = 0.0, raw = \"i16\")] a: f32 }",
            "",
            "{ name = \"a\", type = \"i16\", scale = 0.0 },",
        ),
        (
            "struct S { #[payload(scale = 0.5)] a: bool }",
            "",
            "{ name = \"a\", type = \"bool\", scale = 0.5 },",
        ),
        (
            "struct S { #[payload(raw = \"u36\")] a: u64 }",
            "",
            "{ name = \"a\", type = \"u36\" },",
        ),
        (
            "#[payload(byte_order = \"middle\")] struct S { a: u16 }",
            "byte_order = \"middle\"",
            "{ name = \"a\", type = \"u16\" },",
        ),
    ];
    for (item, keys, fields) in cases {
        let from_derive = derive_errors(item);
        let from_spec = spec_errors(keys, fields);
        assert_eq!(from_derive.len(), 1, "{item}: {from_derive:#?}");
        assert_eq!(from_derive, from_spec, "{item}");
    }
}

/// Every mistake of a derive at once, in field order, as a spec's.
#[test]
fn every_mistake_of_a_derive_is_reported() {
    let errors = derive_errors(
        "struct S { #[payload(pad_before = 0)] a: u8, b: [u8; 0], #[payload(scale = 0.5)] c: bool }",
    );
    assert_eq!(errors.len(), 3, "{errors:#?}");
    assert!(errors[0].starts_with("padding must be at least one byte"));
    assert!(errors[1].starts_with("an array count must be at least 1"));
    assert!(errors[2].starts_with("`scale` applies to number fields, not `bool`"));
}

/// The rule a spec has no use for: a field's Rust type is the one its wire form decodes to.
#[test]
fn a_declared_rust_type_must_be_the_decoded_one() {
    let errors = derive_errors("struct S { #[payload(raw = \"u24\")] total: u16 }");
    assert_eq!(
        errors,
        [
            "field `total` is `u16`, but its wire type `u24` decodes to `u32`\n= help: declare \
          `total` as `u32`, or give it a wire type that decodes to `u16`"
        ]
    );
    let errors = derive_errors("struct S { #[payload(scale = 0.5, raw = \"i16\")] speed: i32 }");
    assert_eq!(errors.len(), 1, "{errors:#?}");
    assert!(errors[0].starts_with("field `speed` is `i32`, but a scaled value decodes to `f32`"));
    // A declared `f64` is the physical type of any scaled integer, as a declared `f32` is.
    assert!(derive_errors("struct S { #[payload(scale = 0.5, raw = \"i16\")] a: f64 }").is_empty());
    assert!(derive_errors("struct S { #[payload(scale = 0.5, raw = \"i32\")] a: f32 }").is_empty());
}

/// Types of the user's crate: nested payloads and enum-like types with `repr` need no spec
/// declaration, and a struct that holds itself is the spec's error.
#[test]
fn user_types_are_named_not_declared() {
    assert!(
        derive_errors(
            "struct S { a: Pose, b: [other::Pose; 2], #[payload(repr = \"u8\")] m: Mode, #[payload(repr = \"u8\")] n: [Mode; 3] }"
        )
        .is_empty()
    );
    let errors = derive_errors("struct S { a: u8, next: Self }");
    assert_eq!(errors.len(), 1, "{errors:#?}");
    assert!(
        errors[0].starts_with("struct `S` contains itself"),
        "{errors:#?}"
    );
}
