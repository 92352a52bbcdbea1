//! Errors of generated code say where: a value that fails to decode or encode names its command
//! and its field (`Struct.field`, `&'static str`s, nothing allocated), and `Display` prints both,
//! as the run-time codec's messages do (`protocol decode` and `protocol encode` show those); the
//! run-time codec refuses the same values at the same fields.
//! Spec: `protocol-codegen/tests/features/payload_types.toml`.

use protocol_dynamic::{DecodeIssue, Interpreter, Value};
use protocol_kit::error::Place;
use protocol_kit::{DecodeError, EncodeError, Group, NulStr};

protocol_kit::protocol!("../protocol-codegen/tests/features/payload_types.toml");

use payload_types::*;

/// A frame of the fixture: sync, length, command, payload, sum of the bytes before it.
fn frame(command: u8, payload: &[u8]) -> Vec<u8> {
    let mut f = vec![0xAA, payload.len() as u8, command];
    f.extend_from_slice(payload);
    let sum = f.iter().fold(0u8, |a, &b| a.wrapping_add(b));
    f.push(sum);
    f
}

fn interpreter() -> Interpreter {
    let path = format!(
        "{}/../protocol-codegen/tests/features/payload_types.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    Interpreter::load(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

#[test]
fn an_enum_value_without_variant_names_its_command_and_field() {
    // Count 1, value 0, an empty name, mode 7 (Mode has 0 and 1).
    let bytes = frame(1, &[1, 0, 0, 0, 7]);
    let e = Packet::decode(&bytes).expect_err("7 is no Mode");
    assert_eq!(
        e,
        DecodeError::InvalidEnum {
            value: 7,
            place: Place::new("READINGS", "Readings.modes"),
        }
    );
    assert_eq!(
        e.to_string(),
        "READINGS: `Readings.modes` holds 0x7, which is no variant of its enum"
    );
    // The run-time codec names the same command and field (its path goes down to the element).
    let issue = interpreter()
        .codec()
        .parse(0, &bytes)
        .expect_err("7 is no Mode");
    let DecodeIssue::InvalidEnum { command, field, .. } = &issue else {
        panic!("the run-time codec: {issue:?}");
    };
    assert_eq!(command, "READINGS");
    assert!(field.contains("modes"), "{issue}");
    assert_eq!(issue.to_runtime(), e.without_place());
}

#[test]
fn a_stated_count_beyond_the_most_names_its_field() {
    // Count 9: the arrays hold 8 at most.
    let bytes = frame(1, &[9, 0, 0, 0]);
    let e = Packet::decode(&bytes).expect_err("9 elements do not fit");
    assert_eq!(e.place(), Some(Place::new("READINGS", "Readings.values")));
    assert_eq!(
        e.to_string(),
        "READINGS: `Readings.values`: a field's size does not match the size another field states"
    );
}

#[test]
fn a_value_that_does_not_fit_names_its_command_and_field_when_encoded() {
    // Two values where the count says three.
    let packet = Packet {
        header: Header {},
        message: Message::Readings(Readings {
            count: 3,
            values: Group::from_slice(&[1, 2]).expect("fits"),
            name: NulStr::new(),
            modes: Group::from_slice(&[Mode::Run, Mode::Run, Mode::Run]).expect("fits"),
        }),
    };
    let mut buf = [0u8; MAX_FRAME_LEN];
    let e = packet
        .encode(&mut buf)
        .expect_err("the count is not the values'");
    assert_eq!(
        e,
        EncodeError::ValueOutOfRange {
            place: Place::new("READINGS", "Readings.values"),
        }
    );
    assert_eq!(
        e.to_string(),
        "READINGS: `Readings.values`: value does not fit its field"
    );
    // The run-time codec refuses the same value of the same frame object, naming the field
    // (its path is the JSON's, `payload.values`) of the command the object names.
    let interpreter = interpreter();
    let codec = interpreter.codec();
    let valid = frame(1, &[2, 1, 0, 2, 0, 0, 1, 1]);
    let decoded = codec.parse(0, &valid).expect("a valid frame");
    let mut object = codec.frame_value(&decoded, 0, &valid);
    let Value::Struct(fields) = &mut object else {
        panic!("a frame object: {object:?}");
    };
    assert_eq!(
        fields.get("command"),
        Some(&Value::String("READINGS".into()))
    );
    let mut payload = fields.get("payload").cloned().expect("a payload");
    let Value::Struct(values) = &mut payload else {
        panic!("a payload struct: {payload:?}");
    };
    values.insert("count", Value::UInt(3));
    fields.insert("payload", payload);
    let issue = codec
        .encode(&object)
        .expect_err("the count is not the values'");
    assert!(issue.path.contains("values"), "{issue}");
}

#[test]
fn an_encode_error_inside_a_nested_value_keeps_the_innermost_field() {
    // A level that the raw `u16` cannot hold: the field is `Levels.levels`, the command LEVELS.
    let packet = Packet {
        header: Header {},
        message: Message::Levels(Levels {
            source: 1,
            levels: Group::from_slice(&[1.0, 1.0e9]).expect("fits"),
        }),
    };
    let mut buf = [0u8; MAX_FRAME_LEN];
    let e = packet.encode(&mut buf).expect_err("1e9 V does not fit");
    assert_eq!(e.place(), Some(Place::new("LEVELS", "Levels.levels")));
    assert_eq!(
        e.to_string(),
        "LEVELS: `Levels.levels`: value does not fit its field"
    );
    // The run-time codec refuses the same value at the same field.
    let interpreter = interpreter();
    let codec = interpreter.codec();
    let valid = frame(2, &[1, 0, 10]);
    let decoded = codec.parse(0, &valid).expect("a valid frame");
    let mut object = codec.frame_value(&decoded, 0, &valid);
    let Value::Struct(fields) = &mut object else {
        panic!("a frame object: {object:?}");
    };
    let mut payload = fields.get("payload").cloned().expect("a payload");
    let Value::Struct(values) = &mut payload else {
        panic!("a payload struct: {payload:?}");
    };
    values.insert(
        "levels",
        Value::Array(vec![Value::F64(1.0), Value::F64(1.0e9)]),
    );
    fields.insert("payload", payload);
    let issue = codec.encode(&object).expect_err("1e9 V does not fit");
    assert!(issue.path.contains("levels"), "{issue}");
}

#[test]
fn errors_of_the_frame_name_no_place() {
    // A wrong sum: the frame is refused before any field is read.
    let mut bytes = frame(1, &[1, 0, 0, 0, 1]);
    let n = bytes.len();
    bytes[n - 1] ^= 1;
    let e = Packet::decode(&bytes).expect_err("a wrong sum");
    assert_eq!(e.place(), None);
    assert!(e.to_string().starts_with("invalid frame"), "{e}");
}
