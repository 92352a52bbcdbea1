//! The Wireshark dissector of `protocol gen wireshark`, run headless in `tshark`, against the
//! run-time codec (`protocol decode`) on the same bytes: for every bundled spec, the golden
//! vectors' frames (one capture of them all, cut into 64-byte packets, so frames straddle
//! packets) and the vector files' noisy streams (cut into 7-byte packets). Both sides must find
//! the same frames (same bytes, same command), and every value `decode` prints must be the
//! value of the dissector's field of that name (floats to the 6 or 15 significant digits that
//! tshark prints them with; a scaled value of type `f32` to 7, as the dissector computes it in
//! double precision). The UDP and SocketCAN registrations are tested in
//! `wireshark_transports`.
//!
//! The test needs `tshark`. Without it, it says so and checks nothing more, unless
//! `PROTOCOL_REQUIRE_TSHARK` is set, as CI sets it: then a missing tshark fails the test.

use crate::{dissect, support};

use std::path::{Path, PathBuf};
use std::process::Command;

use dissect::{
    SPECS, Tally, check_frame, dissector_name, frames_of, tshark_available, vector_bytes,
};
use serde_json::Value;
use support::{interpreter_at, json_lines, protocol, text};

/// Runs the dissector and `decode` over `bytes`, cut into packets of `chunk` bytes, and
/// compares them frame by frame and field by field.
/// `spec` is a bundled spec's name; `spec_path` its file (a fixture's elsewhere).
fn compare(
    (spec, spec_path): (&str, &str),
    lua: &Path,
    bytes: &[u8],
    chunk: usize,
    direction: Option<&str>,
    label: &str,
) -> Tally {
    let p = interpreter_at(spec_path);
    let p = p.protocol();
    let dir = lua.parent().expect("dir");
    let hex: String = bytes.iter().map(|b| format!("{b:02x}")).collect();
    let pcap = dir.join(format!("{label}.pcap"));
    let pcap_s = pcap.to_str().expect("utf-8 path");
    let out = protocol(
        &[
            "export",
            "pcap",
            "--hex",
            "--chunk",
            &chunk.to_string(),
            "-o",
            pcap_s,
        ],
        hex.as_bytes(),
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let mut args = vec!["decode", spec_path, "--hex", "--format", "json"];
    if let Some(d) = direction {
        args.extend(["--direction", d]);
    }
    let decoded = protocol(&args, hex.as_bytes());
    let frames: Vec<Value> = json_lines(&decoded.stdout)
        .into_iter()
        .filter(|f| f.get("hex").is_some())
        .collect();
    let mut tshark = Command::new("tshark");
    tshark
        .arg("-X")
        .arg(format!("lua_script:{}", lua.display()))
        .args(["-r", pcap_s, "-T", "pdml"]);
    if let Some(d) = direction {
        tshark.args(["-o", &format!("{spec}.direction:{d}")]);
    }
    let run = tshark.output().expect("tshark runs");
    let err = text(&run.stderr);
    assert!(
        run.status.success() && !err.contains("Lua"),
        "{label}: tshark: {err}"
    );
    let pdml = text(&run.stdout);
    // The dissector of a spec whose name Wireshark has already is `NAME_spec`.
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
        tally.fields += check_frame(p, &name, direction, frame, shown, label);
    }
    tally
}

#[test]
fn every_spec_dissects_as_decode_decodes() {
    if !tshark_available() {
        return;
    }
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("wireshark");
    std::fs::create_dir_all(&dir).expect("dir");
    let mut total = Tally::default();
    let failed = std::cell::RefCell::new(Vec::new());
    for (spec, file, directions) in SPECS {
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
        let lua = dir.join(format!("{spec}.lua"));
        let spec_path = format!("specs/{spec}.toml");
        let (frames, streams) = vector_bytes(file);
        let passes: Vec<Option<&str>> = if directions.is_empty() {
            vec![None]
        } else {
            directions.iter().map(|d| Some(*d)).collect()
        };
        for d in passes {
            let tag = format!("{spec}{}", d.map_or(String::new(), |d| format!("-{d}")));
            let run = |bytes: &[u8], chunk: usize, label: String| {
                std::panic::catch_unwind(|| {
                    compare((spec, &spec_path), &lua, bytes, chunk, d, &label)
                })
                .unwrap_or_else(|_| {
                    failed.borrow_mut().push(label);
                    Tally::default()
                })
            };
            let vectors = run(&frames, 64, format!("{tag}-vectors"));
            let mut noisy = Tally::default();
            for (k, s) in streams.iter().enumerate() {
                let t = run(s, 7, format!("{tag}-stream{k}"));
                noisy.frames += t.frames;
                noisy.fields += t.fields;
            }
            println!(
                "{tag}: vectors {} frames, {} fields; noisy streams {} frames, {} fields",
                vectors.frames, vectors.fields, noisy.frames, noisy.fields
            );
            if vectors.frames == 0 {
                failed
                    .borrow_mut()
                    .push(format!("{tag}: no vector frame compared"));
            }
            total.frames += vectors.frames + noisy.frames;
            total.fields += vectors.fields + noisy.fields;
        }
    }
    println!(
        "total: {} frames, {} fields compared",
        total.frames, total.fields
    );
    assert!(failed.borrow().is_empty(), "failed: {:?}", failed.borrow());
}

/// The feature fixtures with golden frames of their own whose field kinds the bundled specs do
/// not use: number formats (scaled floats, 40- to 56-bit integers, halves), inverted bools, bit
/// streams with signed and scaled members of up to 38 bits, and byte escaping between flags as
/// HDLC (an XOR) and SLIP (a table) do it (the frames compared unescaped, as decode prints them),
/// and a packet carried in a payload (the carried command and its payload's fields).
const FIXTURES: &[&str] = &[
    "number_formats",
    "inverted_bool",
    "bit_stream",
    "escaped_hdlc",
    "escaped_slip",
    "nested_packets",
];

#[test]
fn feature_fixtures_dissect_as_decode_decodes() {
    if !tshark_available() {
        return;
    }
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("wireshark_fixtures");
    std::fs::create_dir_all(&dir).expect("dir");
    for spec in FIXTURES {
        let spec_path = format!("protocol-codegen/tests/features/{spec}.toml");
        let out = protocol(
            &[
                "gen",
                "wireshark",
                &spec_path,
                "-o",
                dir.to_str().expect("utf-8"),
            ],
            b"",
        );
        assert!(out.status.success(), "{spec}: {}", text(&out.stderr));
        let lua = dir.join(format!("{spec}.lua"));
        let (frames, streams) = vector_bytes(&format!("{spec}.json"));
        let t = compare(
            (spec, &spec_path),
            &lua,
            &frames,
            64,
            None,
            &format!("{spec}-vectors"),
        );
        assert!(t.frames > 0 && t.fields > 0, "{spec}: nothing compared");
        let mut noisy = Tally::default();
        for (k, s) in streams.iter().enumerate() {
            let n = compare(
                (spec, &spec_path),
                &lua,
                s,
                7,
                None,
                &format!("{spec}-stream{k}"),
            );
            noisy.frames += n.frames;
            noisy.fields += n.fields;
        }
        println!(
            "{spec}: vectors {} frames, {} fields; noisy streams {} frames, {} fields",
            t.frames, t.fields, noisy.frames, noisy.fields
        );
    }
}
