//! `protocol decode --candump` and `protocol encode` on a CAN-only link whose identifier is split
//! into members (`specs/dronecan.toml`): pydronecan's frames (`tests/vectors/
//! dronecan_pydronecan.json`), written as a `candump -L` log with a service frame between them,
//! decode to their commands with the identifier's members in `header` and the whole identifier
//! as `can_id`; the service frame is a bad header; the decoded lines encode back to the log.

use crate::support;

use serde_json::Value;
use support::{json_lines, protocol, root, text};

/// pydronecan's frames as `candump -L` lines (`(time) can0 ID#DATA`, 8-digit extended ids).
fn log_lines() -> Vec<(Value, String)> {
    let path = root().join("tests/vectors/dronecan_pydronecan.json");
    let v: Value =
        serde_json::from_str(&std::fs::read_to_string(path).expect("vectors")).expect("JSON");
    v["frames"]
        .as_array()
        .expect("frames")
        .iter()
        .map(|f| {
            let id = f["can_id"].as_u64().expect("can_id");
            let data = f["data"].as_str().expect("data").to_ascii_uppercase();
            (f.clone(), format!("{id:08X}#{data}"))
        })
        .collect()
}

#[test]
fn a_candump_log_of_dronecan_frames_decodes_to_their_members_and_encodes_back() {
    let frames = log_lines();
    let dir = std::env::temp_dir().join(format!("protocol-dronecan-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let log = dir.join("bus.log");
    // A service frame (the service flag, bit 7 of the id, set) after the first message.
    let service_id = frames[0].0["can_id"].as_u64().expect("id") | 0x80;
    let mut text_log = String::new();
    for (i, (_, line)) in frames.iter().enumerate() {
        text_log.push_str(&format!("({i}.000000) can0 {line}\n"));
        if i == 0 {
            text_log.push_str(&format!("(0.500000) can0 {service_id:08X}#00C0\n"));
        }
    }
    std::fs::write(&log, &text_log).expect("the log");
    let log_arg = log.to_str().expect("a UTF-8 path");
    let out = protocol(
        &[
            "decode",
            "specs/dronecan.toml",
            "--candump",
            log_arg,
            "--format",
            "json",
        ],
        b"",
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let lines = json_lines(&out.stdout);
    assert_eq!(lines.len(), frames.len() + 1, "one line per CAN frame");
    assert_eq!(lines[1]["event"], "bad_header", "{}", lines[1]);
    assert_eq!(lines[1]["can_id"], service_id);
    let decoded: Vec<&Value> = lines.iter().filter(|l| l.get("event").is_none()).collect();
    assert_eq!(decoded.len(), frames.len(), "every message decodes");
    for (line, (frame, _)) in decoded.iter().zip(&frames) {
        assert_eq!(line["command"], frame["command"], "{line}");
        assert_eq!(line["can_id"], frame["can_id"], "{line}");
        assert_eq!(line["header"], frame["header"], "{line}");
        assert_eq!(line["hex"], frame["data"], "{line}");
    }

    // The decoded lines encode to the same frames, as candump lines.
    let input: String = decoded.iter().map(|l| format!("{l}\n")).collect();
    let out = protocol(
        &["encode", "specs/dronecan.toml", "--hex"],
        input.as_bytes(),
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let written = text(&out.stdout);
    let written: Vec<&str> = written
        .lines()
        .map(|l| l.rsplit(' ').next().expect("ID#DATA"))
        .collect();
    let want: Vec<&str> = frames.iter().map(|(_, l)| l.as_str()).collect();
    assert_eq!(written, want, "the encoded frames");
    std::fs::remove_dir_all(&dir).expect("clean up");
}
