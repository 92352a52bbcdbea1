//! `protocol encode`, run as a process: `decode --format json | encode` gives back every valid
//! frame of a capture byte for byte (serial and CAN), values the spec computes may be left
//! out, and a bad frame object gets an error naming its line and field while the others are
//! still written.

use crate::support;

use protocol_cli::candump;
use serde_json::{Value, json};
use support::{CAPTURES, json_lines, protocol, text, truth, unhex};

#[test]
fn decode_then_encode_reproduces_every_valid_frame_byte_for_byte() {
    for (spec, name, how) in CAPTURES {
        let capture = format!("examples/captures/{name}.bin");
        let decoded = protocol(
            &[&["decode", spec, &capture, "--format", "json"], *how].concat(),
            b"",
        );
        assert!(decoded.status.success());
        let encoded = protocol(&["encode", spec], &decoded.stdout);
        assert!(
            encoded.status.success(),
            "{name}: {}",
            text(&encoded.stderr)
        );
        let valid: Vec<u8> = truth(name)
            .iter()
            .filter(|t| t["kind"] == "frame")
            .flat_map(|t| unhex(t["hex"].as_str().expect("hex")))
            .collect();
        assert!(!valid.is_empty());
        assert_eq!(
            encoded.stdout, valid,
            "{name}: the valid frames, in order, byte for byte"
        );
        // --hex writes the same frames, one per line.
        let as_hex = protocol(&["encode", spec, "--hex"], &decoded.stdout);
        let lines: Vec<Vec<u8>> = text(&as_hex.stdout).lines().map(unhex).collect();
        assert_eq!(lines.concat(), valid, "{name}: --hex");
    }
}

#[test]
fn decode_then_encode_reproduces_every_valid_can_frame() {
    let decoded = protocol(
        &[
            "decode",
            "specs/scout.toml",
            "--candump",
            "examples/captures/scout_can.log",
            "--format",
            "json",
        ],
        b"",
    );
    let encoded = protocol(&["encode", "specs/scout.toml"], &decoded.stdout);
    assert!(encoded.status.success(), "{}", text(&encoded.stderr));
    let (frames, errors) = candump::parse(&text(&encoded.stdout));
    assert!(
        errors.is_empty(),
        "encode writes candump -L lines: {errors:?}"
    );
    let got: Vec<(u32, Vec<u8>)> = frames.into_iter().map(|(_, r)| (r.id, r.data)).collect();
    let want: Vec<(u32, Vec<u8>)> = truth("scout_can")
        .iter()
        .filter(|t| t["kind"] == "frame")
        .map(|t| {
            (
                t["can_id"].as_u64().expect("id") as u32,
                unhex(t["hex"].as_str().expect("hex")),
            )
        })
        .collect();
    assert_eq!(got, want);
}

