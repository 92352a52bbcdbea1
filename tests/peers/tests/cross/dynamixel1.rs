//! Dynamixel Protocol 1.0 (`tests/vectors/dynamixel_protocol1.json`) against `rustypot` 1.13
//! (Pollen Robotics), a bus master for protocol 1.0 and 2.0 servos.
//!
//! The peer talks through one end of a pseudo-terminal pair; a thread on the other end plays
//! the servo: it reads the instruction packet the peer sends and answers with a status packet.
//! The instructions the peer can send (PING, READ, WRITE, SYNC_WRITE, FACTORY_RESET) must be the
//! vectors' bytes, and every status packet of the vectors must decode in the peer to its
//! parameters and error byte. The peer sends no REG_WRITE, ACTION or BULK_READ, and reads no
//! stream, so those vectors have no peer here.
//!
//! With the spec (`specs/dynamixel1.toml`, generated code): every status packet the servo
//! thread writes is encoded by this project's codec, every instruction packet the peer sends is
//! the one this codec encodes for the same request (and decodes as a request to it), and random
//! instructions and status packets cross in both directions.

use dynamixel1::{Header, Message, Packet, Request, Status, SyncWrite, SyncWriteServo};
use protocol_kit::{Bytes, Group};
use protocol_peers::{frame_bytes, frames, load_vectors, name, uint, uints};
use rustypot::DynamixelProtocolHandler;
use serialport::{SerialPort, TTYPort};
use std::io::{Read, Write};
use std::time::Duration;

protocol_kit::protocol!("../../specs/dynamixel1.toml");

/// A status packet (`FF FF id len error params checksum`), encoded by this project's codec.
fn status(id: u8, error: u8, params: &[u8]) -> Vec<u8> {
    let bit = |n: u8| error & (1 << n) != 0;
    let packet = Packet {
        header: Header { id },
        message: Message::Response(Status {
            input_voltage: bit(0),
            angle_limit: bit(1),
            overheating: bit(2),
            range: bit(3),
            checksum: bit(4),
            overload: bit(5),
            instruction: bit(6),
            error_reserved: error >> 7,
            params: Bytes::from_slice(params).expect("params fit"),
        }),
    };
    encoded(&packet)
}

fn encoded(packet: &Packet) -> Vec<u8> {
    let mut buf = [0u8; dynamixel1::MAX_FRAME_LEN];
    let n = packet.encode(&mut buf).expect("encodes");
    buf[..n].to_vec()
}

/// The instruction packet this codec encodes for `request` to servo `id`; the bytes the peer
/// sent must be it, and decode as a request to it.
fn ours(id: u8, request: Request, sent: &[u8]) -> bool {
    let packet = Packet {
        header: Header { id },
        message: Message::Request(request),
    };
    encoded(&packet) == sent && Packet::decode_request(sent) == Ok(packet)
}

struct Bench {
    dph: DynamixelProtocolHandler,
    port: TTYPort,
    servo: TTYPort,
}

impl Bench {
    fn new() -> Self {
        let (mut port, mut servo) = TTYPort::pair().expect("a pseudo-terminal pair");
        port.set_timeout(Duration::from_millis(300))
            .expect("timeout");
        servo
            .set_timeout(Duration::from_millis(300))
            .expect("timeout");
        Self {
            dph: DynamixelProtocolHandler::v1(),
            port,
            servo,
        }
    }

    /// Runs `f` against the peer while the servo thread answers its instruction with `reply`;
    /// returns the instruction packet the peer sent and `f`'s result.
    fn exchange<R>(
        &mut self,
        reply: Option<Vec<u8>>,
        f: impl FnOnce(&DynamixelProtocolHandler, &mut dyn SerialPort) -> R,
    ) -> (Vec<u8>, R) {
        let mut servo = self.servo.try_clone_native().expect("clone");
        let thread = std::thread::spawn(move || {
            let mut packet = Vec::new();
            let mut byte = [0u8; 1];
            while packet.len() < 4 || packet.len() < 4 + usize::from(packet[3]) {
                match servo.read(&mut byte) {
                    Ok(1) => packet.push(byte[0]),
                    _ => return packet,
                }
            }
            if let Some(reply) = reply {
                servo.write_all(&reply).expect("reply");
            }
            packet
        });
        let result = f(&self.dph, &mut self.port);
        (thread.join().expect("servo thread"), result)
    }
}

