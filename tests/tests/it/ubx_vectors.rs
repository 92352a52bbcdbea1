//! UBX golden vectors (`tests/vectors/ubx.json`: layouts from the u-blox M8 protocol
//! description, frames checked with pyubx2 and the ublox crate): every frame decodes to its
//! recorded fields and those values encode to the exact bytes, by generated code and by the
//! run-time codec; the stream yields exactly its expected frames at every chunk size, in both.
//!
//! The vectors record the raw wire values: a scaled field is the raw integer times its scale
//! (in the spec's `f32` or `f64`, dividing by the integer whose reciprocal the scale is, as the
//! generated code does), a flag word is split into its members lowest bit first, and
//! enumerations (`gps_fix`, `fix_type`, `time_ref`, `gnss_id`) are their variants. MON-VER's
//! texts are `char[N]` fields: strings in the codec's JSON, `FixedStr`s in Rust. The codec's
//! JSON of each frame is the serde JSON of the expected message (`derive(serde)`).

use crate::golden;

use protocol_kit::{FixedStr, Group};
use protocol_tests::{F, assert_stream_at_every_chunk_size, hex, load_vectors, stream_vector};
use serde_json::Value;

protocol_kit::protocol!("../specs/ubx.toml", derive(serde));

use ubx::*;

/// The raw fields of a vector.
struct Raw<'a>(&'a Value);

impl Raw<'_> {
    fn int(&self, k: &str) -> i64 {
        self.0[k]
            .as_i64()
            .unwrap_or_else(|| panic!("`{k}` is not an integer: {}", self.0[k]))
    }
    fn get<T: TryFrom<i64>>(&self, k: &str) -> T {
        T::try_from(self.int(k)).unwrap_or_else(|_| panic!("`{k}` does not fit"))
    }
    /// `n` bits of the word `k` from bit `at`.
    fn bits<T: TryFrom<i64>>(&self, k: &str, at: u32, n: u32) -> T {
        let v = (self.int(k) >> at) & ((1 << n) - 1);
        T::try_from(v).unwrap_or_else(|_| panic!("bits of `{k}` do not fit"))
    }
    fn bit(&self, k: &str, at: u32) -> bool {
        (self.int(k) >> at) & 1 == 1
    }
    /// A field of scale `1 / div` as an `f64`.
    fn f64_per(&self, k: &str, div: f64) -> f64 {
        self.int(k) as f64 / div
    }
    /// A field of scale `1 / div` as an `f32`.
    fn f32_per(&self, k: &str, div: f32) -> f32 {
        self.int(k) as f32 / div
    }
    fn text<const N: usize>(&self, k: &str) -> FixedStr<N> {
        let text = self.0[k]
            .as_str()
            .unwrap_or_else(|| panic!("not text: {k}"));
        FixedStr::from_text(text).unwrap_or_else(|| panic!("{text:?} fits {N} bytes"))
    }
}

