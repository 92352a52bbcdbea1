//! The tokio session client against `protocol twin` over a real pseudo-terminal: the twin
//! process prints its pty's path, the client opens it with `tokio-serial` and holds the
//! spec's conversation with it. HFLink: a request before the handshake is refused by the
//! requester, and when written past it the twin NACKs it; after the handshake every READ and
//! SET is answered with the values the twin was given (or zeros). RoboRTS: acknowledgements
//! matched by sequence number and session id, session modes, requests open together; with
//! frames dropped both ways the client retries, and every request still resolves to exactly
//! one outcome while the twin delivers none twice. Scout: the twin logs the watchdog's lapse
//! once, and the next command arms it again.

use std::io::{BufRead, BufReader, Read};
use std::process::{Child, Command, Stdio};
use std::time::Duration;

use protocol_kit::session::SendError;
use protocol_kit::session::client::{Client, ClientError, Reply, Unsolicited};
use tokio_serial::SerialPortBuilderExt;

mod msp;
mod registers;

protocol_kit::protocol!("../specs/hflink.toml");
protocol_kit::protocol!("../specs/roborts.toml");

/// A running `protocol twin`, interrupted (SIGINT) and reaped on drop.
struct Twin {
    child: Child,
    path: String,
}

impl Twin {
    fn start(args: &[&str]) -> Twin {
        let mut child = Command::new(env!("CARGO_BIN_EXE_protocol"))
            .arg("twin")
            .args(args)
            .arg("--pty")
            .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("protocol twin starts");
        let mut line = String::new();
        let stdout = child.stdout.take().expect("piped");
        BufReader::new(stdout)
            .read_line(&mut line)
            .expect("the twin prints its pty");
        let path = line.trim().to_string();
        assert!(path.starts_with("/dev/"), "not a pty path: {line:?}");
        Twin { child, path }
    }

    /// Interrupts the twin and returns its log (stderr), whose last line is its tally.
    fn stop(mut self) -> String {
        let pid = rustix::process::Pid::from_raw(i32::try_from(self.child.id()).expect("a pid"))
            .expect("a pid");
        rustix::process::kill_process(pid, rustix::process::Signal::INT).expect("SIGINT");
        let mut log = String::new();
        if let Some(mut err) = self.child.stderr.take() {
            err.read_to_string(&mut log).expect("the log");
        }
        let status = self.child.wait().expect("the twin ends");
        assert!(status.success(), "twin: {status}\n{log}");
        log
    }
}

