//! A session with firmware under QEMU, through a fault-injecting relay. The firmware (a RoboRTS
//! chassis of `examples/embassy`, binary `mps2-session`) runs on QEMU's `mps2-an386` with its
//! UART on a pseudo-terminal; this host runs the runtime's `Requester` for the spec's
//! `[session]` on the wall clock, and every frame each way passes a relay that drops,
//! duplicates, corrupts or delays it (delays reorder frames) on a seeded schedule, one fault per
//! frame. The schedule is deterministic; which frame meets which fault depends on the order
//! frames are put on the link, which real time can change.
//!
//! It checks that every request resolves to exactly one outcome (answer, NACK or timeout after
//! its retries), that the firmware delivers no request twice (it prints one semihosting line per
//! frame: delivered, duplicate answered again, stale) and only requests this host sent, and that
//! every answered request was delivered; it prints the fault matrix and the instructions the
//! firmware spent per request (SysTick under `-icount shift=0`: 40 instructions a tick).
//!
//! Usage: `cargo run -p protocol-tests --example qemu_session -- FIRMWARE [--baseline] [--scale N]`
//! (`--baseline`: the fault-free row alone, for the firmware that answers by hand
//! (`mps2-by-hand`), whose duplicate deliveries (after a retry) are counted, not failed;
//! `--scale N`: the session's clock runs N times slower than the wall clock, 4 unless told).
//! The scale is there because an emulated UART is slow and uneven: QEMU passes the firmware
//! one byte per turn of its main loop, so on a busy machine a round trip takes tens of
//! milliseconds, and at the spec's own 50 ms timeout the matrix would count the host's
//! scheduling as link loss.
//! `examples/embassy/session.sh` builds the firmware and runs this.

#[allow(dead_code)]
#[path = "../tests/it/session_sim/link.rs"]
mod link;

use std::collections::{BTreeMap, HashMap};
use std::fs::File;
use std::io::{BufRead, BufReader, Read, Write};
use std::process::{Child, Command, ExitCode, Stdio};
use std::sync::mpsc::{Receiver, channel};
use std::thread;
use std::time::{Duration, Instant};

use link::{DOWN, Fault, Link, UP};
use protocol_kit::session::{Due, Received, Resolution, Ticket};
use protocol_kit::{FrameLayout, StreamDecoder};

protocol_kit::protocol!("../specs/roborts.toml");

/// Open slots of the requester (the firmware's responder remembers 8 numbers).
const SLOTS: usize = 8;
/// Requests in flight at once.
const IN_FLIGHT: usize = 4;
/// Requests per row of the matrix.
const REQUESTS: u16 = 100;
/// Instructions per SysTick tick under `-icount shift=0` (1 GHz virtual clock, 25 MHz tick).
const INSTRUCTIONS_PER_TICK: u64 = 40;

/// One row of the matrix: percent of frames dropped, duplicated, corrupted, delayed.
#[derive(Debug, Clone, Copy)]
struct Faults {
    name: &'static str,
    drop: u64,
    dup: u64,
    corrupt: u64,
    delay: u64,
}

const ROWS: [Faults; 6] = [
    Faults {
        name: "clean",
        drop: 0,
        dup: 0,
        corrupt: 0,
        delay: 0,
    },
    Faults {
        name: "drop",
        drop: 10,
        dup: 0,
        corrupt: 0,
        delay: 0,
    },
    Faults {
        name: "duplicate",
        drop: 0,
        dup: 10,
        corrupt: 0,
        delay: 0,
    },
    Faults {
        name: "corrupt",
        drop: 0,
        dup: 0,
        corrupt: 10,
        delay: 0,
    },
    Faults {
        name: "delay",
        drop: 0,
        dup: 0,
        corrupt: 0,
        delay: 30,
    },
    Faults {
        name: "mixed",
        drop: 5,
        dup: 5,
        corrupt: 5,
        delay: 20,
    },
];

/// A seeded xorshift generator: the schedules are the same on every run.
struct Rng(u64);

impl Rng {
    fn next(&mut self, below: u64) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0 % below
    }
}

