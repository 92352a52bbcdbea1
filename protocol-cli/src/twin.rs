//! The device twin of `protocol twin`: a device that holds its side of the spec's `[session]`
//! on a byte stream (a pseudo-terminal, a serial port). The runtime's [`Responder`] decides
//! what each request is (new, a duplicate, before the handshake, stale); this module builds the
//! frames it answers with through the run-time codec (the reply, the acknowledgement, the
//! answering command, the NACK, and where the spec has an empty direction the error reply to a
//! request it does not know or cannot answer, built in `refusal`; payload values from the
//! caller's table or the payload's all-zero value), sends the commands the spec's `periodic`
//! gives the responder at their rates (the runtime's [`Scheduler`] says when), injects the
//! faults it is told to (frames dropped each way), and logs every exchange. Where the spec has
//! `[registers]`, the twin keeps a register file ([`registers`]): a WRITE stores its data, a
//! READ is answered with the bytes at its address and length, each answer to a SYNC_READ or a
//! BULK_READ with the bytes its device was asked for.
//!
//! Matching, numbering and duplicate suppression are the responder's; reading frames is the
//! engine's ([`Codec::stream`]).

use std::collections::HashMap;
use std::io::{self, Read, Write};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use protocol_dynamic::{Codec, Decoded, Fields, Item, Value};
use protocol_runtime::session::{
    Answer, Heard, Incoming, Responder, Scheduler, Sender, SessionRules,
};
use protocol_spec::session::command_key;

mod refusal;
pub mod registers;

use refusal::{set_direction, zero_header};
use registers::RegisterFile;

/// Requests the twin remembers with their answers (give a host's requester at most as many
/// slots), and the longest answer it remembers, in bytes.
const SLOTS: usize = 32;
const FRAME: usize = 2048;
/// The most periodic commands a spec lists (validation's bound).
const PERIODIC: usize = 16;

/// Payload values per command name (a struct's fields; those left out are zero); with
/// `[registers]`, the key `registers` holds raw register values by name.
pub type Values = HashMap<String, Value>;

/// How the twin answers.
#[derive(Debug, Clone, Default)]
pub struct Options {
    /// Payload values of the answers, per command.
    pub values: Values,
    /// Probability that a frame is dropped, each way (a request read, an answer written).
    pub drop: f64,
    /// Seed of the fault draws.
    pub seed: u64,
}

/// What the twin counted.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Tally {
    /// Requests delivered (new, in the session).
    pub delivered: u64,
    /// Answers written (replies, acknowledgements, answering commands).
    pub answered: u64,
    /// Requests received again and not delivered.
    pub duplicates: u64,
    /// NACKs written to requests before the handshake.
    pub refused: u64,
    /// Error replies (frames of the spec's empty direction) written to requests the twin does
    /// not know or cannot answer.
    pub error_replies: u64,
    /// Frames dropped by the fault injection (read and to be written).
    pub dropped: u64,
    /// Requests the twin could not answer (no payload values, an encode error).
    pub failed: u64,
    /// Periodic commands sent.
    pub periodic: u64,
}

/// Reads `path` as a table of payload values per command: TOML for a `.toml` file, else JSON.
///
/// # Errors
/// The file cannot be read or parsed, or is not a table.
pub fn read_values(path: &std::path::Path) -> Result<Values, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read `{}`: {e}", path.display()))?;
    let parsed = if path.extension().is_some_and(|e| e == "toml") {
        toml::from_str::<Values>(&text).map_err(|e| e.to_string())
    } else {
        serde_json::from_str::<Values>(&text).map_err(|e| e.to_string())
    };
    parsed.map_err(|e| {
        format!(
            "`{}`: not a table of payloads per command: {e}",
            path.display()
        )
    })
}

