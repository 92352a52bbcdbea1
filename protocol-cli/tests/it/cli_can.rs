//! `protocol decode SPEC --can IFACE`: live SocketCAN input (Linux). On a `vcan0` interface
//! (`.ci/run` creates one where the kernel allows it) the frames of the Scout capture log are
//! sent on the bus and must decode exactly as the replay of the log (`--candump`) decodes them.
//! Where `vcan0` does not exist, the command must say it cannot open it, and fail.
#![cfg(target_os = "linux")]

use crate::support;

use std::io::Read;
use std::process::{Command, Stdio};
use std::time::Duration;

use serde_json::Value;
use socketcan::{CanSocket, EmbeddedFrame, ExtendedId, Id, Socket, StandardId};
use support::{json_lines, protocol, root, text};

/// The fields of a decoded line that do not depend on when or where the frame was received.
fn essence(line: &Value) -> Value {
    let mut line = line.clone();
    if let Some(map) = line.as_object_mut() {
        map.remove("time");
        map.remove("interface");
    }
    line
}

#[test]
fn live_can_decodes_as_the_candump_replay() {
    let log = "examples/captures/scout_can.log";
    let Ok(bus) = CanSocket::open("vcan0") else {
        let out = protocol(&["decode", "specs/scout.toml", "--can", "vcan0"], b"");
        assert_eq!(out.status.code(), Some(1));
        let err = text(&out.stderr);
        assert!(err.contains("cannot open CAN interface `vcan0`"), "{err}");
        eprintln!(
            "no vcan0 interface here: the live bus was not run, the replay tests cover the decoding"
        );
        return;
    };
    let replay = protocol(
        &[
            "decode",
            "specs/scout.toml",
            "--candump",
            log,
            "--format",
            "json",
        ],
        b"",
    );
    assert!(replay.status.success(), "{}", text(&replay.stderr));
    let want: Vec<Value> = json_lines(&replay.stdout).iter().map(essence).collect();

    let mut child = Command::new(env!("CARGO_BIN_EXE_protocol"))
        .args([
            "decode",
            "specs/scout.toml",
            "--can",
            "vcan0",
            "--format",
            "json",
        ])
        .current_dir(root())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    std::thread::sleep(Duration::from_millis(500));
    let (records, _) =
        protocol_cli::candump::parse(&std::fs::read_to_string(root().join(log)).expect("the log"));
    for (_, r) in &records {
        let id = if r.extended {
            Id::Extended(ExtendedId::new(r.id).expect("29 bits"))
        } else {
            Id::Standard(StandardId::new(r.id as u16).expect("11 bits"))
        };
        let frame = if r.remote {
            socketcan::CanFrame::new_remote(id, r.data.len())
        } else {
            socketcan::CanFrame::new(id, &r.data)
        };
        bus.write_frame(&frame.expect("a classic frame"))
            .expect("sent on vcan0");
    }
    std::thread::sleep(Duration::from_millis(500));
    let status = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(status.success());
    let mut stdout = Vec::new();
    child
        .stdout
        .take()
        .expect("stdout")
        .read_to_end(&mut stdout)
        .expect("read");
    let exit = child.wait().expect("the binary ends");
    assert!(exit.success(), "{exit:?}");
    let got: Vec<Value> = json_lines(&stdout).iter().map(essence).collect();
    assert_eq!(got, want);
}

#[test]
fn a_missing_interface_is_reported() {
    let out = protocol(&["decode", "specs/scout.toml", "--can", "nosuchcan0"], b"");
    assert_eq!(out.status.code(), Some(1));
    let err = text(&out.stderr);
    assert!(
        err.contains("cannot open CAN interface `nosuchcan0`"),
        "{err}"
    );
    assert!(err.contains("No such device"), "{err}");
}

#[test]
fn can_needs_a_can_transport() {
    let out = protocol(&["decode", "specs/hflink.toml", "--can", "vcan0"], b"");
    assert_eq!(out.status.code(), Some(1));
    let err = text(&out.stderr);
    assert!(err.contains("spec `hflink` has no CAN transport"), "{err}");
}
