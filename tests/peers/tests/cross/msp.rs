//! MSP v1 and v2 (`tests/vectors/msp.json`) against `cu-msp-lib` 1.3 (the Copper project's MSP
//! library: v1, v2 and v2 over v1).
//!
//! Every frame the peer parses yields the recorded command, direction and payload, and the
//! responses whose payload the peer has a struct for decode to the recorded fields. The peer has
//! no jumbo v1 frames (size byte 255): that frame is checked to be rejected there, and decoded
//! here. Random messages cross both ways between the peer and the generated codec; the peer
//! keeps the wire integers where the spec has physical values (attitude angles, voltages,
//! currents), which the adapter converts with the spec's scales (exact in `f32` for every wire
//! value).

use crate::values::{V, assert_fields};
use cu_msp_lib::structs::{
    MspAltitude, MspAnalog, MspApiVersion, MspAttitude, MspFlightControllerVariant,
    MspFlightControllerVersion, MspRawImu, MspStatus,
};
use cu_msp_lib::{MspPacket, MspPacketDirection, MspParsedVersion, MspParser};
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

// ---- Random messages both ways: cu-msp-lib and the generated MSP v1 and v2 codec ----

mod ours {
    protocol_kit::protocol!("../../specs/msp.toml");
}

use crate::{encoded, packet_of};
use ours::msp as spec;
use proptest::prelude::*;
use protocol_peers::harness::{PeerAdapter, assert_every_message_crosses};

/// A wire integer of scale `1 / div` as its physical value, as the generated code computes it.
fn per(wire: impl Into<f32>, div: f32) -> f32 {
    wire.into() / div
}

/// The wire integer of a physical value of scale `1 / div` (exact for the values [`per`] gives).
fn wire(physical: f32, div: f32) -> f64 {
    f64::from((physical * div).round())
}

/// The MSP messages both sides know: replies the peer has a struct for, their empty
/// requests, box names (raw bytes, below the jumbo size the peer does not have) and the error
/// reply of any command, each in a v1 or a v2 frame.
fn messages() -> BoxedStrategy<spec::AnyPacket> {
    use spec::{Message as M, Request as Q, Response as R};
    let api = any::<[u8; 3]>().prop_map(|[a, b, c]| {
        M::Response(R::ApiVersion(spec::ApiVersion {
            protocol_version: a,
            api_version_major: b,
            api_version_minor: c,
        }))
    });
    let version = any::<[u8; 3]>().prop_map(|[a, b, c]| {
        M::Response(R::FcVersion(spec::FcVersion {
            major: a,
            minor: b,
            patch: c,
        }))
    });
    let attitude = any::<[i16; 3]>().prop_map(|[roll, pitch, yaw]| {
        M::Response(R::Attitude(spec::Attitude {
            roll: per(roll, 10.0),
            pitch: per(pitch, 10.0),
            yaw,
        }))
    });
    let altitude = (any::<i32>(), any::<i16>())
        .prop_map(|(altitude, vario)| M::Response(R::Altitude(spec::Altitude { altitude, vario })));
    let imu = any::<[i16; 9]>().prop_map(|v| {
        M::Response(R::RawImu(spec::RawImu {
            acc_x: v[0],
            acc_y: v[1],
            acc_z: v[2],
            gyro_x: v[3],
            gyro_y: v[4],
            gyro_z: v[5],
            mag_x: v[6],
            mag_y: v[7],
            mag_z: v[8],
        }))
    });
    let analog = (
        any::<u8>(),
        any::<u16>(),
        any::<u16>(),
        any::<i16>(),
        any::<u16>(),
    )
        .prop_map(
            |(battery_voltage, mah_drawn, rssi, amperage, battery_voltage_mv)| {
                M::Response(R::Analog(spec::Analog {
                    battery_voltage: per(battery_voltage, 10.0),
                    mah_drawn,
                    rssi,
                    amperage: per(amperage, 100.0),
                    battery_voltage_mv: per(battery_voltage_mv, 100.0),
                }))
            },
        );
    let names = prop::collection::vec(any::<u8>(), 0..=254).prop_map(|n| {
        M::Response(R::Boxnames(spec::BoxNames {
            names: protocol_kit::Bytes::from_slice(&n).expect("fits"),
        }))
    });
    let request = prop_oneof![
        Just(Q::ApiVersion),
        Just(Q::FcVersion),
        Just(Q::Attitude),
        Just(Q::Altitude),
        Just(Q::RawImu),
        Just(Q::Analog),
        Just(Q::Boxnames),
    ]
    .prop_map(M::Request);
    // MSP2_COMMON_SETTING (INAV): a v2-only command, its request a NUL-terminated name.
    let setting = "[a-z0-9_]{1,64}".prop_map(|name| {
        M::Request(Q::CommonSetting(spec::SettingName {
            name: protocol_kit::NulStr::from_text(&name).expect("at most 64 bytes"),
        }))
    });
    // An error reply (`!`, cu-msp-lib's `Unsupported`) of any command: the command alone.
    let refused = (0..spec::Command::ALL.len()).prop_map(|i| M::Error(spec::Command::ALL[i].0));
    let message = prop_oneof![
        api, version, attitude, altitude, imu, analog, names, request, setting, refused
    ];
    (message, any::<bool>())
        .prop_map(|(message, v2)| {
            // A command of an id above 255 travels in v2 frames only.
            // V2_FRAME (255) in a v1 frame carries a v2 frame, which cu-msp-lib reads as such.
            let v2 = v2 || message.command().id() >= 255;
            let direction = match message {
                M::Request(_) => b'<',
                M::Error(_) => b'!',
                M::Response(_) => b'>',
            };
            if v2 {
                spec::AnyPacket::V2(spec::V2Packet {
                    header: spec::V2Header { direction, flag: 0 },
                    message,
                })
            } else {
                spec::AnyPacket::V1(spec::Packet {
                    header: spec::Header { direction },
                    message,
                })
            }
        })
        .boxed()
}