impl Drop for Twin {
    fn drop(&mut self) {
        // A test that failed before `stop`: do not leave the process behind.
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn open(path: &str) -> tokio_serial::SerialStream {
    tokio_serial::new(path, 115_200)
        .open_native_async()
        .expect("the twin's pty opens")
}

/// The last line of the twin's log.
fn tally(log: &str) -> &str {
    log.lines().last().unwrap_or_default()
}

async fn next(unsolicited: &mut Unsolicited) -> Vec<u8> {
    tokio::time::timeout(Duration::from_secs(2), unsolicited.recv())
        .await
        .expect("a frame within 2 s")
        .expect("the client runs")
}

mod hf {
    pub use super::hflink::*;

    pub fn request(r: Request) -> Packet {
        Packet {
            header: Header {
                sender: 0x01,
                receiver: 0x11,
            },
            message: Message::Request(r),
        }
    }

    /// The response an answer frame carries, from the slave to the master.
    pub fn response(reply: super::Reply) -> Response {
        let super::Reply::Answered(frame) = reply else {
            panic!("not answered: {reply:?}");
        };
        let packet = Packet::from_frame(&frame).expect("the answer decodes");
        assert_eq!(
            packet.header,
            Header {
                sender: 0x11,
                receiver: 0x01
            }
        );
        let Message::Response(r) = packet.message else {
            panic!("not a response: {packet:?}");
        };
        r
    }

    pub const ZERO: ChassisCoord = ChassisCoord {
        x: 0.0,
        y: 0.0,
        z: 0.0,
    };
}

#[tokio::test]
async fn hflink_handshake_then_answers_and_a_nack_before_it() {
    use hf::*;
    let dir = tempfile::tempdir().expect("a temp dir");
    let values = dir.path().join("values.toml");
    std::fs::write(&values, "[READ_ROBOT_SPEED]\nx = 1.5\ny = -2.0\nz = 0.25\n")
        .expect("values written");
    let values = values.to_str().expect("a UTF-8 path");
    let twin = Twin::start(&["specs/hflink.toml", "--values", values]);
    let (client, mut unsolicited) =
        Client::spawn::<_, 4, { MAX_FRAME_LEN }>(open(&twin.path), &SESSION);

    // The requester refuses a READ before the handshake; written past it, the twin NACKs it
    // with an empty SHAKING_HANDS, which answers no open request.
    let read = request(Request::ReadRobotSpeed);
    assert_eq!(
        client.request(&read).await,
        Err(ClientError::Send(SendError::Handshake))
    );
    let mut raw = vec![0u8; MAX_FRAME_LEN];
    let n = read.encode(&mut raw).expect("encodes");
    raw.truncate(n);
    client.send_raw(raw).await.expect("written");
    let nack = Packet::from_frame(&next(&mut unsolicited).await).expect("the NACK decodes");
    assert_eq!(nack.message, Message::Response(Response::ShakingHands));

    let hello = client
        .request(&request(Request::ShakingHands(ZERO)))
        .await
        .expect("a reply");
    assert_eq!(response(hello), Response::ShakingHands);

    let speed = ChassisCoord {
        x: 1.5,
        y: -2.0,
        z: 0.25,
    };
    let set = ChassisCoord {
        x: 0.5,
        y: 0.0,
        z: 0.1,
    };
    // Open together: different commands, so their replies are told apart by command.
    let (a, b, c) = tokio::join!(
        client.request(&read),
        client.request(&request(Request::ReadGlobalSpeed)),
        client.request(&request(Request::SetRobotSpeed(set))),
    );
    assert_eq!(response(a.expect("a")), Response::ReadRobotSpeed(speed));
    assert_eq!(response(b.expect("b")), Response::ReadGlobalSpeed(ZERO));
    assert_eq!(response(c.expect("c")), Response::SetRobotSpeed);
    // The same command twice: the second waits for the first's reply (no sequence number).
    let (d, e) = tokio::join!(client.request(&read), client.request(&read));
    assert_eq!(response(d.expect("d")), Response::ReadRobotSpeed(speed));
    assert_eq!(response(e.expect("e")), Response::ReadRobotSpeed(speed));
    // Nothing is lost on a pty, but a loaded machine may answer after the 100 ms timeout:
    // a retry is then delivered again (HFLink numbers nothing) and its second reply is
    // unsolicited. Each count below is exact given the retries.
    let retries = client.retries();
    let mut late = 0;
    while let Ok(frame) = unsolicited.try_recv() {
        assert!(Packet::from_frame(&frame).is_ok(), "{frame:02x?}");
        late += 1;
    }
    assert_eq!(late, retries, "every other frame answered a request");

    drop(client);
    let log = twin.stop();
    assert!(
        log.contains("before the handshake -> NACK SHAKING_HANDS"),
        "{log}"
    );
    let n = 6 + retries;
    assert_eq!(
        tally(&log),
        format!(
            "twin: {n} delivered, {n} answered, 0 duplicates, 1 refused before the handshake, 0 error replies, 0 dropped, 0 not answered, 0 periodic"
        ),
        "{log}"
    );
}

fn rr_request(session_id: u8, vx: i16) -> roborts::Packet {
    use roborts::*;
    Packet {
        header: Header {
            session_id,
            sender: 0,
            receiver: 1,
            seq_num: 0,
        },
        message: Message::SetChassisSpeed(ChassisSpeed {
            vx,
            vy: 0,
            vw: 0,
            rotate_x_offset: 0,
            rotate_y_offset: 0,
        }),
    }
}

/// The header of an acknowledgement.
fn rr_ack(reply: Reply) -> roborts::Header {
    let Reply::Answered(frame) = reply else {
        panic!("not acknowledged: {reply:?}");
    };
    let packet = roborts::Packet::from_frame(&frame).expect("the ack decodes");
    assert!(
        matches!(packet.message, roborts::Message::Ack(ref data) if data.is_empty()),
        "not an empty acknowledgement: {packet:?}"
    );
    packet.header
}

#[tokio::test]
async fn roborts_acknowledges_by_sequence_number() {
    let twin = Twin::start(&["specs/roborts.toml"]);
    let (client, _unsolicited) =
        Client::spawn::<_, 4, { roborts::MAX_FRAME_LEN }>(open(&twin.path), &roborts::SESSION);

    // Mode 0 expects nothing; mode 1 and mode 2 expect an acknowledgement that repeats the
    // sequence number the requester gave and the session id, and swaps the addresses.
    assert_eq!(client.request(&rr_request(0, 1)).await, Ok(Reply::Sent));
    for (seq, session_id) in [(1, 1), (2, 2), (3, 9)] {
        let ack = rr_ack(
            client
                .request(&rr_request(session_id, 2))
                .await
                .expect("a reply"),
        );
        let want = roborts::Header {
            session_id,
            sender: 1,
            receiver: 0,
            seq_num: seq,
        };
        assert_eq!(ack, want);
    }
    // Four open together (the requester's slots): numbered 4 to 7, each acknowledged.
    let (a, b, c, d) = tokio::join!(
        client.request(&rr_request(2, 10)),
        client.request(&rr_request(2, 11)),
        client.request(&rr_request(2, 12)),
        client.request(&rr_request(2, 13)),
    );
    let mut seqs: Vec<u16> = [a, b, c, d]
        .into_iter()
        .map(|r| rr_ack(r.expect("a reply")).seq_num)
        .collect();
    seqs.sort_unstable();
    assert_eq!(seqs, [4, 5, 6, 7]);
    // A retry (an answer later than the 50 ms timeout on a loaded machine) is a duplicate to
    // the twin: acknowledged again, never delivered again.
    let retries = client.retries();

    drop(client);
    let log = twin.stop();
    assert_eq!(
        tally(&log),
        format!(
            "twin: 8 delivered, 7 answered, {retries} duplicates, 0 refused before the handshake, 0 error replies, 0 dropped, 0 not answered, 0 periodic"
        ),
        "{log}"
    );
}

#[tokio::test]
async fn roborts_retries_through_drops_and_resolves_every_request_once() {
    const REQUESTS: usize = 40;
    let twin = Twin::start(&["specs/roborts.toml", "--drop", "0.3", "--seed", "7"]);
    let (client, _unsolicited) =
        Client::spawn::<_, 4, { roborts::MAX_FRAME_LEN }>(open(&twin.path), &roborts::SESSION);

    let (mut answered, mut timed_out) = (0usize, 0usize);
    for batch in 0..REQUESTS / 4 {
        let vx = i16::try_from(batch).expect("small");
        let replies = tokio::join!(
            client.request(&rr_request(2, vx)),
            client.request(&rr_request(2, vx)),
            client.request(&rr_request(2, vx)),
            client.request(&rr_request(2, vx)),
        );
        for reply in [replies.0, replies.1, replies.2, replies.3] {
            match reply.expect("an outcome, not an error") {
                Reply::TimedOut => timed_out += 1,
                answer => {
                    rr_ack(answer);
                    answered += 1;
                }
            }
        }
    }
    assert_eq!(answered + timed_out, REQUESTS);
    let retries = client.retries();
    assert!(retries > 0, "no retry with 30 % of frames dropped");
    assert!(answered > REQUESTS / 2, "{answered} answered of {REQUESTS}");

    drop(client);
    let log = twin.stop();
    let (delivered, duplicates) = counts(tally(&log));
    // Each request at most once (a retry is answered again, never delivered again), and every
    // answered request was delivered.
    assert!(
        delivered <= REQUESTS as u64 && delivered >= answered as u64,
        "{delivered} delivered, {answered} answered\n{log}"
    );
    assert!(duplicates > 0, "no retry reached the twin twice\n{log}");
    assert!(log.contains("dropped (fault)"), "{log}");
    eprintln!(
        "{REQUESTS} requests: {answered} answered, {timed_out} timed out, {} retries; {}",
        retries,
        tally(&log)
    );
}

/// The delivered and duplicate counts of the twin's tally line.
fn counts(tally: &str) -> (u64, u64) {
    let number = |what: &str| {
        tally
            .split(", ")
            .find_map(|part| part.trim_start_matches("twin: ").strip_suffix(what))
            .and_then(|n| n.trim().parse().ok())
            .unwrap_or_else(|| panic!("no `{what}` in {tally:?}"))
    };
    (number(" delivered"), number(" duplicates"))
}

#[test]
fn scout_watchdog_lapse_is_logged_once_per_lapse() {
    use std::io::Write;
    // MOTION_CONTROL (CMD_UART, no motion), as `protocol encode specs/scout.toml` writes it.
    let motion = [
        0x5A, 0xA5, 0x0A, 0x55, 0x01, 0x02, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x61,
    ];
    let twin = Twin::start(&["specs/scout.toml"]);
    // The twin set its pty raw: plain writes reach it byte for byte.
    let mut port = std::fs::OpenOptions::new()
        .write(true)
        .open(&twin.path)
        .expect("the pty opens");
    port.write_all(&motion).expect("written");
    // The watchdog's period is 500 ms: it lapses once, then the next command arms it again.
    std::thread::sleep(Duration::from_millis(900));
    port.write_all(&motion).expect("written");
    std::thread::sleep(Duration::from_millis(100));
    let log = twin.stop();
    let lines: Vec<&str> = log
        .lines()
        .map(|l| l.split_once(" ms  ").map_or(l, |(_, r)| r))
        .collect();
    let motion_line = "MOTION_CONTROL {\"count\":0}  delivered, no answer";
    assert_eq!(
        lines,
        [
            motion_line,
            "watchdog expired",
            motion_line,
            "twin: 2 delivered, 0 answered, 0 duplicates, 0 refused before the handshake, 0 error replies, 0 dropped, 0 not answered, 0 periodic",
        ],
        "{log}"
    );
}

protocol_kit::protocol!("../specs/mavlink.toml");

/// MAVLink's twin (an autopilot) sends its HEARTBEAT once a second, as the spec's `periodic`
/// says, with no request to prompt it.
#[tokio::test]
async fn mavlink_twin_sends_a_heartbeat_a_second() {
    let twin = Twin::start(&["specs/mavlink.toml"]);
    let (_client, mut unsolicited) =
        Client::spawn::<_, 4, { mavlink::MAX_FRAME_LEN }>(open(&twin.path), mavlink::Session);
    let mut at = Vec::new();
    for _ in 0..3 {
        let frame = next(&mut unsolicited).await;
        let packet = mavlink::Packet::from_frame(&frame).expect("a frame of the spec");
        assert!(
            matches!(packet.message, mavlink::Message::Heartbeat(_)),
            "{packet:?}"
        );
        at.push(std::time::Instant::now());
    }
    for w in at.windows(2) {
        let gap = w[1].duration_since(w[0]);
        assert!(
            gap >= Duration::from_millis(800) && gap <= Duration::from_millis(1500),
            "{gap:?}"
        );
    }
    let log = twin.stop();
    assert!(tally(&log).ends_with(" periodic"), "{log}");
    assert!(log.contains("HEARTBEAT  periodic"), "{log}");
}
