//! The Wireshark dissector of `protocol gen wireshark` on its other transports, run headless in
//! `tshark` against `protocol decode` on the same frames, as the `wireshark` test does on raw
//! serial captures:
//!
//! * UDP: for every bundled spec, its golden vectors' frames in Ethernet/IPv4/UDP datagrams of
//!   one, two or three whole frames each, to a port set with the dissector's preference
//!   (`-o NAME.udp_ports:5760`); datagrams to another port must not be dissected.
//! * SocketCAN: `examples/captures/scout_can.log` as a pcap of link type 227 (written by
//!   `protocol export pcap --candump`), found by the dissector's heuristic on the CAN dissector;
//!   and DroneCAN's golden frames, whose command is a member of the CAN id (`can_id_bits`).
//!
//! Both sides must find the same frames, and every value `decode` prints must be the value of
//! the dissector's field of that name. Without `tshark` the test says so and checks nothing
//! more, unless `PROTOCOL_REQUIRE_TSHARK` is set, as CI sets it.

use crate::dissect;
use crate::support;

use std::path::{Path, PathBuf};
use std::process::Command;

use dissect::{
    SPECS, Tally, check_frame, dissector_name, frames_of, tshark_available, vector_bytes,
};
use serde_json::Value;
use support::{interpreter, json_lines, protocol, text};

/// The UDP port the dissector is told to take, and one it is not.
const PORT: u16 = 5760;
const OTHER_PORT: u16 = 5761;

/// A classic pcap file of link type `link` holding `packets`, a millisecond apart.
fn pcap(link: u32, packets: &[Vec<u8>]) -> Vec<u8> {
    let mut out = Vec::new();
    // Magic, version 2.4 (two little-endian u16), zone, accuracy, snap length, link type.
    for word in [0xA1B2_C3D4u32, 0x0004_0002, 0, 0, 65535, link] {
        out.extend_from_slice(&word.to_le_bytes());
    }
    for (i, p) in packets.iter().enumerate() {
        let len = p.len() as u32;
        for word in [1_700_000_000, i as u32 * 1000, len, len] {
            out.extend_from_slice(&word.to_le_bytes());
        }
        out.extend_from_slice(p);
    }
    out
}

/// An Ethernet frame carrying an IPv4 datagram carrying a UDP datagram of `payload` to `port`.
fn udp_packet(payload: &[u8], port: u16) -> Vec<u8> {
    let mut p = Vec::new();
    p.extend_from_slice(&[0x02, 0, 0, 0, 0, 2, 0x02, 0, 0, 0, 0, 1, 0x08, 0x00]);
    let total = (20 + 8 + payload.len()) as u16;
    let mut ip = vec![0x45, 0];
    ip.extend_from_slice(&total.to_be_bytes());
    ip.extend_from_slice(&[0, 1, 0x40, 0, 64, 17, 0, 0, 10, 0, 0, 1, 10, 0, 0, 2]);
    let mut sum: u32 = ip
        .chunks(2)
        .map(|w| u32::from(u16::from_be_bytes([w[0], w[1]])))
        .sum();
    while sum > 0xFFFF {
        sum = (sum & 0xFFFF) + (sum >> 16);
    }
    ip[10..12].copy_from_slice(&(!(sum as u16)).to_be_bytes());
    p.extend_from_slice(&ip);
    p.extend_from_slice(&40000u16.to_be_bytes());
    p.extend_from_slice(&port.to_be_bytes());
    p.extend_from_slice(&((8 + payload.len()) as u16).to_be_bytes());
    // No UDP checksum (zero: none, allowed over IPv4).
    p.extend_from_slice(&[0, 0]);
    p.extend_from_slice(payload);
    p
}

/// The name of the spec's dissector: `NAME_spec` when Wireshark has a protocol `NAME` already.
fn proto_name(spec: &str) -> String {
    let out = Command::new("tshark")
        .args(["-G", "protocols"])
        .output()
        .expect("tshark runs");
    let taken = text(&out.stdout)
        .lines()
        .any(|l| l.split('\t').nth(2) == Some(spec));
    if taken {
        format!("{spec}_spec")
    } else {
        spec.to_string()
    }
}

