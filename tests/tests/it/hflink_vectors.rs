//! HFLink golden vectors (`tests/vectors/hflink.json`, made by running the original C++): every
//! frame decodes to its recorded fields and those values encode to the exact bytes; the stream
//! yields exactly its expected frames at every chunk size.

use protocol_kit::{DecodeError, Reject};
use protocol_tests::{F, assert_stream_at_every_chunk_size, hex, load_vectors, stream_vector};
use serde_json::Value;

protocol_kit::protocol!("../specs/hflink.toml");

use hflink::*;

fn f32_of(v: &Value, k: &str) -> f32 {
    v[k].as_f64().unwrap_or_else(|| panic!("field {k} missing")) as f32
}

fn u_of(v: &Value, k: &str) -> u64 {
    v[k].as_u64().unwrap_or_else(|| panic!("field {k} missing"))
}

fn chassis_coord(v: &Value) -> ChassisCoord {
    ChassisCoord {
        x: f32_of(v, "x"),
        y: f32_of(v, "y"),
        z: f32_of(v, "z"),
    }
}

fn system_info(v: &Value) -> SystemInfo {
    SystemInfo {
        system_time: f32_of(v, "system_time"),
        cpu_temperature: f32_of(v, "cpu_temperature"),
        cpu_usage: f32_of(v, "cpu_usage"),
        battery_voltage: f32_of(v, "battery_voltage"),
        power_remain: f32_of(v, "power_remain"),
    }
}

fn ascii(v: &Value, k: &str) -> u8 {
    let s = v[k].as_str().unwrap_or_else(|| panic!("field {k} missing"));
    s.as_bytes()[0]
}

fn gps_data(v: &Value) -> GpsData {
    let t = &v["uct_time"];
    GpsData {
        utc_time: UtcTime {
            year: u_of(t, "year") as u16,
            month: u_of(t, "month") as u8,
            date: u_of(t, "date") as u8,
            hour: u_of(t, "hour") as u8,
            min: u_of(t, "min") as u8,
            sec: u_of(t, "sec") as u8,
        },
        satellite_num: u_of(v, "satellite_num") as u8,
        altitude: f32_of(v, "altitude"),
        ground_speed: f32_of(v, "ground_speed"),
        latitude: u_of(v, "latitude") as u32,
        nshemi: ascii(v, "nshemi"),
        longitude: u_of(v, "longitude") as u32,
        ewhemi: ascii(v, "ewhemi"),
    }
}

fn motor_parameters(v: &Value) -> MotorParameters {
    let pid = &v["pid"];
    MotorParameters {
        motor_id: u_of(v, "motor_id") as u8,
        encoder_num: f32_of(v, "encoder_num"),
        pwm_max: f32_of(v, "pwm_max"),
        pwm_dead_zone: f32_of(v, "pwm_dead_zone"),
        speed_low_filter: f32_of(v, "speed_low_filter"),
        protect_current: f32_of(v, "protect_current"),
        pid: PidParameters {
            p1: f32_of(pid, "p1"),
            i1: f32_of(pid, "i1"),
            d1: f32_of(pid, "d1"),
            p2: f32_of(pid, "p2"),
            i2: f32_of(pid, "i2"),
            d2: f32_of(pid, "d2"),
        },
    }
}

fn chassis_parameters(v: &Value) -> ChassisParameters {
    ChassisParameters {
        r#type: u_of(v, "type") as u32,
        wheel_radius: f32_of(v, "wheel_radius"),
        body_radius: f32_of(v, "body_radius"),
        speed_low_filter: f32_of(v, "speed_low_filter"),
        motor_pid_t: f32_of(v, "motor_pid_t"),
        dof: u_of(v, "dof") as u8,
        simulation_model: u_of(v, "simulation_model") as u8,
        imu_fusion_enalbe: u_of(v, "imu_fusion_enalbe") as u8,
        control_enable: u_of(v, "control_enable") as u8,
    }
}

/// The message a vector records, built from its JSON fields (not from the bytes).
fn expected_message(frame: &Value) -> Message {
    let command =
        Command::from_id(u_of(frame, "command_id") as u8).expect("command id in the spec");
    let from_master = frame["direction"] == "master->slave";
    let fields = &frame["fields"];
    let payload_type = frame["payload_type"].as_str().unwrap_or("");
    let ty = payload_type.split('(').next().unwrap_or("");
    match (ty, command, from_master) {
        ("ChassisCoord", Command::ShakingHands, true) => {
            Message::Request(Request::ShakingHands(chassis_coord(fields)))
        }
        ("ChassisCoord", Command::SetRobotSpeed, true) => {
            Message::Request(Request::SetRobotSpeed(chassis_coord(fields)))
        }
        ("SystemInfo", Command::ReadSystemInfo, false) => {
            Message::Response(Response::ReadSystemInfo(system_info(fields)))
        }
        ("GPSData", Command::ReadGpsData, false) => {
            Message::Response(Response::ReadGpsData(gps_data(fields)))
        }
        ("MotorParameters", Command::SetMotorParameters, true) => {
            Message::Request(Request::SetMotorParameters(motor_parameters(fields)))
        }
        ("ChassisParameters", Command::SetChassisParameters, true) => {
            Message::Request(Request::SetChassisParameters(chassis_parameters(fields)))
        }
        ("", c, true) => Message::Request(Request::read_payload(c, &[]).expect("empty request")),
        ("", c, false) => {
            Message::Response(Response::read_payload(c, &[]).expect("empty response"))
        }
        other => panic!("vector not covered by this test: {other:?}"),
    }
}

