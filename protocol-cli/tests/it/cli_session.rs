//! `protocol decode --session` on a half-duplex capture (`examples/captures/dynamixel1_bus.bin`:
//! a Dynamixel 1.0 controller and three servos on one wire): every frame of the ground truth
//! decodes, each instruction as a request and each status packet as the response that answers
//! the instruction right before it, of the same id; the READs of a servo that is not on the bus
//! are counted unanswered; and `--session` is refused for a spec without `[session]`.

use crate::support;

use support::{json_lines, protocol, root, text, truth};

const SPEC: &str = "specs/dynamixel1.toml";

fn capture() -> Vec<u8> {
    std::fs::read(root().join("examples/captures/dynamixel1_bus.bin")).expect("capture")
}

#[test]
fn a_half_duplex_capture_decodes_both_directions_and_pairs_them() {
    let out = protocol(
        &["decode", SPEC, "-", "--session", "--format", "json"],
        &capture(),
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let lines = json_lines(&out.stdout);
    let frames: Vec<_> = lines.iter().filter(|l| l.get("hex").is_some()).collect();
    let truth: Vec<_> = truth("dynamixel1_bus")
        .into_iter()
        .filter(|t| t["kind"] == "frame")
        .collect();
    assert_eq!(frames.len(), truth.len());
    let (mut statuses, mut unanswered_reads) = (0, 0);
    for (i, (f, t)) in frames.iter().zip(&truth).enumerate() {
        assert_eq!(f["hex"], t["hex"], "frame {i}");
        assert_eq!(f["frame"], i, "frame numbers count every frame");
        match f["direction"].as_str() {
            Some("response") => {
                statuses += 1;
                // A status answers the instruction right before it, to the same servo.
                let request = &frames[i - 1];
                assert_eq!(f["answers"], i - 1, "{f}");
                assert_eq!(request["direction"], "request");
                assert_eq!(request["header"]["id"], f["header"]["id"]);
                // A READ's status carries the bytes it asked for.
                if request["command"] == "READ" {
                    let asked = request["payload"]["length"].as_u64().expect("length");
                    let params = f["payload"]["params"].as_str().expect("params");
                    assert_eq!(params.len() as u64, 2 * asked, "{f}");
                }
            }
            Some("request") => {
                assert!(f.get("answers").is_none(), "{f}");
                let next = frames.get(i + 1);
                if f["header"]["id"] == 4 {
                    unanswered_reads += 1;
                    assert!(next.is_none_or(|n| n["direction"] == "request"), "{f}");
                }
                // A broadcast expects no status.
                if f["header"]["id"] == 0xFE {
                    assert!(next.is_some_and(|n| n["direction"] == "request"), "{f}");
                }
            }
            other => panic!("frame {i} has direction {other:?}"),
        }
    }
    // 20 cycles of 3 servos, a WRITE's and a READ's status each; a READ of servo 4 every
    // fourth cycle, unanswered.
    assert_eq!((statuses, unanswered_reads), (120, 5));
}

#[test]
fn stats_count_the_unanswered_requests() {
    let out = protocol(
        &[
            "decode",
            SPEC,
            "-",
            "--session",
            "--stats",
            "--format",
            "table",
        ],
        &capture(),
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    assert!(
        stdout.contains(
            "conversation: 120 answers paired with their requests, 5 requests unanswered"
        ),
        "{stdout}"
    );
    assert!(stdout.contains("answers #"), "{stdout}");
}

#[test]
fn session_needs_a_spec_with_a_conversation() {
    let out = protocol(
        &["decode", "specs/referee.toml", "-", "--session"],
        &[0u8; 4],
    );
    assert!(!out.status.success());
    assert!(
        text(&out.stderr).contains("[session]"),
        "{}",
        text(&out.stderr)
    );
}