fn frame<'a>(v: &'a serde_json::Value, wanted: &str) -> &'a serde_json::Value {
    frames(v)
        .iter()
        .find(|f| name(f) == wanted)
        .unwrap_or_else(|| panic!("no frame {wanted}"))
}

#[test]
fn the_instructions_rustypot_sends_are_the_vectors_bytes() {
    let v = load_vectors("dynamixel_protocol1.json");
    let mut bench = Bench::new();
    let mut compared = 0;
    let mut check = |wanted: &str, sent: Vec<u8>| {
        assert_eq!(sent, frame_bytes(frame(&v, wanted)), "{wanted}");
        compared += 1;
    };
    let (sent, found) = bench.exchange(Some(status(1, 0, &[])), |d, p| d.ping(p, 1));
    assert!(found.expect("ping"));
    check("ping", sent);
    let (sent, r) = bench.exchange(Some(status(1, 0, &[])), |d, p| {
        d.write(p, 1, 30, &[0x00, 0x02])
    });
    r.expect("write");
    check("write_goal_position", sent);
    let (sent, r) = bench.exchange(Some(status(7, 0, &[])), |d, p| {
        d.write(p, 7, 116, &[0xFE, 0xFF, 0xFF, 0xFF])
    });
    r.expect("write");
    check("write_4_bytes", sent);
    let (sent, r) = bench.exchange(Some(status(1, 0, &[0, 0, 0, 0])), |d, p| {
        d.read(p, 1, 36, 4)
    });
    r.expect("read");
    check("read_present_position_speed", sent);
    let (sent, r) = bench.exchange(Some(status(0, 0, &[])), |d, p| {
        d.factory_reset(p, 0, false, false)
    });
    r.expect("factory reset");
    check("factory_reset", sent);
    let data = [
        vec![0x10, 0x00, 0x50, 0x01],
        vec![0x20, 0x02, 0x60, 0x03],
        vec![0x30, 0x00, 0x70, 0x01],
        vec![0x20, 0x02, 0x80, 0x03],
    ];
    let (sent, r) = bench.exchange(None, |d, p| d.sync_write(p, &[1, 2, 3, 4], 0x1E, &data));
    r.expect("sync write");
    check("sync_write_position_speed", sent);
    // READ of the temperature, answered by the vectors' own status packet.
    let reply = frame_bytes(frame(&v, "status_temperature"));
    let (sent, r) = bench.exchange(Some(reply), |d, p| d.read(p, 1, 0x2B, 1));
    assert_eq!(r.expect("read"), vec![0x20]);
    check("read_temperature", sent);
    println!("rustypot: {compared} instruction packets compared");
    assert_eq!(compared, 7);
}

#[test]
fn every_status_packet_decodes_in_rustypot() {
    let v = load_vectors("dynamixel_protocol1.json");
    let mut bench = Bench::new();
    let mut decoded = 0;
    for f in frames(&v).iter().filter(|f| f["packet"] == "status") {
        let id = uint(f, "id") as u8;
        let params: Vec<u8> = uints(&f["fields"], "params")
            .iter()
            .map(|&b| b as u8)
            .collect();
        let (_, result) = bench.exchange(Some(frame_bytes(f)), |d, p| {
            d.read_with_error(p, id, 0, params.len() as u8)
        });
        let (data, error) = result.unwrap_or_else(|e| panic!("{}: {e}", name(f)));
        assert_eq!(data, params, "{}", name(f));
        assert_eq!(u64::from(error.byte()), uint(f, "error"), "{}", name(f));
        decoded += 1;
    }
    println!("rustypot: {decoded} status packets decoded");
    assert_eq!(decoded, 4);
}

