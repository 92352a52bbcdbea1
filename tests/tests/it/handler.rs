//! The generated handlers: per seed, an implementation of the handler trait of the side that
//! answers, frames encoded as the other side sends them, decoded, dispatched, and the answer
//! encoded and decoded back (HFLink: a READ's reply, a SET's empty reply, a refusal before the
//! handshake, the answer run through the session machines; Dynamixel: a READ's status and a
//! broadcast that gets none; RoboRTS: an acknowledgement per session mode).

use protocol_kit::session::{Incoming, Received, Reply, Resolution};

protocol_kit::protocol!("../specs/hflink.toml");
protocol_kit::protocol!("../specs/dynamixel.toml");
protocol_kit::protocol!("../specs/roborts.toml");

/// Encodes `packet` into a new buffer of `max` bytes, cut to its length.
fn encode(
    max: usize,
    f: impl FnOnce(&mut [u8]) -> Result<usize, protocol_kit::EncodeError>,
) -> Vec<u8> {
    let mut buf = vec![0u8; max];
    let n = f(&mut buf).expect("encodes");
    buf.truncate(n);
    buf
}

/// An HFLink slave: it answers the handshake, READ_SYSTEM_INFO and SET_GLOBAL_SPEED, and
/// leaves the rest to the trait's defaults.
#[derive(Default)]
struct Slave {
    handshaken: bool,
    speed: Option<hflink::ChassisCoord>,
}

impl hflink::RequestHandler for Slave {
    fn shaking_hands(&mut self, _: &hflink::Header, _: &hflink::ChassisCoord) -> Reply<()> {
        self.handshaken = true;
        Reply::ACK
    }

    fn read_system_info(&mut self, _: &hflink::Header) -> Reply<hflink::SystemInfo> {
        if !self.handshaken {
            return Reply::Refuse;
        }
        Reply::Answer(hflink::SystemInfo {
            system_time: 12.5,
            cpu_temperature: 41.0,
            cpu_usage: 0.25,
            battery_voltage: 12.0,
            power_remain: 80.0,
        })
    }

    fn set_global_speed(&mut self, _: &hflink::Header, speed: &hflink::ChassisCoord) -> Reply<()> {
        self.speed = Some(*speed);
        Reply::ACK
    }
}

/// The HFLink master: it collects the responses the slave sends.
#[derive(Default)]
struct Master {
    system_info: Vec<hflink::SystemInfo>,
    handshakes: usize,
}

impl hflink::ResponseHandler for Master {
    fn shaking_hands(&mut self, _: &hflink::Header) {
        self.handshakes += 1;
    }

    fn read_system_info(&mut self, _: &hflink::Header, info: &hflink::SystemInfo) {
        self.system_info.push(*info);
    }
}

fn hflink_request(message: hflink::Request) -> Vec<u8> {
    let packet = hflink::Packet {
        header: hflink::Header {
            sender: 0x01,
            receiver: 0x11,
        },
        message: hflink::Message::Request(message),
    };
    encode(hflink::MAX_FRAME_LEN, |b| packet.encode(b))
}

/// The slave's answer to `frame`, decoded.
fn hflink_answer(slave: &mut Slave, frame: &[u8]) -> Option<hflink::Packet> {
    let request = hflink::Packet::decode(frame).expect("a request");
    let answer = hflink::dispatch_request(slave, &request)?;
    let bytes = encode(hflink::MAX_FRAME_LEN, |b| answer.encode(b));
    Some(hflink::Packet::decode(&bytes).expect("the answer decodes"))
}

