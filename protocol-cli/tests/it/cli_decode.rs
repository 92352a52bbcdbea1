//! `protocol decode`, run as a process on the captures of `examples/captures/` and their ground
//! truth (what the capture script wrote, frame by frame): clean, noisy and truncated streams,
//! every input form, both output formats, `--stats`, and CAN logs.

use crate::support;

use serde_json::Value;
use support::{CAPTURES, json_lines, protocol, root, text, truth, unhex};

fn capture(name: &str) -> String {
    format!("examples/captures/{name}.bin")
}

/// (offset, hex) of the decoded frames of JSON Lines output.
fn frames(lines: &[Value]) -> Vec<(u64, String)> {
    lines
        .iter()
        .filter(|l| l.get("event").is_none())
        .map(|l| {
            (
                l["offset"].as_u64().expect("offset"),
                l["hex"].as_str().expect("hex").to_string(),
            )
        })
        .collect()
}

/// Asserts two lists of (offset, hex) are equal, naming the first difference.
fn assert_frames(got: &[(u64, String)], want: &[(u64, String)], what: &str) {
    if let Some(i) = (0..got.len().max(want.len())).find(|&i| got.get(i) != want.get(i)) {
        panic!(
            "{what}: {} frames decoded, {} expected; first difference at #{i}: got {:?}, expected {:?}",
            got.len(),
            want.len(),
            got.get(i),
            want.get(i)
        );
    }
}

/// (offset, hex) of the truth entries of one kind.
fn expected(truth: &[Value], kind: &str) -> Vec<(u64, String)> {
    truth
        .iter()
        .filter(|t| t["kind"] == kind)
        .map(|t| {
            (
                t["offset"].as_u64().expect("offset"),
                t["hex"].as_str().expect("hex").to_string(),
            )
        })
        .collect()
}

fn events<'a>(lines: &'a [Value], kind: &str) -> Vec<&'a Value> {
    lines.iter().filter(|l| l["event"] == kind).collect()
}

#[test]
fn noisy_captures_yield_exactly_their_intact_frames_and_account_for_every_byte() {
    for (spec, name, how) in CAPTURES {
        let capture = capture(name);
        let out = protocol(
            &[&["decode", spec, &capture, "--format", "json"], *how].concat(),
            b"",
        );
        assert!(out.status.success(), "{name}: {}", text(&out.stderr));
        let lines = json_lines(&out.stdout);
        let truth = truth(name);
        assert_frames(&frames(&lines), &expected(&truth, "frame"), name);
        let unknown: Vec<u64> = events(&lines, "unknown_command")
            .iter()
            .map(|e| e["offset"].as_u64().expect("offset"))
            .collect();
        let unknown_truth: Vec<u64> = expected(&truth, "unknown_command")
            .iter()
            .map(|e| e.0)
            .collect();
        assert_eq!(unknown, unknown_truth, "{name}: unknown commands");
        let damaged = truth
            .iter()
            .filter(|t| t["kind"] != "frame" && t["kind"] != "unknown_command")
            .count();
        let rejected = lines
            .iter()
            .filter(|l| {
                l["event"]
                    .as_str()
                    .is_some_and(|e| e.starts_with("bad_") || e == "truncated")
            })
            .count();
        assert!(
            damaged == 0 || rejected > 0,
            "{name}: damaged frames must show as rejections"
        );
        // Frames and events account for every byte of the input, once.
        let accounted: u64 = lines
            .iter()
            .map(|l| {
                l.get("length")
                    .or(l.get("bytes"))
                    .and_then(Value::as_u64)
                    .expect("size")
            })
            .sum();
        let size = std::fs::metadata(root().join(&capture))
            .expect("capture")
            .len();
        assert_eq!(accounted, size, "{name}: bytes accounted for");
    }
}

#[test]
fn a_clean_stream_is_all_frames() {
    for (spec, name, how) in CAPTURES {
        let intact = expected(&truth(name), "frame");
        let clean: Vec<u8> = intact.iter().flat_map(|(_, h)| unhex(h)).collect();
        let out = protocol(
            &[&["decode", spec, "-", "--format", "json", "--stats"], *how].concat(),
            &clean,
        );
        assert!(out.status.success(), "{name}: {}", text(&out.stderr));
        let lines = json_lines(&out.stdout);
        assert_eq!(
            lines.len(),
            intact.len(),
            "{name}: one line per frame, no event"
        );
        let hexes: Vec<&str> = lines
            .iter()
            .map(|l| l["hex"].as_str().expect("hex"))
            .collect();
        let want: Vec<&str> = intact.iter().map(|(_, h)| h.as_str()).collect();
        assert_eq!(hexes, want, "{name}");
        let stats = text(&out.stderr);
        assert!(
            stats.contains(&format!("frames decoded: {}", intact.len())),
            "{stats}"
        );
        assert!(stats.contains("link efficiency: 100.0%"), "{stats}");
        assert!(stats.contains("bytes skipped: 0 (0.0%)"), "{stats}");
    }
}

