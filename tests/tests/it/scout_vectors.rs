//! AgileX Scout golden vectors (`tests/vectors/agilex_scout.json`, made by running scout_sdk's C
//! and C++): every message decodes from and encodes to its UART frame and its CAN frame, the
//! UART stream yields its expected frames at every chunk size, the CAN sequence rejects exactly
//! the frames with a wrong checksum, and motion commands scale like `SetMotionCommand`.

use protocol_kit::{CanFrame, DecodeError, Reject};
use protocol_tests::{F, assert_stream_at_every_chunk_size, hex, load_vectors, stream_vector};
use serde_json::Value;

protocol_kit::protocol!("../specs/scout.toml");

use scout::*;

fn u(v: &Value, k: &str) -> u64 {
    v[k].as_u64().unwrap_or_else(|| panic!("field {k} missing"))
}

fn i(v: &Value, k: &str) -> i64 {
    v[k].as_i64().unwrap_or_else(|| panic!("field {k} missing"))
}

fn light_mode(raw: u64) -> LightMode {
    LightMode::from_raw(raw as u8).expect("keep policy never fails")
}

/// The message of a vector, built from its recorded (raw) fields.
fn expected(frame: &Value) -> Message {
    let v = &frame["fields"];
    match frame["message"].as_str().expect("message") {
        "MotionControl" => Message::MotionControl(MotionControl {
            control_mode: ControlMode::from_raw(u(v, "control_mode") as u8).expect("keep"),
            fault_clear_flag: FaultClear::from_raw(u(v, "fault_clear_flag") as u8).expect("keep"),
            linear_velocity: i(v, "linear_velocity_cmd_percent") as f32 * 0.015,
            angular_velocity: i(v, "angular_velocity_cmd_percent") as f32 * 0.005235,
            reserved0: 0,
            reserved1: 0,
        }),
        "LightControl" | "LightStatus" => {
            let enable = u(v, "light_ctrl_enable") == 1;
            let (fm, fc, rm, rc) = (
                light_mode(u(v, "front_light_mode")),
                u(v, "front_light_custom") as u8,
                light_mode(u(v, "rear_light_mode")),
                u(v, "rear_light_custom") as u8,
            );
            if frame["message"] == "LightControl" {
                Message::LightControl(LightControl {
                    light_ctrl_enable: enable,
                    front_light_mode: fm,
                    front_light_custom: fc,
                    rear_light_mode: rm,
                    rear_light_custom: rc,
                    reserved: 0,
                })
            } else {
                Message::LightStatus(LightStatus {
                    light_ctrl_enable: enable,
                    front_light_mode: fm,
                    front_light_custom: fc,
                    rear_light_mode: rm,
                    rear_light_custom: rc,
                    reserved: 0,
                })
            }
        }
        "SystemStatus" => {
            assert_eq!(
                u(v, "fault_code"),
                0,
                "the vectors' status frames carry no fault"
            );
            Message::SystemStatus(SystemStatus {
                base_state: BaseState::from_raw(u(v, "base_state") as u8).expect("keep"),
                control_mode: ControlMode::from_raw(u(v, "control_mode") as u8).expect("keep"),
                battery_voltage: u(v, "battery_voltage_raw") as f32 * 0.1,
                ..no_faults()
            })
        }
        "MotionStatus" => Message::MotionStatus(MotionStatus {
            linear_velocity: i(v, "linear_velocity_raw_mm_s") as f32 * 0.001,
            angular_velocity: i(v, "angular_velocity_raw_mrad_s") as f32 * 0.001,
            reserved: 0,
        }),
        "MotorDriverStatus" => {
            let status = MotorDriverStatus {
                current: i(v, "current_raw") as f32 * 0.1,
                rpm: i(v, "rpm") as i16,
                temperature: i(v, "temperature") as i8,
                reserved: 0,
            };
            match u(v, "motor_id") {
                0 => Message::Motor1DriverStatus(status),
                1 => Message::Motor2DriverStatus(status),
                2 => Message::Motor3DriverStatus(status),
                _ => Message::Motor4DriverStatus(status),
            }
        }
        other => panic!("unknown message {other}"),
    }
}

fn no_faults() -> SystemStatus {
    SystemStatus::default()
}

/// Compare messages allowing the float rounding of `raw * factor` done in f32 here and in f64
/// by the decoder: equal when both encode to the same bytes.
fn same_wire(a: &Message, b: &Message) -> bool {
    let (mut x, mut y) = ([0u8; 16], [0u8; 16]);
    let pa = Packet {
        header: Header { count: 0 },
        message: *a,
    };
    let pb = Packet {
        header: Header { count: 0 },
        message: *b,
    };
    pa.encode(&mut x).is_ok() && pb.encode(&mut y).is_ok() && x == y && a.command() == b.command()
}

