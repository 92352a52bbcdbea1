//! The run-time codec's session rules are generated code's `SESSION`, field for field, for
//! every bundled spec with a `[session]`; and a requester over the codec's rules holds a
//! conversation with a responder over the generated ones (RoboRTS: numbered, acknowledged).

use crate::support;

use protocol_kit::session::{Incoming, Received, Requester, Resolution, Responder, SessionRules};
use support::interpreter;

protocol_kit::protocol!("../specs/hflink.toml");
protocol_kit::protocol!("../specs/roborts.toml");
protocol_kit::protocol!("../specs/scout.toml");
protocol_kit::protocol!("../specs/dynamixel.toml");
protocol_kit::protocol!("../specs/dynamixel1.toml");
protocol_kit::protocol!("../specs/mavlink.toml");

/// The rules as text, without the packet rules they borrow (compared elsewhere).
fn shown(r: &SessionRules<'_>) -> String {
    format!(
        "{:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?}",
        r.default,
        r.exchanges,
        r.sequence,
        r.echo,
        r.swap,
        r.pairs,
        r.nack,
        r.handshake,
        r.watchdog,
        r.modes,
        r.fanouts
    )
}

#[test]
fn the_codec_builds_the_generated_session_rules() {
    let cases: [(&str, &SessionRules<'static>); 6] = [
        ("hflink", &hflink::SESSION),
        ("roborts", &roborts::SESSION),
        ("scout", &scout::SESSION),
        ("dynamixel", &dynamixel::SESSION),
        ("dynamixel1", &dynamixel1::SESSION),
        ("mavlink", &mavlink::SESSION),
    ];
    for (name, generated) in cases {
        let i = interpreter(name);
        let codec = i.codec();
        let built = codec.with_session(shown).expect("a session");
        assert_eq!(built, shown(generated), "{name}");
        let packet = codec
            .with_session(|r| format!("{:?}", r.packet))
            .expect("a session");
        assert_eq!(packet, format!("{:?}", generated.packet), "{name}");
    }
    assert!(interpreter("crsf").codec().with_session(|_| ()).is_none());
}

#[test]
fn a_codec_requester_and_a_generated_responder_converse() {
    let i = interpreter("roborts");
    let codec = i.codec();
    codec
        .with_session(|rules| {
            let mut req = Requester::<_, 2, 64>::new(rules);
            let mut res = Responder::<_, 2, 64>::new(&roborts::SESSION);
            let packet = roborts::Packet {
                header: roborts::Header {
                    session_id: 3,
                    sender: 0,
                    receiver: 1,
                    seq_num: 0,
                },
                message: roborts::Message::Heartbeat(roborts::Heartbeat { heartbeat: 1 }),
            };
            let mut frame = vec![0u8; roborts::MAX_FRAME_LEN];
            let n = packet.encode(&mut frame).expect("encodes");
            frame.truncate(n);
            for round in 0..3u64 {
                let ticket = req
                    .send(round, &mut frame)
                    .expect("sent")
                    .expect("acknowledged");
                assert_eq!(
                    res.on_frame(round, &frame),
                    Incoming::Deliver { answer: true }
                );
                // The same frame again (a duplicate on the wire): not delivered twice.
                assert_eq!(res.on_frame(round, &frame), Incoming::Duplicate(None));
                let ack = roborts::Packet {
                    header: roborts::Header {
                        session_id: 0,
                        sender: 1,
                        receiver: 0,
                        seq_num: 0,
                    },
                    message: roborts::Message::Ack(
                        protocol_kit::Bytes::from_slice(&[]).expect("empty"),
                    ),
                };
                let mut ack_frame = [0u8; 12];
                assert_eq!(ack.encode(&mut ack_frame), Ok(12), "a bare header");
                let mut ack = ack_frame;
                res.answer(&frame, &mut ack).expect("answers");
                // The answer repeats the request's session id and number.
                let decoded = roborts::Packet::from_frame(&ack).expect("an acknowledgement");
                assert_eq!(
                    (decoded.header.session_id, decoded.header.seq_num),
                    (3, round as u16)
                );
                assert_eq!(
                    req.on_frame(round, &ack),
                    Received::Outcome(protocol_kit::session::Outcome {
                        ticket,
                        resolution: Resolution::Answered
                    })
                );
            }
        })
        .expect("a session");
}
