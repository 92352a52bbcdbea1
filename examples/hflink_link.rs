//! A host (master) and a simulated robot (slave) talk HFLink over an in-memory link with
//! deterministic noise: bit flips, garbage bytes, stray sync bytes and truncated frames. Both
//! sides use only what `specs/hflink.toml` generates. The example prints the frames it decodes
//! and the decoders' counters, then checks that every frame the noise did not touch arrived,
//! in order (exit status 1 otherwise).
//!
//! Run: `cargo run -p protocol-examples --example hflink_link`

use protocol_kit::protocol;

protocol!("../specs/hflink.toml");

use hflink::{ChassisCoord, Header, Message, Packet, Request, Response, SystemInfo};

const MASTER: u8 = 0x01;
const SLAVE: u8 = 0x11;
const EXCHANGES: usize = 400;

/// xorshift64*: deterministic noise without dependencies.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

/// What the noisy wire did to a frame.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Fault {
    None,
    BitFlip,
    Truncated,
}

/// A one-way wire: frames go in whole, noise is applied, bytes come out in random chunks.
struct Wire {
    bytes: Vec<u8>,
    rng: Rng,
    sent: Vec<(Vec<u8>, Fault)>,
}

impl Wire {
    fn new(seed: u64) -> Self {
        Wire {
            bytes: Vec::new(),
            rng: Rng(seed),
            sent: Vec::new(),
        }
    }

    fn send(&mut self, frame: &[u8]) {
        // Garbage before the frame, sometimes with stray sync bytes in it.
        if self.rng.below(10) == 0 {
            for _ in 0..self.rng.below(12) {
                let b = if self.rng.below(3) == 0 {
                    0xFF
                } else {
                    self.rng.next() as u8
                };
                self.bytes.push(b);
            }
        }
        let mut frame = frame.to_vec();
        let fault = match self.rng.below(20) {
            0 => {
                let bit = self.rng.below(frame.len() as u64 * 8) as usize;
                frame[bit / 8] ^= 1 << (bit % 8);
                Fault::BitFlip
            }
            1 => {
                let keep = 1 + self.rng.below(frame.len() as u64 - 1) as usize;
                frame.truncate(keep);
                Fault::Truncated
            }
            _ => Fault::None,
        };
        self.bytes.extend_from_slice(&frame);
        self.sent.push((frame, fault));
    }

    /// Deliver everything in chunks of 1..=64 bytes to `receive`.
    fn deliver(&mut self, mut receive: impl FnMut(&[u8])) {
        let bytes = std::mem::take(&mut self.bytes);
        let mut rest = &bytes[..];
        while !rest.is_empty() {
            let n = (1 + self.rng.below(64) as usize).min(rest.len());
            receive(&rest[..n]);
            rest = &rest[n..];
        }
    }
}

fn robot_reply(request: &Request, state: &mut ChassisCoord) -> Option<Response> {
    Some(match request {
        Request::SetRobotSpeed(speed) => {
            *state = *speed;
            Response::SetRobotSpeed
        }
        Request::ReadRobotSpeed => Response::ReadRobotSpeed(*state),
        Request::ReadSystemInfo => Response::ReadSystemInfo(SystemInfo {
            system_time: 12.5,
            cpu_temperature: 41.0,
            cpu_usage: 0.25,
            battery_voltage: 12.3,
            power_remain: 80.0,
        }),
        _ => return None,
    })
}

fn main() {
    let mut to_robot = Wire::new(0x5EED_0001);
    let mut to_host = Wire::new(0x5EED_0002);
    let mut buf = [0u8; hflink::MAX_FRAME_LEN];

    // The host sends its requests.
    for i in 0..EXCHANGES {
        let request = match i % 3 {
            0 => Request::SetRobotSpeed(ChassisCoord {
                x: i as f32 * 0.01,
                y: 0.0,
                z: -0.5,
            }),
            1 => Request::ReadRobotSpeed,
            _ => Request::ReadSystemInfo,
        };
        let packet = Packet {
            header: Header {
                sender: MASTER,
                receiver: SLAVE,
            },
            message: Message::Request(request),
        };
        let n = packet.encode(&mut buf).expect("request fits");
        to_robot.send(&buf[..n]);
    }

    // The robot decodes whatever arrives and answers each request it understood.
    let mut robot_decoder = hflink::decoder();
    let mut robot_state = ChassisCoord::default();
    let mut robot_received = Vec::new();
    let mut replies = Vec::new();
    to_robot.deliver(|chunk| {
        let mut input = chunk;
        while let Some(frame) = robot_decoder.decode(&mut input) {
            robot_received.push(frame.bytes.to_vec());
            let reply = match Packet::from_frame(frame.bytes) {
                Ok(Packet {
                    message: Message::Request(req),
                    ..
                }) => robot_reply(&req, &mut robot_state),
                _ => None,
            };
            if let Some(resp) = reply {
                replies.push(Packet {
                    header: Header {
                        sender: SLAVE,
                        receiver: MASTER,
                    },
                    message: Message::Response(resp),
                });
            }
        }
    });
    for reply in &replies {
        let n = reply.encode(&mut buf).expect("reply fits");
        to_host.send(&buf[..n]);
    }

    // The host decodes the replies.
    let mut host_decoder = hflink::decoder();
    let mut host_received = Vec::new();
    let mut shown = 0;
    to_host.deliver(|chunk| {
        let mut input = chunk;
        while let Some(frame) = host_decoder.decode(&mut input) {
            if shown < 6 {
                match Packet::from_frame(frame.bytes) {
                    Ok(p) => println!("host  <- @{:<6} {:?}", frame.offset, p.message),
                    Err(e) => println!("host  <- @{:<6} undecodable: {e}", frame.offset),
                }
                shown += 1;
            }
            host_received.push(frame.bytes.to_vec());
        }
    });

    let mut ok = true;
    for (name, wire, received, dec) in [
        ("robot", &to_robot, &robot_received, robot_decoder.stats()),
        ("host", &to_host, &host_received, host_decoder.stats()),
    ] {
        let untouched: Vec<&Vec<u8>> = wire
            .sent
            .iter()
            .filter(|(_, f)| *f == Fault::None)
            .map(|(b, _)| b)
            .collect();
        let flipped = wire
            .sent
            .iter()
            .filter(|(_, f)| *f == Fault::BitFlip)
            .count();
        let truncated = wire
            .sent
            .iter()
            .filter(|(_, f)| *f == Fault::Truncated)
            .count();
        // Every untouched frame must be among the received ones, in order.
        let mut it = received.iter();
        let all_arrived = untouched.iter().all(|u| it.any(|r| r == *u));
        println!(
            "{name:>5}: sent {} frames ({} untouched, {flipped} bit-flipped, {truncated} truncated); decoded {} frames",
            wire.sent.len(),
            untouched.len(),
            received.len()
        );
        println!(
            "       decoder: frames {}, bad checksum {}, bad length {}, skipped bytes {}; every untouched frame arrived in order: {}",
            dec.frames, dec.bad_checksum, dec.bad_length, dec.skipped_bytes, all_arrived
        );
        ok &= all_arrived;
    }
    if !ok {
        eprintln!("a frame that the noise did not touch was lost");
        std::process::exit(1);
    }
}
