//! `protocol decode --session` types a frame's register bytes by the spec's `[registers]`: on
//! the half-duplex capture (`examples/captures/dynamixel1_bus.bin`, written by
//! `protocol-cli/examples/make_captures`), each WRITE shows the goal position it writes and
//! each status answering a READ the present position it reads, which the capture's servos set
//! 3 below their goal; a READ that starts and ends inside registers shows the whole ones and
//! names the cut ones; an answer shorter than its READ asked says so.

use std::collections::HashMap;

use crate::support;

use support::{json_lines, protocol, root, text};

const SPEC: &str = "specs/dynamixel1.toml";

/// `FF FF id len instruction params checksum`, the checksum `~(id + len + ... ) & 0xFF`.
fn packet(id: u8, instruction: u8, params: &[u8]) -> Vec<u8> {
    let len = u8::try_from(params.len() + 2).expect("short");
    let mut body = vec![id, len, instruction];
    body.extend_from_slice(params);
    let sum = body.iter().fold(0u8, |s, b| s.wrapping_add(*b));
    let mut out = vec![0xFF, 0xFF];
    out.extend_from_slice(&body);
    out.push(!sum);
    out
}

fn decode(input: &[u8]) -> Vec<serde_json::Value> {
    let out = protocol(
        &["decode", SPEC, "-", "--session", "--format", "json"],
        input,
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    json_lines(&out.stdout)
        .into_iter()
        .filter(|l| l.get("hex").is_some())
        .collect()
}

#[test]
fn statuses_of_the_capture_decode_to_the_positions_read() {
    let capture =
        std::fs::read(root().join("examples/captures/dynamixel1_bus.bin")).expect("capture");
    let frames = decode(&capture);
    let mut goal: HashMap<u64, u64> = HashMap::new();
    let (mut positions, mut leds) = (0, Vec::new());
    for f in &frames {
        assert!(
            f.get("registers_note").is_none(),
            "whole registers only: {f}"
        );
        let id = f["header"]["id"].as_u64().expect("id");
        let registers = &f["registers"];
        match (f["direction"].as_str(), f["command"].as_str()) {
            (Some("request"), Some("WRITE")) if id == 0xFE => {
                leds.push(registers["led"].as_u64().expect("led"));
            }
            (Some("request"), Some("WRITE")) => {
                let g = registers["goal_position"].as_u64().expect("goal");
                assert_eq!(registers.as_object().map(|o| o.len()), Some(1), "{f}");
                goal.insert(id, g);
            }
            (Some("request"), _) => assert!(registers.is_null(), "{f}"),
            (Some("response"), _) => {
                let request = &frames[f["answers"].as_u64().expect("answers") as usize];
                if request["command"] == "READ" {
                    let present = registers["present_position"].as_u64().expect("position");
                    assert_eq!(present + 3, goal[&id], "{f}");
                    positions += 1;
                } else {
                    // A WRITE's status carries no data.
                    assert_eq!(registers.as_object().map(|o| o.len()), None, "{f}");
                }
            }
            other => panic!("unexpected frame {other:?}: {f}"),
        }
    }
    // 20 cycles of 3 servos; a broadcast LED write every fifth cycle, on every other one.
    assert_eq!(positions, 60);
    assert_eq!(leds, [1, 0, 1, 0]);
}

#[test]
fn a_read_across_register_boundaries_shows_the_whole_ones_and_names_the_cut_ones() {
    let mut wire = packet(1, 0x02, &[37, 4]);
    wire.extend(packet(1, 0x00, &[0x11, 0x22, 0x33, 0x44]));
    let frames = decode(&wire);
    assert_eq!(frames.len(), 2);
    let status = &frames[1];
    assert_eq!(status["answers"], 0);
    assert_eq!(
        status["registers"],
        serde_json::json!({ "present_speed": 0x3322 })
    );
    let note = status["registers_note"].as_str().expect("a note");
    assert!(
        note.contains("`present_position`") && note.contains("`present_load`"),
        "{note}"
    );
}

#[test]
fn an_answer_shorter_than_asked_says_so() {
    let mut wire = packet(2, 0x02, &[42, 4]);
    wire.extend(packet(2, 0x00, &[120, 41]));
    let frames = decode(&wire);
    let status = &frames[1];
    // Present voltage is 0.1 V per unit.
    assert_eq!(
        status["registers"],
        serde_json::json!({ "present_voltage": 12.0, "present_temperature": 41 })
    );
    let note = status["registers_note"].as_str().expect("a note");
    assert!(note.contains("carries 2 of the 4 bytes asked"), "{note}");
}
