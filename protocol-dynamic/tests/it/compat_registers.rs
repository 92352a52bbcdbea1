//! The compatibility report on register maps (`[registers]`), one edit of the AX-12A control
//! table of `specs/dynamixel1.toml` per kind of change: a register moved, resized, retyped or
//! removed is breaking; one added, or a unit, access or doc changed, is compatible.

use protocol_dynamic::compat::{Change, Class, diff};
use protocol_spec::ir::Protocol;
use protocol_spec::source::SpecSource;

const SPEC: &str = "../specs/dynamixel1.toml";
const POSITION: &str = r#"{ name = "present_position", address = 36, type = "u16", access = "r", unit = "0.29°", doc = "0 to 1023." },"#;

fn compile(name: &str, text: &str) -> Protocol {
    protocol_spec::compile(&SpecSource::new(name, text))
        .unwrap_or_else(|d| panic!("{name} does not compile: {d:?}"))
}

/// The changes from the spec to the spec with `from` replaced by `to`, that name a register.
fn changes(from: &str, to: &str) -> Vec<Change> {
    let path = format!("{}/{SPEC}", env!("CARGO_MANIFEST_DIR"));
    let old = std::fs::read_to_string(path).expect("spec");
    assert!(old.contains(from), "`{from}` is not in the spec");
    let new = old.replacen(from, to, 1);
    diff(&compile("old.toml", &old), &compile("new.toml", &new))
        .into_iter()
        .filter(|c| c.subject.starts_with("register"))
        .collect()
}

/// The one change of `changes`: its class and its text.
fn one(changes: &[Change]) -> (Class, String) {
    match changes {
        [c] => (c.class, c.to_string()),
        other => panic!("not one change: {other:?}"),
    }
}

#[test]
fn a_moved_resized_retyped_or_removed_register_breaks_the_wire() {
    let (class, text) = one(&changes(
        r#"name = "registered", address = 44,"#,
        r#"name = "registered", address = 45,"#,
    ));
    assert_eq!(class, Class::Breaking);
    assert!(
        text.contains("register registered: moved from address 44 to 45"),
        "{text}"
    );

    let resized = changes(
        POSITION,
        &POSITION.replace(
            r#"address = 36, type = "u16""#,
            r#"address = 36, type = "u8""#,
        ),
    );
    assert!(
        resized.iter().all(|c| c.class == Class::Breaking),
        "{resized:?}"
    );
    assert!(
        resized
            .iter()
            .any(|c| c.reason == "resized from 2 to 1 bytes"),
        "{resized:?}"
    );

    let (class, text) = one(&changes(
        POSITION,
        &POSITION.replace(r#""u16""#, r#""i16""#),
    ));
    assert_eq!(class, Class::Breaking);
    assert!(text.contains("retyped from `u16`"), "{text}");

    let (class, text) = one(&changes(POSITION, ""));
    assert_eq!(class, Class::Breaking);
    assert!(
        text.contains("register present_position: removed (2 bytes at 36)"),
        "{text}"
    );
}

#[test]
fn an_added_register_or_its_words_are_compatible() {
    let added = r#"{ name = "spare", address = 45, type = "u8" },"#;
    let (class, text) = one(&changes(POSITION, &format!("{POSITION}\n  {added}")));
    assert_eq!(class, Class::Compatible);
    assert!(
        text.contains("register spare: added (1 bytes at 45)"),
        "{text}"
    );

    let words = changes(
        POSITION,
        &POSITION
            .replace(r#"access = "r""#, r#"access = "rw""#)
            .replace("0.29°", "deg")
            .replace("0 to 1023.", "Where it is."),
    );
    assert_eq!(words.len(), 3, "{words:?}");
    assert!(
        words.iter().all(|c| c.class == Class::Compatible),
        "{words:?}"
    );
}

#[test]
fn a_register_map_added_is_compatible_and_removed_is_breaking() {
    let path = format!("{}/{SPEC}", env!("CARGO_MANIFEST_DIR"));
    let with = std::fs::read_to_string(path).expect("spec");
    let start = with.find("\n[registers]").expect("a map");
    let end = with[start..].find("\n[commands]").expect("commands follow") + start;
    // Without the map, the commands' `registers` go too.
    let without: String = with[..start].to_string()
        + &with[end..]
            .lines()
            .map(|l| match l.find(", registers = {") {
                Some(i) => {
                    let close = l[i..].find("}").expect("closes") + i + 1;
                    format!("{}{}", &l[..i], &l[close..])
                }
                None => l.to_string(),
            })
            .collect::<Vec<_>>()
            .join("\n");
    let (w, wo) = (
        compile("with.toml", &with),
        compile("without.toml", &without),
    );
    let removed: Vec<Change> = diff(&w, &wo)
        .into_iter()
        .filter(|c| c.subject == "registers")
        .collect();
    assert_eq!(one(&removed).0, Class::Breaking);
    let added: Vec<Change> = diff(&wo, &w)
        .into_iter()
        .filter(|c| c.subject == "registers")
        .collect();
    assert_eq!(one(&added).0, Class::Compatible);
    assert_eq!(diff(&w, &w), Vec::new());
}
