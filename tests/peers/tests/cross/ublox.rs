//! UBX (`tests/vectors/ubx.json`) against `ublox` 0.10 (ublox-rs), protocol 23 packets.
//!
//! Every frame goes through the peer's parser: the packets it knows decode to the recorded raw
//! fields; the ones it only sends (CFG-MSG, CFG-RATE) come back as unknown packets with the
//! recorded class, id and payload, so at least their framing and checksum are confirmed.
//!
//! Random messages cross between the peer and the code generated from `specs/ubx.toml`, one way
//! each (the peer writes only what a host sends and parses only what a receiver sends).

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

// ---- Random messages: the `ublox` crate and the generated UBX codec ----

mod ours {
    protocol_kit::protocol!("../../specs/ubx.toml");
}

use crate::encoded;
use ours::ubx as spec;
use proptest::prelude::*;
use protocol_peers::harness::{PeerAdapter, cross_check};
use spec::Message as M;
use ublox::cfg_msg::{CfgMsgAllPortsBuilder, CfgMsgSinglePortBuilder};
use ublox::cfg_rate::{AlignmentToReferenceTime, CfgRateBuilder};

/// The `ublox` crate splits UBX by direction: what a receiver sends it only parses, what a host
/// sends it only writes. So the messages both sides know cross one way each: CFG-MSG (both
/// forms) and CFG-RATE are written by the peer, decoded here and compared byte for byte with
/// this project's frame; NAV-POSLLH, NAV-STATUS, NAV-DOP, NAV-PVT, NAV-VELNED, NAV-TIMEUTC,
/// ACK-ACK and ACK-NAK are written here and decoded by the peer. NAV-SAT and MON-VER (variable
/// length) are left to the vectors above.
struct Ublox;

fn fix(raw: u8) -> spec::GpsFix {
    spec::GpsFix::from_raw(raw).expect("an unknown fix type is kept")
}

fn carr_soln(raw: u8) -> spec::CarrSoln {
    spec::CarrSoln::from_raw(raw).expect("an unknown solution is kept")
}

/// `n` bits of `word` from bit `at`.
fn bits(word: u16, at: u32, n: u32) -> u8 {
    u8::try_from((word >> at) & ((1 << n) - 1)).expect("at most 8 bits")
}

fn bit(word: u16, at: u32) -> bool {
    (word >> at) & 1 == 1
}

// The spec's messages from raw wire values, as the peer gives them: a scaled field is the raw
// integer divided by the integer whose reciprocal its scale is (as the generated decoder
// computes it), a flag word its members lowest bit first.

fn posllh(itow: u32, i: [i32; 4], u: [u32; 2]) -> spec::NavPosllh {
    spec::NavPosllh {
        itow,
        lon: f64::from(i[0]) / 1e7,
        lat: f64::from(i[1]) / 1e7,
        height: i[2],
        h_msl: i[3],
        h_acc: u[0],
        v_acc: u[1],
    }
}

/// NAV-STATUS from itow, ttff, msss and gpsFix, flags, fixStat, flags2.
fn status(u: [u32; 3], b: [u8; 4]) -> spec::NavStatus {
    let [flags, fix_stat, flags2] = [b[1], b[2], b[3]].map(u16::from);
    spec::NavStatus {
        itow: u[0],
        gps_fix: fix(b[0]),
        gps_fix_ok: bit(flags, 0),
        diff_soln: bit(flags, 1),
        wkn_set: bit(flags, 2),
        tow_set: bit(flags, 3),
        flags_reserved: bits(flags, 4, 4),
        diff_corr: bit(fix_stat, 0),
        carr_soln_valid: bit(fix_stat, 1),
        reserved0: bits(fix_stat, 2, 4),
        map_matching: bits(fix_stat, 6, 2),
        psm_state: bits(flags2, 0, 2),
        reserved1: bit(flags2, 2),
        spoof_det_state: bits(flags2, 3, 2),
        reserved2: bit(flags2, 5),
        carr_soln: carr_soln(bits(flags2, 6, 2)),
        ttff: u[1],
        msss: u[2],
    }
}

fn dop(itow: u32, d: [u16; 7]) -> spec::NavDop {
    let d = d.map(|v| f32::from(v) / 100.0);
    spec::NavDop {
        itow,
        g_dop: d[0],
        p_dop: d[1],
        t_dop: d[2],
        v_dop: d[3],
        h_dop: d[4],
        n_dop: d[5],
        e_dop: d[6],
    }
}

