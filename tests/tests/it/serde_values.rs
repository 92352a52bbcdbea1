//! The serde impls of the runtime's value types and of generated types (the `serde` feature,
//! `protocol!(..., derive(serde))`) at their edges: what each writes, what each refuses to
//! read, and that whatever is written reads back as the same value (bits included, for floats).

use protocol_kit::{Bytes, FixedStr, Group};
use serde::{Deserialize, Serialize};
use serde_json::{from_str, json, to_string, to_value};

protocol_kit::protocol!(
    derive(serde),
    inline = r#"
[protocol]
name = "gauge"

[frames.main]
layout = [
  { sync = [0xAA] },
  { field = "node", type = "u8" },
  { field = "len", type = "u8", length_of = "payload" },
  { field = "cmd", type = "u8" },
  { payload = { max = 64 } },
  { check = "sum8", over = "frame" },
]
dispatch = ["cmd"]

[commands]
READ = { id = 1, payload = "Reading" }
RESET = { id = 2 }

[enums.Mode]
type = "i8"
values = { OFF = 0, ON = 1, REVERSE = -1 }

[enums.Source]
type = "u8"
unknown = "keep"
values = { A = 0, B = 1 }

[structs.Reading]
fields = [
  { name = "mode", type = "Mode" },
  { name = "source", type = "Source" },
  { name = "level", type = "f32" },
  { name = "history", type = "u8", count = 40 },
]
"#
);

fn reading() -> gauge::Reading {
    gauge::Reading {
        mode: gauge::Mode::Reverse,
        source: gauge::Source::Unknown(200),
        level: f32::from_bits(0x7fc0_0001),
        history: core::array::from_fn(|i| i as u8),
    }
}