#[test]
fn hflink_read_is_answered_by_its_reply() {
    let mut slave = Slave::default();
    let read = hflink_request(hflink::Request::ReadSystemInfo);
    // Before the handshake the slave refuses: an empty SHAKING_HANDS, the spec's NACK.
    let refused = hflink_answer(&mut slave, &read).expect("a refusal");
    assert_eq!(
        refused.message,
        hflink::Message::Response(hflink::Response::ShakingHands)
    );
    let coord = hflink::ChassisCoord {
        x: 1.0,
        y: 2.0,
        z: 0.5,
    };
    let hello = hflink_answer(
        &mut slave,
        &hflink_request(hflink::Request::ShakingHands(coord)),
    )
    .expect("the handshake's reply");
    assert_eq!(
        hello.message,
        hflink::Message::Response(hflink::Response::ShakingHands)
    );
    let reply = hflink_answer(&mut slave, &read).expect("the reply");
    // The reply swaps the addresses, so it decodes as a response (its sender is a slave).
    assert_eq!(
        reply.header,
        hflink::Header {
            sender: 0x11,
            receiver: 0x01
        }
    );
    let hflink::Message::Response(hflink::Response::ReadSystemInfo(info)) = reply.message else {
        panic!("not READ_SYSTEM_INFO's reply: {reply:?}");
    };
    assert_eq!(info.cpu_temperature, 41.0);
    let set = hflink_request(hflink::Request::SetGlobalSpeed(coord));
    let ack = hflink_answer(&mut slave, &set).expect("the SET's reply");
    assert_eq!(
        ack.message,
        hflink::Message::Response(hflink::Response::SetGlobalSpeed)
    );
    assert_eq!(slave.speed, Some(coord));
    // A command the slave does not implement: the default refuses it.
    let save = hflink_request(hflink::Request::SaveMotorParameters);
    let refused = hflink_answer(&mut slave, &save).expect("a refusal");
    assert_eq!(
        refused.message,
        hflink::Message::Response(hflink::Response::ShakingHands)
    );
}

/// The whole round: the master's requester sends, the slave's responder delivers, the handler
/// answers, the responder seals the answer, the requester resolves the ticket, and the
/// master's handler gets the response.
#[test]
fn hflink_handlers_hold_the_session() {
    let (mut slave, mut master) = (Slave::default(), Master::default());
    let mut requester = hflink::Requester::<4>::new(hflink::Session);
    let mut responder = hflink::Responder::<4>::new(hflink::Session);
    let coord = hflink::ChassisCoord {
        x: 0.0,
        y: 0.0,
        z: 0.0,
    };
    let requests = [
        hflink::Request::ShakingHands(coord),
        hflink::Request::ReadSystemInfo,
    ];
    for (now, message) in (0u64..).zip(requests) {
        let mut frame = hflink_request(message);
        let ticket = requester
            .send(now, &mut frame)
            .expect("sent")
            .expect("answered");
        let Incoming::Deliver { answer: true } = responder.on_frame(now, &frame) else {
            panic!("not delivered");
        };
        let request = hflink::Packet::decode(&frame).expect("decodes");
        let answer = hflink::dispatch_request(&mut slave, &request).expect("an answer");
        let mut bytes = encode(hflink::MAX_FRAME_LEN, |b| answer.encode(b));
        responder.answer(&frame, &mut bytes).expect("sealed");
        assert_eq!(
            requester.on_frame(now, &bytes),
            Received::Outcome(protocol_kit::session::Outcome {
                ticket,
                resolution: Resolution::Answered
            })
        );
        hflink::dispatch_response(
            &mut master,
            &hflink::Packet::decode(&bytes).expect("decodes"),
        );
    }
    assert_eq!(master.system_info.len(), 1);
    assert_eq!(
        master.handshakes, 1,
        "the handshake's reply is an empty SHAKING_HANDS"
    );
}

/// A Dynamixel servo: its control table, read and written.
struct Servo {
    table: [u8; 256],
}

impl dynamixel::Handler for Servo {
    fn read(&mut self, _: &dynamixel::Header, read: &dynamixel::Read) -> Reply<dynamixel::Status> {
        let (at, n) = (usize::from(read.address), usize::from(read.length));
        let Some(data) = self.table.get(at..at + n) else {
            return Reply::Answer(dynamixel::Status {
                error_number: 7, // data range error
                alert: false,
                data: protocol_kit::Bytes::new(),
            });
        };
        Reply::Answer(dynamixel::Status {
            error_number: 0,
            alert: false,
            data: protocol_kit::Bytes::from_slice(data).expect("fits"),
        })
    }

    fn write(
        &mut self,
        _: &dynamixel::Header,
        write: &dynamixel::Write,
    ) -> Reply<dynamixel::Status> {
        let at = usize::from(write.address);
        if let Some(cells) = self.table.get_mut(at..at + write.data.len()) {
            cells.copy_from_slice(&write.data);
        }
        Reply::Answer(dynamixel::Status {
            error_number: 0,
            alert: false,
            data: protocol_kit::Bytes::new(),
        })
    }
}