/// The payload of `m`, written field by field as the MSP documentation lays it out
/// (little-endian), for the peer to frame.
fn payload_of(m: &spec::Message) -> Vec<u8> {
    use spec::{Message as M, Request as Q, Response as R};
    let mut out = Vec::new();
    match m {
        M::Request(Q::CommonSetting(s)) => {
            out.extend_from_slice(s.name.text());
            out.push(0);
        }
        M::Request(_) | M::Error(_) => {}
        M::Response(R::ApiVersion(a)) => {
            out.extend([a.protocol_version, a.api_version_major, a.api_version_minor]);
        }
        M::Response(R::FcVersion(v)) => out.extend([v.major, v.minor, v.patch]),
        M::Response(R::Attitude(a)) => {
            for x in [wire(a.roll, 10.0) as i16, wire(a.pitch, 10.0) as i16, a.yaw] {
                out.extend(x.to_le_bytes());
            }
        }
        M::Response(R::Altitude(a)) => {
            out.extend(a.altitude.to_le_bytes());
            out.extend(a.vario.to_le_bytes());
        }
        M::Response(R::RawImu(i)) => {
            let all = [
                i.acc_x, i.acc_y, i.acc_z, i.gyro_x, i.gyro_y, i.gyro_z, i.mag_x, i.mag_y, i.mag_z,
            ];
            for x in all {
                out.extend(x.to_le_bytes());
            }
        }
        M::Response(R::Analog(a)) => {
            out.push(wire(a.battery_voltage, 10.0) as u8);
            out.extend(a.mah_drawn.to_le_bytes());
            out.extend(a.rssi.to_le_bytes());
            out.extend((wire(a.amperage, 100.0) as i16).to_le_bytes());
            out.extend((wire(a.battery_voltage_mv, 100.0) as u16).to_le_bytes());
        }
        M::Response(R::Boxnames(n)) => out.extend_from_slice(n.names.as_slice()),
        other => panic!("not drawn: {other:?}"),
    }
    out
}

