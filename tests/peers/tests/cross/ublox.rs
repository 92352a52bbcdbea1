//! UBX (`tests/vectors/ubx.json`) against `ublox` 0.10 (ublox-rs), protocol 23 packets.
//!
//! Every frame goes through the peer's parser: the packets it knows decode to the recorded raw
//! fields; the ones it only sends (CFG-MSG, CFG-RATE) come back as unknown packets with the
//! recorded class, id and payload, so at least their framing and checksum are confirmed.

use crate::values::{V, assert_fields};
use protocol_peers::{expected_frames, frame_bytes, frames, hex, load_vectors, name, uint};
use serde_json::Value;
use ublox::proto23::{PacketRef, Proto23};
use ublox::{Parser, UbxPacket};

fn text(bytes: &[u8]) -> V {
    let end = bytes.iter().position(|&b| b == 0).unwrap_or(bytes.len());
    V::S(String::from_utf8(bytes[..end].to_vec()).expect("ascii"))
}

/// Decoded fields, by name.
type Fields = Vec<(&'static str, V)>;

/// A packet the peer does not decode: class, id, payload.
type Unknown = (u8, u8, Vec<u8>);

/// The peer's raw fields under the snake_case u-blox names, or the unknown packet's class, id
/// and payload.
fn fields(packet: &PacketRef<'_>) -> Result<Fields, Unknown> {
    use V::I;
    Ok(match packet {
        PacketRef::NavPosLlh(p) => vec![
            ("itow", I(p.itow().into())),
            ("lon", I(p.lon_degrees_raw().into())),
            ("lat", I(p.lat_degrees_raw().into())),
            ("height", I(p.height_meters_raw().into())),
            ("h_msl", I(p.height_msl_raw().into())),
            ("h_acc", I(p.h_ack_raw().into())),
            ("v_acc", I(p.v_acc_raw().into())),
        ],
        PacketRef::NavStatus(p) => vec![
            ("itow", I(p.itow().into())),
            ("gps_fix", I(p.fix_type_raw().into())),
            ("flags", I(p.flags_raw().into())),
            ("fix_stat", I(p.fix_stat_raw().into())),
            ("flags2", I(p.flags2_raw().into())),
            ("ttff", I(p.time_to_first_fix().into())),
            ("msss", I(p.uptime_ms().into())),
        ],
        PacketRef::NavDop(p) => vec![
            ("itow", I(p.itow().into())),
            ("g_dop", I(p.geometric_dop_raw().into())),
            ("p_dop", I(p.position_dop_raw().into())),
            ("t_dop", I(p.time_dop_raw().into())),
            ("v_dop", I(p.vertical_dop_raw().into())),
            ("h_dop", I(p.horizontal_dop_raw().into())),
            ("n_dop", I(p.northing_dop_raw().into())),
            ("e_dop", I(p.easting_dop_raw().into())),
        ],
        PacketRef::NavTimeUTC(p) => vec![
            ("itow", I(p.itow().into())),
            ("t_acc", I(p.time_accuracy_estimate_ns().into())),
            ("nano", I(p.nanos().into())),
            ("year", I(p.year().into())),
            ("month", I(p.month().into())),
            ("day", I(p.day().into())),
            ("hour", I(p.hour().into())),
            ("min", I(p.min().into())),
            ("sec", I(p.sec().into())),
            ("valid", I(p.valid_raw().into())),
        ],
        PacketRef::NavVelNed(p) => vec![
            ("itow", I(p.itow().into())),
            ("vel_n", I(p.vel_north_raw().into())),
            ("vel_e", I(p.vel_east_raw().into())),
            ("vel_d", I(p.vel_down_raw().into())),
            ("speed", I(p.speed_3d_raw().into())),
            ("g_speed", I(p.ground_speed_raw().into())),
            ("heading", I(p.heading_degrees_raw().into())),
            ("s_acc", I(p.speed_accuracy_estimate_raw().into())),
            ("c_acc", I(p.course_heading_accuracy_estimate_raw().into())),
        ],
        PacketRef::NavPvt(p) => vec![
            ("itow", I(p.itow().into())),
            ("year", I(p.year().into())),
            ("month", I(p.month().into())),
            ("day", I(p.day().into())),
            ("hour", I(p.hour().into())),
            ("min", I(p.min().into())),
            ("sec", I(p.sec().into())),
            ("valid", I(p.valid_raw().into())),
            ("t_acc", I(p.time_accuracy().into())),
            ("nano", I(p.nanosec().into())),
            ("fix_type", I(p.fix_type_raw().into())),
            ("flags", I(p.flags_raw().into())),
            ("flags2", I(p.flags2_raw().into())),
            ("num_sv", I(p.num_satellites().into())),
            ("lon", I(p.longitude_raw().into())),
            ("lat", I(p.latitude_raw().into())),
            ("height", I(p.height_above_ellipsoid_raw().into())),
            ("h_msl", I(p.height_msl_raw().into())),
            ("h_acc", I(p.horizontal_accuracy_raw().into())),
            ("v_acc", I(p.vertical_accuracy_raw().into())),
            ("vel_n", I(p.vel_north_raw().into())),
            ("vel_e", I(p.vel_east_raw().into())),
            ("vel_d", I(p.vel_down_raw().into())),
            ("g_speed", I(p.ground_speed_2d_raw().into())),
            ("head_mot", I(p.heading_motion_raw().into())),
            ("s_acc", I(p.speed_accuracy_raw().into())),
            ("head_acc", I(p.heading_accuracy_raw().into())),
            ("p_dop", I(p.pdop_raw().into())),
            ("flags3", I(p.flags3_raw().into())),
            ("head_veh", I(p.heading_vehicle_raw().into())),
            ("mag_dec", I(p.magnetic_declination_raw().into())),
            ("mag_acc", I(p.magnetic_declination_accuracy_raw().into())),
        ],
        PacketRef::NavSat(p) => {
            let svs: Vec<_> = p.svs().collect();
            let list = |f: &dyn Fn(&ublox::nav_sat::NavSatSvInfoRef<'_>) -> i128| {
                V::List(svs.iter().map(f).collect())
            };
            vec![
                ("itow", I(p.itow().into())),
                ("version", I(p.version().into())),
                ("num_svs", I(p.num_svs().into())),
                ("svs.gnss_id", list(&|s| s.gnss_id().into())),
                ("svs.sv_id", list(&|s| s.sv_id().into())),
                ("svs.cno", list(&|s| s.cno().into())),
                ("svs.elev", list(&|s| s.elev().into())),
                ("svs.azim", list(&|s| s.azim().into())),
                ("svs.pr_res", list(&|s| s.pr_res().into())),
                ("svs.flags", list(&|s| s.flags_raw().into())),
            ]
        }
        PacketRef::AckAck(p) => vec![
            ("cls_id", I(p.class().into())),
            ("msg_id", I(p.msg_id().into())),
        ],
        PacketRef::AckNak(p) => vec![
            ("cls_id", I(p.class().into())),
            ("msg_id", I(p.msg_id().into())),
        ],
        PacketRef::MonVer(p) => {
            let mut f = vec![
                ("sw_version", text(p.software_version_raw())),
                ("hw_version", text(p.hardware_version_raw())),
            ];
            let ext: Vec<String> = p.extension().map(str::to_string).collect();
            f.push(("extension", V::Strings(ext)));
            f
        }
        PacketRef::Unknown(u) => return Err((u.class, u.msg_id, u.payload.to_vec())),
        other => panic!("no vector has {other:?}"),
    })
}

/// The recorded fields, with NAV-SAT's blocks as one list per block field and MON-VER's
/// extension blocks as a list of strings, the forms `fields` gives.
fn recorded(frame: &Value) -> Value {
    let mut f = frame["fields"].clone();
    let obj = f.as_object_mut().expect("fields");
    if let Some(Value::Array(svs)) = obj.remove("svs") {
        for key in ["gnss_id", "sv_id", "cno", "elev", "azim", "pr_res", "flags"] {
            let column = svs.iter().map(|s| s[key].clone()).collect();
            obj.insert(format!("svs.{key}"), Value::Array(column));
        }
    }
    if let Some(Value::Array(ext)) = obj.remove("extension") {
        let texts = ext.iter().map(|e| e["extension"].clone()).collect();
        obj.insert("extension".into(), Value::Array(texts));
    }
    f
}

#[test]
fn every_frame_decodes_in_ublox_to_its_fields() {
    let v = load_vectors("ubx.json");
    let (mut decoded, mut framing_only) = (0, 0);
    for frame in frames(&v) {
        let bytes = frame_bytes(frame);
        let mut parser = Parser::<_, Proto23>::default();
        let mut it = parser.consume_ubx(&bytes);
        let Some(Ok(UbxPacket::Proto23(packet))) = it.next() else {
            panic!("{}: ublox does not parse it", name(frame))
        };
        match fields(&packet) {
            Ok(got) => {
                assert_fields(name(frame), &got, &recorded(frame));
                decoded += 1;
            }
            Err((class, id, payload)) => {
                assert_eq!(
                    u64::from(class),
                    uint(frame, "msg_class"),
                    "{}",
                    name(frame)
                );
                assert_eq!(u64::from(id), uint(frame, "msg_id"), "{}", name(frame));
                assert_eq!(payload, bytes[6..bytes.len() - 2], "{}", name(frame));
                framing_only += 1;
            }
        }
    }
    println!("ublox: {decoded} frames decoded to their fields, {framing_only} framing only");
    assert_eq!(decoded + framing_only, frames(&v).len());
    assert!(decoded >= 11);
}

#[test]
fn the_stream_yields_its_expected_frames_in_ublox() {
    let v = load_vectors("ubx.json");
    for stream in v["streams"].as_array().expect("streams") {
        let bytes = hex(stream["hex"].as_str().expect("hex"));
        let mut parser = Parser::<_, Proto23>::default();
        let mut it = parser.consume_ubx(&bytes);
        let mut seen = Vec::new();
        while let Some(item) = it.next() {
            if let Ok(UbxPacket::Proto23(p)) = item {
                seen.push(format!("{:?}", fields(&p).map(|f| f.len())));
            }
        }
        let wanted: Vec<String> = expected_frames(stream)
            .iter()
            .map(|(_, b)| {
                let mut parser = Parser::<_, Proto23>::default();
                let mut it = parser.consume_ubx(b);
                let Some(Ok(UbxPacket::Proto23(p))) = it.next() else {
                    panic!("expected frame not parsed")
                };
                format!("{:?}", fields(&p).map(|f| f.len()))
            })
            .collect();
        assert_eq!(seen, wanted, "{}", stream["name"]);
    }
}