fn dynamixel_answer(
    servo: &mut Servo,
    id: u8,
    message: dynamixel::Message,
) -> Option<dynamixel::Packet> {
    let packet = dynamixel::Packet {
        header: dynamixel::Header { id },
        message,
    };
    let frame = encode(dynamixel::MAX_FRAME_LEN, |b| packet.encode(b));
    let answer = dynamixel::dispatch(servo, &dynamixel::Packet::decode(&frame).expect("decodes"))?;
    let bytes = encode(dynamixel::MAX_FRAME_LEN, |b| answer.encode(b));
    Some(dynamixel::Packet::decode(&bytes).expect("the status decodes"))
}

#[test]
fn dynamixel_read_is_answered_by_a_status() {
    let mut servo = Servo { table: [0; 256] };
    // A broadcast WRITE (id 0xFE) is applied and gets no status.
    let write = dynamixel::Message::Write(dynamixel::Write {
        address: 116,
        data: protocol_kit::Bytes::from_slice(&[0x00, 0x08, 0x00, 0x00]).expect("fits"),
    });
    assert_eq!(dynamixel_answer(&mut servo, 0xFE, write), None);
    let read = dynamixel::Message::Read(dynamixel::Read {
        address: 116,
        length: 4,
    });
    let status = dynamixel_answer(&mut servo, 1, read).expect("a status");
    assert_eq!(status.header.id, 1, "the status repeats the servo's id");
    let dynamixel::Message::Status(s) = status.message else {
        panic!("not a status: {status:?}");
    };
    assert_eq!(
        (s.error_number, &s.data[..]),
        (0, &[0x00, 0x08, 0x00, 0x00][..])
    );
    // PING is not implemented: the default refuses, and the spec has no NACK, so nothing.
    assert_eq!(
        dynamixel_answer(&mut servo, 1, dynamixel::Message::Ping),
        None
    );
    // A status received is not a request: nothing is answered.
    let status = dynamixel::Message::Status(s);
    assert_eq!(dynamixel_answer(&mut servo, 1, status), None);
}

/// A RoboRTS chassis: it takes speed commands.
#[derive(Default)]
struct Chassis {
    speeds: Vec<roborts::ChassisSpeed>,
}

impl roborts::Handler for Chassis {
    fn set_chassis_speed(
        &mut self,
        _: &roborts::Header,
        speed: &roborts::ChassisSpeed,
    ) -> Reply<()> {
        self.speeds.push(*speed);
        Reply::ACK
    }
}

#[test]
fn roborts_commands_are_acknowledged_by_their_mode() {
    let mut chassis = Chassis::default();
    let speed = roborts::ChassisSpeed {
        vx: 100,
        vy: -5,
        vw: 3,
        rotate_x_offset: 0,
        rotate_y_offset: 0,
    };
    let answer = |chassis: &mut Chassis, session_id: u8, message: roborts::Message| {
        let packet = roborts::Packet {
            header: roborts::Header {
                session_id,
                sender: 0,
                receiver: 1,
                seq_num: 7,
            },
            message,
        };
        let frame = encode(roborts::MAX_FRAME_LEN, |b| packet.encode(b));
        let answer =
            roborts::dispatch(chassis, &roborts::Packet::decode(&frame).expect("decodes"))?;
        let bytes = encode(roborts::MAX_FRAME_LEN, |b| answer.encode(b));
        Some(roborts::Packet::decode(&bytes).expect("the ack decodes"))
    };
    // Session 2: acknowledged, with the session id and sequence number, addresses swapped.
    let ack = answer(&mut chassis, 2, roborts::Message::SetChassisSpeed(speed)).expect("an ack");
    assert!(matches!(ack.message, roborts::Message::Ack(ref d) if d.is_empty()));
    assert_eq!(
        ack.header,
        roborts::Header {
            session_id: 2,
            sender: 1,
            receiver: 0,
            seq_num: 7
        }
    );
    // Session 0: delivered, not acknowledged.
    assert_eq!(
        answer(&mut chassis, 0, roborts::Message::SetChassisSpeed(speed)),
        None
    );
    assert_eq!(chassis.speeds, [speed, speed]);
    // A command the chassis does not handle: refused, and RoboRTS has no NACK, so nothing.
    let heartbeat = roborts::Message::Heartbeat(roborts::Heartbeat { heartbeat: 1 });
    assert_eq!(answer(&mut chassis, 2, heartbeat), None);
}
