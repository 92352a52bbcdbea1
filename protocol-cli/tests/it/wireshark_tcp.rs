//! The Wireshark dissector's TCP registration, run headless in `tshark` against `protocol
//! decode` on the same bytes: for every bundled spec and the feature fixtures of the `wireshark`
//! test (a bit stream, HDLC and SLIP escaping), the golden vectors' frames as one TCP stream
//! cut into segments of 7 bytes, to the port set with `-o NAME.tcp_ports:5760`. Wireshark
//! desegments a frame cut by a segment's end as the dissector asks (the bytes a length names,
//! or for an escaped frame one segment more until its closing flag). Both sides must find the
//! same frames, and every value `decode` prints must be the value of the dissector's field of
//! that name. Without `tshark` the test says so and passes, unless `PROTOCOL_REQUIRE_TSHARK`
//! is set, as CI sets it.

use crate::{dissect, support};

use std::path::{Path, PathBuf};
use std::process::Command;

use dissect::{
    SPECS, Tally, check_frame, dissector_name, frames_of, tshark_available, vector_bytes,
};
use serde_json::Value;
use support::{interpreter_at, json_lines, protocol, text};

const PORT: u16 = 5760;
/// Bytes per segment: fewer than most frames, so most frames are desegmented.
const SEGMENT: usize = 7;

/// An Ethernet frame carrying an IPv4 datagram carrying the TCP segment `payload` at sequence
/// number `seq` (checksums unset but the IP header's: Wireshark verifies neither by default).
fn tcp_packet(payload: &[u8], seq: u32) -> Vec<u8> {
    let mut p = vec![0x02, 0, 0, 0, 0, 2, 0x02, 0, 0, 0, 0, 1, 0x08, 0x00];
    let total = (20 + 20 + payload.len()) as u16;
    let mut ip = vec![0x45, 0];
    ip.extend_from_slice(&total.to_be_bytes());
    ip.extend_from_slice(&[0, 1, 0x40, 0, 64, 6, 0, 0, 10, 0, 0, 1, 10, 0, 0, 2]);
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
    p.extend_from_slice(&PORT.to_be_bytes());
    p.extend_from_slice(&seq.to_be_bytes());
    // Acknowledgement number 1; a 20-byte header; PSH and ACK; the window; no checksum.
    p.extend_from_slice(&[0, 0, 0, 1, 0x50, 0x18, 0xFF, 0xFF, 0, 0, 0, 0]);
    p.extend_from_slice(payload);
    p
}

/// A classic pcap file of Ethernet packets, a millisecond apart.
fn pcap(packets: &[Vec<u8>]) -> Vec<u8> {
    let mut out = Vec::new();
    for word in [0xA1B2_C3D4u32, 0x0004_0002, 0, 0, 65535, 1] {
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

/// The spec at `spec_path` (dissector `spec`) on `bytes` as one TCP stream, in `direction`.
fn tcp(spec: &str, spec_path: &str, bytes: &[u8], direction: Option<&str>, label: &str) -> Tally {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("wireshark-tcp");
    std::fs::create_dir_all(&dir).expect("dir");
    let out = protocol(
        &[
            "gen",
            "wireshark",
            spec_path,
            "-o",
            dir.to_str().expect("utf-8"),
        ],
        b"",
    );
    assert!(out.status.success(), "{spec}: {}", text(&out.stderr));
    let lua = dir.join(format!("{spec}.lua"));
    let mut seq = 1000u32;
    let mut packets = Vec::new();
    for segment in bytes.chunks(SEGMENT) {
        packets.push(tcp_packet(segment, seq));
        seq += segment.len() as u32;
    }
    let path = dir.join(format!("{label}.pcap"));
    std::fs::write(&path, pcap(&packets)).expect("pcap");
    let hex: String = bytes.iter().map(|b| format!("{b:02x}")).collect();
    let mut args = vec!["decode", spec_path, "--hex", "--format", "json"];
    if let Some(d) = direction {
        args.extend(["--direction", d]);
    }
    let decoded = protocol(&args, hex.as_bytes());
    let frames: Vec<Value> = json_lines(&decoded.stdout)
        .into_iter()
        .filter(|f| f.get("hex").is_some())
        .collect();
    let pdml = tshark(spec, &lua, &path, direction, label);
    let p = interpreter_at(spec_path);
    let name = dissector_name(&pdml, spec);
    let shown = frames_of(&pdml, &name);
    let got: Vec<&str> = shown.iter().map(|s| s.hex.as_str()).collect();
    let want: Vec<&str> = frames
        .iter()
        .map(|f| f["hex"].as_str().unwrap_or(""))
        .collect();
    assert_eq!(
        got, want,
        "{label}: the dissector and decode find other frames"
    );
    let mut tally = Tally {
        frames: frames.len(),
        fields: 0,
    };
    for (frame, shown) in frames.iter().zip(&shown) {
        tally.fields += check_frame(p.protocol(), &name, direction, frame, shown, label);
    }
    tally
}

/// `tshark -T pdml` of a capture with the dissector on the TCP port.
fn tshark(spec: &str, lua: &Path, pcap: &Path, direction: Option<&str>, label: &str) -> String {
    let taken = Command::new("tshark")
        .args(["-G", "protocols"])
        .output()
        .expect("tshark runs");
    let taken = text(&taken.stdout)
        .lines()
        .any(|l| l.split('\t').nth(2) == Some(spec));
    let name = if taken {
        format!("{spec}_spec")
    } else {
        spec.to_string()
    };
    let mut cmd = Command::new("tshark");
    cmd.arg("-X")
        .arg(format!("lua_script:{}", lua.display()))
        .arg("-r")
        .arg(pcap)
        .args(["-T", "pdml", "-o", &format!("{name}.tcp_ports:{PORT}")]);
    if let Some(d) = direction {
        cmd.args(["-o", &format!("{name}.direction:{d}")]);
    }
    let run = cmd.output().expect("tshark runs");
    let err = text(&run.stderr);
    assert!(
        run.status.success() && !err.contains("Lua") && !err.contains("Dissector bug"),
        "{label}: tshark: {err}"
    );
    text(&run.stdout)
}

#[test]
fn every_spec_dissects_over_tcp_as_decode_decodes() {
    if !tshark_available() {
        return;
    }
    let fixtures = ["bit_stream", "escaped_hdlc", "escaped_slip"];
    let mut runs: Vec<(String, String, String, &[&str])> = SPECS
        .iter()
        .map(|(spec, file, dirs)| {
            (
                spec.to_string(),
                format!("specs/{spec}.toml"),
                file.to_string(),
                *dirs,
            )
        })
        .collect();
    for spec in fixtures {
        runs.push((
            spec.to_string(),
            format!("protocol-codegen/tests/features/{spec}.toml"),
            format!("{spec}.json"),
            &[],
        ));
    }
    let mut total = Tally::default();
    let mut failed = Vec::new();
    for (spec, spec_path, file, directions) in &runs {
        let (frames, _) = vector_bytes(file);
        let passes: Vec<Option<&str>> = if directions.is_empty() {
            vec![None]
        } else {
            directions.iter().map(|d| Some(*d)).collect()
        };
        for d in passes {
            let label = format!("{spec}{}-tcp", d.map_or(String::new(), |d| format!("-{d}")));
            let tally = std::panic::catch_unwind(|| tcp(spec, spec_path, &frames, d, &label))
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
        "TCP total: {} frames, {} fields compared",
        total.frames, total.fields
    );
    assert!(failed.is_empty(), "failed: {failed:?}");
}
