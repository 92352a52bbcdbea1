//! Dynamixel Protocol 1.0 (`tests/vectors/dynamixel_protocol1.json`) against `rustypot` 1.13
//! (Pollen Robotics), a bus master for protocol 1.0 and 2.0 servos.
//!
//! The peer talks through one end of a pseudo-terminal pair; a thread on the other end plays
//! the servo: it reads the instruction packet the peer sends and answers with a status packet.
//! The instructions the peer can send (PING, READ, WRITE, SYNC_WRITE, FACTORY_RESET) must be the
//! vectors' bytes, and every status packet of the vectors must decode in the peer to its
//! parameters and error byte. The peer sends no REG_WRITE, ACTION or BULK_READ, and reads no
//! stream, so those vectors have no peer here.

use protocol_peers::{frame_bytes, frames, load_vectors, name, uint, uints};
use rustypot::DynamixelProtocolHandler;
use serialport::{SerialPort, TTYPort};
use std::io::{Read, Write};
use std::time::Duration;

/// A status packet: `FF FF id len error params checksum`.
fn status(id: u8, error: u8, params: &[u8]) -> Vec<u8> {
    let mut p = vec![0xFF, 0xFF, id, params.len() as u8 + 2, error];
    p.extend_from_slice(params);
    let sum: u32 = p[2..].iter().map(|&b| u32::from(b)).sum();
    p.push(!(sum as u8));
    p
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