/// NAV-PVT's raw wire values.
#[derive(Debug, Clone, Copy)]
struct PvtRaw {
    /// itow, t_acc, h_acc, v_acc, s_acc, head_acc.
    u: [u32; 6],
    /// nano, lon, lat, height, h_msl, vel_n, vel_e, vel_d, g_speed, head_mot, head_veh.
    i: [i32; 11],
    /// month, day, hour, min, sec, valid, fix_type, flags, flags2, num_sv.
    b: [u8; 10],
    /// year, p_dop, mag_acc, flags3.
    w: [u16; 4],
    mag_dec: i16,
}

fn pvt(r: PvtRaw) -> spec::NavPvt {
    let (u, i, b, w) = (r.u, r.i, r.b, r.w);
    let [valid, flags, flags2] = [b[5], b[7], b[8]].map(u16::from);
    let flags3 = w[3];
    spec::NavPvt {
        itow: u[0],
        year: w[0],
        month: b[0],
        day: b[1],
        hour: b[2],
        min: b[3],
        sec: b[4],
        valid_date: bit(valid, 0),
        valid_time: bit(valid, 1),
        fully_resolved: bit(valid, 2),
        valid_mag: bit(valid, 3),
        valid_reserved: bits(valid, 4, 4),
        t_acc: u[1],
        nano: i[0],
        fix_type: fix(b[6]),
        gnss_fix_ok: bit(flags, 0),
        diff_soln: bit(flags, 1),
        psm_state: bits(flags, 2, 3),
        head_veh_valid: bit(flags, 5),
        carr_soln: carr_soln(bits(flags, 6, 2)),
        reserved: bits(flags2, 0, 5),
        confirmed_avai: bit(flags2, 5),
        confirmed_date: bit(flags2, 6),
        confirmed_time: bit(flags2, 7),
        num_sv: b[9],
        lon: f64::from(i[1]) / 1e7,
        lat: f64::from(i[2]) / 1e7,
        height: i[3],
        h_msl: i[4],
        h_acc: u[2],
        v_acc: u[3],
        vel_n: i[5],
        vel_e: i[6],
        vel_d: i[7],
        g_speed: i[8],
        head_mot: f64::from(i[9]) / 1e5,
        s_acc: u[4],
        head_acc: f64::from(u[5]) / 1e5,
        p_dop: f32::from(w[1]) / 100.0,
        invalid_llh: bit(flags3, 0),
        last_correction_age: bits(flags3, 1, 4),
        reserved1: bits(flags3, 5, 8),
        auth_time: bit(flags3, 13),
        nma_fix_status: bit(flags3, 14),
        flags3_reserved: bits(flags3, 15, 1),
        head_veh: f64::from(i[10]) / 1e5,
        mag_dec: f32::from(r.mag_dec) / 100.0,
        mag_acc: f32::from(w[2]) / 100.0,
    }
}

/// NAV-VELNED from itow, speed, g_speed, s_acc, c_acc and vel_n, vel_e, vel_d, heading.
fn velned(u: [u32; 5], i: [i32; 4]) -> spec::NavVelned {
    spec::NavVelned {
        itow: u[0],
        vel_n: i[0],
        vel_e: i[1],
        vel_d: i[2],
        speed: u[1],
        g_speed: u[2],
        heading: f64::from(i[3]) / 1e5,
        s_acc: u[3],
        c_acc: f64::from(u[4]) / 1e5,
    }
}

/// NAV-TIMEUTC from itow, t_acc, nano, year and month, day, hour, min, sec, valid.
fn timeutc(u: [u32; 2], nano: i32, year: u16, b: [u8; 6]) -> spec::NavTimeutc {
    let valid = u16::from(b[5]);
    spec::NavTimeutc {
        itow: u[0],
        t_acc: u[1],
        nano,
        year,
        month: b[0],
        day: b[1],
        hour: b[2],
        min: b[3],
        sec: b[4],
        valid_tow: bit(valid, 0),
        valid_wkn: bit(valid, 1),
        valid_utc: bit(valid, 2),
        auth_status: bit(valid, 3),
        utc_standard: bits(valid, 4, 4),
    }
}