#[test]
fn bytes_are_hex_and_read_back_from_hex_only_when_they_fit() {
    let b = Bytes::<4>::from_slice(&[0x00, 0xAB, 0x7F]).expect("fits");
    assert_eq!(to_string(&b).expect("writes"), r#""00ab7f""#);
    assert_eq!(from_str::<Bytes<4>>(r#""00AB7f""#).expect("reads"), b);
    assert_eq!(
        from_str::<Bytes<4>>(r#""""#).expect("reads"),
        Bytes::<4>::new()
    );
    for bad in [r#""0ab""#, r#""0g""#, r#""0102030405""#, "[1, 2]"] {
        assert!(from_str::<Bytes<4>>(bad).is_err(), "{bad} is refused");
    }
}

#[test]
fn text_is_a_string_when_canonical_and_its_bytes_otherwise() {
    let t = FixedStr::<6>::from_text("héllo").expect("fits");
    assert_eq!(to_string(&t).expect("writes"), r#""héllo""#);
    assert_eq!(from_str::<FixedStr<6>>(r#""héllo""#).expect("reads"), t);
    // Bytes after the NUL, and text that is not UTF-8: every byte, as an array.
    for raw in [[b'o', b'k', 0, b'x', 0, 0], [0xFF, b'a', 0, 0, 0, 0]] {
        let t = FixedStr::from_bytes(raw);
        let v = to_value(t).expect("writes");
        assert_eq!(v, json!(raw));
        assert_eq!(from_str::<FixedStr<6>>(&v.to_string()).expect("reads"), t);
    }
    assert!(from_str::<FixedStr<6>>(r#""toolong""#).is_err());
    assert!(from_str::<FixedStr<6>>("[1, 2, 3]").is_err());
}

#[test]
fn groups_are_lists_of_at_most_their_capacity() {
    let g = Group::<u16, 3>::from_slice(&[1, 2]).expect("fits");
    assert_eq!(to_string(&g).expect("writes"), "[1,2]");
    assert_eq!(from_str::<Group<u16, 3>>("[1,2]").expect("reads"), g);
    assert!(from_str::<Group<u16, 3>>("[1,2,3,4]").is_err());
}

#[test]
fn generated_structs_keep_unknown_values_long_arrays_and_nan_bits() {
    let r = reading();
    let v = to_value(r).expect("writes");
    assert_eq!(v["mode"], json!("REVERSE"));
    assert_eq!(v["source"], json!(200));
    assert_eq!(v["level"], json!("NaN(0x7fc00001)"));
    assert_eq!(v["history"].as_array().map(Vec::len), Some(40));
    let back: gauge::Reading = from_str(&v.to_string()).expect("reads");
    assert_eq!(back.level.to_bits(), r.level.to_bits());
    assert_eq!(
        (back.mode, back.source, back.history),
        (r.mode, r.source, r.history)
    );

    // Names or numbers in; a number with no variant only where the enum keeps it.
    let mut text = v.clone();
    text["mode"] = json!(-1);
    text["source"] = json!("B");
    text["level"] = json!("-inf");
    let read: gauge::Reading = from_str(&text.to_string()).expect("reads");
    assert_eq!(
        (read.mode, read.source),
        (gauge::Mode::Reverse, gauge::Source::B)
    );
    assert_eq!(read.level, f32::NEG_INFINITY);
    for (key, bad) in [
        ("mode", json!(5)),
        ("mode", json!("SIDEWAYS")),
        ("source", json!(300)),
        ("level", json!("fast")),
        ("history", json!([1, 2, 3])),
    ] {
        let mut wrong = v.clone();
        wrong[key] = bad.clone();
        assert!(
            from_str::<gauge::Reading>(&wrong.to_string()).is_err(),
            "{key} = {bad} is refused"
        );
    }
}

#[test]
fn packets_read_command_and_header_before_payload_and_skip_other_keys() {
    let packet = gauge::Packet {
        header: gauge::Header { node: 3 },
        message: gauge::Message::Read(reading()),
    };
    let text = to_string(&packet).expect("writes");
    let mut v: serde_json::Value = from_str(&text).expect("JSON");
    assert_eq!(v["command"], json!("READ"));
    assert_eq!(v["header"], json!({ "node": 3 }));
    v["offset"] = json!(12);
    v["hex"] = json!("aa");
    let back: gauge::Packet = from_str(&v.to_string()).expect("reads");
    assert_eq!(to_string(&back).expect("writes"), text);

    let reset = r#"{"command":"RESET","header":{"node":1},"payload":{}}"#;
    let read: gauge::Packet = from_str(reset).expect("reads");
    assert_eq!(read.message, gauge::Message::Reset);
    assert_eq!(to_string(&read).expect("writes"), reset);

    for bad in [
        r#"{"header":{"node":1},"command":"RESET","payload":{"x":1}}"#,
        r#"{"command":"STOP","header":{"node":1},"payload":{}}"#,
        r#"{"command":"RESET","payload":{},"header":{"node":1}}"#,
        r#"{"header":{"node":1},"payload":{}}"#,
        r#"{"command":"RESET","header":{"node":1}}"#,
    ] {
        assert!(from_str::<gauge::Packet>(bad).is_err(), "{bad} is refused");
    }
}

/// serde's own derive next to the runtime's helpers, as a user's type holding generated ones.
#[derive(Serialize, Deserialize, Debug, PartialEq)]
struct Log {
    packets: Vec<gauge::Packet>,
}

#[test]
fn generated_types_nest_in_a_users_own_serde_types() {
    let log = Log {
        packets: vec![gauge::Packet {
            header: gauge::Header { node: 9 },
            message: gauge::Message::Reset,
        }],
    };
    let text = to_string(&log).expect("writes");
    assert_eq!(from_str::<Log>(&text).expect("reads"), log);
}

#[test]
fn text_given_as_bytes_reads_up_to_its_capacity_and_no_further() {
    use protocol_kit::{NulStr, Str};
    let bytes = [0xFF, b'a', b'b', 0x80];
    let s = from_str::<Str<4>>("[255, 97, 98, 128]").expect("reads");
    assert_eq!(s.text(), bytes);
    assert_eq!(
        from_str::<Str<4>>(&to_string(&s).expect("writes")).expect("reads"),
        s
    );
    let n = from_str::<NulStr<4>>("[255, 97, 98, 128]").expect("reads");
    assert_eq!(n.text(), bytes);
    // One byte beyond the capacity is refused, in both.
    assert!(from_str::<Str<4>>("[1, 2, 3, 4, 5]").is_err());
    assert!(from_str::<NulStr<4>>("[1, 2, 3, 4, 5]").is_err());
}
