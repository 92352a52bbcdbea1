//! The compatibility report (`protocol diff`), in process: one edit of a spec per kind of
//! change, and the class and reason each gets.

use protocol_dynamic::compat::{Change, Class, diff};
use protocol_spec::ir::Protocol;
use protocol_spec::source::SpecSource;

fn compile(name: &str, text: &str) -> Protocol {
    protocol_spec::compile(&SpecSource::new(name, text))
        .unwrap_or_else(|d| panic!("{name} does not compile: {d:?}"))
}

fn spec(path: &str) -> String {
    std::fs::read_to_string(format!("{}/{path}", env!("CARGO_MANIFEST_DIR"))).expect("spec")
}

/// The changes from `path` to `path` with `from` replaced by `to`.
fn changes(path: &str, from: &str, to: &str) -> Vec<Change> {
    let old = spec(path);
    assert!(old.contains(from), "`{from}` is not in {path}");
    let new = old.replacen(from, to, 1);
    diff(&compile("old.toml", &old), &compile("new.toml", &new))
}

fn assert_one(changes: &[Change], class: Class, needle: &str) {
    assert!(
        changes
            .iter()
            .any(|c| c.class == class && c.to_string().contains(needle)),
        "no {class:?} change mentioning `{needle}` in:\n{}",
        changes
            .iter()
            .map(|c| format!("  {c}\n"))
            .collect::<String>()
    );
}

fn breaking(changes: &[Change]) -> usize {
    changes
        .iter()
        .filter(|c| c.class == Class::Breaking)
        .count()
}

const HFLINK: &str = "../specs/hflink.toml";
const FEATURES: &str = "tests/fixtures/features.toml";

#[test]
fn a_spec_is_compatible_with_itself() {
    for path in [
        HFLINK,
        "../specs/referee.toml",
        "../specs/scout.toml",
        FEATURES,
    ] {
        let p = compile("x.toml", &spec(path));
        assert_eq!(diff(&p, &p), Vec::new(), "{path}");
    }
}

#[test]
fn payload_changes_break() {
    let c = changes(
        HFLINK,
        "{ name = \"cpu_usage\", type = \"f32\" }",
        "{ name = \"cpu_usage\", type = \"f64\" }",
    );
    assert_one(
        &c,
        Class::Breaking,
        "READ_SYSTEM_INFO (id 0x01): response payload: field `cpu_usage` (offset 8): f32 (little-endian) → f64 (little-endian)",
    );
    let c = changes(
        HFLINK,
        "{ name = \"power_remain\", type = \"f32\", unit = \"%\" },",
        "{ name = \"power_remain\", type = \"f32\", unit = \"%\" },\n  { name = \"extra\", type = \"u8\" },",
    );
    assert_one(
        &c,
        Class::Breaking,
        "fields added, 20 → 21 bytes (payload sizes are exact)",
    );
    let c = changes(
        HFLINK,
        "{ name = \"x\", type = \"f32\", unit = \"m or m/s\" },",
        "{ name = \"x\", type = \"f32be\", unit = \"m or m/s\" },",
    );
    assert_one(
        &c,
        Class::Breaking,
        "f32 (little-endian) → f32 (big-endian)",
    );
    let c = changes(
        HFLINK,
        "READ_SYSTEM_INFO = { id = 1, response = \"SystemInfo\"",
        "READ_SYSTEM_INFO = { id = 1, response = \"ImuSensorData\"",
    );
    assert!(
        breaking(&c) == 0,
        "same size and types: the wire is the same: {c:?}"
    );
    let c = changes(
        HFLINK,
        "SAVE_MOTOR_PARAMETERS = { id = 3,",
        "SAVE_MOTOR_PARAMETERS = { id = 3, request = \"ChassisCoord\",",
    );
    assert_one(
        &c,
        Class::Breaking,
        "request payload: none → `ChassisCoord` (12 bytes)",
    );
}

