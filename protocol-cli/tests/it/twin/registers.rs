//! The twin of a spec with `[registers]` (Dynamixel 2.0's XM430-W350) over a real
//! pseudo-terminal: a READ is answered with the register file's bytes at its address and
//! length (zeros, or the values file's raw values), a WRITE changes what the next READ gets,
//! and a SYNC_READ to the broadcast id is answered by every servo it lists, each status with
//! its own id, which the client collects into one reply.

use protocol_kit::session::client::{Client, Reply};

use super::{Twin, open, tally};

protocol_kit::protocol!("../specs/dynamixel.toml");

use dynamixel::{Header, Message, Packet, Read, Status, SyncRead, Write};

fn to(id: u8, message: Message) -> Packet {
    Packet {
        header: Header { id },
        message,
    }
}

/// The status an answer frame carries, from servo `id`.
fn status(id: u8, frame: &[u8]) -> Status {
    let packet = Packet::from_frame(frame).expect("the status decodes");
    assert_eq!(packet.header.id, id);
    let Message::Status(s) = packet.message else {
        panic!("not a status: {packet:?}");
    };
    s
}

/// The data of the status that answers a request to servo `id`.
fn data(id: u8, reply: Reply) -> Vec<u8> {
    let Reply::Answered(frame) = reply else {
        panic!("not answered: {reply:?}");
    };
    status(id, &frame).data.to_vec()
}

fn read(id: u8, address: u16, length: u16) -> Packet {
    to(id, Message::Read(Read { address, length }))
}

#[tokio::test]
async fn dynamixel_reads_and_writes_the_twins_registers() {
    let dir = tempfile::tempdir().expect("a temp dir");
    let values = dir.path().join("values.toml");
    // 2048 (the middle) and a negative current, as raw values.
    std::fs::write(
        &values,
        "[registers]\npresent_position = 2048\ngoal_current = -2\n",
    )
    .expect("values written");
    let values = values.to_str().expect("a UTF-8 path");
    let twin = Twin::start(&["specs/dynamixel.toml", "--values", values]);
    let (client, _unsolicited) =
        Client::spawn::<_, 4, { dynamixel::MAX_FRAME_LEN }>(open(&twin.path), dynamixel::Session);

    // Present position (132, 4 bytes) and goal current (102, 2 bytes), little-endian.
    let got = data(1, client.request(&read(1, 132, 4)).await.expect("a reply"));
    assert_eq!(got, [0x00, 0x08, 0x00, 0x00]);
    let got = data(1, client.request(&read(1, 102, 2)).await.expect("a reply"));
    assert_eq!(got, [0xFE, 0xFF]);
    // Nothing given: zeros; a run across several registers is the bytes of each.
    let got = data(2, client.request(&read(2, 64, 2)).await.expect("a reply"));
    assert_eq!(got, [0, 0]);

    // A WRITE of goal position (116): its status carries no data, and the next READ sees it.
    let goal = protocol_kit::Bytes::from_slice(&[0x00, 0x04, 0x00, 0x00]).expect("fits");
    let write = to(
        1,
        Message::Write(Write {
            address: 116,
            data: goal,
        }),
    );
    assert_eq!(
        data(1, client.request(&write).await.expect("a reply")),
        [] as [u8; 0]
    );
    let got = data(1, client.request(&read(1, 112, 8)).await.expect("a reply"));
    assert_eq!(got, [0, 0, 0, 0, 0x00, 0x04, 0x00, 0x00]);

    // A SYNC_READ to the broadcast id: the twin answers as each listed servo.
    let mut ids = protocol_kit::Group::new();
    for id in [3u8, 1, 7] {
        ids.push(id).expect("room");
    }
    let sync = to(
        0xFE,
        Message::SyncRead(SyncRead {
            address: 132,
            length: 4,
            ids,
        }),
    );
    let reply = client.request(&sync).await.expect("a reply");
    let Reply::AnsweredAll(frames) = reply else {
        panic!("not answered by every servo: {reply:?}");
    };
    let from: Vec<u8> = frames
        .iter()
        .map(|f| Packet::from_frame(f).expect("decodes").header.id)
        .collect();
    assert_eq!(from, [1, 3, 7]);

    drop(client);
    let log = twin.stop();
    assert!(log.contains("STATUS (read 4 bytes at 132)"), "{log}");
    assert!(log.contains("(wrote 4 bytes at 116)"), "{log}");
    assert_eq!(
        tally(&log),
        "twin: 6 delivered, 6 answered, 0 duplicates, 0 refused before the handshake, 0 error replies, 0 dropped, 0 not answered, 0 periodic",
        "{log}"
    );
}

#[test]
fn a_register_the_map_does_not_have_is_refused_at_start() {
    let dir = tempfile::tempdir().expect("a temp dir");
    let values = dir.path().join("values.toml");
    std::fs::write(&values, "[registers]\nno_such_register = 1\n").expect("values written");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_protocol"))
        .args(["twin", "specs/dynamixel.toml", "--pty", "--values"])
        .arg(&values)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .output()
        .expect("protocol twin runs");
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("registers.no_such_register"), "{err}");
}
