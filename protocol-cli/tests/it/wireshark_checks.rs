//! The Wireshark dissector on the check fixtures of `protocol-codegen/tests/features`: a CRC-24
//! in three bytes (`crc24_rtcm3.toml`, RTCM 3 frames from pyrtcm), seeded sums and XORs and
//! CRCs narrower than a byte register (`seeded_checks.toml`), and a check stored before the
//! payload it covers (`check_before_payload.toml`). In `tshark`, every check of every good
//! frame shows `[correct]`, a frame with a changed payload byte is a rejected candidate with a
//! bad check, and the frame after it is found: the frames `protocol decode` finds, in order.
//! Without `tshark` the test says so and passes, unless `PROTOCOL_REQUIRE_TSHARK` is set.

use crate::support;

use std::path::PathBuf;
use std::process::Command;

use support::{json_lines, protocol, text};

fn tshark_available() -> bool {
    let found = Command::new("tshark").arg("--version").output().is_ok();
    if !found {
        assert!(
            std::env::var_os("PROTOCOL_REQUIRE_TSHARK").is_none(),
            "PROTOCOL_REQUIRE_TSHARK is set and no tshark is on the PATH"
        );
        eprintln!("no tshark on the PATH: the dissectors are not run");
    }
    found
}

/// The frames `protocol decode` finds in `hex`, as hex.
fn decoded(spec: &str, hex: &str) -> Vec<String> {
    let out = protocol(
        &["decode", spec, "--hex", "--format", "json"],
        hex.as_bytes(),
    );
    json_lines(&out.stdout)
        .into_iter()
        .filter_map(|f| f.get("hex").and_then(|h| h.as_str()).map(str::to_string))
        .collect()
}

/// `tshark -T pdml` of `hex` cut into packets of `chunk` bytes, with the dissector of `spec`.
fn pdml(dir: &std::path::Path, name: &str, spec: &str, hex: &str, chunk: usize) -> String {
    let out = protocol(
        &["gen", "wireshark", spec, "-o", dir.to_str().expect("utf-8")],
        b"",
    );
    assert!(out.status.success(), "{spec}: {}", text(&out.stderr));
    let pcap = dir.join(format!("{name}-{chunk}.pcap"));
    let pcap_s = pcap.to_str().expect("utf-8");
    let chunk_s = chunk.to_string();
    let out = protocol(
        &["export", "pcap", "--hex", "--chunk", &chunk_s, "-o", pcap_s],
        hex.as_bytes(),
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let lua = dir.join(format!("{name}.lua"));
    let run = Command::new("tshark")
        .arg("-X")
        .arg(format!("lua_script:{}", lua.display()))
        .args(["-r", pcap_s, "-T", "pdml"])
        .output()
        .expect("tshark runs");
    let err = text(&run.stderr);
    assert!(
        run.status.success() && !err.contains("Lua"),
        "{name}: {err}"
    );
    text(&run.stdout)
}

/// The `show` attribute of every PDML line whose field is `field` (`NAME.frame`, ...).
fn shown(pdml: &str, field: &str) -> Vec<String> {
    let key = format!("name=\"{field}\"");
    pdml.lines()
        .filter(|l| l.contains(&key))
        .filter_map(|l| l.split(" show=\"").nth(1)?.split('"').next())
        .map(|s| s.replace(':', ""))
        .collect()
}

#[test]
fn the_dissector_computes_narrow_seeded_and_forward_checks() {
    if !tshark_available() {
        return;
    }
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("wireshark_checks");
    std::fs::create_dir_all(&dir).expect("dir");
    // (fixture, good frames, a good frame with its byte `at` changed).
    let cases: [(&str, &[&str], usize); 3] = [
        (
            "crc24_rtcm3",
            &[
                "d300133ed7d30302980edeef34f264d93d09d4be30efc607c4",
                "d300153ee01103097d3c3648022b6da4160b2df529123a982e1eab",
            ],
            5,
        ),
        (
            "seeded_checks",
            &["7e0205b912d4feb004fe07153732", "7e0100b3120ff60082"],
            6,
        ),
        (
            "check_before_payload",
            &["aa55bf1905024fd4feb004fe", "aa550000000107"],
            8,
        ),
    ];
    for (name, frames, at) in cases {
        let spec = format!("protocol-codegen/tests/features/{name}.toml");
        let mut bad = support::unhex(frames[0]);
        bad[at] ^= 0x01;
        let bad: String = bad.iter().map(|b| format!("{b:02x}")).collect();
        let good = frames.concat();
        let stream = format!("{bad}{good}");
        assert_eq!(decoded(&spec, &good), frames, "{name}: decode");
        for chunk in [5, 64] {
            let out = pdml(&dir, name, &spec, &stream, chunk);
            assert_eq!(
                shown(&out, &format!("{name}.frame")),
                frames,
                "{name} at {chunk}"
            );
            let verdicts: Vec<&str> = out
                .lines()
                .filter(|l| l.contains("[correct]") || l.contains("[wrong]"))
                .collect();
            assert!(!verdicts.is_empty(), "{name}: no check shown");
            assert!(
                verdicts.iter().all(|l| l.contains("[correct]")),
                "{name}: {verdicts:?}"
            );
            assert_eq!(
                shown(&out, &format!("{name}.rejected")).len(),
                1,
                "{name} at {chunk}: the changed frame is one rejected candidate"
            );
            assert!(
                out.contains(&format!("name=\"{name}.bad_check\"")),
                "{name}"
            );
            println!(
                "{name} in {chunk}-byte packets: {} frames, {} checks",
                frames.len(),
                verdicts.len()
            );
        }
    }
}