/// Serves the session of `codec`'s spec on `port` until `stop` is set or the port hangs up,
/// logging each exchange to `log`. A read that times out is a tick of the clock (the
/// watchdog is checked), so give the port a read timeout.
///
/// # Errors
/// The spec has no `[session]` (`InvalidInput`), or the port fails.
pub fn serve<P: Read + Write>(
    codec: &Codec<'_>,
    port: &mut P,
    options: &Options,
    log: &mut dyn Write,
    stop: &AtomicBool,
) -> io::Result<Tally> {
    let no_session = || io::Error::new(io::ErrorKind::InvalidInput, "the spec has no [session]");
    let format = codec
        .protocol()
        .session
        .as_ref()
        .ok_or_else(no_session)?
        .frame;
    let registers = RegisterFile::new(codec.protocol(), options.values.get(registers::KEY))
        .map_err(|e| io::Error::new(io::ErrorKind::InvalidInput, e))?;
    codec
        .with_session(|rules| {
            let mut twin = Twin {
                registers,
                codec,
                rules,
                format,
                options,
                responder: Box::new(Responder::new(rules)),
                scheduler: Scheduler::new(rules, Sender::Responder, 0),
                last_header: None,
                rng: options.seed ^ 0x9E37_79B9_7F4A_7C15,
                start: Instant::now(),
                tally: Tally::default(),
            };
            twin.run(port, log, stop).map(|()| twin.tally)
        })
        .ok_or_else(no_session)?
}

struct Twin<'c, 'r> {
    codec: &'c Codec<'c>,
    rules: &'r SessionRules<'r>,
    format: usize,
    options: &'c Options,
    responder: Box<Responder<&'r SessionRules<'r>, SLOTS, FRAME>>,
    scheduler: Scheduler<&'r SessionRules<'r>, PERIODIC>,
    /// The register file, when the spec has `[registers]`.
    registers: Option<RegisterFile>,
    /// The header of the last request's answer (its addresses swapped): the header of the
    /// periodic frames, so that they reach the host that spoke last.
    last_header: Option<Fields>,
    rng: u64,
    start: Instant,
    tally: Tally,
}

impl Twin<'_, '_> {
    fn run<P: Read + Write>(
        &mut self,
        port: &mut P,
        log: &mut dyn Write,
        stop: &AtomicBool,
    ) -> io::Result<()> {
        let mut stream = self
            .codec
            .stream(self.format)
            .ok_or(io::ErrorKind::InvalidInput)?;
        let mut buf = [0u8; 1024];
        while !stop.load(Ordering::Relaxed) {
            let n = match port.read(&mut buf) {
                Ok(0) => return Ok(()),
                Ok(n) => n,
                Err(e) if is_tick(&e) => 0,
                // A port that hangs up (the host closed a pty whose other end the twin does
                // not hold, an unplugged adapter) ends the session.
                Err(e) if e.kind() == io::ErrorKind::BrokenPipe || e.raw_os_error() == Some(5) => {
                    return Ok(());
                }
                Err(e) => return Err(e),
            };
            let mut input = buf.get(..n).unwrap_or_default();
            while let Some(item) = stream.next_item(&mut input) {
                if let Item::Frame { bytes, decoded, .. } = item {
                    let (bytes, decoded) = (bytes.to_vec(), decoded.ok());
                    self.on_frame(&bytes, decoded.as_ref(), port, log)?;
                }
            }
            if self.responder.poll(self.now()).is_some() {
                writeln!(log, "{:>7} ms  watchdog expired", self.now())?;
            }
            while let Some(key) = self.scheduler.poll(self.now()) {
                self.periodic(key, port, log)?;
            }
        }
        Ok(())
    }

    fn now(&self) -> u64 {
        u64::try_from(self.start.elapsed().as_millis()).unwrap_or(u64::MAX)
    }

    /// Sends a frame of the periodic command `key`: the given payload values over zeros, the
    /// header of the last answer (zeros before any request).
    fn periodic<P: Write>(
        &mut self,
        key: u64,
        port: &mut P,
        log: &mut dyn Write,
    ) -> io::Result<()> {
        let now = self.now();
        let built = self.build_periodic(key);
        let (name, frame) = match built {
            Ok(b) => b,
            Err(e) => {
                self.tally.failed += 1;
                return writeln!(log, "{now:>7} ms  periodic frame not sent: {e}");
            }
        };
        if self.draw_drop() {
            return writeln!(log, "{now:>7} ms  {name}  periodic, dropped (fault)");
        }
        port.write_all(&frame)?;
        port.flush()?;
        self.tally.periodic += 1;
        writeln!(log, "{now:>7} ms  {name}  periodic")
    }

