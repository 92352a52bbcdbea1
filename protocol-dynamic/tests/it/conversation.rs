//! Session-aware decoding in the run-time codec ([`Conversation`]): HFLink requests and replies
//! heard on one wire with their times pair up with their round-trip times, a request sent
//! again counts the first unanswered, and a request that outlives its retries counts
//! unanswered when a later frame is heard.

use crate::support;

use protocol_dynamic::Conversation;
use support::interpreter;

protocol_kit::protocol!("../specs/hflink.toml");

use hflink::{ChassisCoord, Header, Message, Packet, Request, Response};

fn frame(sender: u8, receiver: u8, message: Message) -> Vec<u8> {
    let mut buf = vec![0u8; hflink::MAX_FRAME_LEN];
    let n = Packet {
        header: Header { sender, receiver },
        message,
    }
    .encode(&mut buf)
    .expect("encodes");
    buf.truncate(n);
    buf
}

#[test]
fn replies_pair_with_their_requests_and_round_trip_times() {
    let i = interpreter("hflink");
    let codec = i.codec();
    let coord = ChassisCoord {
        x: 1.0,
        y: 0.0,
        z: 0.0,
    };
    let read = frame(0x01, 0x11, Message::Request(Request::ReadRobotSpeed));
    let reply = frame(
        0x11,
        0x01,
        Message::Response(Response::ReadRobotSpeed(coord)),
    );
    let set = frame(0x01, 0x11, Message::Request(Request::SetRobotSpeed(coord)));
    let ack = frame(0x11, 0x01, Message::Response(Response::SetRobotSpeed));
    // (time in ms, frame): a READ sent twice (its first reply lost), a SET between.
    let wire = [
        (1000, &read),
        (1100, &read),
        (1104, &set),
        (1109, &reply),
        (1112, &ack),
        // Never answered: its requester gives up after 100 + 200 + 400 ms.
        (2000, &set),
        (3000, &read),
        (3007, &reply),
    ];
    let mut c = Conversation::new();
    let heard: Vec<_> = wire
        .iter()
        .map(|(at, f)| {
            let d = codec.decode_frame(0, f);
            assert!(d.is_ok(), "{d:?}");
            c.hear(&codec, 0, f, Some(*at), d)
        })
        .collect();
    let answers: Vec<_> = heard
        .iter()
        .map(|h| h.answers.map(|a| (a.request, a.round_trip)))
        .collect();
    assert_eq!(
        answers,
        [
            None,
            None,
            None,
            Some((1, Some(9))),
            Some((2, Some(8))),
            None,
            None,
            Some((6, Some(7)))
        ]
    );
    assert_eq!(
        heard.iter().map(|h| h.index).collect::<Vec<_>>(),
        (0..8).collect::<Vec<u64>>()
    );
    // The first READ (sent again) and the SET at 2000 (expired by 3000).
    assert_eq!((c.answered(), c.finish()), (3, 2));
}