/// Our message for a packet the peer parsed, its payload read by the peer's structs.
fn from_peer(p: &MspPacket) -> Result<spec::Message, String> {
    use spec::{Message as M, Request as Q, Response as R};
    let cmd = p.cmd;
    let command = spec::Command::from_id(cmd).ok_or(format!("command {cmd}"))?;
    if p.direction == MspPacketDirection::Unsupported {
        if !p.data.as_slice().is_empty() {
            return Err("an error reply with a payload".into());
        }
        return Ok(M::Error(command));
    }
    if p.direction == MspPacketDirection::ToFlightController {
        if command == spec::Command::CommonSetting {
            let [name @ .., 0] = p.data.as_slice() else {
                return Err("a setting name without its NUL".into());
            };
            let name = std::str::from_utf8(name).map_err(|e| e.to_string())?;
            return Ok(M::Request(Q::CommonSetting(spec::SettingName {
                name: protocol_kit::NulStr::from_text(name).ok_or("a name too long")?,
            })));
        }
        if !p.data.as_slice().is_empty() {
            return Err("a request with a payload".into());
        }
        return Ok(M::Request(match command {
            spec::Command::ApiVersion => Q::ApiVersion,
            spec::Command::FcVersion => Q::FcVersion,
            spec::Command::Attitude => Q::Attitude,
            spec::Command::Altitude => Q::Altitude,
            spec::Command::RawImu => Q::RawImu,
            spec::Command::Analog => Q::Analog,
            spec::Command::Boxnames => Q::Boxnames,
            other => return Err(format!("{other:?}")),
        }));
    }
    Ok(M::Response(match command {
        spec::Command::ApiVersion => {
            let a: MspApiVersion = decoded(p.decode_as())?;
            R::ApiVersion(spec::ApiVersion {
                protocol_version: a.protocol_version,
                api_version_major: a.api_version_major,
                api_version_minor: a.api_version_minor,
            })
        }
        spec::Command::FcVersion => {
            let v: MspFlightControllerVersion = decoded(p.decode_as())?;
            R::FcVersion(spec::FcVersion {
                major: v.major,
                minor: v.minor,
                patch: v.patch,
            })
        }
        spec::Command::Attitude => {
            let a: MspAttitude = decoded(p.decode_as())?;
            R::Attitude(spec::Attitude {
                roll: per(a.roll, 10.0),
                pitch: per(a.pitch, 10.0),
                yaw: a.yaw,
            })
        }
        spec::Command::Altitude => {
            let a: MspAltitude = decoded(p.decode_as())?;
            R::Altitude(spec::Altitude {
                altitude: a.altitude,
                vario: a.vario,
            })
        }
        spec::Command::RawImu => {
            let m: MspRawImu = decoded(p.decode_as())?;
            R::RawImu(spec::RawImu {
                acc_x: m.acc_x,
                acc_y: m.acc_y,
                acc_z: m.acc_z,
                gyro_x: m.gyro_x,
                gyro_y: m.gyro_y,
                gyro_z: m.gyro_z,
                mag_x: m.mag_x,
                mag_y: m.mag_y,
                mag_z: m.mag_z,
            })
        }
        spec::Command::Analog => {
            let a: MspAnalog = decoded(p.decode_as())?;
            R::Analog(spec::Analog {
                battery_voltage: per(a.battery_voltage, 10.0),
                mah_drawn: a.mah_drawn,
                rssi: a.rssi,
                amperage: per(a.amperage, 100.0),
                battery_voltage_mv: per(a.battery_voltage_mv, 100.0),
            })
        }
        spec::Command::Boxnames => R::Boxnames(spec::BoxNames {
            names: protocol_kit::Bytes::from_slice(p.data.as_slice()).ok_or("too long")?,
        }),
        other => return Err(format!("{other:?}")),
    }))
}

/// A peer's decoding, its error as text.
fn decoded<T, E: std::fmt::Debug>(r: Result<T, E>) -> Result<T, String> {
    r.map_err(|e| format!("{e:?}"))
}

struct CuMsp;

/// The direction byte of a packet of either format.
fn direction_byte(m: &spec::AnyPacket) -> u8 {
    match m {
        spec::AnyPacket::V1(p) => p.header.direction,
        spec::AnyPacket::V2(p) => p.header.direction,
    }
}