    /// The frame of the periodic command `key`: its name and bytes.
    fn build_periodic(&self, key: u64) -> Result<(String, Vec<u8>), String> {
        let p = self.codec.protocol();
        let ci = self
            .command_of(key)
            .ok_or("no command of the periodic key")?;
        let f = &p.frames[self.format];
        let header = self.last_header.clone().unwrap_or_else(|| zero_header(f));
        // The responder's direction: the second, with directions.
        let direction = (!p.directions.is_empty()).then_some(1);
        let mut object = Fields::new();
        object.insert("format", Value::from(f.name.clone()));
        object.insert("header", Value::Struct(header));
        if let Some(dir) = direction.filter(|_| p.directions_given()) {
            object.insert("direction", Value::from(p.directions[dir].name.clone()));
        }
        let name = p.commands[ci].name.clone();
        object.insert("command", Value::from(name.clone()));
        object.insert("payload", self.payload(ci, direction)?);
        let frame = self
            .codec
            .encode(&Value::Struct(object))
            .map_err(|e| format!("{name} not encoded: {e}"))?
            .bytes;
        Ok((name, frame))
    }

    /// True with the probability of a drop.
    fn draw_drop(&mut self) -> bool {
        // splitmix64: a fixed sequence per seed, so that a run can be repeated.
        self.rng = self.rng.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.rng;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        let hit = ((z >> 11) as f64) / ((1u64 << 53) as f64) < self.options.drop;
        if hit {
            self.tally.dropped += 1;
        }
        hit
    }

    /// A frame read: what the responder makes of it, and the answer written.
    fn on_frame<P: Write>(
        &mut self,
        request: &[u8],
        decoded: Option<&Decoded>,
        port: &mut P,
        log: &mut dyn Write,
    ) -> io::Result<()> {
        let now = self.now();
        let what = describe(self.codec, decoded);
        if self.draw_drop() {
            return writeln!(log, "{now:>7} ms  {what}  dropped (fault)");
        }
        let (verdict, answer) = match self.responder.on_frame(now, request) {
            Incoming::Deliver { answer: false } => {
                self.tally.delivered += 1;
                let wrote = self.write_registers(decoded);
                (format!("delivered, no answer{wrote}"), None)
            }
            Incoming::Deliver { answer: true } => {
                self.tally.delivered += 1;
                let wrote = self.write_registers(decoded);
                let (verdict, answer) = self.answer(request, decoded, false);
                (format!("{verdict}{wrote}"), answer)
            }
            Incoming::Duplicate(sent) => {
                self.tally.duplicates += 1;
                let again = sent.map(<[u8]>::to_vec);
                ("duplicate, not delivered".to_string(), again)
            }
            Incoming::BeforeHandshake if self.rules.nack.is_some() => {
                self.answer(request, decoded, true)
            }
            Incoming::BeforeHandshake => ("before the handshake".to_string(), None),
            Incoming::Stale => ("stale, neither delivered nor answered".to_string(), None),
            Incoming::Ack => ("an acknowledgement".to_string(), None),
            Incoming::Unreadable(e) => (format!("unreadable: {e}"), None),
        };
        let Some(answer) = answer else {
            return writeln!(log, "{now:>7} ms  {what}  {verdict}");
        };
        if self.draw_drop() {
            return writeln!(
                log,
                "{now:>7} ms  {what}  {verdict}, answer dropped (fault)"
            );
        }
        let (frames, reads) = self.answers_of_each_listed(request, decoded, answer);
        for frame in frames {
            port.write_all(&frame)?;
        }
        port.flush()?;
        writeln!(log, "{now:>7} ms  {what}  {verdict}{reads}")
    }

    /// The answers to `request`: `answer` itself, or, for a request answered once by each id
    /// it lists (a SYNC_READ), one per listed id with that id as its sender, in id order: the
    /// twin plays every device on the bus. Where the request asks each device a run of
    /// registers of its own (a BULK_READ), each answer is built anew with its device's run,
    /// and what each read is returned to log.
    fn answers_of_each_listed(
        &mut self,
        request: &[u8],
        decoded: Option<&Decoded>,
        answer: Vec<u8>,
    ) -> (Vec<Vec<u8>>, String) {
        let Ok(Heard::Command(key)) = self.rules.heard(request) else {
            return (vec![answer], String::new());
        };
        let Some(fanout) = self.rules.fanout(key) else {
            return (vec![answer], String::new());
        };
        let ids = fanout
            .listed(self.rules.packet, request)
            .unwrap_or_default();
        let per_device = decoded.filter(|d| self.per_device(d));
        let mut reads = Vec::new();
        let mut frames = Vec::new();
        for id in ids.iter() {
            let mut frame = match per_device {
                Some(d) => match self.build(request, d, false, Some(id)) {
                    Ok((name, frame)) => {
                        reads.push(format!("{id}: {name}"));
                        frame
                    }
                    Err(e) => {
                        reads.push(format!("{id}: not answered: {e}"));
                        continue;
                    }
                },
                None => answer.clone(),
            };
            let written = fanout.id.write(&mut frame, u64::from(id));
            if written.is_some() && self.rules.packet.layout.seal(&mut frame).is_ok() {
                frames.push(frame);
            }
        }
        let reads = if reads.is_empty() {
            String::new()
        } else {
            format!(" [{}]", reads.join(", "))
        };
        (frames, reads)
    }

