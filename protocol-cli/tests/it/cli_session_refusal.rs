//! `protocol decode --session` on MSP, whose error replies (`!`, the spec's empty direction)
//! refuse the request of their command: an error reply after a request of its command is that
//! request's refusal (`"refused": true`, `refuses #N` in a table), a reply its answer, and an
//! error reply of a command nothing asked for pairs with nothing.

use crate::support;

use support::{json_lines, protocol, text};

const SPEC: &str = "specs/msp.toml";

/// STATUS asked and refused, ATTITUDE asked and answered (roll 1.0, pitch -1.0, yaw 90), and
/// an error reply of RC, which nothing asked for.
fn capture() -> Vec<u8> {
    let mut bytes = Vec::new();
    bytes.extend([0x24, 0x4D, 0x3C, 0x00, 0x65, 0x65]); // `$M<` STATUS
    bytes.extend([0x24, 0x4D, 0x21, 0x00, 0x65, 0x65]); // `$M!` STATUS
    bytes.extend([0x24, 0x4D, 0x3C, 0x00, 0x6C, 0x6C]); // `$M<` ATTITUDE
    bytes.extend([
        0x24, 0x4D, 0x3E, 0x06, 0x6C, 0x0A, 0x00, 0xF6, 0xFF, 0x5A, 0x00, 0x33,
    ]);
    bytes.extend([0x24, 0x4D, 0x21, 0x00, 0x69, 0x69]); // `$M!` RC
    bytes
}

#[test]
fn an_error_reply_is_the_refusal_of_the_request_of_its_command() {
    let out = protocol(
        &["decode", SPEC, "-", "--session", "--format", "json"],
        &capture(),
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let lines = json_lines(&out.stdout);
    let frames: Vec<_> = lines.iter().filter(|l| l.get("hex").is_some()).collect();
    assert_eq!(frames.len(), 5, "{lines:?}");
    let shown: Vec<_> = frames
        .iter()
        .map(|f| {
            (
                f["command"].as_str().unwrap_or_default().to_string(),
                f["header"]["direction"].as_u64(),
                f["answers"].as_u64(),
                f.get("refused").is_some(),
            )
        })
        .collect();
    let (lt, gt, bang) = (Some(0x3C), Some(0x3E), Some(0x21));
    assert_eq!(
        shown,
        [
            ("STATUS".to_string(), lt, None, false),
            ("STATUS".to_string(), bang, Some(0), true),
            ("ATTITUDE".to_string(), lt, None, false),
            ("ATTITUDE".to_string(), gt, Some(2), false),
            ("RC".to_string(), bang, None, false),
        ]
    );
    assert_eq!(frames[1]["refused"], true);
}

#[test]
fn a_table_says_which_request_a_refusal_refuses() {
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
    assert!(stdout.contains("refuses #0"), "{stdout}");
    assert!(stdout.contains("answers #2"), "{stdout}");
    assert!(
        stdout
            .contains("conversation: 2 answers paired with their requests, 0 requests unanswered"),
        "{stdout}"
    );
}