#[test]
fn every_frame_decodes_to_its_fields_and_encodes_to_its_bytes() {
    let v = load_vectors("hflink.json");
    let mut typed = 0;
    for frame in v["frames"].as_array().expect("frames") {
        let name = frame["name"].as_str().unwrap_or("?");
        let bytes = hex(frame["hex"].as_str().expect("hex"));
        let data = hex(frame["data_hex"].as_str().unwrap_or(""));
        // Framing: every vector whose length field counts a command byte is a valid frame.
        let parsed = LAYOUT.parse(&bytes);
        if data.is_empty() {
            assert_eq!(
                parsed,
                Err(DecodeError::Frame(Reject::BadLength)),
                "{name}: a length-0 frame has no command byte"
            );
            continue;
        }
        assert_eq!(parsed, Ok(&bytes[..]), "{name}: framing");
        let header = Header {
            sender: u_of(frame, "sender") as u8,
            receiver: u_of(frame, "receiver") as u8,
        };
        match Command::from_id(data[0]) {
            None => panic!("{name}: unknown command {}", data[0]),
            Some(cmd) => {
                let payload_len = data.len() - 1;
                let is_struct = frame["payload_type"].is_string();
                let declared = Packet::decode(&bytes);
                if !is_struct && payload_len > 0 {
                    // A payload the command does not carry (the originals' raw `sendMessage`
                    // tests): framing accepts it, typed decoding names the size mismatch.
                    match declared {
                        Err(DecodeError::PayloadLength { actual, .. }) => {
                            assert_eq!(actual, payload_len, "{name}")
                        }
                        other => panic!("{name}: expected a payload length error, got {other:?}"),
                    }
                    assert_eq!(cmd.id(), data[0]);
                    continue;
                }
                let expected = Packet {
                    header,
                    message: expected_message(frame),
                };
                assert_eq!(declared, Ok(expected), "{name}: decode");
                let mut buf = [0u8; MAX_FRAME_LEN];
                let n = expected
                    .encode(&mut buf)
                    .unwrap_or_else(|e| panic!("{name}: encode failed: {e}"));
                assert_eq!(F(&buf[..n]), F(&bytes), "{name}: encode");
                typed += 1;
            }
        }
    }
    assert_eq!(
        typed, 10,
        "every typed vector was checked in both directions"
    );
}

#[test]
fn stream_yields_expected_frames_at_every_chunk_size() {
    let v = load_vectors("hflink.json");
    let (bytes, expected) = stream_vector(&v["streams"][0]);
    assert_stream_at_every_chunk_size::<MAX_FRAME_LEN>(&LAYOUT, &bytes, &expected, |frame| {
        let packet = Packet::from_frame(frame).expect("every expected frame decodes");
        assert_eq!(packet.header.sender, 0x11);
    });
}

#[test]
fn the_original_decoder_loses_a_frame_that_ours_keeps() {
    let v = load_vectors("hflink.json");
    let stream = &v["streams"][0];
    let ours = stream["expected_frames"]
        .as_array()
        .expect("expected")
        .len();
    let original = stream["original_decoder"]["frames"]
        .as_array()
        .expect("original")
        .len();
    assert_eq!(
        (ours, original),
        (4, 3),
        "the vector documents the original's loss"
    );
    let mut dec = decoder();
    let bytes = hex(stream["hex"].as_str().expect("hex"));
    let mut input = &bytes[..];
    let mut n = 0;
    while dec.decode(&mut input).is_some() {
        n += 1;
    }
    assert_eq!(n, ours);
}

#[test]
fn direction_follows_the_sender_address() {
    // A READ request carries no payload, its response a struct; the same command byte.
    let request = Packet {
        header: Header {
            sender: 0x01,
            receiver: 0x11,
        },
        message: Message::Request(Request::ReadSystemInfo),
    };
    let mut buf = [0u8; MAX_FRAME_LEN];
    let n = request.encode(&mut buf).expect("encodes");
    assert_eq!(F(&buf[..n]), F(&hex("ffff011100010114")));
    // The same message from a slave address is refused: it would decode as a response.
    let wrong = Packet {
        header: Header {
            sender: 0x11,
            receiver: 0x01,
        },
        ..request
    };
    assert!(wrong.encode(&mut buf).is_err());
    // A frame from an address outside both ranges decodes to UnknownDirection.
    let mut frame = hex("ffff011100010114");
    frame[2] = 0x50;
    let sum: u32 = frame[..7].iter().map(|&b| u32::from(b)).sum();
    frame[7] = (sum % 255) as u8;
    assert_eq!(Packet::decode(&frame), Err(DecodeError::UnknownDirection));
}

#[test]
fn short_buffers_and_oversized_lengths_are_errors_not_panics() {
    let p = Packet {
        header: Header {
            sender: 1,
            receiver: 0x11,
        },
        message: Message::Request(Request::SetArmState(ArmDofVector { servo: [1.0; 8] })),
    };
    for len in 0..p.encoded_len() {
        let mut buf = vec![0u8; len];
        assert!(
            matches!(
                p.encode(&mut buf),
                Err(protocol_kit::EncodeError::BufferTooSmall { .. })
            ),
            "buffer of {len}"
        );
    }
    // length 0x0079 = 121 > 120: rejected before the payload is awaited.
    assert_eq!(
        LAYOUT.parse(&hex("ffff0111007900")),
        Err(DecodeError::Frame(Reject::BadLength))
    );
}