    /// True when request `d` asks each device it lists a run of registers of its own.
    fn per_device(&self, d: &Decoded) -> bool {
        let p = self.codec.protocol();
        let select = p.registers.as_ref().zip(d.command);
        select.is_some_and(|(map, ci)| map.select(ci).is_some_and(|s| s.each.is_some()))
    }

    /// A delivered request's data stored in the register file, when it writes registers:
    /// what to log.
    fn write_registers(&mut self, decoded: Option<&Decoded>) -> String {
        let p = self.codec.protocol();
        match (self.registers.as_mut(), decoded) {
            (Some(file), Some(d)) => file
                .apply_request(p, d)
                .map_or_else(String::new, |w| format!(" ({w})")),
            _ => String::new(),
        }
    }

    /// The answer to a delivered request, or the NACK to one before the handshake: what to
    /// log, and the frame.
    fn answer(
        &mut self,
        request: &[u8],
        decoded: Option<&Decoded>,
        nack: bool,
    ) -> (String, Option<Vec<u8>>) {
        let built = decoded
            .ok_or_else(|| "not a message of the spec".to_string())
            .and_then(|d| self.build(request, d, nack, None));
        match built {
            Ok((name, frame)) => {
                if nack {
                    self.tally.refused += 1;
                    (format!("before the handshake -> NACK {name}"), Some(frame))
                } else {
                    self.tally.answered += 1;
                    (format!("delivered -> {name}"), Some(frame))
                }
            }
            Err(e) => match self.error_reply(request, decoded) {
                Some((name, frame)) => {
                    self.tally.error_replies += 1;
                    (
                        format!("not answered: {e} -> error reply {name}"),
                        Some(frame),
                    )
                }
                None => {
                    self.tally.failed += 1;
                    (format!("not answered: {e}"), None)
                }
            },
        }
    }

    /// Encodes the answer the spec says `request` expects (or the NACK; for a request that
    /// asks each listed device a run of registers of its own, `device`'s answer) and lets the
    /// responder write what it repeats and seal it: the answer's name and frame.
    fn build(
        &mut self,
        request: &[u8],
        d: &Decoded,
        nack: bool,
        device: Option<u8>,
    ) -> Result<(String, Vec<u8>), String> {
        let p = self.codec.protocol();
        let Ok(Heard::Command(key)) = self.rules.heard(request) else {
            return Err("not a request".into());
        };
        let kind = if nack {
            Answer::Command(self.rules.nack.unwrap_or(key))
        } else {
            self.rules.expects(key, request).answer
        };
        let mut object = Fields::new();
        object.insert("format", Value::from(p.frames[self.format].name.clone()));
        let mut header = swapped(p, d);
        let direction = answer_direction(p, d.direction);
        if let Some(dir) = direction {
            set_direction(p, &p.frames[self.format], &mut header, dir);
        }
        self.last_header = Some(header.clone());
        object.insert("header", Value::Struct(header));
        if let Some(dir) = direction.filter(|_| p.directions_given()) {
            object.insert("direction", Value::from(p.directions[dir].name.clone()));
        }
        let name = match kind {
            Answer::None => return Err("the request expects no answer".into()),
            // A command-less frame of the answer direction (Dynamixel 1.0's status packet):
            // its values depend on what the request asked, which `--values` cannot say.
            Answer::Message => {
                return Err("an answer of kind `message` (a struct without a command) is not built by the twin".into());
            }
            Answer::Ack => {
                object.insert("ack", Value::Bool(true));
                object.insert("payload", Value::Bytes(Vec::new()));
                "ACK".to_string()
            }
            Answer::Reply | Answer::Command(_) => {
                let other = match kind {
                    Answer::Command(k) => Some(k),
                    _ => None,
                };
                let ci = match other {
                    None => d.command.ok_or("a frame without a command")?,
                    Some(k) => self.command_of(k).ok_or("no command of the answer's key")?,
                };
                let command = &p.commands[ci];
                object.insert("command", Value::from(command.name.clone()));
                let mut payload = self.payload(ci, direction)?;
                let read = match (&self.registers, nack) {
                    (Some(file), false) => file.fill_answer(p, d, device, &mut payload),
                    _ => None,
                };
                object.insert("payload", payload);
                match read {
                    Some(read) => format!("{} ({read})", command.name),
                    None => command.name.clone(),
                }
            }
        };
        let mut frame = self
            .codec
            .encode(&Value::Struct(object))
            .map_err(|e| format!("{name} not encoded: {e}"))?
            .bytes;
        self.responder
            .answer(request, &mut frame)
            .map_err(|e| format!("{name}: {e:?}"))?;
        Ok((name, frame))
    }

