//! MAVLink v1 and v2 (`tests/vectors/mavlink.json`) against `mavlink` 0.21 (rust-mavlink), the
//! common dialect with extension fields and signing.
//!
//! Every frame decodes in the peer to its recorded header and fields (signed frames with their
//! signature verified against the recorded key), and the stream yields its expected frames from
//! the peer's reader, which resynchronises after a bad candidate.

use crate::values::{V, assert_fields};
use mavlink::dialects::common::MavMessage;
use mavlink::{MAVLinkMessageRaw, MavlinkReader};
use protocol_peers::{expected_frames, frame_bytes, frames, hex, load_vectors, name, uint};

fn arr<const N: usize>(a: &[u16; N]) -> V {
    V::List(a.iter().map(|&x| i128::from(x)).collect())
}

/// The peer's fields under the names the MAVLink XML gives them.
fn fields(msg: &MavMessage) -> (&'static str, Vec<(&'static str, V)>) {
    use V::{F, I, S};
    let i = |x: i128| I(x);
    match msg {
        MavMessage::HEARTBEAT(m) => (
            "HEARTBEAT",
            vec![
                ("type", i(m.mavtype as i128)),
                ("autopilot", i(m.autopilot as i128)),
                ("base_mode", i(m.base_mode.bits().into())),
                ("custom_mode", i(m.custom_mode.into())),
                ("system_status", i(m.system_status as i128)),
                ("mavlink_version", i(m.mavlink_version.into())),
            ],
        ),
        MavMessage::SYS_STATUS(m) => (
            "SYS_STATUS",
            vec![
                (
                    "onboard_control_sensors_present",
                    i(m.onboard_control_sensors_present.bits().into()),
                ),
                (
                    "onboard_control_sensors_enabled",
                    i(m.onboard_control_sensors_enabled.bits().into()),
                ),
                (
                    "onboard_control_sensors_health",
                    i(m.onboard_control_sensors_health.bits().into()),
                ),
                ("load", i(m.load.into())),
                ("voltage_battery", i(m.voltage_battery.into())),
                ("current_battery", i(m.current_battery.into())),
                ("battery_remaining", i(m.battery_remaining.into())),
                ("drop_rate_comm", i(m.drop_rate_comm.into())),
                ("errors_comm", i(m.errors_comm.into())),
                ("errors_count1", i(m.errors_count1.into())),
                ("errors_count2", i(m.errors_count2.into())),
                ("errors_count3", i(m.errors_count3.into())),
                ("errors_count4", i(m.errors_count4.into())),
                (
                    "onboard_control_sensors_present_extended",
                    i(m.onboard_control_sensors_present_extended.bits().into()),
                ),
                (
                    "onboard_control_sensors_enabled_extended",
                    i(m.onboard_control_sensors_enabled_extended.bits().into()),
                ),
                (
                    "onboard_control_sensors_health_extended",
                    i(m.onboard_control_sensors_health_extended.bits().into()),
                ),
            ],
        ),
        MavMessage::SYSTEM_TIME(m) => (
            "SYSTEM_TIME",
            vec![
                ("time_unix_usec", i(m.time_unix_usec.into())),
                ("time_boot_ms", i(m.time_boot_ms.into())),
            ],
        ),
        MavMessage::GPS_RAW_INT(m) => (
            "GPS_RAW_INT",
            vec![
                ("time_usec", i(m.time_usec.into())),
                ("fix_type", i(m.fix_type as i128)),
                ("lat", i(m.lat.into())),
                ("lon", i(m.lon.into())),
                ("alt", i(m.alt.into())),
                ("eph", i(m.eph.into())),
                ("epv", i(m.epv.into())),
                ("vel", i(m.vel.into())),
                ("cog", i(m.cog.into())),
                ("satellites_visible", i(m.satellites_visible.into())),
                ("alt_ellipsoid", i(m.alt_ellipsoid.into())),
                ("h_acc", i(m.h_acc.into())),
                ("v_acc", i(m.v_acc.into())),
                ("vel_acc", i(m.vel_acc.into())),
                ("hdg_acc", i(m.hdg_acc.into())),
                ("yaw", i(m.yaw.into())),
            ],
        ),
        MavMessage::ATTITUDE(m) => (
            "ATTITUDE",
            vec![
                ("time_boot_ms", i(m.time_boot_ms.into())),
                ("roll", F(m.roll)),
                ("pitch", F(m.pitch)),
                ("yaw", F(m.yaw)),
                ("rollspeed", F(m.rollspeed)),
                ("pitchspeed", F(m.pitchspeed)),
                ("yawspeed", F(m.yawspeed)),
            ],
        ),
        MavMessage::GLOBAL_POSITION_INT(m) => (
            "GLOBAL_POSITION_INT",
            vec![
                ("time_boot_ms", i(m.time_boot_ms.into())),
                ("lat", i(m.lat.into())),
                ("lon", i(m.lon.into())),
                ("alt", i(m.alt.into())),
                ("relative_alt", i(m.relative_alt.into())),
                ("vx", i(m.vx.into())),
                ("vy", i(m.vy.into())),
                ("vz", i(m.vz.into())),
                ("hdg", i(m.hdg.into())),
            ],
        ),
        MavMessage::RC_CHANNELS(m) => {
            let ch = [
                m.chan1_raw,
                m.chan2_raw,
                m.chan3_raw,
                m.chan4_raw,
                m.chan5_raw,
                m.chan6_raw,
                m.chan7_raw,
                m.chan8_raw,
                m.chan9_raw,
                m.chan10_raw,
                m.chan11_raw,
                m.chan12_raw,
                m.chan13_raw,
                m.chan14_raw,
                m.chan15_raw,
                m.chan16_raw,
                m.chan17_raw,
                m.chan18_raw,
            ];
            const NAMES: [&str; 18] = [
                "chan1_raw",
                "chan2_raw",
                "chan3_raw",
                "chan4_raw",
                "chan5_raw",
                "chan6_raw",
                "chan7_raw",
                "chan8_raw",
                "chan9_raw",
                "chan10_raw",
                "chan11_raw",
                "chan12_raw",
                "chan13_raw",
                "chan14_raw",
                "chan15_raw",
                "chan16_raw",
                "chan17_raw",
                "chan18_raw",
            ];
            let mut f = vec![
                ("time_boot_ms", i(m.time_boot_ms.into())),
                ("chancount", i(m.chancount.into())),
                ("rssi", i(m.rssi.into())),
            ];
            f.extend(NAMES.iter().zip(ch).map(|(n, v)| (*n, i(v.into()))));
            ("RC_CHANNELS", f)
        }
        MavMessage::COMMAND_LONG(m) => (
            "COMMAND_LONG",
            vec![
                ("target_system", i(m.target_system.into())),
                ("target_component", i(m.target_component.into())),
                ("command", i(m.command as i128)),
                ("confirmation", i(m.confirmation.into())),
                ("param1", F(m.param1)),
                ("param2", F(m.param2)),
                ("param3", F(m.param3)),
                ("param4", F(m.param4)),
                ("param5", F(m.param5)),
                ("param6", F(m.param6)),
                ("param7", F(m.param7)),
            ],
        ),
        MavMessage::COMMAND_ACK(m) => (
            "COMMAND_ACK",
            vec![
                ("command", i(m.command as i128)),
                ("result", i(m.result as i128)),
                ("progress", i(m.progress.into())),
                ("result_param2", i(m.result_param2.into())),
                ("target_system", i(m.target_system.into())),
                ("target_component", i(m.target_component.into())),
            ],
        ),
        MavMessage::PARAM_VALUE(m) => (
            "PARAM_VALUE",
            vec![
                (
                    "param_id",
                    S(m.param_id.to_str().expect("utf-8").to_string()),
                ),
                ("param_value", F(m.param_value)),
                ("param_type", i(m.param_type as i128)),
                ("param_count", i(m.param_count.into())),
                ("param_index", i(m.param_index.into())),
            ],
        ),
        MavMessage::STATUSTEXT(m) => (
            "STATUSTEXT",
            vec![
                ("severity", i(m.severity as i128)),
                ("text", S(m.text.to_str().expect("utf-8").to_string())),
                ("id", i(m.id.into())),
                ("chunk_seq", i(m.chunk_seq.into())),
            ],
        ),
        MavMessage::BATTERY_STATUS(m) => (
            "BATTERY_STATUS",
            vec![
                ("id", i(m.id.into())),
                ("battery_function", i(m.battery_function as i128)),
                ("type", i(m.mavtype as i128)),
                ("temperature", i(m.temperature.into())),
                ("voltages", arr(&m.voltages)),
                ("current_battery", i(m.current_battery.into())),
                ("current_consumed", i(m.current_consumed.into())),
                ("energy_consumed", i(m.energy_consumed.into())),
                ("battery_remaining", i(m.battery_remaining.into())),
                ("time_remaining", i(m.time_remaining.into())),
                ("charge_state", i(m.charge_state as i128)),
                ("voltages_ext", arr(&m.voltages_ext)),
                ("mode", i(m.mode as i128)),
                ("fault_bitmask", i(m.fault_bitmask.bits().into())),
            ],
        ),
        other => panic!("no vector has {other:?}"),
    }
}

