//! The twin of a spec with an empty direction (MSP's error replies, `!`) over a real
//! pseudo-terminal: a request it answers gets its reply (`>`), and one it does not know (a
//! command the spec does not list) or cannot answer (a value its reply cannot hold) gets the
//! error reply of its command, which the client resolves as the request's refusal.

use protocol_kit::session::client::{Client, Reply};

use super::{Twin, open, tally};

protocol_kit::protocol!("../specs/msp.toml");

use msp::{Command, Header, Message, Packet, Request, Response};

fn request(r: Request) -> Packet {
    Packet {
        header: Header { direction: b'<' },
        message: Message::Request(r),
    }
}

/// The packet a reply's frame carries.
fn packet(frame: &[u8]) -> Packet {
    Packet::from_frame(frame).expect("the reply decodes")
}

#[tokio::test]
async fn msp_answers_what_it_can_and_refuses_the_rest_with_error_replies() {
    let dir = tempfile::tempdir().expect("a temp dir");
    let values = dir.path().join("values.toml");
    // 70000 µs does not fit STATUS's u16 cycle time: the twin cannot answer STATUS.
    std::fs::write(
        &values,
        "[API_VERSION]\nprotocol_version = 0\napi_version_major = 1\napi_version_minor = 46\n\n[STATUS]\ncycle_time = 70000\n",
    )
    .expect("values written");
    let values = values.to_str().expect("a UTF-8 path");
    let twin = Twin::start(&["specs/msp.toml", "--values", values]);
    let (client, _unsolicited) =
        Client::spawn::<_, 4, { msp::MAX_FRAME_LEN }>(open(&twin.path), msp::Session);

    let Reply::Answered(frame) = client
        .request(&request(Request::ApiVersion))
        .await
        .expect("a reply")
    else {
        panic!("API_VERSION not answered");
    };
    let reply = packet(&frame);
    assert_eq!(reply.header.direction, b'>');
    assert_eq!(
        reply.message,
        Message::Response(Response::ApiVersion(msp::ApiVersion {
            protocol_version: 0,
            api_version_major: 1,
            api_version_minor: 46,
        }))
    );

    let Reply::Refused(frame) = client
        .request(&request(Request::Status))
        .await
        .expect("a reply")
    else {
        panic!("STATUS not refused");
    };
    let refusal = packet(&frame);
    assert_eq!(refusal.header.direction, b'!');
    assert_eq!(refusal.message, Message::Error(Command::Status));

    // `$M<`, no payload, command 99 (no command of the spec); the requester seals it.
    let unknown = vec![0x24, 0x4D, 0x3C, 0x00, 99, 0x00];
    let Reply::Refused(frame) = client.request_frame(unknown).await.expect("a reply") else {
        panic!("command 99 not refused");
    };
    // The error reply of command 99: `$M!`, no payload, 99, the XOR of size and command.
    assert_eq!(frame, [0x24, 0x4D, 0x21, 0x00, 99, 99]);

    let retries = client.retries();
    drop(client);
    let log = twin.stop();
    assert!(log.contains("-> error reply STATUS"), "{log}");
    assert!(log.contains("-> error reply command 0x63"), "{log}");
    // A loaded machine may answer after the 1000 ms timeout: a retry is then delivered and
    // answered again (MSP numbers nothing), so the counts are exact only without retries.
    if retries == 0 {
        assert_eq!(
            tally(&log),
            "twin: 3 delivered, 1 answered, 0 duplicates, 0 refused before the handshake, 2 error replies, 0 dropped, 0 not answered, 0 periodic",
            "{log}"
        );
    } else {
        assert!(tally(&log).contains(", 0 not answered,"), "{log}");
    }
}
