//! MSP v1 and v2 (`tests/vectors/msp.json`) against `cu-msp-lib` 1.3 (the Copper project's MSP
//! library: v1, v2 and v2 over v1).
//!
//! Every frame the peer parses yields the recorded command, direction and payload, and the
//! responses whose payload the peer has a struct for decode to the recorded fields. The peer has
//! no jumbo v1 frames (size byte 255): that frame is checked to be rejected.

use crate::values::{V, assert_fields};
use cu_msp_lib::structs::{
    MspAltitude, MspAnalog, MspApiVersion, MspAttitude, MspFlightControllerVariant,
    MspFlightControllerVersion, MspRawImu, MspStatus,
};
use cu_msp_lib::{MspPacket, MspPacketDirection, MspParser};
use protocol_peers::{expected_frames, frame_bytes, frames, hex, load_vectors, name, uint};
use serde_json::Value;

/// Every packet the peer finds in `bytes`, fed one byte at a time.
fn parse(bytes: &[u8]) -> Vec<MspPacket> {
    let mut parser = MspParser::new();
    bytes
        .iter()
        .filter_map(|&b| parser.parse(b).ok().flatten())
        .collect()
}

fn direction(d: MspPacketDirection) -> &'static str {
    match d {
        MspPacketDirection::ToFlightController => "<",
        MspPacketDirection::FromFlightController => ">",
        MspPacketDirection::Unsupported => "!",
    }
}

/// The fields of a response the peer has a struct for.
fn fields(p: &MspPacket) -> Option<Vec<(&'static str, V)>> {
    use V::I;
    let d = p.data.as_slice();
    if p.direction != MspPacketDirection::FromFlightController || d.is_empty() {
        return None;
    }
    Some(match p.cmd {
        1 => {
            let a: MspApiVersion = p.decode_as().ok()?;
            vec![
                ("protocol_version", I(a.protocol_version.into())),
                ("api_version_major", I(a.api_version_major.into())),
                ("api_version_minor", I(a.api_version_minor.into())),
            ]
        }
        2 => {
            let v: MspFlightControllerVariant = p.decode_as().ok()?;
            vec![(
                "identifier",
                V::S(String::from_utf8(v.identifier.to_vec()).ok()?),
            )]
        }
        3 => {
            let v: MspFlightControllerVersion = p.decode_as().ok()?;
            vec![
                ("major", I(v.major.into())),
                ("minor", I(v.minor.into())),
                ("patch", I(v.patch.into())),
            ]
        }
        101 => {
            let s = MspStatus::from_bytes(d).ok()?;
            let sensors = u16::from(s.sensors.acc)
                | u16::from(s.sensors.baro) << 1
                | u16::from(s.sensors.mag) << 2
                | u16::from(s.sensors.gps) << 3
                | u16::from(s.sensors.rangefinder) << 4
                | u16::from(s.sensors.gyro) << 5
                | u16::from(s.sensors.optical_flow) << 6;
            vec![
                ("cycle_time", I(s.cycle_time.into())),
                ("i2c_errors", I(s.i2c_errors.into())),
                ("sensors", I(sensors.into())),
                ("flight_mode_flags", I(s.flight_mode_flags.into())),
                (
                    "current_pid_profile_index",
                    I(s.current_pid_profile_index.into()),
                ),
                (
                    "average_system_load_percent",
                    I(s.average_system_load_percent.into()),
                ),
                ("gyro_cycle_time", I(s.gyro_cycle_time.into())),
                (
                    "extra_flight_mode_flags",
                    V::List(
                        s.extra_flight_mode_flags
                            .iter()
                            .map(|&x| x.into())
                            .collect(),
                    ),
                ),
                (
                    "arming_disable_flags_count",
                    I(s.arming_disable_flags_count.into()),
                ),
                ("arming_disable_flags", I(s.arming_disable_flags.into())),
                ("config_state_flags", I(s.config_state_flags.into())),
                ("core_temp_celsius", I(s.core_temp_celsius.into())),
                (
                    "control_rate_profile_count",
                    I(s.control_rate_profile_count.into()),
                ),
            ]
        }
        102 => {
            let m: MspRawImu = p.decode_as().ok()?;
            vec![
                ("acc_x", I(m.acc_x.into())),
                ("acc_y", I(m.acc_y.into())),
                ("acc_z", I(m.acc_z.into())),
                ("gyro_x", I(m.gyro_x.into())),
                ("gyro_y", I(m.gyro_y.into())),
                ("gyro_z", I(m.gyro_z.into())),
                ("mag_x", I(m.mag_x.into())),
                ("mag_y", I(m.mag_y.into())),
                ("mag_z", I(m.mag_z.into())),
            ]
        }
        108 => {
            let a: MspAttitude = p.decode_as().ok()?;
            vec![
                ("roll", I(a.roll.into())),
                ("pitch", I(a.pitch.into())),
                ("yaw", I(a.yaw.into())),
            ]
        }
        109 => {
            let a: MspAltitude = p.decode_as().ok()?;
            vec![
                ("altitude", I(a.altitude.into())),
                ("vario", I(a.vario.into())),
            ]
        }
        110 => {
            let a: MspAnalog = p.decode_as().ok()?;
            vec![
                ("battery_voltage", I(a.battery_voltage.into())),
                ("mah_drawn", I(a.mah_drawn.into())),
                ("rssi", I(a.rssi.into())),
                ("amperage", I(a.amperage.into())),
                ("battery_voltage_mv", I(a.battery_voltage_mv.into())),
            ]
        }
        _ => return None,
    })
}