#[test]
fn computed_values_may_be_left_out() {
    // No offset, length, hex or id; the command by its Rust name; a hex string for a u8.
    let object = json!({
        "command": "SetRobotSpeed",
        "header": { "sender": "0x01", "receiver": 17 },
        "payload": { "x": 0.5, "y": 0, "z": -0.25 },
    });
    let out = protocol(
        &["encode", "specs/hflink.toml", "--hex"],
        format!("{object}\n").as_bytes(),
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let frame = unhex(text(&out.stdout).trim());
    let back = protocol(
        &["decode", "specs/hflink.toml", "-", "--format", "json"],
        &frame,
    );
    let line = &json_lines(&back.stdout)[0];
    assert_eq!(line["command"], "SET_ROBOT_SPEED");
    assert_eq!(line["payload"], json!({ "x": 0.5, "y": 0.0, "z": -0.25 }));
    assert_eq!(line["header"], json!({ "sender": 1, "receiver": 17 }));
}

#[test]
fn bad_frame_objects_name_their_line_and_field_and_write_nothing() {
    let good = json!({"command": "READ_SYSTEM_INFO", "header": {"sender": 1, "receiver": 17}});
    let good_hex = "ffff011100010114";
    let cases: &[(&str, &str)] = &[
        (
            r#"{"command":"SET_ROBOT_SPEED","header":{"sender":1,"receiver":17},"payload":{"x":0.5,"z":0.1}}"#,
            "`payload.y`: missing",
        ),
        (
            r#"{"command":"SET_ROBOT_SPEED","header":{"sender":1,"receiver":17},"payload":{"x":"fast","y":0,"z":0}}"#,
            "`payload.x`: expected a number (f32), got the string \"fast\"",
        ),
        (
            r#"{"command":"READ_SYSTEM_INFO","header":{"sender":300,"receiver":17}}"#,
            "`header.sender`: 300 does not fit u8",
        ),
        (
            r#"{"command":"FLY","header":{"sender":1,"receiver":17}}"#,
            "`command`: no command `FLY` in the spec",
        ),
        (
            r#"{"command":"READ_GPS_DATA","header":{"sender":17,"receiver":1},"payload":{"utc_time":{"year":2017,"month":3,"date":14,"hour":9,"min":26},"satellite_num":9,"altitude":1,"ground_speed":0,"latitude":1,"nshemi":78,"longitude":1,"ewhemi":69}}"#,
            "`payload.utc_time.sec`: missing",
        ),
        (
            r#"{"command":"READ_SYSTEM_INFO","header":{"sender":100,"receiver":17}}"#,
            "`header`: the header matches no direction of the spec",
        ),
        (
            r#"{"command":"SET_ROBOT_SPEED","header":{"sender":1,"receiver":17},"payload":{"x":1,"y":2,"z":3,"w":4}}"#,
            "`payload.w`: struct `ChassisCoord` has no such field",
        ),
        (r#"{"command": "READ_SYSTEM_INFO", "header": "#, "not JSON"),
    ];
    let mut input = String::new();
    for (bad, _) in cases {
        input.push_str(&format!("{good}\n{bad}\n"));
    }
    input.push_str(&format!("{good}\n"));
    let out = protocol(&["encode", "specs/hflink.toml", "--hex"], input.as_bytes());
    assert_eq!(out.status.code(), Some(1), "a bad line fails the run");
    let written: Vec<String> = text(&out.stdout).lines().map(str::to_string).collect();
    assert_eq!(
        written,
        vec![good_hex.to_string(); cases.len() + 1],
        "only the good lines are written"
    );
    let stderr = text(&out.stderr);
    let errors: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("error: "))
        .collect();
    assert_eq!(errors.len(), cases.len(), "{stderr}");
    for (i, ((_, message), line)) in cases.iter().zip(&errors).enumerate() {
        let line_no = 2 * i + 2;
        assert!(
            line.starts_with(&format!("error: stdin:{line_no}: ")),
            "{line}"
        );
        assert!(
            line.contains(message),
            "line {line_no}: `{line}` lacks `{message}`"
        );
    }
    assert!(
        stderr.contains(&format!("{} lines not encoded", cases.len())),
        "{stderr}"
    );
}

#[test]
fn events_are_skipped_and_enums_take_names_or_numbers() {
    let input = [
        json!({"offset": 3, "event": "bad_checksum", "bytes": 1}),
        json!({"command": "SYSTEM_STATUS", "header": {"count": 7}, "payload": {
            "base_state": "ESTOP", "control_mode": 9, "battery_voltage": 23.9,
            "bat_under_vol_f": false, "bat_over_vol_f": false, "motor1_comm_f": true,
            "motor2_comm_f": true, "motor3_comm_f": true, "motor4_comm_f": true,
            "motor_drv_overheat_f": false, "motor_overcurrent_f": false,
            "can_checksum_error": false, "motor_drv_overheat_w": false,
            "motor_overcurrent_w": false, "bat_under_vol_w": false, "rc_signal_loss": false}}),
    ]
    .iter()
    .map(Value::to_string)
    .collect::<Vec<_>>()
    .join("\n");
    let out = protocol(&["encode", "specs/scout.toml", "--hex"], input.as_bytes());
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(lines.len(), 1, "the event line writes nothing");
    let back = protocol(
        &["decode", "specs/scout.toml", "--hex", "--format", "json"],
        lines[0].as_bytes(),
    );
    let frame = &json_lines(&back.stdout)[0];
    assert_eq!(frame["payload"]["base_state"], "ESTOP");
    assert_eq!(
        frame["payload"]["control_mode"], 9,
        "an unknown value of a keeping enum stays a number"
    );
    assert_eq!(frame["payload"]["battery_voltage"], 23.9);
    assert_eq!(frame["payload"]["motor3_comm_f"], true);
}