#[test]
fn every_message_round_trips_over_uart_and_can() {
    let v = load_vectors("agilex_scout.json");
    let mut n = 0;
    for frame in v["frames"].as_array().expect("frames") {
        let name = frame["name"].as_str().unwrap_or("?");
        let message = expected(frame);
        let count = u(&frame["fields"], "count") as u8;

        // UART
        let uart = hex(frame["uart"]["hex"].as_str().expect("uart hex"));
        let decoded = Packet::decode(&uart).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(decoded.header.count, count, "{name}");
        assert!(
            same_wire(&decoded.message, &message),
            "{name}: decoded {:?}, expected {message:?}",
            decoded.message
        );
        let mut buf = [0u8; MAX_FRAME_LEN];
        let len = Packet {
            header: Header { count },
            message: decoded.message,
        }
        .encode(&mut buf)
        .expect("encodes");
        assert_eq!(F(&buf[..len]), F(&uart), "{name}: UART encode");

        // CAN: same payload, CAN id, count and the CAN checksum.
        let can_id = u(&frame["can"], "can_id") as u32;
        let data = hex(frame["can"]["data_hex"].as_str().expect("can data"));
        let can = CanFrame::new(can_id, &data).expect("8 bytes");
        let decoded_can = CanPacket::decode(&can).unwrap_or_else(|e| panic!("{name}: CAN {e}"));
        assert_eq!(decoded_can.header.count, count, "{name}");
        assert_eq!(
            decoded_can.message, decoded.message,
            "{name}: UART and CAN carry the same message"
        );
        let encoded = CanPacket {
            header: CanHeader { count },
            message: decoded.message,
        }
        .encode()
        .expect("CAN encodes");
        assert_eq!(
            (encoded.id, F(encoded.data())),
            (can_id, F(&data)),
            "{name}: CAN encode"
        );
        n += 1;
    }
    assert_eq!(n, 8);
}

#[test]
fn captured_can_frames_from_a_real_robot_decode() {
    let v = load_vectors("agilex_scout.json");
    let captured = v["can_frames_captured"].as_array().expect("captured");
    let status = CanFrame::new(
        u(&captured[0], "can_id") as u32,
        &hex(captured[0]["data_hex"].as_str().expect("hex")),
    )
    .expect("frame");
    let p = CanPacket::decode(&status).expect("captured frame decodes");
    let Message::SystemStatus(s) = p.message else {
        panic!("0x151 is the system status")
    };
    assert_eq!(s.base_state, BaseState::Estop);
    assert!((s.battery_voltage - 23.9).abs() < 1e-4);
    // fault 0x003C: the four motor communication faults.
    assert!(s.motor1_comm_f && s.motor2_comm_f && s.motor3_comm_f && s.motor4_comm_f);
    assert!(!s.bat_under_vol_f && !s.bat_over_vol_f && !s.motor_drv_overheat_f);
    let light = CanFrame::new(
        u(&captured[1], "can_id") as u32,
        &hex(captured[1]["data_hex"].as_str().expect("hex")),
    )
    .expect("frame");
    let Message::LightStatus(l) = CanPacket::decode(&light).expect("decodes").message else {
        panic!("0x141")
    };
    assert_eq!(
        (l.rear_light_mode, l.rear_light_custom),
        (LightMode::Breath, 15)
    );
}

#[test]
fn can_sequence_rejects_exactly_the_wrong_checksums() {
    let v = load_vectors("agilex_scout.json");
    let stream = v["streams"]
        .as_array()
        .expect("streams")
        .iter()
        .find(|s| s["frames"].is_array())
        .expect("CAN sequence");
    let expected: Vec<bool> = stream["expected_accepted"]
        .as_array()
        .expect("expected")
        .iter()
        .map(|b| b.as_bool().expect("bool"))
        .collect();
    let got: Vec<bool> = stream["frames"]
        .as_array()
        .expect("frames")
        .iter()
        .map(|f| {
            let can = CanFrame::new(
                u(f, "can_id") as u32,
                &hex(f["data_hex"].as_str().expect("hex")),
            )
            .expect("frame");
            match CanPacket::decode(&can) {
                Ok(_) => true,
                Err(DecodeError::Frame(Reject::BadChecksum)) => false,
                Err(e) => panic!("unexpected error {e}"),
            }
        })
        .collect();
    assert_eq!(got, expected);
}

#[test]
fn uart_stream_yields_expected_frames_at_every_chunk_size() {
    let v = load_vectors("agilex_scout.json");
    let stream = v["streams"]
        .as_array()
        .expect("streams")
        .iter()
        .find(|s| s["hex"].is_string())
        .expect("UART stream");
    let (bytes, expected) = stream_vector(stream);
    assert_stream_at_every_chunk_size::<MAX_FRAME_LEN>(&LAYOUT, &bytes, &expected, |frame| {
        assert!(Packet::from_frame(frame).is_ok());
    });
    // The corrupt motion status, and the truncated light status read with the 6 bytes that
    // follow it: both rejected, never reported as frames (the original reports both).
    let mut dec = decoder();
    let mut input = &bytes[..];
    while dec.decode(&mut input).is_some() {}
    assert_eq!(dec.stats().bad_checksum, 2);
}

#[test]
#[allow(clippy::approx_constant)] // 0.5235 rad/s is the Scout's limit, not pi/6.
fn motion_commands_clamp_and_truncate_like_set_motion_command() {
    // (linear m/s, angular rad/s) -> (linear %, angular %), from running the original.
    for ((lin, ang), (lp, ap)) in [
        ((1.5, -0.5235), (100, -100)),
        ((0.75, -0.3), (50, -57)),
        ((3.0, 0.3), (100, 57)),
        ((-0.015, 0.0052), (-1, 0)),
    ] {
        let cmd = MotionControl {
            control_mode: ControlMode::CmdUart,
            fault_clear_flag: FaultClear::None,
            linear_velocity: lin,
            angular_velocity: ang,
            reserved0: 0,
            reserved1: 0,
        };
        let mut buf = [0u8; MAX_FRAME_LEN];
        let n = Packet {
            header: Header { count: 0 },
            message: Message::MotionControl(cmd),
        }
        .encode(&mut buf)
        .expect("encodes");
        assert_eq!(n, 13);
        assert_eq!(
            (buf[7] as i8, buf[8] as i8),
            (lp, ap),
            "SetMotionCommand({lin}, {ang})"
        );
    }
}