fn messages() -> BoxedStrategy<spec::Packet> {
    let posllh = (any::<u32>(), any::<[i32; 4]>(), any::<[u32; 2]>())
        .prop_map(|(itow, i, u)| M::NavPosllh(posllh(itow, i, u)));
    let status =
        (any::<[u32; 3]>(), any::<[u8; 4]>()).prop_map(|(u, b)| M::NavStatus(status(u, b)));
    let dop = (any::<u32>(), any::<[u16; 7]>()).prop_map(|(itow, d)| M::NavDop(dop(itow, d)));
    let pvt = (
        any::<[u32; 6]>(),
        any::<[i32; 11]>(),
        any::<[u8; 10]>(),
        any::<[u16; 4]>(),
        any::<i16>(),
    )
        .prop_map(|(u, i, b, w, mag_dec)| {
            M::NavPvt(pvt(PvtRaw {
                u,
                i,
                b,
                w,
                mag_dec,
            }))
        });
    let velned =
        (any::<[u32; 5]>(), any::<[i32; 4]>()).prop_map(|(u, i)| M::NavVelned(velned(u, i)));
    let timeutc = (
        any::<[u32; 2]>(),
        any::<i32>(),
        any::<u16>(),
        any::<[u8; 6]>(),
    )
        .prop_map(|(u, nano, year, b)| M::NavTimeutc(timeutc(u, nano, year, b)));
    let ack = (any::<bool>(), any::<[u8; 2]>()).prop_map(|(acked, [cls_id, msg_id])| {
        let a = spec::Ack { cls_id, msg_id };
        if acked { M::AckAck(a) } else { M::AckNak(a) }
    });
    let cfg_msg = (any::<[u8; 3]>(), prop::option::of(any::<[u8; 5]>())).prop_map(
        |([msg_class, msg_id, rate], ports)| {
            M::CfgMsg(spec::CfgMsg {
                msg_class,
                msg_id,
                rate,
                ports: ports.map(|rate| spec::CfgMsgPorts { rate }),
            })
        },
    );
    // The peer's time reference is an enum of the five documented systems: it cannot write
    // another value (this spec keeps one, `unknown = "keep"`).
    let cfg_rate = (any::<[u16; 2]>(), 0u16..=4).prop_map(|([meas_rate, nav_rate], r)| {
        M::CfgRate(spec::CfgRate {
            meas_rate,
            nav_rate,
            time_ref: spec::TimeRef::from_raw(r).expect("a documented time system"),
        })
    });
    prop_oneof![
        posllh, status, dop, pvt, velned, timeutc, ack, cfg_msg, cfg_rate
    ]
    .prop_map(|message| spec::Packet {
        header: spec::Header {},
        message,
    })
    .boxed()
}

fn time_ref(r: spec::TimeRef) -> Result<AlignmentToReferenceTime, String> {
    Ok(match r.to_raw() {
        0 => AlignmentToReferenceTime::Utc,
        1 => AlignmentToReferenceTime::Gps,
        2 => AlignmentToReferenceTime::Glo,
        3 => AlignmentToReferenceTime::Bds,
        4 => AlignmentToReferenceTime::Gal,
        other => return Err(format!("time reference {other} not drawn")),
    })
}

impl PeerAdapter for Ublox {
    type Message = spec::Packet;