/// `len` faults drawn at `row`'s rates: delays of 2 to 40 ms, a corrupt byte XORed with a
/// mask of 1 to 0xFE.
fn schedule(row: &Faults, seed: u64, len: usize) -> Vec<Fault> {
    let mut rng = Rng(seed);
    let mut faults = Vec::with_capacity(len);
    for _ in 0..len {
        let r = rng.next(100);
        let late = 2 + rng.next(39);
        let fault = if r < row.drop {
            Fault::Drop
        } else if r < row.drop + row.dup {
            Fault::Twice(1, late)
        } else if r < row.drop + row.dup + row.corrupt {
            let at = usize::try_from(rng.next(64)).unwrap_or(0);
            Fault::Corrupt(1, at, u8::try_from(1 + rng.next(254)).unwrap_or(1))
        } else if r < row.drop + row.dup + row.corrupt + row.delay {
            Fault::Pass(late)
        } else {
            Fault::Pass(1)
        };
        faults.push(fault);
    }
    faults
}

/// QEMU running the firmware: its UART's pseudo-terminal and its output lines.
struct Qemu {
    child: Child,
    lines: Receiver<String>,
    port: File,
    bytes: Receiver<Vec<u8>>,
}

impl Qemu {
    fn start(firmware: &str) -> Result<Self, String> {
        let mut child = Command::new("qemu-system-arm")
            .args(["-M", "mps2-an386", "-cpu", "cortex-m4", "-display", "none"])
            .args(["-monitor", "none", "-icount", "shift=0", "-serial", "pty"])
            .args([
                "-semihosting-config",
                "enable=on,target=native",
                "-kernel",
                firmware,
            ])
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|e| format!("qemu-system-arm: {e}"))?;
        let (tx, lines) = channel();
        let out = child.stdout.take().ok_or("no stdout")?;
        let err = child.stderr.take().ok_or("no stderr")?;
        let tx2 = tx.clone();
        thread::spawn(move || {
            BufReader::new(out)
                .lines()
                .map_while(Result::ok)
                .try_for_each(|l| tx.send(l))
        });
        thread::spawn(move || {
            BufReader::new(err)
                .lines()
                .map_while(Result::ok)
                .try_for_each(|l| tx2.send(l))
        });
        let mut pty = None;
        let mut ready = false;
        while !(ready && pty.is_some()) {
            let line = lines
                .recv_timeout(Duration::from_secs(30))
                .map_err(|_| "QEMU did not start the firmware within 30 s".to_string())?;
            if let Some(rest) = line.split("redirected to ").nth(1) {
                pty = rest.split_whitespace().next().map(str::to_string);
            } else if line == "ready" {
                ready = true;
            } else if line.starts_with("size ") {
                println!("firmware {line}");
            }
        }
        let path = pty.unwrap_or_default();
        let raw = Command::new("stty")
            .args(["-F", &path, "raw", "-echo"])
            .status();
        if !raw.is_ok_and(|s| s.success()) {
            return Err(format!("stty cannot make {path} raw"));
        }
        let port = File::options()
            .read(true)
            .write(true)
            .open(&path)
            .map_err(|e| format!("{path}: {e}"))?;
        // QEMU notices that a pseudo-terminal's other end is open by polling it once a second,
        // and holds the UART's output until then: a session started earlier meets answers a
        // second late.
        thread::sleep(Duration::from_millis(1500));
        let mut reading = port.try_clone().map_err(|e| e.to_string())?;
        let (tx, bytes) = channel();
        thread::spawn(move || {
            let mut buf = [0u8; 256];
            while let Ok(n @ 1..) = reading.read(&mut buf) {
                if tx.send(buf[..n].to_vec()).is_err() {
                    break;
                }
            }
        });
        Ok(Self {
            child,
            lines,
            port,
            bytes,
        })
    }
}

/// What one row counted on the host side.
#[derive(Debug, Default, Clone)]
struct Tally {
    requests: u64,
    answered: u64,
    refused: u64,
    timed_out: u64,
    resends: u64,
    late: u64,
    faults: link::Faults,
}