#[test]
fn a_truncated_capture_keeps_every_complete_frame_and_reports_the_cut_one() {
    for (spec, name, how) in CAPTURES {
        let bytes = std::fs::read(root().join(capture(name))).expect("capture");
        let intact = expected(&truth(name), "frame");
        // Cut the last intact frame in the middle.
        let (last_at, last_hex) = intact.last().expect("frames").clone();
        let cut = last_at as usize + last_hex.len() / 4;
        let out = protocol(
            &[&["decode", spec, "-", "--format", "json"], *how].concat(),
            &bytes[..cut],
        );
        assert!(out.status.success(), "{name}: {}", text(&out.stderr));
        let lines = json_lines(&out.stdout);
        assert_frames(&frames(&lines), &intact[..intact.len() - 1], name);
        let tail: Vec<&Value> = lines
            .iter()
            .filter(|l| l["offset"].as_u64() >= Some(last_at))
            .collect();
        assert_eq!(
            tail.first().map(|l| l["event"].clone()),
            Some(Value::from("truncated")),
            "{name}: {tail:?}"
        );
    }
}

#[test]
fn every_input_form_gives_the_same_output() {
    let (spec, name, _) = CAPTURES[0];
    let path = capture(name);
    let bytes = std::fs::read(root().join(&path)).expect("capture");
    let from_file = protocol(&["decode", spec, &path, "--format", "json"], b"");
    let from_stdin = protocol(&["decode", spec, "--format", "json"], &bytes);
    let dash = protocol(&["decode", spec, "-", "--format", "json"], &bytes);
    // Hex text as people paste it: spaces, line breaks, 0x prefixes.
    let hex_text: String = bytes
        .chunks(16)
        .map(|line| {
            line.iter()
                .map(|b| format!("0x{b:02X} "))
                .collect::<String>()
                + "\n"
        })
        .collect();
    let from_hex = protocol(
        &["decode", spec, "--hex", "--format", "json"],
        hex_text.as_bytes(),
    );
    for out in [&from_stdin, &dash, &from_hex] {
        assert!(out.status.success(), "{}", text(&out.stderr));
        assert_eq!(text(&out.stdout), text(&from_file.stdout));
    }
    let bad_hex = protocol(&["decode", spec, "--hex"], b"ff ff 0g");
    assert_eq!(bad_hex.status.code(), Some(1));
    assert!(
        text(&bad_hex.stderr).contains("stdin:1:8: `g` is not a hex digit"),
        "{}",
        text(&bad_hex.stderr)
    );
}

#[test]
fn the_json_shape_is_the_documented_one() {
    let out = protocol(
        &[
            "decode",
            "specs/hflink.toml",
            &capture("hflink"),
            "--format",
            "json",
        ],
        b"",
    );
    let lines = json_lines(&out.stdout);
    let frame = lines
        .iter()
        .find(|l| {
            l["command"] == "READ_GPS_DATA" && l["payload"] != Value::Object(Default::default())
        })
        .expect("a GPS fix");
    let keys: Vec<&str> = frame
        .as_object()
        .expect("object")
        .keys()
        .map(String::as_str)
        .collect();
    assert_eq!(
        keys,
        [
            "offset", "length", "format", "command", "id", "header", "payload", "hex"
        ]
    );
    assert_eq!(frame["format"], "link");
    assert_eq!(frame["id"], 26);
    assert_eq!(
        frame["header"],
        serde_json::json!({"sender": 17, "receiver": 1})
    );
    // Nested structs as objects, fields in spec order, padding absent.
    let payload: Vec<&str> = frame["payload"]
        .as_object()
        .expect("payload")
        .keys()
        .map(String::as_str)
        .collect();
    assert_eq!(
        payload,
        [
            "utc_time",
            "satellite_num",
            "altitude",
            "ground_speed",
            "latitude",
            "nshemi",
            "longitude",
            "ewhemi"
        ]
    );
    assert_eq!(frame["payload"]["utc_time"]["year"], 2017);
    assert_eq!(
        frame["payload"]["altitude"], 45.2,
        "floats print as their shortest decimal"
    );
    for e in lines.iter().filter(|l| l.get("event").is_some()) {
        let keys: Vec<&str> = e
            .as_object()
            .expect("object")
            .keys()
            .map(String::as_str)
            .take(3)
            .collect();
        assert_eq!(keys, ["offset", "event", "bytes"], "{e}");
    }
    // A two-field key is an array; bitfield members are keys of their own.
    let scout = json_lines(
        &protocol(
            &[
                "decode",
                "specs/scout.toml",
                &capture("scout"),
                "--format",
                "json",
            ],
            b"",
        )
        .stdout,
    );
    let status = scout
        .iter()
        .find(|l| l["command"] == "SYSTEM_STATUS")
        .expect("a system status");
    assert_eq!(status["id"], serde_json::json!([0xAA, 0x01]));
    assert_eq!(status["payload"]["base_state"], "NORMAL", "enums by name");
    assert_eq!(
        status["payload"]["battery_voltage"], 26.4,
        "scaled fields as physical values"
    );
    assert!(status["payload"]["bat_under_vol_w"].is_boolean());
}