fn payload(frame: &Value) -> Vec<u8> {
    hex(frame["payload_hex"].as_str().expect("payload_hex"))
}

#[test]
fn every_frame_parses_in_cu_msp_lib_to_its_command_and_payload() {
    let v = load_vectors("msp.json");
    let (mut parsed, mut decoded, mut jumbo) = (0, 0, 0);
    for frame in frames(&v) {
        let found = parse(&frame_bytes(frame));
        if payload(frame).len() >= 255 {
            // The peer reads the size byte 255 as a length: no packet comes out.
            assert!(found.is_empty(), "{}: {found:?}", name(frame));
            jumbo += 1;
            continue;
        }
        let [p] = found.as_slice() else {
            panic!("{}: {found:?}", name(frame))
        };
        assert_eq!(u64::from(p.cmd), uint(frame, "cmd"), "{}", name(frame));
        assert_eq!(
            direction(p.direction),
            frame["direction"],
            "{}",
            name(frame)
        );
        assert_eq!(p.data.as_slice(), payload(frame), "{}", name(frame));
        parsed += 1;
        if let Some(got) = fields(p) {
            assert_fields(name(frame), &got, &frame["fields"]);
            decoded += 1;
        }
    }
    println!(
        "cu-msp-lib: {parsed} frames parsed, {decoded} payloads decoded, {jumbo} jumbo rejected"
    );
    assert_eq!(parsed + jumbo, frames(&v).len());
    assert_eq!(jumbo, 1);
    assert!(decoded >= 9);
}

#[test]
fn the_stream_yields_expected_frames_in_cu_msp_lib() {
    let v = load_vectors("msp.json");
    for stream in v["streams"].as_array().expect("streams") {
        let seen: Vec<_> = parse(&hex(stream["hex"].as_str().expect("hex")))
            .iter()
            .map(|p| (p.cmd, p.data.as_slice().to_vec()))
            .collect();
        let wanted: Vec<_> = expected_frames(stream)
            .iter()
            .flat_map(|(_, b)| parse(b))
            .map(|p| (p.cmd, p.data.as_slice().to_vec()))
            .collect();
        let mut rest = wanted.iter();
        for s in &seen {
            assert!(rest.any(|w| w == s), "{}: {s:?} unexpected", stream["name"]);
        }
        println!(
            "cu-msp-lib: {} of {} expected frames",
            seen.len(),
            expected_frames(stream).len()
        );
        assert!(!seen.is_empty());
    }
}
