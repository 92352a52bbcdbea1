//! A tokio host talks HFLink to a simulated robot over a real pseudo-terminal, opened with
//! `tokio-serial` (`SerialStream::pair`: the robot holds the master end, the host the
//! `/dev/pts/N` serial port). Both ends run `protocol`'s `PacketCodec` under `tokio_util`'s
//! `Framed`; the robot writes noise between its answers (garbage, a stray sync word, a frame
//! with a bad sum), which the host reads as items and counts, not as errors.
//!
//! The host sends a handshake, then asks for the robot's speed and sets it a few times, and
//! checks every answer; it prints what it sent and received and the decoder's counters. Exit
//! status 1 on a wrong or missing answer. Where no pseudo-terminal can be opened (a sandbox
//! without `/dev/ptmx`), it says so and exits 0 without running.
//!
//! Run: `cargo run -p protocol-examples --example tokio_serial_host`

use std::process::ExitCode;
use std::time::Duration;

use futures_util::{SinkExt, StreamExt};
use protocol_kit::codec::PacketCodec;
use protocol_kit::{PacketEvent, protocol};
use tokio_serial::SerialStream;
use tokio_util::codec::Framed;

protocol!("../specs/hflink.toml");

use hflink::{
    ChassisCoord, DECODER_BUFFER_LEN, Header, Layout, Message, Packet, Request, Response,
};

const MASTER: u8 = 0x01;
const SLAVE: u8 = 0x11;

type Link = Framed<SerialStream, PacketCodec<Layout, DECODER_BUFFER_LEN>>;

/// Noise the robot writes before each answer, in turn.
const NOISE: [&[u8]; 4] = [
    &[0x00, 0x13, 0x7E],
    &[0xFF, 0xFF, 0x11],
    // A SET_ROBOT_SPEED acknowledgement with a bad sum.
    &[0xFF, 0xFF, 0x11, 0x01, 0x00, 0x01, 0x0C, 0x1E],
    &[],
];

/// The simulated robot: answers every request it decodes, after some noise.
async fn robot(port: SerialStream) {
    let mut link: Link = Framed::new(port, PacketCodec::new(Layout));
    let mut speed = ChassisCoord {
        x: 0.0,
        y: 0.0,
        z: 0.0,
    };
    let mut turn = 0;
    while let Some(Ok(event)) = link.next().await {
        let Some(Packet {
            message: Message::Request(request),
            ..
        }) = event.packet()
        else {
            continue;
        };
        let answer = match request {
            Request::ShakingHands(_) => Response::ShakingHands,
            Request::ReadRobotSpeed => Response::ReadRobotSpeed(speed),
            Request::SetRobotSpeed(s) => {
                speed = s;
                Response::SetRobotSpeed
            }
            _ => continue,
        };
        link.write_buffer_mut()
            .extend_from_slice(NOISE[turn % NOISE.len()]);
        turn += 1;
        let reply = Packet {
            header: Header {
                sender: SLAVE,
                receiver: MASTER,
            },
            message: Message::Response(answer),
        };
        if link.send(reply).await.is_err() {
            return;
        }
    }
}

/// Sends `request` and waits for the next packet, reporting the noise read before it.
async fn ask(link: &mut Link, request: Request) -> Result<Response, String> {
    let packet = Packet {
        header: Header {
            sender: MASTER,
            receiver: SLAVE,
        },
        message: Message::Request(request),
    };
    println!("host -> robot  {request:?}");
    link.send(packet).await.map_err(|e| format!("send: {e}"))?;
    loop {
        let event = tokio::time::timeout(Duration::from_secs(5), link.next())
            .await
            .map_err(|_| "no answer within 5 s".to_string())?
            .ok_or("the port closed")?
            .map_err(|e| format!("read: {e}"))?;
        match event {
            PacketEvent::Packet {
                packet:
                    Packet {
                        message: Message::Response(r),
                        ..
                    },
                ..
            } => {
                println!("robot -> host  {r:?}");
                return Ok(r);
            }
            PacketEvent::Packet { packet, .. } => {
                return Err(format!("not a response: {packet:?}"));
            }
            PacketEvent::Invalid { offset, error } => println!("  (noise at {offset}: {error})"),
            PacketEvent::Skipped { offset, len } => {
                println!("  (noise at {offset}: {len} bytes skipped)")
            }
        }
    }
}

async fn session(link: &mut Link) -> Result<(), String> {
    let expect = |got: Response, want: Response| {
        if got == want {
            Ok(())
        } else {
            Err(format!("expected {want:?}, got {got:?}"))
        }
    };
    let here = ChassisCoord {
        x: 3.0,
        y: 4.0,
        z: 0.5,
    };
    expect(
        ask(link, Request::ShakingHands(here)).await?,
        Response::ShakingHands,
    )?;
    for i in 0..4u8 {
        let speed = ChassisCoord {
            x: f32::from(i) * 0.25,
            y: -0.5,
            z: 0.125,
        };
        expect(
            ask(link, Request::SetRobotSpeed(speed)).await?,
            Response::SetRobotSpeed,
        )?;
        expect(
            ask(link, Request::ReadRobotSpeed).await?,
            Response::ReadRobotSpeed(speed),
        )?;
    }
    Ok(())
}

#[tokio::main(flavor = "current_thread")]
async fn main() -> ExitCode {
    let (robot_end, host_end) = match SerialStream::pair() {
        Ok(pair) => pair,
        Err(e) => {
            println!("tokio_serial_host: no pseudo-terminal can be opened here ({e}); not run");
            return ExitCode::SUCCESS;
        }
    };
    let name = tokio_serial::SerialPort::name(&host_end).unwrap_or_else(|| "a pty".into());
    println!("host on {name}, robot on its master end");
    tokio::spawn(robot(robot_end));
    let mut link: Link = Framed::new(host_end, PacketCodec::new(Layout));
    let result = session(&mut link).await;
    let stats = *link.codec_mut().decoder().stats();
    println!(
        "host decoder: {} frames, {} bytes skipped, {} bad checksums, {} rejected",
        stats.frames,
        stats.skipped_bytes,
        stats.bad_checksum,
        stats.rejected()
    );
    match result {
        Ok(()) if stats.frames == 9 && stats.bad_checksum >= 1 => {
            println!("ok: 9 answers, the noise read as items");
            ExitCode::SUCCESS
        }
        Ok(()) => {
            println!("error: unexpected counts");
            ExitCode::FAILURE
        }
        Err(e) => {
            println!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