#[test]
fn table_output_and_stats() {
    let out = protocol(
        &[
            "decode",
            "specs/hflink.toml",
            &capture("hflink"),
            "--format",
            "table",
            "--stats",
        ],
        b"",
    );
    assert!(out.status.success());
    let stdout = text(&out.stdout);
    let intact = expected(&truth("hflink"), "frame").len();
    let first = stdout.lines().next().expect("a line");
    assert!(
        first.contains("SHAKING_HANDS")
            && first.contains("request")
            && first.contains("x=0.0 (m or m/s)"),
        "{first}"
    );
    assert!(stdout.contains("! bad checksum"), "events are lines too");
    assert!(
        stdout.contains("! unknown command  id=0x30"),
        "unknown commands are events"
    );
    for needle in [
        format!("frames decoded: {intact} ("),
        "SET_ROBOT_SPEED".to_string(),
        "checksum failures: ".to_string(),
        "length rejections: ".to_string(),
        "bytes skipped: ".to_string(),
        "link efficiency: ".to_string(),
    ] {
        assert!(stdout.contains(&needle), "stats lack `{needle}`:\n{stdout}");
    }
    assert!(text(&out.stderr).is_empty(), "{}", text(&out.stderr));
}

#[test]
fn candump_logs_decode_on_the_can_frame_format() {
    let out = protocol(
        &[
            "decode",
            "specs/scout.toml",
            "--candump",
            "examples/captures/scout_can.log",
            "--format",
            "json",
            "--stats",
        ],
        b"",
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let lines = json_lines(&out.stdout);
    let truth = truth("scout_can");
    assert_eq!(lines.len(), truth.len(), "one line per CAN frame");
    for (line, t) in lines.iter().zip(&truth) {
        assert_eq!(line["offset"], t["offset"]);
        assert_eq!(line["can_id"], t["can_id"], "{line}");
        match t["kind"].as_str() {
            Some("frame") => {
                assert_eq!(line["hex"], t["hex"]);
                assert_eq!(line["format"], "can");
            }
            Some(kind) => assert_eq!(line["event"], kind, "{line}"),
            None => panic!("truth without a kind"),
        }
    }
    assert!(
        text(&out.stderr).contains("CAN frames rejected: bad checksum"),
        "{}",
        text(&out.stderr)
    );
}

#[test]
fn candump_needs_a_can_transport() {
    let out = protocol(
        &[
            "decode",
            "specs/hflink.toml",
            "--candump",
            "examples/captures/scout_can.log",
        ],
        b"",
    );
    assert_eq!(out.status.code(), Some(1));
    let err = text(&out.stderr);
    assert!(err.contains("spec `hflink` has no CAN transport"), "{err}");
    assert!(out.stdout.is_empty());
}

#[test]
fn an_unknown_frame_format_is_named() {
    let out = protocol(
        &[
            "decode",
            "specs/scout.toml",
            "--frame",
            "radio",
            &capture("scout"),
        ],
        b"",
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(
        text(&out.stderr).contains("no frame format `radio` (it has: uart, can)"),
        "{}",
        text(&out.stderr)
    );
}
