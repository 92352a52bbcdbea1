//! Referee system golden vectors (`tests/vectors/robomaster_referee.json`, made by running the
//! RoboRTS firmware's C): every 2019 frame decodes to its recorded fields and encodes back to the
//! exact bytes; the stream yields exactly its expected frames at every chunk size.

use protocol_kit::DecodeError;
use protocol_tests::{F, assert_stream_at_every_chunk_size, hex, load_vectors, stream_vector};
use serde_json::Value;

protocol_kit::protocol!("../specs/referee.toml");

use referee::*;

fn u(v: &Value, k: &str) -> u64 {
    v[k].as_u64().unwrap_or_else(|| panic!("field {k} missing"))
}

fn f(v: &Value, k: &str) -> f32 {
    v[k].as_f64().unwrap_or_else(|| panic!("field {k} missing")) as f32
}

/// The message a vector records, built from its JSON fields.
fn expected(cmd: u64, v: &Value) -> Option<Message> {
    Some(match cmd {
        0x0001 => Message::GameState(GameState {
            game_type: u(v, "game_type") as u8,
            game_progress: u(v, "game_progress") as u8,
            stage_remain_time: u(v, "stage_remain_time") as u16,
        }),
        0x0002 => Message::GameResult(GameResult {
            winner: u(v, "winner") as u8,
        }),
        0x0101 => Message::EventData(EventData {
            event_type: u(v, "event_type") as u32,
        }),
        0x0102 => Message::SupplyProjectileAction(SupplyProjectileAction {
            supply_projectile_id: u(v, "supply_projectile_id") as u8,
            supply_robot_id: u(v, "supply_robot_id") as u8,
            supply_projectile_step: u(v, "supply_projectile_step") as u8,
            supply_projectile_num: u(v, "supply_projectile_num") as u8,
        }),
        0x0103 => Message::SupplyProjectileBooking(SupplyProjectileBooking {
            supply_projectile_id: u(v, "supply_projectile_id") as u8,
            supply_robot_id: u(v, "supply_robot_id") as u8,
            supply_num: u(v, "supply_num") as u8,
        }),
        0x0201 => Message::GameRobotState(GameRobotState {
            robot_id: u(v, "robot_id") as u8,
            robot_level: u(v, "robot_level") as u8,
            remain_hp: u(v, "remain_HP") as u16,
            max_hp: u(v, "max_HP") as u16,
            shooter_heat0_cooling_rate: u(v, "shooter_heat0_cooling_rate") as u16,
            shooter_heat0_cooling_limit: u(v, "shooter_heat0_cooling_limit") as u16,
            shooter_heat1_cooling_rate: u(v, "shooter_heat1_cooling_rate") as u16,
            shooter_heat1_cooling_limit: u(v, "shooter_heat1_cooling_limit") as u16,
            mains_power_gimbal_output: u(v, "mains_power_gimbal_output") == 1,
            mains_power_chassis_output: u(v, "mains_power_chassis_output") == 1,
            mains_power_shooter_output: u(v, "mains_power_shooter_output") == 1,
        }),
        0x0203 => Message::GameRobotPos(GameRobotPos {
            x: f(v, "x"),
            y: f(v, "y"),
            z: f(v, "z"),
            yaw: f(v, "yaw"),
        }),
        0x0204 => Message::BuffMusk(BuffMusk {
            power_rune_buff: u(v, "power_rune_buff") as u8,
        }),
        0x0206 => Message::RobotHurt(RobotHurt {
            armor_id: u(v, "armor_id") as u8,
            hurt_type: u(v, "hurt_type") as u8,
        }),
        0x0301 => {
            let (head, data) = match v["data_cmd_id"].as_u64() {
                Some(id) => (
                    [id, u(v, "sender_ID"), u(v, "receiver_ID")],
                    hex(v["data_hex"].as_str().expect("data")),
                ),
                // The 118-byte vector records the whole payload: its first 6 bytes are the
                // sub-header.
                None => {
                    let all = hex(v["data_hex"].as_str()?);
                    let word = |i: usize| u64::from(u16::from_le_bytes([all[i], all[i + 1]]));
                    ([word(0), word(2), word(4)], all[6..].to_vec())
                }
            };
            Message::StudentInteractive(StudentInteractive {
                data_cmd_id: head[0] as u16,
                sender_id: head[1] as u16,
                receiver_id: head[2] as u16,
                data: protocol_kit::Bytes::from_slice(&data).expect("fits"),
            })
        }
        _ => return None,
    })
}