/// The host: the requester, the relay and what each request became.
struct Host {
    requester: roborts::Requester<SLOTS>,
    decoder: StreamDecoder<&'static FrameLayout<'static>, { roborts::DECODER_BUFFER_LEN }>,
    epoch: Instant,
    /// Wall-clock milliseconds per millisecond of the session's clock.
    scale: u64,
    /// Each request: its row and sequence number.
    tickets: HashMap<Ticket, (usize, u16)>,
    /// Each request's outcome: exactly one is recorded.
    outcomes: HashMap<Ticket, Resolution>,
}

/// The `i`th request: a speed command; every fifth in session mode 1 (acknowledged, sent once),
/// the others in modes 2 to 31 (acknowledged, with retries).
fn request(i: u16) -> Vec<u8> {
    use roborts::*;
    let session_id = if i % 5 == 4 {
        1
    } else {
        2 + u8::try_from(i % 30).unwrap_or(0)
    };
    let packet = Packet {
        header: Header {
            session_id,
            sender: 0,
            receiver: 1,
            seq_num: 0,
        },
        message: Message::SetChassisSpeed(ChassisSpeed {
            vx: i16::try_from(i).unwrap_or(0),
            vy: -5,
            vw: 3,
            rotate_x_offset: 0,
            rotate_y_offset: 0,
        }),
    };
    let mut buf = vec![0u8; MAX_FRAME_LEN];
    let len = packet.encode(&mut buf).expect("a speed command encodes");
    buf.truncate(len);
    buf
}

/// Whether `frame` is a checked RoboRTS frame that decodes (a corrupted one is not).
fn decodes(frame: &[u8]) -> bool {
    roborts::LAYOUT
        .parse(frame)
        .is_ok_and(|f| f.len() == frame.len())
        && roborts::Packet::from_frame(frame).is_ok()
}

impl Host {
    fn now(&self) -> u64 {
        u64::try_from(self.epoch.elapsed().as_millis()).unwrap_or(u64::MAX) / self.scale
    }

    fn record(&mut self, t: &mut Tally, ticket: Ticket, resolution: Resolution) {
        let first = self.outcomes.insert(ticket, resolution);
        assert!(first.is_none(), "request {ticket:?} resolved twice");
        match resolution {
            Resolution::Answered => t.answered += 1,
            // RoboRTS's acknowledgements carry no result value: a refusal is a refusal.
            Resolution::Refused | Resolution::Rejected(_) => t.refused += 1,
            Resolution::TimedOut => t.timed_out += 1,
            Resolution::Incomplete(_) => panic!("RoboRTS's requests list no answerers"),
        }
    }

    /// Sends request `i` of row `row` if the requester takes it now; true when it did.
    fn try_send(&mut self, row: usize, i: u16, link: &mut Link) -> bool {
        let now = self.now();
        let mut frame = request(i);
        match self.requester.send(now, &mut frame) {
            Ok(Some(ticket)) => {
                let seq = roborts::Packet::from_frame(&frame)
                    .expect("sent")
                    .header
                    .seq_num;
                self.tickets.insert(ticket, (row, seq));
                link.send(DOWN, now, &frame);
                true
            }
            Ok(None) => panic!("every request of this harness expects an answer"),
            Err(_) => false,
        }
    }

    /// Moves what is due: retries and timeouts, frames the relay lets through each way.
    fn step(&mut self, t: &mut Tally, link: &mut Link, qemu: &mut Qemu) {
        let now = self.now();
        while let Some(due) = self.requester.poll(now) {
            match due {
                Due::Resend { frame, .. } => {
                    t.resends += 1;
                    link.send(DOWN, now, frame);
                }
                Due::Outcome(o) => self.record(t, o.ticket, o.resolution),
            }
        }
        for frame in link.arrived(DOWN, now) {
            qemu.port
                .write_all(&frame)
                .expect("the pseudo-terminal takes the frame");
        }
        while let Ok(bytes) = qemu.bytes.try_recv() {
            let mut input = &bytes[..];
            while let Some(frame) = self.decoder.decode(&mut input) {
                link.send(UP, now, frame.bytes);
            }
        }
        for frame in link.arrived(UP, now) {
            if !decodes(&frame) {
                continue;
            }
            match self.requester.on_frame(now, &frame) {
                Received::Outcome(o) => self.record(t, o.ticket, o.resolution),
                Received::Unsolicited => t.late += 1,
                Received::Progress { .. } => panic!("RoboRTS's answers say no progress"),
                Received::Partial { .. } => panic!("RoboRTS's requests list no answerers"),
                Received::Unreadable(e) => panic!("a checked frame is unreadable: {e}"),
            }
        }
    }

