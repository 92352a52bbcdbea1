//! `protocol decode --serial`, against a real pseudo-terminal pair: the test holds the master
//! side, the command opens the slave side as its serial port (a pty is a real tty: termios,
//! baud rate, hangup), the capture's bytes are written into the master in uneven chunks, and
//! the command prints each frame as it arrives, then its stats when the master hangs up.
#![cfg(unix)]

use crate::support;

use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use rustix::fs::{Mode, OFlags};
use rustix::pty::{OpenptFlags, grantpt, openpt, ptsname, unlockpt};
use rustix::termios::{OptionalActions, tcgetattr, tcsetattr};
use serde_json::Value;
use support::{Rng, root, text, truth};

/// How long the command may take to show a frame written into the port.
const PATIENCE: Duration = Duration::from_secs(30);

#[test]
fn decodes_a_live_serial_port_until_it_hangs_up() {
    let master =
        openpt(OpenptFlags::RDWR | OpenptFlags::NOCTTY | OpenptFlags::CLOEXEC).expect("openpt");
    grantpt(&master).expect("grantpt");
    unlockpt(&master).expect("unlockpt");
    let name = ptsname(&master, Vec::new()).expect("ptsname");
    let path = name.to_str().expect("utf-8 path").to_string();
    // Raw mode before the first byte: a fresh pty is in canonical mode with echo, which would
    // rewrite the bytes written before the command sets raw mode itself.
    let slave = rustix::fs::open(path.as_str(), OFlags::RDWR | OFlags::NOCTTY, Mode::empty())
        .expect("open the slave");
    let mut termios = tcgetattr(&slave).expect("tcgetattr");
    termios.make_raw();
    tcsetattr(&slave, OptionalActions::Now, &termios).expect("tcsetattr");

    let mut child = Command::new(env!("CARGO_BIN_EXE_protocol"))
        .args([
            "decode",
            "specs/hflink.toml",
            "--serial",
            &path,
            "--baud",
            "115200",
            "--format",
            "json",
            "--stats",
        ])
        .current_dir(root())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    let stdout = child.stdout.take().expect("stdout");
    let (tx, rx) = mpsc::channel::<String>();
    let reader = std::thread::spawn(move || {
        for line in BufReader::new(stdout).lines().map_while(Result::ok) {
            if tx.send(line).is_err() {
                break;
            }
        }
    });

    // The noisy capture, in chunks of 1 to 64 bytes, as a UART driver delivers them.
    let capture = std::fs::read(root().join("examples/captures/hflink.bin")).expect("capture");
    let mut rng = Rng(0x5E41_0001);
    let mut at = 0;
    while at < capture.len() {
        let n = (1 + rng.range(0, 63) as usize).min(capture.len() - at);
        let mut chunk = &capture[at..at + n];
        while !chunk.is_empty() {
            let written = rustix::io::write(&master, chunk).expect("write to the master");
            chunk = &chunk[written..];
        }
        at += n;
        if rng.range(0, 9) == 0 {
            std::thread::sleep(Duration::from_millis(2));
        }
    }

    // Every intact frame shows up while the port is still open.
    let expected: Vec<(u64, String)> = truth("hflink")
        .iter()
        .filter(|t| t["kind"] == "frame")
        .map(|t| {
            (
                t["offset"].as_u64().expect("offset"),
                t["hex"].as_str().expect("hex").to_string(),
            )
        })
        .collect();
    let mut frames = Vec::new();
    let deadline = Instant::now() + PATIENCE;
    while frames.len() < expected.len() {
        let left = deadline.saturating_duration_since(Instant::now());
        let line = rx.recv_timeout(left).unwrap_or_else(|_| {
            let _ = child.kill();
            panic!(
                "{} of {} frames after {PATIENCE:?}",
                frames.len(),
                expected.len()
            )
        });
        let v: Value = serde_json::from_str(&line).expect("JSON Lines");
        if v.get("event").is_none() {
            frames.push((
                v["offset"].as_u64().expect("offset"),
                v["hex"].as_str().expect("hex").to_string(),
            ));
        }
    }
    assert_eq!(
        frames, expected,
        "the frames of the capture, at their offsets"
    );

    // Hang up: the command ends by itself and prints its stats.
    drop(master);
    drop(slave);
    let deadline = Instant::now() + PATIENCE;
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait") {
            break status;
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            panic!("the command did not end when the port hung up");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let _ = reader.join();
    let mut stderr = String::new();
    if let Some(mut e) = child.stderr.take() {
        std::io::Read::read_to_string(&mut e, &mut stderr).expect("stderr");
    }
    assert!(status.success(), "{status:?}: {stderr}");
    assert!(
        stderr.contains(&format!("frames decoded: {} (", expected.len())),
        "{stderr}"
    );
    assert!(
        stderr.contains("link efficiency: "),
        "{}",
        text(stderr.as_bytes())
    );
}

#[test]
fn a_missing_port_is_named() {
    let out = support::protocol(
        &[
            "decode",
            "specs/hflink.toml",
            "--serial",
            "/dev/does-not-exist-protocol",
        ],
        b"",
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(
        text(&out.stderr).contains("cannot open serial port `/dev/does-not-exist-protocol`"),
        "{}",
        text(&out.stderr)
    );
}