#[test]
fn every_2019_frame_decodes_to_its_fields_and_encodes_to_its_bytes() {
    let v = load_vectors("robomaster_referee.json");
    let (mut typed, mut framed) = (0, 0);
    for frame in v["frames"].as_array().expect("frames") {
        let name = frame["name"].as_str().unwrap_or("?");
        let bytes = hex(frame["hex"].as_str().expect("hex"));
        // Framing (CRC8, length, CRC16) holds for every vector, both seasons.
        assert_eq!(LAYOUT.parse(&bytes), Ok(&bytes[..]), "{name}: framing");
        framed += 1;
        if frame["protocol_year"] != "2019" {
            continue;
        }
        let cmd = u(frame, "cmd_id");
        let Some(message) = expected(cmd, &frame["fields"]) else {
            // A 0x0301 frame without its 6-byte sub-header: the original firmware hands it on,
            // here it is a payload length error.
            assert_eq!(u(frame, "data_length"), 0, "{name}");
            assert_eq!(
                Packet::decode(&bytes),
                Err(DecodeError::PayloadLength {
                    expected: 6,
                    actual: 0
                }),
                "{name}"
            );
            continue;
        };
        let packet = Packet {
            header: Header {
                seq: u(frame, "seq") as u8,
            },
            message,
        };
        assert_eq!(Packet::decode(&bytes), Ok(packet), "{name}: decode");
        let mut buf = [0u8; MAX_FRAME_LEN];
        let n = packet.encode(&mut buf).expect("encodes");
        assert_eq!(F(&buf[..n]), F(&bytes), "{name}: encode");
        typed += 1;
    }
    assert_eq!((framed, typed), (14, 12));
}

#[test]
fn stream_yields_expected_frames_at_every_chunk_size() {
    let v = load_vectors("robomaster_referee.json");
    let (bytes, expected) = stream_vector(&v["streams"][0]);
    assert_stream_at_every_chunk_size::<MAX_FRAME_LEN>(&LAYOUT, &bytes, &expected, |frame| {
        assert!(Packet::from_frame(frame).is_ok());
    });
}

mod season_2018 {
    use super::*;

    protocol_kit::protocol!("../specs/referee2018.toml");

    #[test]
    fn the_2018_frame_decodes_with_the_2018_table_and_encodes_back() {
        let v = load_vectors("robomaster_referee.json");
        let frame = v["frames"]
            .as_array()
            .expect("frames")
            .iter()
            .find(|f| f["protocol_year"] == "2018")
            .expect("a 2018 frame");
        let bytes = hex(frame["hex"].as_str().expect("hex"));
        let fields = &frame["fields"];
        let expected = referee2018::Packet {
            header: referee2018::Header {
                seq: u(frame, "seq") as u8,
            },
            message: referee2018::Message::RealPowerData(referee2018::RealPowerData {
                chassis_volt: f(fields, "chassis_volt"),
                chassis_current: f(fields, "chassis_current"),
                chassis_power: f(fields, "chassis_power"),
                chassis_pwr_buf: f(fields, "chassis_pwr_buf"),
                shooter1_heat: u(fields, "shooter1_heat") as u16,
                shooter2_heat: u(fields, "shooter2_heat") as u16,
            }),
        };
        assert_eq!(referee2018::Packet::decode(&bytes), Ok(expected));
        let mut buf = [0u8; referee2018::MAX_FRAME_LEN];
        let n = expected.encode(&mut buf).expect("encodes");
        assert_eq!(F(&buf[..n]), F(&bytes));
        // Id 0x0004 does not exist in the 2019 table: a 2019 decoder names the unknown id.
        assert!(matches!(
            Packet::decode(&bytes),
            Err(DecodeError::UnknownCommand { key: 4 })
        ));
    }
}