    /// Runs one row: `REQUESTS` requests through a relay with `faults`, until each resolved
    /// and the relay is empty.
    fn run(&mut self, row: usize, faults: &Faults, qemu: &mut Qemu) -> Tally {
        let seed = 0x5EED_0000 + row as u64;
        let mut link = Link::new(schedule(faults, seed, 8 * usize::from(REQUESTS)));
        let mut t = Tally::default();
        let mut next = 0;
        let started = Instant::now();
        while next < REQUESTS || self.requester.open() > 0 || !link.quiet() {
            while next < REQUESTS
                && self.requester.open() < IN_FLIGHT
                && self.try_send(row, next, &mut link)
            {
                next += 1;
                t.requests += 1;
            }
            self.step(&mut t, &mut link, qemu);
            assert!(
                started.elapsed() < Duration::from_secs(30),
                "row {} took over 30 s",
                faults.name
            );
            thread::sleep(Duration::from_millis(1));
        }
        t.faults = link.faults;
        t
    }
}

/// What the firmware reported: per sequence number, deliveries, answers repeated and ticks.
#[derive(Debug, Default)]
struct Firmware {
    delivered: BTreeMap<u16, u64>,
    duplicates: BTreeMap<u16, u64>,
    stale: BTreeMap<u16, u64>,
    deliver_ticks: Vec<u64>,
    duplicate_ticks: Vec<u64>,
    other: Vec<String>,
}

fn firmware_lines(lines: &Receiver<String>) -> Firmware {
    let mut fw = Firmware::default();
    while let Ok(line) = lines.recv_timeout(Duration::from_millis(500)) {
        let words: Vec<&str> = line.split_whitespace().collect();
        let num = |i: usize| {
            words
                .get(i)
                .and_then(|w| w.parse::<u64>().ok())
                .unwrap_or(0)
        };
        let seq = u16::try_from(num(1)).unwrap_or(u16::MAX);
        match words.first().copied() {
            Some("delivered") => {
                *fw.delivered.entry(seq).or_default() += 1;
                fw.deliver_ticks.push(num(3));
            }
            Some("duplicate") => {
                *fw.duplicates.entry(seq).or_default() += 1;
                fw.duplicate_ticks.push(num(2));
            }
            Some("stale") => *fw.stale.entry(seq).or_default() += 1,
            Some("ignored") => {}
            _ => fw.other.push(line),
        }
    }
    fw
}

