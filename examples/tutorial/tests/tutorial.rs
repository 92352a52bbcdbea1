//! `docs/tutorial.md` shows this crate as it is: every block marked `file=PATH` is that file of
//! the tutorial's crate (`PATH` from the crate's root), which is this crate but for its
//! `Cargo.toml` (the tutorial's crate belongs to no workspace), and the host's run prints what
//! the tutorial shows and writes the committed capture. (The `protocol` commands of the
//! tutorial are checked by `protocol-cli/tests/it/tutorial.rs`; `scripts/tutorial.sh` follows the
//! whole tutorial in a crate of its own.)

use std::path::{Path, PathBuf};
use std::process::Command;

use rover_link::rover::{Drive, Header, Message, Packet};

/// A fenced code block: its info string and its text.
struct Block {
    info: String,
    text: String,
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// This crate's directory, where the tutorial's crate-relative paths point.
fn krate() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()
}

fn read(path: &str) -> String {
    std::fs::read_to_string(root().join(path)).unwrap_or_else(|e| panic!("{path}: {e}"))
}

fn blocks() -> Vec<Block> {
    let mut out = Vec::new();
    let mut open: Option<Block> = None;
    for line in read("docs/tutorial.md").lines() {
        match (&mut open, line.strip_prefix("```")) {
            (None, Some(info)) => {
                open = Some(Block {
                    info: info.to_string(),
                    text: String::new(),
                })
            }
            (Some(_), Some("")) => out.extend(open.take()),
            (Some(b), _) => {
                b.text.push_str(line);
                b.text.push('\n');
            }
            (None, None) => {}
        }
    }
    assert!(open.is_none(), "an unclosed code block");
    out
}

/// The value of `key=` in a block's info string.
fn attr<'a>(b: &'a Block, key: &str) -> Option<&'a str> {
    b.info
        .split_whitespace()
        .find_map(|w| w.strip_prefix(key)?.strip_prefix('='))
}

#[test]
fn the_files_shown_are_the_files() {
    let mut shown = Vec::new();
    for b in blocks() {
        let Some(path) = attr(&b, "file") else {
            continue;
        };
        shown.push(path.to_string());
        // The tutorial's crate's manifest: `scripts/tutorial.sh` builds with it.
        if path == "Cargo.toml" {
            continue;
        }
        let file = std::fs::read_to_string(krate().join(path))
            .unwrap_or_else(|e| panic!("examples/tutorial/{path}: {e}"));
        assert_eq!(
            b.text, file,
            "docs/tutorial.md shows another examples/tutorial/{path}"
        );
    }
    for path in [
        "Cargo.toml",
        "specs/rover.toml",
        "specs/rover-v2.toml",
        "src/lib.rs",
        "src/bin/host.rs",
    ] {
        assert!(
            shown.iter().any(|s| s == path),
            "the tutorial does not show {path}"
        );
    }
}

#[test]
fn the_host_prints_what_the_tutorial_shows_and_writes_the_capture() {
    const RUN: &str = "$ cargo run --bin host -- ";
    let runs: Vec<(String, String)> = blocks()
        .iter()
        .filter_map(|b| {
            let (command, output) = b.text.split_once('\n')?;
            Some((command.strip_prefix(RUN)?.to_string(), output.to_string()))
        })
        .collect();
    assert_eq!(runs.len(), 1, "one run of the host");
    let (capture, shown) = &runs[0];
    let dir = std::env::temp_dir().join(format!("protocol-tutorial-{}", std::process::id()));
    std::fs::create_dir_all(dir.join(capture).parent().expect("a directory")).expect("temp dir");
    let out = Command::new(env!("CARGO_BIN_EXE_host"))
        .arg(capture)
        .current_dir(&dir)
        .output()
        .expect("the host runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(String::from_utf8_lossy(&out.stdout), *shown);
    let written = std::fs::read(dir.join(capture)).expect("the capture");
    let committed = std::fs::read(krate().join(capture)).expect("the committed capture");
    std::fs::remove_dir_all(&dir).expect("cleaned up");
    assert_eq!(
        written, committed,
        "the committed {capture} is not the host's output"
    );
}

#[test]
fn a_speed_the_field_cannot_carry_is_refused() {
    let packet = Packet {
        header: Header {},
        message: Message::Drive(Drive {
            speed: 40.0,
            turn: 0.0,
        }),
    };
    let mut buf = [0u8; rover_link::rover::MAX_FRAME_LEN];
    assert_eq!(
        packet.encode(&mut buf),
        Err(protocol_kit::EncodeError::ValueOutOfRange {
            place: protocol_kit::error::Place::new("DRIVE", "Drive.speed")
        })
    );
}