/// A seeded xorshift, so a failing exchange is reproducible.
struct Rng(u64);

impl Rng {
    fn below(&mut self, n: u64) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0 % n
    }
    fn byte(&mut self) -> u8 {
        self.below(256) as u8
    }
    fn bytes(&mut self, n: usize) -> Vec<u8> {
        (0..n).map(|_| self.byte()).collect()
    }
}

/// Random instructions sent by the peer are the packets this codec encodes for them, and the
/// status packets this codec encodes for the answers (any error bits but the reserved one,
/// which the SDK refuses) decode in the peer to their data and error byte.
#[test]
fn random_exchanges_cross_with_rustypot() {
    const ROUNDS: usize = 120;
    let mut rng = Rng(0x00D1_5EA5_E5D1_A11E);
    let mut bench = Bench::new();
    let (mut instructions, mut statuses) = (0, 0);
    for round in 0..ROUNDS {
        let id = rng.below(253) as u8;
        let address = rng.byte();
        let error = rng.below(0x80) as u8;
        match round % 4 {
            0 => {
                let length = 1 + rng.below(8) as u8;
                let data = rng.bytes(usize::from(length));
                let reply = status(id, error, &data);
                let (sent, r) = bench.exchange(Some(reply), |d, p| {
                    d.read_with_error(p, id, address, length)
                });
                let (got, err) = r.unwrap_or_else(|e| panic!("round {round}: {e}"));
                assert_eq!((got, err.byte()), (data, error), "round {round}");
                statuses += 1;
                let read = Request::Read(dynamixel1::Read { address, length });
                assert!(ours(id, read, &sent), "round {round}: {sent:02x?}");
            }
            1 => {
                let n = 1 + rng.below(8) as usize;
                let data = rng.bytes(n);
                let (sent, r) = bench.exchange(Some(status(id, 0, &[])), |d, p| {
                    d.write(p, id, address, &data)
                });
                r.unwrap_or_else(|e| panic!("round {round}: {e}"));
                statuses += 1;
                let write = Request::Write(dynamixel1::Write {
                    address,
                    data: Bytes::from_slice(&data).expect("fits"),
                });
                assert!(ours(id, write, &sent), "round {round}: {sent:02x?}");
            }
            2 => {
                let (sent, found) = bench.exchange(Some(status(id, 0, &[])), |d, p| d.ping(p, id));
                assert!(found.expect("ping"), "round {round}");
                statuses += 1;
                assert!(ours(id, Request::Ping, &sent), "round {round}: {sent:02x?}");
            }
            _ => {
                let len = 1 + rng.below(4) as usize;
                let ids: Vec<u8> = (0..1 + rng.below(6))
                    .map(|_| rng.below(253) as u8)
                    .collect();
                let data: Vec<Vec<u8>> = ids.iter().map(|_| rng.bytes(len)).collect();
                let (sent, r) = bench.exchange(None, |d, p| d.sync_write(p, &ids, address, &data));
                r.unwrap_or_else(|e| panic!("round {round}: {e}"));
                let mut servos = Group::new();
                for (sid, d) in ids.iter().zip(&data) {
                    servos
                        .push(SyncWriteServo {
                            id: *sid,
                            data: Bytes::from_slice(d).expect("fits"),
                        })
                        .expect("room");
                }
                let sync = Request::SyncWrite(SyncWrite {
                    start_address: address,
                    data_length: len as u8,
                    servos,
                });
                assert!(ours(0xFE, sync, &sent), "round {round}: {sent:02x?}");
            }
        }
        instructions += 1;
    }
    println!(
        "rustypot: {instructions} random instruction packets equal ours, {statuses} status packets of ours decoded"
    );
    assert_eq!(instructions, ROUNDS);
}