impl PeerAdapter for CuMsp {
    type Message = spec::AnyPacket;

    fn peer(&self) -> &'static str {
        "cu-msp-lib 1.3"
    }

    fn messages(&self) -> BoxedStrategy<spec::AnyPacket> {
        messages()
    }

    fn peer_write(&mut self, m: &spec::AnyPacket) -> Result<Option<Vec<u8>>, String> {
        let packet = MspPacket {
            cmd: m.message().command().id(),
            direction: match direction_byte(m) {
                b'<' => MspPacketDirection::ToFlightController,
                b'!' => MspPacketDirection::Unsupported,
                _ => MspPacketDirection::FromFlightController,
            },
            data: payload_of(m.message()).as_slice().into(),
        };
        let frame = if let spec::AnyPacket::V2(_) = m {
            let mut frame = vec![0u8; packet.packet_size_bytes_v2()];
            packet.serialize_v2(&mut frame).map(|()| frame)
        } else {
            let mut frame = vec![0u8; packet.packet_size_bytes()];
            packet.serialize(&mut frame).map(|()| frame)
        };
        frame.map(Some).map_err(|e| format!("{e:?}"))
    }

    fn peer_read(
        &mut self,
        frame: &[u8],
        _like: &spec::AnyPacket,
    ) -> Result<Option<spec::AnyPacket>, String> {
        let mut parser = MspParser::new();
        let mut found = frame.iter().filter_map(|&b| {
            parser
                .parse(b)
                .ok()
                .flatten()
                .map(|p| (p, parser.last_packet_info()))
        });
        let (Some((p, info)), None) = (found.next(), found.next()) else {
            return Err("not one packet".into());
        };
        let (direction, message) = (p.direction.to_byte(), from_peer(&p)?);
        Ok(Some(match info.map(|i| i.version) {
            Some(MspParsedVersion::V2Native) => spec::AnyPacket::V2(spec::V2Packet {
                header: spec::V2Header { direction, flag: 0 },
                message,
            }),
            Some(MspParsedVersion::V1) => spec::AnyPacket::V1(spec::Packet {
                header: spec::Header { direction },
                message,
            }),
            other => return Err(format!("parsed as {other:?}")),
        }))
    }

    fn ours_write(&self, m: &spec::AnyPacket) -> Result<Vec<u8>, String> {
        encoded(m)
    }

    /// Through the link's one decoder, which finds the frame's format by its sync.
    fn ours_read(&self, frame: &[u8]) -> Result<spec::AnyPacket, String> {
        packet_of::<_, { spec::ANY_DECODER_BUFFER_LEN }>(spec::AnyLayout, frame)
    }
}

const CASES: usize = 2000;

#[test]
fn random_messages_cross_between_cu_msp_lib_and_the_generated_codec() {
    assert_every_message_crosses(&mut CuMsp, CASES, "cu-msp-lib");
}

#[test]
fn the_vector_frames_decode_here_the_jumbo_one_included() {
    // The v1 and v2 frames the spec expresses decode here, through the link's one decoder, to
    // their command, the jumbo frame the peer cannot read among them.
    let v = load_vectors("msp.json");
    let (mut v1, mut v2) = (0, 0);
    for frame in frames(&v) {
        let bytes = frame_bytes(frame);
        let Ok(packet) = CuMsp.ours_read(&bytes) else {
            continue;
        };
        // A v2 frame inside a v1 frame is MSP_V2_FRAME here; the vector records the inner
        // command.
        let cmd = if frame["version"] == "v2-over-v1" {
            255
        } else {
            uint(frame, "cmd")
        };
        assert_eq!(
            u64::from(packet.message().command().id()),
            cmd,
            "{}",
            name(frame)
        );
        match packet {
            spec::AnyPacket::V1(_) => v1 += 1,
            spec::AnyPacket::V2(_) => v2 += 1,
        }
    }
    println!("msp: {v1} v1 and {v2} v2 vector frames decode here");
    assert_eq!((v1, v2), (13, 3), "v2 over v1 counts as v1");
}
