//! Receive times of a live input: `protocol decode --serial` on a pseudo-terminal pair stamps
//! every frame and event with the time its bytes were read: `time` (seconds since the Unix
//! epoch) after `offset` in JSON Lines, the UTC time of day in front of a table line. Two
//! bursts of frames written a known pause apart must show the pause in their times, and every
//! time must lie between the test's own clock readings around the writes.
#![cfg(unix)]

use crate::support;

use std::io::{BufRead, BufReader};
use std::os::fd::OwnedFd;
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

use rustix::fs::{Mode, OFlags};
use rustix::pty::{OpenptFlags, grantpt, openpt, ptsname, unlockpt};
use rustix::termios::{OptionalActions, tcgetattr, tcsetattr};
use serde_json::Value;
use support::{root, unhex};

/// How long the command may take to show a frame written into the port.
const PATIENCE: Duration = Duration::from_secs(30);

/// The pause between the two bursts.
const PAUSE: Duration = Duration::from_millis(400);

/// Two HFLink frames (speed command, speed reading) and a byte of noise between them.
const BURST: &str =
    "ffff0111000d0ccdcccc3e00000000000080be10 00 ffff1101000d0d5b99d03e43739d3b189584beb0";

/// A pty pair in raw mode: the master the test writes to, the slave's path, the slave.
fn pty() -> (OwnedFd, String, OwnedFd) {
    let master =
        openpt(OpenptFlags::RDWR | OpenptFlags::NOCTTY | OpenptFlags::CLOEXEC).expect("openpt");
    grantpt(&master).expect("grantpt");
    unlockpt(&master).expect("unlockpt");
    let name = ptsname(&master, Vec::new()).expect("ptsname");
    let path = name.to_str().expect("utf-8 path").to_string();
    let slave = rustix::fs::open(path.as_str(), OFlags::RDWR | OFlags::NOCTTY, Mode::empty())
        .expect("open the slave");
    let mut termios = tcgetattr(&slave).expect("tcgetattr");
    termios.make_raw();
    tcsetattr(&slave, OptionalActions::Now, &termios).expect("tcsetattr");
    (master, path, slave)
}

fn write_all(master: &OwnedFd, mut bytes: &[u8]) {
    while !bytes.is_empty() {
        let n = rustix::io::write(master, bytes).expect("write to the master");
        bytes = &bytes[n..];
    }
}

fn now() -> f64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .expect("after 1970")
        .as_secs_f64()
}

/// Starts `decode --serial PATH --format FORMAT` and a thread that sends its lines.
fn start(path: &str, format: &str) -> (Child, mpsc::Receiver<String>) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_protocol"))
        .args([
            "decode",
            "specs/hflink.toml",
            "--serial",
            path,
            "--format",
            format,
        ])
        .current_dir(root())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("the binary runs");
    let stdout = child.stdout.take().expect("stdout");
    let (tx, rx) = mpsc::channel::<String>();
    std::thread::spawn(move || {
        for line in BufReader::new(stdout).lines().map_while(Result::ok) {
            if tx.send(line).is_err() {
                break;
            }
        }
    });
    (child, rx)
}

/// The next `n` lines, or a failure naming what is missing.
fn lines(child: &mut Child, rx: &mpsc::Receiver<String>, n: usize) -> Vec<String> {
    let deadline = Instant::now() + PATIENCE;
    (0..n)
        .map(|i| {
            let left = deadline.saturating_duration_since(Instant::now());
            rx.recv_timeout(left).unwrap_or_else(|_| {
                let _ = child.kill();
                panic!("line {i} of {n} missing after {PATIENCE:?}")
            })
        })
        .collect()
}

/// Writes a burst, waits for its three lines (two frames, a skipped byte); returns them with
/// the clock read before the write and after the lines arrived.
fn burst(
    master: &OwnedFd,
    child: &mut Child,
    rx: &mpsc::Receiver<String>,
) -> (f64, Vec<String>, f64) {
    let before = now();
    write_all(master, &unhex(BURST));
    let got = lines(child, rx, 3);
    (before, got, now())
}

#[test]
fn json_lines_of_a_serial_port_carry_receive_times() {
    let (master, path, slave) = pty();
    let (mut child, rx) = start(&path, "json");
    let (before1, first, after1) = burst(&master, &mut child, &rx);
    std::thread::sleep(PAUSE);
    let (before2, second, after2) = burst(&master, &mut child, &rx);
    drop(master);
    drop(slave);
    let _ = child.wait();

    let parse = |l: &String| serde_json::from_str::<Value>(l).expect("JSON");
    let first: Vec<Value> = first.iter().map(parse).collect();
    let second: Vec<Value> = second.iter().map(parse).collect();
    let mut last = 0.0;
    for (values, lo, hi) in [(&first, before1, after1), (&second, before2, after2)] {
        for v in values {
            let keys: Vec<&str> = v
                .as_object()
                .expect("object")
                .keys()
                .map(String::as_str)
                .collect();
            assert_eq!(
                &keys[..2],
                ["offset", "time"],
                "`time` follows `offset`: {v}"
            );
            let t = v["time"].as_f64().expect("a time in seconds");
            // A millisecond of slack: the command's clock reading is rounded to the microsecond.
            assert!(
                t >= lo - 1e-3 && t <= hi + 1e-3,
                "{t} not in [{lo}, {hi}]: {v}"
            );
            assert!(t >= last, "times go back: {v}");
            last = t;
        }
    }
    let frames = |vs: &[Value]| vs.iter().filter(|v| v.get("event").is_none()).count();
    assert_eq!(
        (frames(&first), frames(&second)),
        (2, 2),
        "{first:?} {second:?}"
    );
    let gap = second[0]["time"].as_f64().expect("time") - first[2]["time"].as_f64().expect("time");
    assert!(gap >= PAUSE.as_secs_f64() - 1e-3, "the pause is {gap} s");
}

#[test]
fn table_lines_of_a_serial_port_start_with_receive_times() {
    let (master, path, slave) = pty();
    let (mut child, rx) = start(&path, "table");
    let (before, got, after) = burst(&master, &mut child, &rx);
    drop(master);
    drop(slave);
    let _ = child.wait();
    // The UTC time of day, to the microsecond, in front of each line.
    let of_day = |t: f64| t.rem_euclid(86_400.0);
    for line in &got {
        let (time, rest) = line.split_once("  ").expect("a time column");
        let parts: Vec<f64> = time
            .split(':')
            .map(|p| p.parse().expect("a number"))
            .collect();
        let [h, m, s] = parts[..] else {
            panic!("HH:MM:SS.ffffff: {line}")
        };
        let t = h * 3600.0 + m * 60.0 + s;
        // Around midnight the test's readings wrap: then only the form is checked.
        if of_day(before) <= of_day(after) {
            assert!(
                t >= of_day(before) - 1e-3 && t <= of_day(after) + 1e-3,
                "{line}: not between the test's clock readings"
            );
        }
        assert!(!rest.trim().is_empty(), "{line}");
    }
    assert!(got.iter().any(|l| l.contains("SET_ROBOT_SPEED")), "{got:?}");
}
