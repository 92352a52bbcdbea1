//! The host's side of the tutorial's link: sends the rover five commands over a simulated
//! serial line that adds noise and flips a bit, prints what comes back, and writes every byte
//! that crossed the line to a capture file for `protocol decode`.

use rover_link::Rover;
use rover_link::rover::{self, Drive, Header, Lights, Message, Packet, Status};

fn frame(message: Message) -> Result<Vec<u8>, protocol_kit::EncodeError> {
    let mut buf = [0u8; rover::MAX_FRAME_LEN];
    let n = Packet {
        header: Header {},
        message,
    }
    .encode(&mut buf)?;
    Ok(buf[..n].to_vec())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "rover.bin".into());
    let mut rover = Rover::new(Status {
        battery: 12.6,
        odometer: 1250,
    });
    let mut host = rover::decoder();
    let mut line = vec![0x00, 0xA5]; // every byte on the line, both ways; it starts with noise
    let lights = Message::Lights(Lights {
        on: true,
        level: 200,
    });
    let commands = [
        Message::Ping,
        Message::Drive(Drive {
            speed: 0.5,
            turn: -0.25,
        }),
        lights,
        lights,
        Message::Ping,
    ];
    for (i, message) in commands.into_iter().enumerate() {
        let mut bytes = frame(message)?;
        if i == 2 {
            bytes[4] ^= 0x01; // a bit flip on the line: the CRC catches it
        }
        line.extend(&bytes);
        let mut replies = Vec::new();
        rover.receive(&bytes, &mut |reply| replies.extend_from_slice(reply))?;
        line.extend(&replies);
        let mut input = &replies[..];
        while let Some(reply) = host.decode(&mut input) {
            println!("host <- {:?}", Packet::from_frame(reply.bytes)?.message);
        }
    }
    println!("rover: drive {:?}, lights {:?}", rover.drive, rover.lights);
    let link = rover.link();
    println!(
        "rover's link: {} frames, {} bad CRC, {} bytes skipped",
        link.frames, link.bad_checksum, link.skipped_bytes
    );
    std::fs::write(&path, &line)?;
    println!("{} bytes written to {path}", line.len());
    Ok(())
}