/// Runs tshark with the dissector on a capture; its PDML.
fn tshark(lua: &Path, pcap: &Path, prefs: &[String], label: &str) -> String {
    let mut cmd = Command::new("tshark");
    cmd.arg("-X")
        .arg(format!("lua_script:{}", lua.display()))
        .arg("-r")
        .arg(pcap)
        .args(["-T", "pdml"]);
    for p in prefs {
        cmd.args(["-o", p]);
    }
    let run = cmd.output().expect("tshark runs");
    let err = text(&run.stderr);
    assert!(
        run.status.success() && !err.contains("Lua"),
        "{label}: tshark: {err}"
    );
    text(&run.stdout)
}

/// Compares the frames the dissector shows in `pdml` with `decode`'s `frames`; `hex` gives a
/// decoded frame's bytes as the dissector shows them.
fn compare(
    spec: &str,
    pdml: &str,
    frames: &[Value],
    direction: Option<&str>,
    hex: &dyn Fn(&Value) -> String,
    label: &str,
) -> Tally {
    let p = interpreter(spec);
    let p = p.protocol();
    let name = dissector_name(pdml, spec);
    let shown = frames_of(pdml, &name);
    let got: Vec<&str> = shown.iter().map(|s| s.hex.as_str()).collect();
    let want: Vec<String> = frames.iter().map(hex).collect();
    assert_eq!(
        got, want,
        "{label}: the dissector and decode find other frames"
    );
    let mut tally = Tally {
        frames: frames.len(),
        fields: 0,
    };
    for (frame, shown) in frames.iter().zip(&shown) {
        tally.fields += check_frame(p, &name, direction, frame, shown, label);
    }
    tally
}

fn generate(spec: &str, dir: &Path) -> PathBuf {
    let out = protocol(
        &[
            "gen",
            "wireshark",
            &format!("specs/{spec}.toml"),
            "-o",
            dir.to_str().expect("utf-8"),
        ],
        b"",
    );
    assert!(out.status.success(), "{spec}: {}", text(&out.stderr));
    dir.join(format!("{spec}.lua"))
}

/// One spec's golden frames over UDP, in one direction.
fn udp(spec: &str, lua: &Path, bytes: &[u8], direction: Option<&str>, label: &str) -> Tally {
    let hex: String = bytes.iter().map(|b| format!("{b:02x}")).collect();
    let spec_path = format!("specs/{spec}.toml");
    let mut args = vec!["decode", spec_path.as_str(), "--hex", "--format", "json"];
    if let Some(d) = direction {
        args.extend(["--direction", d]);
    }
    let decoded = protocol(&args, hex.as_bytes());
    let frames: Vec<Value> = json_lines(&decoded.stdout)
        .into_iter()
        .filter(|f| f.get("hex").is_some())
        .collect();
    // Datagrams of 1, 2, 3, 1, 2, 3, ... whole frames, each followed by one to another port
    // (which must not be dissected).
    let mut packets = Vec::new();
    let mut at = 0;
    for n in (1..=3).cycle() {
        if at >= frames.len() {
            break;
        }
        let group = &frames[at..(at + n).min(frames.len())];
        let payload: Vec<u8> = group
            .iter()
            .flat_map(|f| support::unhex(f["hex"].as_str().expect("hex")))
            .collect();
        packets.push(udp_packet(&payload, PORT));
        packets.push(udp_packet(&payload, OTHER_PORT));
        at += n;
    }
    let dir = lua.parent().expect("dir");
    let path = dir.join(format!("{label}.pcap"));
    std::fs::write(&path, pcap(1, &packets)).expect("pcap");
    let name = proto_name(spec);
    let mut prefs = vec![format!("{name}.udp_ports:{PORT}")];
    if let Some(d) = direction {
        prefs.push(format!("{name}.direction:{d}"));
    }
    let pdml = tshark(lua, &path, &prefs, label);
    let hex_of = |f: &Value| f["hex"].as_str().unwrap_or("").to_string();
    compare(spec, &pdml, &frames, direction, &hex_of, label)
}

