//! The tokio session client surfaces what a request hears before it resolves: a MAVLink
//! COMMAND_LONG answered `IN_PROGRESS` then `ACCEPTED` yields one `Update::Progress` and then
//! the final answer; a Dynamixel 2.0 SYNC_READ yields an `Update::Partial` per servo but the
//! last and resolves to every answer, or to the ids that did not answer. The device is the
//! test, at the other end of an in-memory pipe.

use std::time::Duration;

use protocol_kit::session::client::{Client, Reply, Update};
use tokio::io::{AsyncReadExt, AsyncWriteExt, DuplexStream};

protocol_kit::protocol!("../specs/mavlink.toml");
protocol_kit::protocol!("../specs/dynamixel.toml");

/// Reads at least one byte the host wrote (a request; its bytes are not needed here).
async fn heard(device: &mut DuplexStream) {
    let mut buf = [0u8; 512];
    let n = tokio::time::timeout(Duration::from_secs(2), device.read(&mut buf))
        .await
        .expect("a request within 2 s")
        .expect("read");
    assert!(n > 0);
}

fn mavlink_ack(result: u8) -> Vec<u8> {
    use mavlink::{CommandAck, Header, Message, Packet};
    let packet = Packet {
        header: Header {
            sysid: 1,
            compid: 1,
            ..Header::default()
        },
        message: Message::CommandAck(CommandAck {
            command: 400,
            result,
            progress: 40,
            result_param2: 0,
            target_system: 255,
            target_component: 190,
        }),
    };
    let mut buf = vec![0u8; mavlink::MAX_FRAME_LEN];
    let n = packet.encode(&mut buf).expect("encodes");
    buf.truncate(n);
    buf
}

#[tokio::test(flavor = "current_thread")]
async fn an_in_progress_ack_is_an_update_and_the_final_ack_the_reply() {
    use mavlink::{CommandLong, Header, Message, Packet};
    let (host, mut device) = tokio::io::duplex(4096);
    let (client, mut unsolicited) =
        Client::spawn::<_, 4, { mavlink::MAX_FRAME_LEN }>(host, mavlink::Session);
    let arm = Packet {
        header: Header {
            sysid: 255,
            compid: 190,
            ..Header::default()
        },
        message: Message::CommandLong(CommandLong {
            param1: 1.0,
            param2: 0.0,
            param3: 0.0,
            param4: 0.0,
            param5: 0.0,
            param6: 0.0,
            param7: 0.0,
            command: 400,
            target_system: 1,
            target_component: 1,
            confirmation: 0,
        }),
    };
    let (reply, mut updates) = client.request_watched(&arm);
    let reply = tokio::spawn(reply);
    heard(&mut device).await;
    device.write_all(&mavlink_ack(5)).await.expect("written");
    let update = tokio::time::timeout(Duration::from_secs(2), updates.recv())
        .await
        .expect("an update within 2 s")
        .expect("an update");
    assert_eq!(
        update,
        Update::Progress {
            value: 5,
            frame: mavlink_ack(5)
        }
    );
    device.write_all(&mavlink_ack(0)).await.expect("written");
    let reply = reply.await.expect("joined").expect("a reply");
    assert_eq!(reply, Reply::Answered(mavlink_ack(0)));
    // The channel closes with the request; nothing was unsolicited.
    assert_eq!(updates.recv().await, None);
    assert!(unsolicited.try_recv().is_err());
}

fn dynamixel_frame(id: u8, message: dynamixel::Message) -> Vec<u8> {
    let packet = dynamixel::Packet {
        header: dynamixel::Header { id },
        message,
    };
    let mut buf = vec![0u8; dynamixel::MAX_FRAME_LEN];
    let n = packet.encode(&mut buf).expect("encodes");
    buf.truncate(n);
    buf
}

fn status(id: u8) -> Vec<u8> {
    dynamixel_frame(
        id,
        dynamixel::Message::Status(dynamixel::Status {
            error_number: 0,
            alert: false,
            data: protocol_kit::Bytes::from_slice(&[id, 0, 0, 0]).expect("fits"),
        }),
    )
}

fn sync_read(ids: &[u8]) -> dynamixel::Packet {
    let mut list = protocol_kit::Group::new();
    for &id in ids {
        list.push(id).expect("room");
    }
    dynamixel::Packet {
        header: dynamixel::Header { id: 0xFE },
        message: dynamixel::Message::SyncRead(dynamixel::SyncRead {
            address: 132,
            length: 4,
            ids: list,
        }),
    }
}

#[tokio::test(flavor = "current_thread")]
async fn a_sync_read_reports_each_servo_and_resolves_to_every_answer_or_the_missing() {
    let (host, mut device) = tokio::io::duplex(4096);
    let (client, _unsolicited) =
        Client::spawn::<_, 4, { dynamixel::MAX_FRAME_LEN }>(host, dynamixel::Session);

    let (reply, mut updates) = client.request_watched(&sync_read(&[1, 2]));
    let reply = tokio::spawn(reply);
    heard(&mut device).await;
    device.write_all(&status(2)).await.expect("written");
    device.write_all(&status(1)).await.expect("written");
    let reply = reply.await.expect("joined").expect("a reply");
    assert_eq!(reply, Reply::AnsweredAll(vec![status(2), status(1)]));
    assert_eq!(
        updates.recv().await,
        Some(Update::Partial {
            id: 2,
            frame: status(2)
        })
    );
    assert_eq!(updates.recv().await, None);

    // Servo 9 never answers: after Dynamixel's 50 ms, the reply names it.
    let reply = tokio::spawn(client.request(&sync_read(&[4, 9])));
    heard(&mut device).await;
    device.write_all(&status(4)).await.expect("written");
    let reply = reply.await.expect("joined").expect("a reply");
    assert_eq!(
        reply,
        Reply::Incomplete {
            frames: vec![status(4)],
            missing: vec![9]
        }
    );
}
