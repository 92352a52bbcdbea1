//! UBX golden vectors (`tests/vectors/ubx.json`: layouts from the u-blox M8 protocol
//! description, frames checked with pyubx2 and the ublox crate): every frame decodes to its
//! recorded fields and those values encode to the exact bytes, by generated code and by the
//! run-time codec; the stream yields exactly its expected frames at every chunk size, in both.
//!
//! The vectors record raw integers; enumerations (`gps_fix`, `fix_type`, `time_ref`) are
//! looked up in the u-blox names below. MON-VER's texts are `char[N]` fields: strings in the
//! codec's JSON, `FixedStr`s in Rust.

use crate::golden;

use protocol_kit::{FixedStr, Group};
use protocol_tests::{F, assert_stream_at_every_chunk_size, hex, load_vectors, stream_vector};
use serde_json::Value;

protocol_kit::protocol!("../specs/ubx.toml");

use ubx::*;

/// The u-blox names of a fix type (gpsFix, fixType).
const FIX_NAMES: [&str; 6] = [
    "NO_FIX",
    "DEAD_RECKONING_ONLY",
    "FIX_2D",
    "FIX_3D",
    "GPS_AND_DEAD_RECKONING",
    "TIME_ONLY",
];
/// The u-blox names of CFG-RATE's time systems (timeRef).
const TIME_REF_NAMES: [&str; 5] = ["UTC", "GPS", "GLONASS", "BEIDOU", "GALILEO"];

/// A field read from a vector's JSON, refusing a value that does not fit.
trait FromJson {
    fn from_json(v: &Value) -> Self;
}

macro_rules! from_json_int {
    ($($t:ty),*) => {$(
        impl FromJson for $t {
            fn from_json(v: &Value) -> Self {
                let n = v.as_i64().unwrap_or_else(|| panic!("not an integer: {v}"));
                <$t>::try_from(n).unwrap_or_else(|_| panic!("{n} does not fit"))
            }
        }
    )*};
}
from_json_int!(u8, i8, u16, i16, u32, i32);

impl FromJson for GpsFix {
    fn from_json(v: &Value) -> Self {
        GpsFix::from_raw(u8::from_json(v)).expect("a fix type")
    }
}

impl FromJson for TimeRef {
    fn from_json(v: &Value) -> Self {
        TimeRef::from_raw(u16::from_json(v)).expect("a time reference")
    }
}

impl<const N: usize> FromJson for FixedStr<N> {
    fn from_json(v: &Value) -> Self {
        let text = v.as_str().unwrap_or_else(|| panic!("not text: {v}"));
        FixedStr::from_text(text).unwrap_or_else(|| panic!("{text:?} fits {N} bytes"))
    }
}

/// A struct whose fields are all read from the same-named keys of `$v`.
macro_rules! from_fields {
    ($ty:ident, $v:expr; $($f:ident),* $(,)?) => {
        $ty { $($f: FromJson::from_json(&$v[stringify!($f)])),* }
    };
}

fn group<T: Copy + Default + std::fmt::Debug, const N: usize>(
    list: &Value,
    each: impl Fn(&Value) -> T,
) -> Group<T, N> {
    let mut g = Group::new();
    for v in list.as_array().expect("a list") {
        g.push(each(v)).expect("room in the group");
    }
    g
}

