//! A tokio host holds HFLink's conversation with a device on a serial port through the session
//! client: the handshake first (a READ before it is refused without being sent), then READs and
//! SETs, each resolved to its answer, a NACK, or a timeout after the spec's retries (100 ms,
//! doubled on each of 2 retries). It prints each outcome and the retries it took.
//!
//! With no robot at hand, the device twin answers on a pseudo-terminal as the spec says, and
//! drops frames to show the retries:
//!
//! ```text
//! protocol twin specs/hflink.toml --pty --drop 0.2     # prints the port, e.g. /dev/pts/3
//! cargo run -p protocol-examples --example session_host -- /dev/pts/3
//! ```
//!
//! Exit status 1 when the handshake is not answered or the port cannot be opened.

use std::process::ExitCode;

use protocol_kit::protocol;
use protocol_kit::session::client::{Client, Reply};
use tokio_serial::SerialPortBuilderExt;

protocol!("../specs/hflink.toml");

use hflink::{ChassisCoord, Header, MAX_FRAME_LEN, Message, Packet, Request, Session};

fn to_slave(request: Request) -> Packet {
    Packet {
        header: Header {
            sender: 0x01,
            receiver: 0x11,
        },
        message: Message::Request(request),
    }
}

/// One line per outcome: the answer decoded, the NACK, or the timeout.
fn show(what: &str, reply: &Reply) {
    match reply {
        Reply::Answered(frame) => match Packet::from_frame(frame) {
            Ok(p) => println!("{what}: {:?}", p.message),
            Err(e) => println!("{what}: an answer that does not decode ({e})"),
        },
        Reply::Refused(_) => println!("{what}: refused (NACK)"),
        Reply::Rejected { value, .. } => println!("{what}: refused with result {value}"),
        Reply::TimedOut => println!("{what}: no answer after the retries"),
        Reply::AnsweredAll(frames) => println!("{what}: {} answers", frames.len()),
        Reply::Incomplete { missing, .. } => println!("{what}: no answer from {missing:?}"),
        Reply::Sent => println!("{what}: sent"),
    }
}

#[tokio::main(flavor = "current_thread")]
async fn main() -> ExitCode {
    let Some(path) = std::env::args().nth(1) else {
        println!(
            "usage: session_host PORT   (a serial port, or the pty `protocol twin --pty` prints)"
        );
        return ExitCode::SUCCESS;
    };
    let port = match tokio_serial::new(&path, 115_200).open_native_async() {
        Ok(port) => port,
        Err(e) => {
            println!("cannot open {path}: {e}");
            return ExitCode::FAILURE;
        }
    };
    // Up to 4 requests open at once.
    let (client, mut unsolicited) = Client::spawn::<_, 4, MAX_FRAME_LEN>(port, Session);

    let read = to_slave(Request::ReadRobotSpeed);
    match client.request(&read).await {
        Err(e) => println!("READ before the handshake: {e}"),
        Ok(reply) => show("READ before the handshake", &reply),
    }
    let here = ChassisCoord {
        x: 0.0,
        y: 0.0,
        z: 0.0,
    };
    match client.request(&to_slave(Request::ShakingHands(here))).await {
        Ok(reply @ Reply::Answered(_)) => show("SHAKING_HANDS", &reply),
        other => {
            println!("SHAKING_HANDS: {other:?}");
            return ExitCode::FAILURE;
        }
    }
    for i in 0..5u8 {
        let speed = ChassisCoord {
            x: f32::from(i) * 0.25,
            y: 0.0,
            z: 0.1,
        };
        // Sent together; each resolves on its own.
        let (set, get) = tokio::join!(
            client.request(&to_slave(Request::SetRobotSpeed(speed))),
            client.request(&read),
        );
        for (what, reply) in [("SET_ROBOT_SPEED", set), ("READ_ROBOT_SPEED", get)] {
            match reply {
                Ok(reply) => show(what, &reply),
                Err(e) => println!("{what}: {e}"),
            }
        }
    }
    let mut late = 0;
    while unsolicited.try_recv().is_ok() {
        late += 1;
    }
    println!(
        "{} retries; {late} frames answered no open request",
        client.retries()
    );
    ExitCode::SUCCESS
}