#[test]
fn commands_removed_or_renumbered_break_and_added_ones_do_not() {
    let c = changes(
        HFLINK,
        "READ_GPS_DATA = { id = 26, response = \"GpsData\", doc = \"Read the GPS fix.\" }\n",
        "",
    );
    assert_one(
        &c,
        Class::Breaking,
        "command READ_GPS_DATA (id 0x1a): removed",
    );
    let c = changes(
        HFLINK,
        "READ_GPS_DATA = { id = 26,",
        "READ_GPS_DATA = { id = 40,",
    );
    assert_one(&c, Class::Breaking, "id changed to 0x28");
    assert_eq!(
        c.len(),
        1,
        "a changed id is one change, not also an added command: {c:?}"
    );
    let c = changes(
        HFLINK,
        "READ_GPS_DATA = { id = 26,",
        "READ_GPS_FIX = { id = 26,",
    );
    assert_one(&c, Class::SourceBreaking, "renamed to READ_GPS_FIX");
    assert_eq!(breaking(&c), 0);
    let c = changes(
        HFLINK,
        "READ_GPS_DATA = { id = 26, response = \"GpsData\"",
        "READ_ODOMETRY = { id = 26, response = \"ChassisCoord\"",
    );
    assert_one(
        &c,
        Class::Breaking,
        "the id is reused for another payload (READ_ODOMETRY is not READ_GPS_DATA)",
    );
}

#[test]
fn framing_changes_break() {
    let c = changes(HFLINK, "{ check = \"sum-mod-255\"", "{ check = \"sum8\"");
    assert_one(
        &c,
        Class::Breaking,
        "check `checksum`: sum mod 255 → sum mod 256",
    );
    let c = changes(HFLINK, "{ sync = [0xFF, 0xFF] }", "{ sync = [0xFF, 0xFE] }");
    assert_one(&c, Class::Breaking, "sync bytes FF FF → FF FE");
    let c = changes(
        HFLINK,
        "{ payload = { max = 119 } }",
        "{ payload = { max = 100 } }",
    );
    assert_one(&c, Class::Breaking, "payload bounds 0..=119 → 0..=100");
    let c = changes(
        HFLINK,
        "slave = { range = [0x11, 0x40]",
        "slave = { range = [0x11, 0x50]",
    );
    assert_one(
        &c,
        Class::Breaking,
        "`response`: `sender` in 0x11..=0x40 → `sender` in 0x11..=0x50",
    );
    let c = changes(
        "../specs/referee.toml",
        "{ check = \"crc-16-mcrf4xx\"",
        "{ check = \"crc-16-kermit\"",
    );
    assert_one(
        &c,
        Class::Breaking,
        "check `frame_crc16`: crc-16-mcrf4xx (poly 0x1021, init 0xffff, refin true, refout true, xorout 0x0) → crc-16-kermit",
    );
}

#[test]
fn enums_break_when_old_decoders_would_refuse_a_value() {
    let c = changes(
        FEATURES,
        "values = { OFF = 0, MANUAL = 1, AUTO = 7 }",
        "values = { OFF = 0, MANUAL = 1, AUTO = 7, SPORT = 8 }",
    );
    assert_one(
        &c,
        Class::Breaking,
        "enum `Drive` gained SPORT = 8, which old decoders reject",
    );
    let c = changes(
        FEATURES,
        "values = { DOWN = -1, LEVEL = 0, UP = 1 }",
        "values = { DOWN = -1, LEVEL = 0, UP = 1, FLIP = 2 }",
    );
    assert_one(
        &c,
        Class::SourceBreaking,
        "enum `Trim` gained FLIP = 2 (old decoders keep it as an unknown value; the generated enum gains a variant",
    );
    assert_eq!(breaking(&c), 0, "{c:?}");
    let c = changes(
        FEATURES,
        "values = { OFF = 0, MANUAL = 1, AUTO = 7 }",
        "values = { OFF = 0, MANUAL = 1, AUTOMATIC = 7 }",
    );
    assert_one(
        &c,
        Class::SourceBreaking,
        "value 7 renamed AUTO → AUTOMATIC",
    );
    let c = changes(
        FEATURES,
        "values = { OFF = 0, MANUAL = 1, AUTO = 7 }",
        "values = { OFF = 0, MANUAL = 1 }",
    );
    assert_one(&c, Class::Breaking, "enum `Drive` lost the value 7 (AUTO)");
}

#[test]
fn names_break_the_source_and_docs_are_compatible() {
    let c = changes(
        HFLINK,
        "{ name = \"cpu_usage\", type = \"f32\" }",
        "{ name = \"cpu_load\", type = \"f32\", doc = \"Load, 0 to 1.\" }",
    );
    assert_one(
        &c,
        Class::SourceBreaking,
        "field `cpu_load` (offset 8): renamed from `cpu_usage`",
    );
    assert_one(
        &c,
        Class::Compatible,
        "field `cpu_load` (offset 8): doc changed",
    );
    assert_eq!(breaking(&c), 0);
    let c = changes(
        HFLINK,
        "doc = \"Read the GPS fix.\"",
        "doc = \"Read the latest GPS fix.\"",
    );
    assert_one(
        &c,
        Class::Compatible,
        "command READ_GPS_DATA (id 0x1a): doc changed",
    );
    let c = changes(HFLINK, "version = \"2017.02\"", "version = \"2017.03\"");
    assert_one(&c, Class::Compatible, "version `2017.02` → `2017.03`");
}