/// The message a vector records, built from its JSON fields (not from the bytes).
fn expected(frame: &Value) -> Message {
    let v = &frame["fields"];
    match frame["message"].as_str().expect("message") {
        "NAV-POSLLH" => Message::NavPosllh(from_fields!(NavPosllh, v;
            itow, lon, lat, height, h_msl, h_acc, v_acc)),
        "NAV-STATUS" => Message::NavStatus(from_fields!(NavStatus, v;
            itow, gps_fix, flags, fix_stat, flags2, ttff, msss)),
        "NAV-DOP" => Message::NavDop(from_fields!(NavDop, v;
            itow, g_dop, p_dop, t_dop, v_dop, h_dop, n_dop, e_dop)),
        "NAV-PVT" => Message::NavPvt(from_fields!(NavPvt, v;
            itow, year, month, day, hour, min, sec, valid, t_acc, nano, fix_type, flags, flags2,
            num_sv, lon, lat, height, h_msl, h_acc, v_acc, vel_n, vel_e, vel_d, g_speed, head_mot,
            s_acc, head_acc, p_dop, flags3, head_veh, mag_dec, mag_acc)),
        "NAV-VELNED" => Message::NavVelned(from_fields!(NavVelned, v;
            itow, vel_n, vel_e, vel_d, speed, g_speed, heading, s_acc, c_acc)),
        "NAV-TIMEUTC" => Message::NavTimeutc(from_fields!(NavTimeutc, v;
            itow, t_acc, nano, year, month, day, hour, min, sec, valid)),
        "NAV-SAT" => Message::NavSat(NavSat {
            itow: FromJson::from_json(&v["itow"]),
            version: FromJson::from_json(&v["version"]),
            num_svs: FromJson::from_json(&v["num_svs"]),
            svs: group(
                &v["svs"],
                |s| from_fields!(NavSatSv, s; gnss_id, sv_id, cno, elev, azim, pr_res, flags),
            ),
        }),
        "ACK-ACK" => Message::AckAck(from_fields!(Ack, v; cls_id, msg_id)),
        "ACK-NAK" => Message::AckNak(from_fields!(Ack, v; cls_id, msg_id)),
        "CFG-MSG" => Message::CfgMsg(CfgMsg {
            msg_class: FromJson::from_json(&v["msg_class"]),
            msg_id: FromJson::from_json(&v["msg_id"]),
            rate: FromJson::from_json(&v["rate"]),
            ports: None,
        }),
        "CFG-RATE" => Message::CfgRate(from_fields!(CfgRate, v; meas_rate, nav_rate, time_ref)),
        "MON-VER" => Message::MonVer(MonVer {
            sw_version: FromJson::from_json(&v["sw_version"]),
            hw_version: FromJson::from_json(&v["hw_version"]),
            extension: group(
                &v["extension"],
                |e| from_fields!(MonVerExtension, e; extension),
            ),
        }),
        other => panic!("vector not covered by this test: {other}"),
    }
}

/// The payload as the run-time codec shows it, built from the vector's fields.
fn expected_json(frame: &Value) -> Value {
    let mut p = frame["fields"].clone();
    let name =
        |names: &[&str], v: &Value| Value::from(names[v.as_u64().expect("a number") as usize]);
    for k in ["gps_fix", "fix_type"] {
        if let Some(v) = p.get(k).cloned() {
            p[k] = name(&FIX_NAMES, &v);
        }
    }
    match frame["message"].as_str().expect("message") {
        "CFG-RATE" => p["time_ref"] = name(&TIME_REF_NAMES, &p["time_ref"]),
        "CFG-MSG" => p["ports"] = Value::Null,
        _ => {}
    }
    p
}

#[test]
fn every_frame_decodes_to_its_fields_and_encodes_to_its_bytes() {
    let v = load_vectors("ubx.json");
    let interp = golden::interpreter("ubx");
    let mut n = 0;
    for frame in v["frames"].as_array().expect("frames") {
        let name = frame["name"].as_str().unwrap_or("?");
        let bytes = hex(frame["hex"].as_str().expect("hex"));
        let message = expected(frame);
        let (class, id) = message.command().id();
        assert_eq!(
            frame["msg_class"].as_u64(),
            Some(u64::from(class)),
            "{name}"
        );
        assert_eq!(frame["msg_id"].as_u64(), Some(u64::from(id)), "{name}");
        let packet = Packet {
            header: Header {},
            message,
        };
        assert_eq!(Packet::decode(&bytes), Ok(packet), "{name}: decode");
        let mut buf = [0u8; MAX_FRAME_LEN];
        let len = packet
            .encode(&mut buf)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(F(&buf[..len]), F(&bytes), "{name}: encode");
        let command = frame["message"]
            .as_str()
            .expect("message")
            .replace('-', "_");
        golden::frame(&interp, name, &bytes, Some(&command), &expected_json(frame));
        n += 1;
    }
    assert_eq!(n, 17, "every vector was checked");
}

#[test]
fn stream_yields_expected_frames_at_every_chunk_size() {
    let v = load_vectors("ubx.json");
    let (bytes, expected) = stream_vector(&v["streams"][0]);
    assert_stream_at_every_chunk_size::<DECODER_BUFFER_LEN>(&LAYOUT, &bytes, &expected, |f| {
        assert!(Packet::from_frame(f).is_ok(), "{:?}", F(f));
    });
    golden::stream(&golden::interpreter("ubx"), &bytes, &expected);
}