/// Instructions of the median and the least of `ticks`.
fn instructions(ticks: &mut [u64]) -> (u64, u64) {
    ticks.sort_unstable();
    let median = ticks.get(ticks.len() / 2).copied().unwrap_or(0);
    let least = ticks.first().copied().unwrap_or(0);
    (
        median * INSTRUCTIONS_PER_TICK,
        least * INSTRUCTIONS_PER_TICK,
    )
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().collect();
    let Some(firmware) = args.get(1) else {
        eprintln!("usage: qemu_session FIRMWARE [--baseline] [--scale N]");
        return ExitCode::FAILURE;
    };
    let scale = args
        .iter()
        .position(|a| a == "--scale")
        .and_then(|i| args.get(i + 1)?.parse::<u64>().ok())
        .unwrap_or(4)
        .max(1);
    println!(
        "session clock: 1 ms of the spec's timeouts and the relay's delays = {scale} ms of wall time"
    );
    let baseline = args.iter().any(|a| a == "--baseline");
    println!(
        "roborts: longest frame {} bytes, decoder buffer {} bytes",
        roborts::MAX_FRAME_LEN,
        roborts::DECODER_BUFFER_LEN
    );
    let rows = if baseline { &ROWS[..1] } else { &ROWS[..] };
    let mut qemu = match Qemu::start(firmware) {
        Ok(q) => q,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    let mut host = Host {
        requester: roborts::Requester::new(roborts::Session),
        decoder: StreamDecoder::new(&roborts::LAYOUT),
        epoch: Instant::now(),
        scale,
        tickets: HashMap::new(),
        outcomes: HashMap::new(),
    };
    let tallies: Vec<Tally> = rows
        .iter()
        .enumerate()
        .map(|(i, f)| host.run(i, f, &mut qemu))
        .collect();
    let fw = firmware_lines(&qemu.lines);
    let _ = qemu.child.kill();
    let _ = qemu.child.wait();
    match check(&host, &fw, baseline) {
        Ok(()) => {
            print_matrix(rows, &tallies, &host, fw);
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("FAILED: {e}");
            ExitCode::FAILURE
        }
    }
}

/// The properties: one outcome per request, no duplicate delivery (unless `baseline`),
/// nothing delivered that was not sent, every answered request delivered.
fn check(host: &Host, fw: &Firmware, baseline: bool) -> Result<(), String> {
    if let Some(e) = fw.other.iter().find(|l| l.starts_with("panic")) {
        return Err(format!("the firmware stopped: {e}"));
    }
    if let Some(t) = host.tickets.keys().find(|t| !host.outcomes.contains_key(t)) {
        return Err(format!("request {t:?} has no outcome"));
    }
    if let Some((seq, n)) = fw.delivered.iter().find(|(_, n)| **n > 1 && !baseline) {
        return Err(format!("the firmware delivered request {seq} {n} times"));
    }
    let sent: HashMap<u16, Ticket> = host.tickets.iter().map(|(t, (_, s))| (*s, *t)).collect();
    if let Some(seq) = fw.delivered.keys().find(|s| !sent.contains_key(s)) {
        return Err(format!(
            "the firmware delivered {seq}, which was never sent"
        ));
    }
    for (ticket, (_, seq)) in &host.tickets {
        if host.outcomes.get(ticket) == Some(&Resolution::Answered)
            && !fw.delivered.contains_key(seq)
        {
            return Err(format!("request {seq} was answered but never delivered"));
        }
    }
    Ok(())
}

fn print_matrix(rows: &[Faults], tallies: &[Tally], host: &Host, mut fw: Firmware) {
    println!(
        "{:<10} {:>5} {:>4} {:>7} {:>5} {:>6} {:>5} {:>8} {:>4} {:>7} {:>7} {:>9} {:>9} {:>12}",
        "faults%",
        "drop",
        "dup",
        "corrupt",
        "delay",
        "frames",
        "reqs",
        "answered",
        "nack",
        "timeout",
        "resends",
        "delivered",
        "dup-again",
        "dup-delivered"
    );
    for (i, (row, t)) in rows.iter().zip(tallies).enumerate() {
        let of_row = |s: &u16| host.tickets.values().any(|(r, q)| *r == i && q == s);
        let delivered = fw.delivered.keys().filter(|s| of_row(s)).count();
        let again: u64 = fw
            .duplicates
            .iter()
            .filter(|(s, _)| of_row(s))
            .map(|(_, n)| n)
            .sum();
        let twice = fw
            .delivered
            .iter()
            .filter(|(s, n)| of_row(s) && **n > 1)
            .count();
        println!(
            "{:<10} {:>5} {:>4} {:>7} {:>5} {:>6} {:>5} {:>8} {:>4} {:>7} {:>7} {:>9} {:>9} {:>12}",
            row.name,
            row.drop,
            row.dup,
            row.corrupt,
            row.delay,
            t.faults.frames,
            t.requests,
            t.answered,
            t.refused,
            t.timed_out,
            t.resends,
            delivered,
            again,
            twice
        );
    }
    let late: u64 = tallies.iter().map(|t| t.late).sum();
    let stale: u64 = fw.stale.values().sum();
    println!(
        "late answers (after their request resolved): {late}; stale requests at the firmware: {stale}"
    );
    let (median, least) = instructions(&mut fw.deliver_ticks);
    println!(
        "instructions per delivered request to its answer ready: median {median}, least {least} (n = {})",
        fw.deliver_ticks.len()
    );
    if !fw.duplicate_ticks.is_empty() {
        let (median, least) = instructions(&mut fw.duplicate_ticks);
        println!(
            "instructions per duplicate to its answer found: median {median}, least {least} (n = {})",
            fw.duplicate_ticks.len()
        );
    }
}
