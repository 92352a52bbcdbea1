//! The run-time codec's session rules are generated code's `SESSION`, field for field, for
//! every bundled spec with a `[session]`; and a requester over the codec's rules holds a
//! conversation with a responder over the generated ones (RoboRTS: numbered, acknowledged).
//! MSP's error replies: requesters over the codec's rules and the generated ones, given the
//! same frames, resolve each request alike (an error reply of its command refuses it).

use crate::support;

use protocol_kit::session::{Incoming, Received, Requester, Resolution, Responder, SessionRules};
use support::interpreter;

protocol_kit::protocol!("../specs/hflink.toml");
protocol_kit::protocol!("../specs/roborts.toml");
protocol_kit::protocol!("../specs/scout.toml");
protocol_kit::protocol!("../specs/dynamixel.toml");
protocol_kit::protocol!("../specs/dynamixel1.toml");
protocol_kit::protocol!("../specs/mavlink.toml");
protocol_kit::protocol!("../specs/msp.toml");

/// The rules as text, without the packet rules they borrow (compared elsewhere).
fn shown(r: &SessionRules<'_>) -> String {
    format!(
        "{:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?}",
        r.default,
        r.exchanges,
        r.sequence,
        r.echo,
        r.swap,
        r.pairs,
        r.nack,
        r.refusals,
        r.handshake,
        r.watchdog,
        r.modes,
        r.fanouts
    )
}

#[test]
fn the_codec_builds_the_generated_session_rules() {
    let cases: [(&str, &SessionRules<'static>); 7] = [
        ("hflink", &hflink::SESSION),
        ("msp", &msp::SESSION),
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

/// The outcomes a requester over `rules` gives: for each command, its request sent, then the
/// error reply of another command (which refuses nothing), then `answer(command)`.
fn outcomes<S: protocol_kit::session::SessionRef>(
    rules: S,
    answer: impl Fn(msp::Command) -> Vec<u8>,
) -> Vec<String> {
    let mut out = Vec::new();
    for (command, name) in msp::Command::ALL {
        // v1 frames carry the commands whose id fits their byte.
        let Ok(id) = u8::try_from(command.id()) else {
            continue;
        };
        let mut req = Requester::<_, 2, { msp::MAX_FRAME_LEN }>::new(rules);
        let mut frame = msp_frame(b'<', id);
        let ticket = req.send(0, &mut frame).expect("sent").expect("answered");
        let other = msp_frame(b'!', id.wrapping_add(1));
        let unsolicited = req.on_frame(1, &other);
        let heard = req.on_frame(2, &answer(command));
        out.push(format!(
            "{name}: {unsolicited:?} then {heard:?} ({ticket:?})"
        ));
    }
    out
}

/// A v1 frame of `direction` and command `id`, without payload, sealed.
fn msp_frame(direction: u8, id: u8) -> Vec<u8> {
    let mut frame = vec![0x24, 0x4D, direction, 0, id, 0];
    msp::LAYOUT.seal(&mut frame).expect("sealed");
    frame
}

/// The generated encoding of the error reply of `command`.
fn error_reply(command: msp::Command) -> Vec<u8> {
    let packet = msp::Packet {
        header: msp::Header { direction: b'!' },
        message: msp::Message::Error(command),
    };
    let mut buf = [0u8; msp::MAX_FRAME_LEN];
    let n = packet.encode(&mut buf).expect("encodes");
    buf[..n].to_vec()
}

#[test]
fn msp_requesters_over_codec_and_generated_rules_read_error_replies_alike() {
    let i = interpreter("msp");
    let codec = i.codec();
    for answer in [
        error_reply as fn(msp::Command) -> Vec<u8>,
        |c: msp::Command| msp_frame(b'>', u8::try_from(c.id()).expect("a v1 id")),
    ] {
        let generated = outcomes(msp::Session, answer);
        let built = codec
            .with_session(|rules| outcomes(rules, answer))
            .expect("a session");
        assert_eq!(built, generated);
        assert!(generated.len() > 20, "{generated:?}");
        for line in &generated {
            assert!(line.contains("Unsolicited then Outcome"), "{line}");
        }
    }
    // An error reply refuses; a reply (empty here, as a SET's) answers.
    let refused = outcomes(msp::Session, error_reply);
    assert!(
        refused.iter().all(|l| l.contains("resolution: Refused")),
        "{refused:?}"
    );
    let answered = outcomes(msp::Session, |c| {
        msp_frame(b'>', u8::try_from(c.id()).expect("a v1 id"))
    });
    assert!(
        answered.iter().all(|l| l.contains("resolution: Answered")),
        "{answered:?}"
    );
}

/// A flight controller that answers API_VERSION and refuses the rest (the handler's default).
struct Fc;

impl msp::RequestHandler for Fc {
    fn api_version(&mut self, _: &msp::Header) -> protocol_kit::session::Reply<msp::ApiVersion> {
        protocol_kit::session::Reply::Answer(msp::ApiVersion {
            protocol_version: 0,
            api_version_major: 1,
            api_version_minor: 46,
        })
    }
}

#[test]
fn msp_dispatch_answers_with_the_reply_or_the_error_reply_of_the_command() {
    let mut req = Requester::<_, 2, { msp::MAX_FRAME_LEN }>::new(msp::Session);
    let mut buf = [0u8; msp::MAX_FRAME_LEN];
    for (request, answered) in [
        (msp::Request::ApiVersion, true),
        (msp::Request::Status, false),
    ] {
        let packet = msp::Packet {
            header: msp::Header { direction: b'<' },
            message: msp::Message::Request(request),
        };
        let n = packet.encode(&mut buf).expect("encodes");
        let mut frame = buf[..n].to_vec();
        let ticket = req.send(0, &mut frame).expect("sent").expect("answered");
        let answer = msp::dispatch_request(&mut Fc, &packet).expect("an answer");
        // The answer's header tells its direction: `>` for the reply, `!` for the refusal.
        let expected = if answered { b'>' } else { b'!' };
        assert_eq!(answer.header.direction, expected, "{answer:?}");
        let n = answer.encode(&mut buf).expect("the answer encodes");
        let resolution = if answered {
            Resolution::Answered
        } else {
            assert_eq!(answer.message, msp::Message::Error(msp::Command::Status));
            Resolution::Refused
        };
        assert_eq!(
            req.on_frame(1, &buf[..n]),
            Received::Outcome(protocol_kit::session::Outcome { ticket, resolution })
        );
    }
}