#[test]
fn every_spec_dissects_over_udp_as_decode_decodes() {
    if !tshark_available() {
        return;
    }
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("wireshark-udp");
    std::fs::create_dir_all(&dir).expect("dir");
    let mut total = Tally::default();
    let mut failed = Vec::new();
    for (spec, file, directions) in SPECS {
        let lua = generate(spec, &dir);
        let (frames, _) = vector_bytes(file);
        let passes: Vec<Option<&str>> = if directions.is_empty() {
            vec![None]
        } else {
            directions.iter().map(|d| Some(*d)).collect()
        };
        for d in passes {
            let label = format!("{spec}{}-udp", d.map_or(String::new(), |d| format!("-{d}")));
            let tally = std::panic::catch_unwind(|| udp(spec, &lua, &frames, d, &label))
                .unwrap_or_else(|_| {
                    failed.push(label.clone());
                    Tally::default()
                });
            println!("{label}: {} frames, {} fields", tally.frames, tally.fields);
            if tally.frames == 0 {
                failed.push(format!("{label}: no frame compared"));
            }
            total.frames += tally.frames;
            total.fields += tally.fields;
        }
    }
    println!(
        "UDP total: {} frames, {} fields compared",
        total.frames, total.fields
    );
    assert!(failed.is_empty(), "failed: {failed:?}");
}

/// A candump log of `spec` as a SocketCAN capture (link type 227, written by `protocol export
/// pcap --candump`), dissected by the CAN heuristic and compared with `decode --candump`.
fn socketcan(spec: &str, log: &Path, dir: &Path) -> Tally {
    let lua = generate(spec, dir);
    let path = dir.join(format!("{spec}_can.pcap"));
    let log = log.to_str().expect("utf-8");
    let out = protocol(
        &[
            "export",
            "pcap",
            "--candump",
            log,
            "-o",
            path.to_str().expect("utf-8"),
        ],
        b"",
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let pcap = std::fs::read(&path).expect("pcap");
    assert_eq!(
        pcap.get(20..24),
        Some(&227u32.to_le_bytes()[..]),
        "SocketCAN"
    );
    let spec_path = format!("specs/{spec}.toml");
    let decoded = protocol(
        &["decode", &spec_path, "--candump", log, "--format", "json"],
        b"",
    );
    assert!(decoded.status.success(), "{}", text(&decoded.stderr));
    // The frames of a command: the dissector's heuristic takes a CAN frame whose id names one.
    let frames: Vec<Value> = json_lines(&decoded.stdout)
        .into_iter()
        .filter(|f| f.get("command").is_some())
        .collect();
    let label = format!("{spec}-can");
    let pdml = tshark(&lua, &path, &[], &label);
    // The dissector shows a CAN frame as the frame the spec describes: the id (big-endian u32),
    // the data length and the data.
    let hex_of = |f: &Value| {
        let data = f["hex"].as_str().unwrap_or("");
        let id = f["can_id"].as_u64().expect("can_id");
        format!("{id:08x}{:02x}{data}", data.len() / 2)
    };
    compare(spec, &pdml, &frames, None, &hex_of, &label)
}

#[test]
fn a_socketcan_capture_dissects_as_decode_decodes() {
    if !tshark_available() {
        return;
    }
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("wireshark-can");
    std::fs::create_dir_all(&dir).expect("dir");
    let log = support::root().join("examples/captures/scout_can.log");
    let tally = socketcan("scout", &log, &dir);
    println!(
        "SocketCAN: {} frames, {} fields compared",
        tally.frames, tally.fields
    );
    assert!(tally.frames > 100, "{} frames", tally.frames);
}

/// DroneCAN's golden frames (pydronecan's), whose 29-bit ids hold the priority, the message type
/// id the command is found by, the service flag and the source node (`can_id_bits`): every id
/// member is a header value of the dissector, and the command is the message type's.
#[test]
fn can_id_members_dissect_as_decode_decodes() {
    if !tshark_available() {
        return;
    }
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("wireshark-can-ids");
    std::fs::create_dir_all(&dir).expect("dir");
    let path = support::root().join("tests/vectors/dronecan_pydronecan.json");
    let v: Value =
        serde_json::from_str(&std::fs::read_to_string(path).expect("vectors")).expect("JSON");
    let mut log = String::new();
    for (i, f) in v["frames"].as_array().expect("frames").iter().enumerate() {
        let id = f["can_id"].as_u64().expect("can_id");
        let data = f["data"].as_str().expect("data").to_uppercase();
        log.push_str(&format!(
            "(1700000000.{:06}) can0 {id:08X}#{data}\n",
            i * 1000
        ));
    }
    let log_path = dir.join("dronecan.log");
    std::fs::write(&log_path, log).expect("log");
    let tally = socketcan("dronecan", &log_path, &dir);
    println!(
        "DroneCAN over SocketCAN: {} frames, {} fields compared",
        tally.frames, tally.fields
    );
    let vectors = v["frames"].as_array().map_or(0, Vec::len);
    assert_eq!(tally.frames, vectors, "every golden frame decoded");
}
