//! The YAMSPy frames (`tests/vectors/msp_yamspy.json`) against `cu-msp-lib` 1.3, a second
//! reader of the same bytes: every frame parses there to its command, direction and payload, and
//! the replies it has a struct for decode to the recorded values (the leading fields its struct
//! holds, where Betaflight's reply grew after it). cu-msp-lib keeps the wire integers where the
//! spec has physical values (rates, voltages, currents): they are divided by the integer whose
//! reciprocal the spec's scale is, in `f64` as the vectors' generator computes them.

use cu_msp_lib::structs::{
    MspBatteryState, MspBoardInfo, MspBuildInfo, MspMotor, MspRcTuning, MspStatusEx, MspUniqueId,
};
use cu_msp_lib::{MspPacket, MspPacketDirection, MspParser};
use protocol_peers::{frame_bytes, frames, load_vectors, name, uint};
use serde_json::{Value, json};

fn parse(bytes: &[u8]) -> Vec<MspPacket> {
    let mut parser = MspParser::new();
    bytes
        .iter()
        .filter_map(|&b| parser.parse(b).ok().flatten())
        .collect()
}

/// A wire integer of scale `1 / div` as its physical value.
fn per(wire: impl Into<f64>, div: f64) -> Value {
    json!(wire.into() / div)
}

fn text(bytes: &[u8]) -> Value {
    json!(String::from_utf8(bytes.to_vec()).expect("ASCII"))
}

/// The values cu-msp-lib decodes from a reply it has a struct for, by the spec's names.
fn fields(p: &MspPacket) -> Option<Vec<(&'static str, Value)>> {
    Some(match p.cmd {
        4 => {
            let b: MspBoardInfo = p.decode_as().ok()?;
            vec![
                ("board_identifier", text(&b.board_id)),
                ("hardware_revision", json!(b.hardware_revision)),
                ("board_type", json!(b.fc_type)),
            ]
        }
        5 => {
            let b: MspBuildInfo = p.decode_as().ok()?;
            vec![
                ("build_date", text(&b.date_str)),
                ("build_time", text(&b.time_str)),
                ("short_git_revision", text(&b.git_str)),
            ]
        }
        104 => {
            let m: MspMotor = p.decode_as().ok()?;
            vec![("motors", json!(m.motors))]
        }
        111 => {
            let r: MspRcTuning = p.decode_as().ok()?;
            vec![
                ("rc_rate", per(r.rc_rate8, 100.0)),
                ("rc_expo", per(r.rc_expo8, 100.0)),
                ("roll_rate", per(r.rate_roll, 100.0)),
                ("pitch_rate", per(r.rate_pitch, 100.0)),
                ("yaw_rate", per(r.rate_yaw, 100.0)),
                ("dynamic_thr_pid", per(r.dyn_thr_pid, 100.0)),
                ("throttle_mid", per(r.thr_mid8, 100.0)),
                ("throttle_expo", per(r.thr_expo8, 100.0)),
                ("dynamic_thr_breakpoint", json!(r.tpa_breakpoint)),
                ("rc_yaw_expo", per(r.rc_yaw_expo8, 100.0)),
                ("rc_yaw_rate", per(r.rc_yaw_rate8, 100.0)),
            ]
        }
        130 => {
            let b: MspBatteryState = p.decode_as().ok()?;
            vec![
                ("cell_count", json!(b.battery_cell_count)),
                ("capacity", json!(b.battery_capacity)),
                ("legacy_battery_voltage", per(b.battery_voltage, 10.0)),
                ("mah_drawn", json!(b.mah_drawn)),
                ("amperage", per(b.amperage, 100.0)),
                ("battery_state", json!(b.alerts)),
                ("battery_voltage", per(b.battery_voltage_mv, 100.0)),
            ]
        }
        150 => {
            let s = MspStatusEx::from_bytes(p.data.as_slice()).ok()?;
            vec![
                ("cycle_time", json!(s.cycle_time)),
                ("i2c_errors", json!(s.i2c_errors)),
                ("flight_mode_flags", json!(s.flight_mode_flags)),
                (
                    "current_pid_profile_index",
                    json!(s.current_pid_profile_index),
                ),
                (
                    "average_system_load_percent",
                    json!(s.average_system_load_percent),
                ),
                ("pid_profile_count", json!(s.max_profile_count)),
                (
                    "current_control_rate_profile_index",
                    json!(s.current_control_rate_profile_index),
                ),
                (
                    "extra_flight_mode_flags",
                    json!(hex_text(&s.extra_flight_mode_flags)),
                ),
                (
                    "arming_disable_flags_count",
                    json!(s.arming_disable_flags_count),
                ),
                ("arming_disable_flags", json!(s.arming_disable_flags)),
                ("config_state_flags", json!(s.config_state_flags)),
                ("core_temp_celsius", json!(s.core_temp_celsius)),
                (
                    "control_rate_profile_count",
                    json!(s.control_rate_profile_count),
                ),
            ]
        }
        160 => {
            let u: MspUniqueId = p.decode_as().ok()?;
            let words: Vec<u32> = u
                .uid
                .chunks(4)
                .map(|w| u32::from_le_bytes(w.try_into().expect("4 bytes")))
                .collect();
            vec![("uid", json!(words))]
        }
        _ => return None,
    })
}

/// Bytes as the vectors write them (lowercase hex).
fn hex_text(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

#[test]
fn every_yamspy_frame_parses_in_cu_msp_lib_to_its_values() {
    let v = load_vectors("msp_yamspy.json");
    let (mut parsed, mut decoded) = (0, 0);
    for frame in frames(&v) {
        let at = name(frame);
        let bytes = frame_bytes(frame);
        let [p] = parse(&bytes)
            .try_into()
            .unwrap_or_else(|f| panic!("{at}: {f:?}"));
        assert_eq!(u64::from(p.cmd), uint(frame, "id"), "{at}");
        let direction = match p.direction {
            MspPacketDirection::ToFlightController => "request",
            MspPacketDirection::FromFlightController => "response",
            MspPacketDirection::Unsupported => "error",
        };
        assert_eq!(direction, frame["direction"], "{at}");
        parsed += 1;
        if direction == "response"
            && let Some(got) = fields(&p)
        {
            for (key, value) in got {
                assert_eq!(value, frame["payload"][key], "{at}.{key}");
            }
            decoded += 1;
        }
    }
    println!("cu-msp-lib: {parsed} YAMSPy frames parsed, {decoded} replies decoded");
    assert_eq!(parsed, frames(&v).len());
    assert!(decoded >= 40, "{decoded}");
}