    fn peer(&self) -> &'static str {
        "ublox 0.10"
    }

    fn messages(&self) -> BoxedStrategy<spec::Packet> {
        messages()
    }

    fn peer_write(&mut self, m: &spec::Packet) -> Result<Option<Vec<u8>>, String> {
        Ok(Some(match &m.message {
            M::CfgMsg(c) => match c.ports {
                None => CfgMsgSinglePortBuilder {
                    msg_class: c.msg_class,
                    msg_id: c.msg_id,
                    rate: c.rate,
                }
                .into_packet_bytes()
                .to_vec(),
                Some(p) => {
                    let r = p.rate;
                    CfgMsgAllPortsBuilder {
                        msg_class: c.msg_class,
                        msg_id: c.msg_id,
                        rates: [c.rate, r[0], r[1], r[2], r[3], r[4]],
                    }
                    .into_packet_bytes()
                    .to_vec()
                }
            },
            M::CfgRate(c) => CfgRateBuilder {
                measure_rate_ms: c.meas_rate,
                nav_rate: c.nav_rate,
                time_ref: time_ref(c.time_ref)?,
            }
            .into_packet_bytes()
            .to_vec(),
            _ => return Ok(None),
        }))
    }

    fn peer_read(
        &mut self,
        frame: &[u8],
        _like: &spec::Packet,
    ) -> Result<Option<spec::Packet>, String> {
        let mut parser = Parser::<_, Proto23>::default();
        let mut it = parser.consume_ubx(frame);
        let packet = match it.next() {
            Some(Ok(UbxPacket::Proto23(p))) => p,
            other => return Err(format!("{other:?}")),
        };
        let message = match packet {
            PacketRef::NavPosLlh(p) => M::NavPosllh(posllh(
                p.itow(),
                [
                    p.lon_degrees_raw(),
                    p.lat_degrees_raw(),
                    p.height_meters_raw(),
                    p.height_msl_raw(),
                ],
                [p.h_ack_raw(), p.v_acc_raw()],
            )),
            PacketRef::NavStatus(p) => M::NavStatus(status(
                [p.itow(), p.time_to_first_fix(), p.uptime_ms()],
                [
                    p.fix_type_raw(),
                    p.flags_raw(),
                    p.fix_stat_raw(),
                    p.flags2_raw(),
                ],
            )),
            PacketRef::NavDop(p) => M::NavDop(dop(
                p.itow(),
                [
                    p.geometric_dop_raw(),
                    p.position_dop_raw(),
                    p.time_dop_raw(),
                    p.vertical_dop_raw(),
                    p.horizontal_dop_raw(),
                    p.northing_dop_raw(),
                    p.easting_dop_raw(),
                ],
            )),
            // The peer reads bytes 78..83 as the spec does: flags3 a `u16` (the later
            // protocols' X2), four reserved bytes.
            PacketRef::NavPvt(p) => M::NavPvt(pvt(PvtRaw {
                u: [
                    p.itow(),
                    p.time_accuracy(),
                    p.horizontal_accuracy_raw(),
                    p.vertical_accuracy_raw(),
                    p.speed_accuracy_raw(),
                    p.heading_accuracy_raw(),
                ],
                i: [
                    p.nanosec(),
                    p.longitude_raw(),
                    p.latitude_raw(),
                    p.height_above_ellipsoid_raw(),
                    p.height_msl_raw(),
                    p.vel_north_raw(),
                    p.vel_east_raw(),
                    p.vel_down_raw(),
                    p.ground_speed_2d_raw(),
                    p.heading_motion_raw(),
                    p.heading_vehicle_raw(),
                ],
                b: [
                    p.month(),
                    p.day(),
                    p.hour(),
                    p.min(),
                    p.sec(),
                    p.valid_raw(),
                    p.fix_type_raw(),
                    p.flags_raw(),
                    p.flags2_raw(),
                    p.num_satellites(),
                ],
                w: [
                    p.year(),
                    p.pdop_raw(),
                    p.magnetic_declination_accuracy_raw(),
                    p.flags3_raw(),
                ],
                mag_dec: p.magnetic_declination_raw(),
            })),
            PacketRef::NavVelNed(p) => M::NavVelned(velned(
                [
                    p.itow(),
                    p.speed_3d_raw(),
                    p.ground_speed_raw(),
                    p.speed_accuracy_estimate_raw(),
                    p.course_heading_accuracy_estimate_raw(),
                ],
                [
                    p.vel_north_raw(),
                    p.vel_east_raw(),
                    p.vel_down_raw(),
                    p.heading_degrees_raw(),
                ],
            )),
            PacketRef::NavTimeUTC(p) => M::NavTimeutc(timeutc(
                [p.itow(), p.time_accuracy_estimate_ns()],
                p.nanos(),
                p.year(),
                [
                    p.month(),
                    p.day(),
                    p.hour(),
                    p.min(),
                    p.sec(),
                    p.valid_raw(),
                ],
            )),
            PacketRef::AckAck(p) => M::AckAck(spec::Ack {
                cls_id: p.class(),
                msg_id: p.msg_id(),
            }),
            PacketRef::AckNak(p) => M::AckNak(spec::Ack {
                cls_id: p.class(),
                msg_id: p.msg_id(),
            }),
            // A packet the peer only writes (CFG-MSG, CFG-RATE) comes back unknown, with the
            // frame's class, id and payload: its framing and checksum pass, its values are not
            // read.
            PacketRef::Unknown(u) => {
                let framed = (u.class, u.msg_id, u.payload);
                if framed != (frame[2], frame[3], &frame[6..frame.len() - 2]) {
                    return Err(format!("unknown packet {framed:02x?}"));
                }
                return Ok(None);
            }
            other => return Err(format!("{other:?}")),
        };
        Ok(Some(spec::Packet {
            header: spec::Header {},
            message,
        }))
    }

    fn ours_write(&self, m: &spec::Packet) -> Result<Vec<u8>, String> {
        encoded(m)
    }

    fn ours_read(&self, frame: &[u8]) -> Result<spec::Packet, String> {
        spec::Packet::decode(frame).map_err(|e| e.to_string())
    }
}

#[test]
fn random_messages_cross_between_ublox_and_the_generated_codec_one_way_each() {
    const CASES: usize = 2000;
    let tally = cross_check(&mut Ublox, CASES).unwrap_or_else(|e| panic!("{e}"));
    println!("ublox: {tally:?}");
    assert_eq!(tally.messages, CASES);
    // Every message crossed exactly one way: the configuration messages from the peer (and as
    // the same bytes), the rest to it.
    assert_eq!(tally.peer_to_ours + tally.ours_to_peer, CASES);
    assert_eq!(tally.same_bytes, tally.peer_to_ours);
    // Nine kinds drawn evenly, two of them written by the peer: about two ninths.
    assert!(tally.peer_to_ours > CASES / 8, "{tally:?}");
    assert!(tally.ours_to_peer > CASES / 2, "{tally:?}");
}