/// The peer's decoding of the first message in `bytes` (signatures not checked).
fn read(bytes: &[u8]) -> (mavlink::MavHeader, MavMessage) {
    MavlinkReader::new(bytes)
        .read_any_message_signed::<MavMessage>(None)
        .unwrap_or_else(|e| panic!("mavlink rejects {bytes:02x?}: {e:?}"))
}

/// Whether the peer computes the frame's signature from `key`. The peer's own verification
/// (`SigningData`) also applies its replay rule, which refuses a new stream whose timestamp is
/// over a minute behind the local clock; the vectors' timestamps are fixed, so the signature is
/// checked with the peer's `calculate_signature` instead.
fn signature_matches(bytes: &[u8], key: &[u8]) -> bool {
    let raw = MavlinkReader::new(bytes)
        .read_any_raw_message::<MavMessage>()
        .unwrap_or_else(|e| panic!("mavlink rejects {bytes:02x?}: {e:?}"));
    let MAVLinkMessageRaw::V2(raw) = raw else {
        panic!("a signed frame is MAVLink 2")
    };
    let mut signature = [0u8; 6];
    raw.calculate_signature(key, &mut signature);
    signature == raw.signature_value()
}

#[test]
fn every_frame_decodes_in_mavlink_to_its_fields() {
    let v = load_vectors("mavlink.json");
    let (mut checked, mut signed) = (0, 0);
    for frame in frames(&v) {
        let bytes = frame_bytes(frame);
        if let Some(sig) = frame.get("signature") {
            let key = hex(sig["secret_key_hex"].as_str().expect("key"));
            assert!(
                signature_matches(&bytes, &key),
                "{}: signature",
                name(frame)
            );
            assert_eq!(bytes[bytes.len() - 13], uint(sig, "link_id") as u8);
            signed += 1;
        }
        let (header, msg) = read(&bytes);
        assert_eq!(
            u64::from(header.sequence),
            uint(frame, "seq"),
            "{}",
            name(frame)
        );
        assert_eq!(
            u64::from(header.system_id),
            uint(frame, "sysid"),
            "{}",
            name(frame)
        );
        assert_eq!(
            u64::from(header.component_id),
            uint(frame, "compid"),
            "{}",
            name(frame)
        );
        let (message, got) = fields(&msg);
        assert_eq!(message, frame["message"], "{}", name(frame));
        assert_fields(name(frame), &got, &frame["fields"]);
        checked += 1;
    }
    println!("mavlink: {checked} frames decoded to their fields, {signed} signatures verified");
    assert_eq!(checked, frames(&v).len());
    assert_eq!(signed, 2);
}

#[test]
fn a_signature_from_another_key_does_not_match_in_mavlink() {
    let v = load_vectors("mavlink.json");
    let frame = frames(&v)
        .iter()
        .find(|f| f["signed"] == true)
        .expect("a signed frame");
    assert!(
        !signature_matches(&frame_bytes(frame), &[0x55; 32]),
        "{}",
        name(frame)
    );
}

#[test]
fn the_stream_yields_its_expected_frames_in_mavlink() {
    let v = load_vectors("mavlink.json");
    for stream in v["streams"].as_array().expect("streams") {
        let bytes = hex(stream["hex"].as_str().expect("hex"));
        let expected = expected_frames(stream);
        let mut reader = MavlinkReader::new(&bytes[..]);
        let mut seen = Vec::new();
        while let Ok((header, msg)) = reader.read_any_message_signed::<MavMessage>(None) {
            seen.push((header.sequence, fields(&msg).0));
        }
        let wanted: Vec<(u8, &str)> = expected
            .iter()
            .map(|(_, b)| {
                let (h, m) = read(b);
                (h.sequence, fields(&m).0)
            })
            .collect();
        assert_eq!(seen, wanted, "{}", stream["name"]);
    }
}
