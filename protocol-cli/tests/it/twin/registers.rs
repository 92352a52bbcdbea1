//! The twin of a spec with `[registers]` (Dynamixel 2.0's XM430-W350) over a real
//! pseudo-terminal: a READ is answered with the register file's bytes at its address and
//! length (zeros, or the values file's raw values), a WRITE changes what the next READ gets,
//! and a SYNC_READ to the broadcast id is answered by every servo it lists, each status with
//! its own id, which the client collects into one reply; each status of a SYNC_READ or a
//! BULK_READ carries the registers its servo was asked for, read back through the generated
//! `registers` accessors.

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

/// The statuses of a request answered by every servo it lists, by sender id.
fn statuses(reply: Reply) -> Vec<(u8, Status)> {
    let Reply::AnsweredAll(frames) = reply else {
        panic!("not answered by every servo: {reply:?}");
    };
    frames
        .iter()
        .map(|f| {
            let id = Packet::from_frame(f).expect("decodes").header.id;
            (id, status(id, f))
        })
        .collect()
}

#[tokio::test]
async fn each_servo_answering_a_sync_or_bulk_read_carries_the_registers_it_was_asked() {
    use dynamixel::registers::{
        PRESENT_POSITION, PRESENT_TEMPERATURE, PRESENT_VELOCITY, bulk_read_answer, sync_read_answer,
    };
    use dynamixel::{BulkRead, BulkReadServo};
    let dir = tempfile::tempdir().expect("a temp dir");
    let values = dir.path().join("values.toml");
    std::fs::write(
        &values,
        "[registers]\npresent_position = 3000\npresent_velocity = -7\npresent_temperature = 39\n",
    )
    .expect("values written");
    let values = values.to_str().expect("a UTF-8 path");
    let twin = Twin::start(&["specs/dynamixel.toml", "--values", values]);
    let (client, _unsolicited) =
        Client::spawn::<_, 4, { dynamixel::MAX_FRAME_LEN }>(open(&twin.path), dynamixel::Session);

    // SYNC_READ: every listed servo is asked velocity and position (8 bytes from 128).
    let mut ids = protocol_kit::Group::new();
    for id in [5u8, 2] {
        ids.push(id).expect("room");
    }
    let sync = SyncRead {
        address: 128,
        length: 8,
        ids,
    };
    let reply = client
        .request(&to(0xFE, Message::SyncRead(sync)))
        .await
        .expect("a reply");
    let answers = statuses(reply);
    assert_eq!(
        answers.iter().map(|(id, _)| *id).collect::<Vec<_>>(),
        [2, 5]
    );
    for (_, s) in &answers {
        let window = sync_read_answer(&sync, s);
        assert_eq!(PRESENT_POSITION.read(window), Some(3000));
        let velocity = PRESENT_VELOCITY.read(window).expect("whole");
        assert!((velocity + 7.0 * 0.229).abs() < 1e-4, "{velocity}");
    }

    // BULK_READ: servo 3 is asked its temperature, servo 8 its position.
    let mut servos = protocol_kit::Group::new();
    for (id, address, length) in [(8u8, 132u16, 4u16), (3, 146, 1)] {
        let servo = BulkReadServo {
            id,
            address,
            length,
        };
        servos.push(servo).expect("room");
    }
    let bulk = BulkRead { servos };
    let reply = client
        .request(&to(0xFE, Message::BulkRead(bulk)))
        .await
        .expect("a reply");
    let answers = statuses(reply);
    assert_eq!(
        answers.iter().map(|(id, _)| *id).collect::<Vec<_>>(),
        [3, 8]
    );
    for (id, s) in &answers {
        let window = bulk_read_answer(&bulk, *id, s).expect("a listed servo");
        match id {
            3 => {
                assert_eq!(s.data.as_slice(), [39]);
                assert_eq!(PRESENT_TEMPERATURE.read(window), Some(39));
            }
            _ => {
                assert_eq!(s.data.len(), 4);
                assert_eq!(PRESENT_POSITION.read(window), Some(3000));
            }
        }
    }
    assert!(bulk_read_answer(&bulk, 4, &answers[0].1).is_none());

    drop(client);
    let log = twin.stop();
    assert!(log.contains("3: STATUS (read 1 bytes at 146)"), "{log}");
    assert!(log.contains("8: STATUS (read 4 bytes at 132)"), "{log}");
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