fn group<T: Copy + Default + std::fmt::Debug, const N: usize>(
    list: &Value,
    each: impl Fn(Raw<'_>) -> T,
) -> Group<T, N> {
    let mut g = Group::new();
    for v in list.as_array().expect("a list") {
        g.push(each(Raw(v))).expect("room in the group");
    }
    g
}

fn fix(r: &Raw<'_>, k: &str) -> GpsFix {
    GpsFix::from_raw(r.get(k)).expect("an unknown fix type is kept")
}

fn carr_soln(r: &Raw<'_>, k: &str, at: u32) -> CarrSoln {
    CarrSoln::from_raw(r.bits(k, at, 2)).expect("an unknown solution is kept")
}

fn nav_status(r: &Raw<'_>) -> NavStatus {
    NavStatus {
        itow: r.get("itow"),
        gps_fix: fix(r, "gps_fix"),
        gps_fix_ok: r.bit("flags", 0),
        diff_soln: r.bit("flags", 1),
        wkn_set: r.bit("flags", 2),
        tow_set: r.bit("flags", 3),
        flags_reserved: r.bits("flags", 4, 4),
        diff_corr: r.bit("fix_stat", 0),
        carr_soln_valid: r.bit("fix_stat", 1),
        reserved0: r.bits("fix_stat", 2, 4),
        map_matching: r.bits("fix_stat", 6, 2),
        psm_state: r.bits("flags2", 0, 2),
        reserved1: r.bit("flags2", 2),
        spoof_det_state: r.bits("flags2", 3, 2),
        reserved2: r.bit("flags2", 5),
        carr_soln: carr_soln(r, "flags2", 6),
        ttff: r.get("ttff"),
        msss: r.get("msss"),
    }
}

fn nav_dop(r: &Raw<'_>) -> NavDop {
    NavDop {
        itow: r.get("itow"),
        g_dop: r.f32_per("g_dop", 100.0),
        p_dop: r.f32_per("p_dop", 100.0),
        t_dop: r.f32_per("t_dop", 100.0),
        v_dop: r.f32_per("v_dop", 100.0),
        h_dop: r.f32_per("h_dop", 100.0),
        n_dop: r.f32_per("n_dop", 100.0),
        e_dop: r.f32_per("e_dop", 100.0),
    }
}

fn nav_pvt(r: &Raw<'_>) -> NavPvt {
    NavPvt {
        itow: r.get("itow"),
        year: r.get("year"),
        month: r.get("month"),
        day: r.get("day"),
        hour: r.get("hour"),
        min: r.get("min"),
        sec: r.get("sec"),
        valid_date: r.bit("valid", 0),
        valid_time: r.bit("valid", 1),
        fully_resolved: r.bit("valid", 2),
        valid_mag: r.bit("valid", 3),
        valid_reserved: r.bits("valid", 4, 4),
        t_acc: r.get("t_acc"),
        nano: r.get("nano"),
        fix_type: fix(r, "fix_type"),
        gnss_fix_ok: r.bit("flags", 0),
        diff_soln: r.bit("flags", 1),
        psm_state: r.bits("flags", 2, 3),
        head_veh_valid: r.bit("flags", 5),
        carr_soln: carr_soln(r, "flags", 6),
        reserved: r.bits("flags2", 0, 5),
        confirmed_avai: r.bit("flags2", 5),
        confirmed_date: r.bit("flags2", 6),
        confirmed_time: r.bit("flags2", 7),
        num_sv: r.get("num_sv"),
        lon: r.f64_per("lon", 1e7),
        lat: r.f64_per("lat", 1e7),
        height: r.get("height"),
        h_msl: r.get("h_msl"),
        h_acc: r.get("h_acc"),
        v_acc: r.get("v_acc"),
        vel_n: r.get("vel_n"),
        vel_e: r.get("vel_e"),
        vel_d: r.get("vel_d"),
        g_speed: r.get("g_speed"),
        head_mot: r.f64_per("head_mot", 1e5),
        s_acc: r.get("s_acc"),
        head_acc: r.f64_per("head_acc", 1e5),
        p_dop: r.f32_per("p_dop", 100.0),
        invalid_llh: r.bit("flags3", 0),
        last_correction_age: r.bits("flags3", 1, 4),
        reserved1: r.bits("flags3", 5, 8),
        auth_time: r.bit("flags3", 13),
        nma_fix_status: r.bit("flags3", 14),
        flags3_reserved: r.bits("flags3", 15, 1),
        head_veh: r.f64_per("head_veh", 1e5),
        mag_dec: r.f32_per("mag_dec", 100.0),
        mag_acc: r.f32_per("mag_acc", 100.0),
    }
}

fn nav_sat_sv(r: Raw<'_>) -> NavSatSv {
    let on = |at| r.bit("flags", at);
    NavSatSv {
        gnss_id: GnssId::from_raw(r.get("gnss_id")).expect("an unknown GNSS is kept"),
        sv_id: r.get("sv_id"),
        cno: r.get("cno"),
        elev: r.get("elev"),
        azim: r.get("azim"),
        pr_res: r.f32_per("pr_res", 10.0),
        quality_ind: r.bits("flags", 0, 3),
        sv_used: on(3),
        health: r.bits("flags", 4, 2),
        diff_corr: on(6),
        smoothed: on(7),
        orbit_source: r.bits("flags", 8, 3),
        eph_avail: on(11),
        alm_avail: on(12),
        ano_avail: on(13),
        aop_avail: on(14),
        reserved13: on(15),
        sbas_corr_used: on(16),
        rtcm_corr_used: on(17),
        slas_corr_used: on(18),
        spartn_corr_used: on(19),
        pr_corr_used: on(20),
        cr_corr_used: on(21),
        do_corr_used: on(22),
        clas_corr_used: on(23),
        lpp_corr_used: on(24),
        has_corr_used: on(25),
        flags_reserved: r.bits("flags", 26, 6),
    }
}

/// The message a vector records, built from its JSON fields (not from the bytes).
fn expected(frame: &Value) -> Message {
    let r = Raw(&frame["fields"]);
    match frame["message"].as_str().expect("message") {
        "NAV-POSLLH" => Message::NavPosllh(NavPosllh {
            itow: r.get("itow"),
            lon: r.f64_per("lon", 1e7),
            lat: r.f64_per("lat", 1e7),
            height: r.get("height"),
            h_msl: r.get("h_msl"),
            h_acc: r.get("h_acc"),
            v_acc: r.get("v_acc"),
        }),
        "NAV-STATUS" => Message::NavStatus(nav_status(&r)),
        "NAV-DOP" => Message::NavDop(nav_dop(&r)),
        "NAV-PVT" => Message::NavPvt(nav_pvt(&r)),
        "NAV-VELNED" => Message::NavVelned(NavVelned {
            itow: r.get("itow"),
            vel_n: r.get("vel_n"),
            vel_e: r.get("vel_e"),
            vel_d: r.get("vel_d"),
            speed: r.get("speed"),
            g_speed: r.get("g_speed"),
            heading: r.f64_per("heading", 1e5),
            s_acc: r.get("s_acc"),
            c_acc: r.f64_per("c_acc", 1e5),
        }),
        "NAV-TIMEUTC" => Message::NavTimeutc(NavTimeutc {
            itow: r.get("itow"),
            t_acc: r.get("t_acc"),
            nano: r.get("nano"),
            year: r.get("year"),
            month: r.get("month"),
            day: r.get("day"),
            hour: r.get("hour"),
            min: r.get("min"),
            sec: r.get("sec"),
            valid_tow: r.bit("valid", 0),
            valid_wkn: r.bit("valid", 1),
            valid_utc: r.bit("valid", 2),
            auth_status: r.bit("valid", 3),
            utc_standard: r.bits("valid", 4, 4),
        }),
        "NAV-SAT" => Message::NavSat(NavSat {
            itow: r.get("itow"),
            version: r.get("version"),
            num_svs: r.get("num_svs"),
            svs: group(&r.0["svs"], nav_sat_sv),
        }),
        "ACK-ACK" => Message::AckAck(Ack {
            cls_id: r.get("cls_id"),
            msg_id: r.get("msg_id"),
        }),
        "ACK-NAK" => Message::AckNak(Ack {
            cls_id: r.get("cls_id"),
            msg_id: r.get("msg_id"),
        }),
        "CFG-MSG" => Message::CfgMsg(CfgMsg {
            msg_class: r.get("msg_class"),
            msg_id: r.get("msg_id"),
            rate: r.get("rate"),
            ports: None,
        }),
        "CFG-RATE" => Message::CfgRate(CfgRate {
            meas_rate: r.get("meas_rate"),
            nav_rate: r.get("nav_rate"),
            time_ref: TimeRef::from_raw(r.get("time_ref")).expect("a time reference"),
        }),
        "MON-VER" => Message::MonVer(MonVer {
            sw_version: r.text("sw_version"),
            hw_version: r.text("hw_version"),
            extension: group(&r.0["extension"], |e| MonVerExtension {
                extension: e.text("extension"),
            }),
        }),
        other => panic!("vector not covered by this test: {other}"),
    }
}

/// The payload as the run-time codec shows it: the serde JSON of the expected message, through
/// its text (an `f32` keeps its shortest form).
fn expected_json(packet: &Packet) -> Value {
    let text = serde_json::to_string(packet).expect("JSON");
    let shown: Value = serde_json::from_str(&text).expect("JSON");
    shown["payload"].clone()
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
        golden::frame(
            &interp,
            name,
            &bytes,
            Some(&command),
            &expected_json(&packet),
        );
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
