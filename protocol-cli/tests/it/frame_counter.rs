//! Lost and reordered frames from a spec's frame counter (`counter = true`; Scout's `count`):
//! a capture is made with `protocol encode` from one frame of the bundled Scout capture, its
//! counter set to 0, 1, 2, ... 299 (wrapping at 256), with four frames dropped, two swapped
//! and one sent twice. `decode --stats` and the HTML report must count exactly that.

use crate::support;

use serde_json::Value;
use support::{json_lines, protocol, text};

/// The counters the capture leaves out.
const DROPPED: [u64; 4] = [10, 11, 12, 100];

/// The capture: frames with counters 0..300, wrapping at 256, with the changes above.
fn counters() -> Vec<u64> {
    let mut order: Vec<u64> = (0..300).filter(|c| !DROPPED.contains(c)).collect();
    // 51 arrives before 50.
    let at = order.iter().position(|&c| c == 50).expect("50");
    order.swap(at, at + 1);
    // 200 arrives twice.
    let at = order.iter().position(|&c| c == 200).expect("200");
    order.insert(at, 200);
    order
}

fn capture() -> Vec<u8> {
    let decoded = protocol(
        &[
            "decode",
            "specs/scout.toml",
            "examples/captures/scout.bin",
            "--format",
            "json",
        ],
        b"",
    );
    let template = json_lines(&decoded.stdout)
        .into_iter()
        .find(|v| v["command"] == "MOTION_STATUS")
        .expect("a MOTION_STATUS frame");
    let mut lines = String::new();
    for c in counters() {
        let mut frame = template.clone();
        frame["header"]["count"] = Value::from(c % 256);
        lines.push_str(&frame.to_string());
        lines.push('\n');
    }
    let encoded = protocol(&["encode", "specs/scout.toml"], lines.as_bytes());
    assert!(encoded.status.success(), "{}", text(&encoded.stderr));
    encoded.stdout
}

#[test]
fn decode_stats_and_the_report_count_lost_and_reordered_frames() {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("frame_counter");
    std::fs::create_dir_all(&dir).expect("dir");
    let bytes = capture();
    let frames = counters().len();
    let path = dir.join("scout_gaps.bin");
    std::fs::write(&path, &bytes).expect("write");
    let path_s = path.to_str().expect("utf-8");

    let expected = format!(
        "frame counter: 4 lost, 1 reordered, 1 repeated (of {frames} frames with a frame counter)"
    );
    let out = protocol(
        &[
            "decode",
            "specs/scout.toml",
            path_s,
            "--format",
            "json",
            "--stats",
        ],
        b"",
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let decoded = json_lines(&out.stdout);
    assert_eq!(decoded.len(), frames, "every frame decodes");
    let stats = text(&out.stderr);
    assert!(stats.contains(&expected), "{stats}");

    let html = dir.join("scout_gaps.html");
    let out = protocol(
        &[
            "report",
            "specs/scout.toml",
            path_s,
            "-o",
            html.to_str().expect("utf-8"),
        ],
        b"",
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let page = std::fs::read_to_string(&html).expect("the report");
    let row = format!(
        "<tr><th>frame counter</th><td>{}</td></tr>",
        &expected["frame counter: ".len()..]
    );
    assert!(page.contains(&row), "no `{row}` in the report");

    // A spec without a counter prints no such line.
    let out = protocol(
        &[
            "decode",
            "specs/hflink.toml",
            "examples/captures/hflink.bin",
            "--format",
            "json",
            "--stats",
        ],
        b"",
    );
    assert!(
        !text(&out.stderr).contains("frame counter"),
        "{}",
        text(&out.stderr)
    );
}