    /// The index of the command of `key` in the session's format.
    fn command_of(&self, key: u64) -> Option<usize> {
        let p = self.codec.protocol();
        let f = &p.frames[self.format];
        (0..p.commands.len()).find(|&ci| command_key(p, f, ci) == Some(key))
    }

    /// The payload of command `ci` in `direction`: the caller's values over the payload's
    /// all-zero value.
    fn payload(&self, ci: usize, direction: Option<usize>) -> Result<Value, String> {
        let p = self.codec.protocol();
        let command = &p.commands[ci];
        let si = command
            .payloads
            .get(direction.unwrap_or(0))
            .or(command.payloads.first())
            .copied()
            .flatten();
        let given = self.options.values.get(&command.name);
        let Some(si) = si else {
            return Ok(Value::Struct(Fields::new()));
        };
        let zero = self.codec.zero_payload(si);
        match (zero, given) {
            (Some(Value::Struct(mut fields)), Some(Value::Struct(given))) => {
                for (name, v) in given.iter() {
                    fields.insert(name, v.clone());
                }
                Ok(Value::Struct(fields))
            }
            (_, Some(given)) => Ok(given.clone()),
            (Some(zero), None) => Ok(zero),
            (None, None) => Err(format!(
                "zero bytes are no payload of `{}`: give its values (--values)",
                command.name
            )),
        }
    }
}

/// The request's header with its addresses swapped, as the answer's.
fn swapped(p: &protocol_spec::ir::Protocol, d: &Decoded) -> Fields {
    let mut header = d.header.clone();
    let Some((s, f)) = p.session.as_ref().map(|s| (s, &p.frames[s.frame])) else {
        return header;
    };
    if let Some((a, b)) = s.swap {
        let (a, b) = (&f.values[a].name, &f.values[b].name);
        let (va, vb) = (header.get(a).cloned(), header.get(b).cloned());
        if let (Some(va), Some(vb)) = (va, vb) {
            header.insert(a.clone(), vb);
            header.insert(b.clone(), va);
        }
    }
    header
}

/// The direction of an answer to a request of `direction`: another direction of the spec.
fn answer_direction(p: &protocol_spec::ir::Protocol, direction: Option<usize>) -> Option<usize> {
    let d = direction?;
    (0..p.directions.len()).find(|&i| i != d).or(Some(d))
}

/// A request as the log names it: its command, or ACK, and its header.
fn describe(codec: &Codec<'_>, d: Option<&Decoded>) -> String {
    let Some(d) = d else {
        return "a frame of no message".into();
    };
    let p = codec.protocol();
    let name = match d.command.and_then(|ci| p.commands.get(ci)) {
        Some(c) => c.name.as_str(),
        None if d.ack => "ACK",
        None => "?",
    };
    let header = serde_json::to_string(&Value::Struct(d.header.clone())).unwrap_or_default();
    format!("{name} {header}")
}

/// A read that ended without bytes and without failing: a tick of the clock.
fn is_tick(e: &io::Error) -> bool {
    matches!(
        e.kind(),
        io::ErrorKind::TimedOut | io::ErrorKind::WouldBlock | io::ErrorKind::Interrupted
    )
}