#[test]
fn breaking_changes_come_first() {
    let c = changes(
        HFLINK,
        "READ_GPS_DATA = { id = 26,",
        "READ_GPS_DATA = { id = 40,",
    );
    let classes: Vec<Class> = c.iter().map(|x| x.class).collect();
    let mut sorted = classes.clone();
    sorted.sort();
    assert_eq!(classes, sorted);
}

const MAVLINK1: &str = "../tests/check_specs/mavlink1.toml";

#[test]
fn check_changes_that_keep_the_bytes_are_compatible_and_others_break() {
    // An alias of the same catalogue entry, or another table size, changes no byte.
    let c = changes(
        "../specs/referee.toml",
        "{ check = \"crc-16-mcrf4xx\"",
        "{ check = \"CRC-16/MCRF4XX\"",
    );
    assert_eq!(breaking(&c), 0, "{c:?}");
    let c = changes(
        "../specs/roborts.toml",
        "check = 0x2752 }",
        "check = 0x2752 }\ntable = 1",
    );
    assert_eq!(breaking(&c), 0, "{c:?}");
    // A complemented sum is another algorithm.
    let c = changes(
        HFLINK,
        "{ check = \"sum-mod-255\"",
        "{ check = \"fletcher-16\"",
    );
    assert!(breaking(&c) > 0, "{c:?}");
    // A command's extra byte, and folding one in at all.
    let c = changes(
        MAVLINK1,
        "payload = \"Heartbeat\", check_extra = 50",
        "payload = \"Heartbeat\", check_extra = 51",
    );
    assert_one(&c, Class::Breaking, "check_extra 50 → 51");
    let old = spec(MAVLINK1);
    let new = old
        .replacen(", extra = \"command\"", "", 1)
        .replace(", check_extra = 50", "")
        .replace(", check_extra = 137", "");
    let c = diff(&compile("old.toml", &old), &compile("new.toml", &new));
    assert_one(&c, Class::Breaking, "no longer folds in a byte per command");
}

const ROVER: &str = "../examples/tutorial/specs/rover.toml";

#[test]
fn an_added_command_keeps_the_wire_and_breaks_exhaustive_matches() {
    let c = changes(
        ROVER,
        "STATUS = { id = 0x20,",
        "BEEP = { id = 0x12 }\nSTATUS = { id = 0x20,",
    );
    assert_one(
        &c,
        Class::SourceBreaking,
        "command BEEP (id 0x12): added (old receivers count its frames as unknown commands; the generated enum gains a variant: an exhaustive `match` in the crate that expands the spec needs one more arm)",
    );
    assert_eq!(breaking(&c), 0, "{c:?}");
}

#[test]
fn changes_are_said_in_the_specs_words() {
    let c = changes(
        ROVER,
        "over = \"len..payload\" }",
        "over = \"len..payload\", byte_order = \"big\" }",
    );
    assert_one(
        &c,
        Class::Breaking,
        "frame `link`: check `checksum`: stored big-endian, was little-endian",
    );
    assert_eq!(c.len(), 1, "the byte order is the one change: {c:?}");
    let c = changes(
        ROVER,
        "over = \"len..payload\" }",
        "over = \"cmd..payload\" }",
    );
    assert_one(
        &c,
        Class::Breaking,
        "covers the bytes from byte 3 up to 2 bytes before the end, was from byte 2 up to 2 bytes before the end",
    );
    let c = changes(
        ROVER,
        "{ name = \"battery\", type = \"u16\", scale = 0.01, unit = \"V\" }",
        "{ name = \"battery\", type = \"i16\", scale = 0.01, unit = \"V\" }",
    );
    assert_one(
        &c,
        Class::Breaking,
        "field `battery` (offset 0): u16 (little-endian), scale 0.01 → i16 (little-endian), scale 0.01",
    );
    let c = changes(
        ROVER,
        "{ field = \"cmd\", type = \"u8\" }",
        "{ field = \"cmd\", type = \"u16be\" }",
    );
    assert_one(
        &c,
        Class::Breaking,
        "header value `cmd`: u16 (big-endian) at byte 3, was u8 at byte 3",
    );
    for change in &c {
        assert!(
            !change.reason.contains("Little") && !change.reason.contains("Start("),
            "Debug wording in `{change}`"
        );
    }
}
