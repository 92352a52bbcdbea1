//! `protocol decode SPEC [INPUT|-] [--hex] [--serial PORT --baud N] [--candump FILE]
//! [--can IFACE] [--format table|json] [--stats] [--frame NAME] [--direction NAME]`: find and
//! decode the frames of a byte stream with the runtime's stream engine, on the layout
//! `protocol-dynamic` builds of the spec.
//!
//! This module owns where the bytes come from (a file, stdin, hex text, a serial port, a CAN
//! log, a live SocketCAN interface) and when the input ends; what a line says is the session's business.

use std::io::{self, IsTerminal, Read, Write};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, SystemTime, UNIX_EPOCH};

use indicatif::{ProgressBar, ProgressStyle};
use miette::{IntoDiagnostic, Result, WrapErr, miette};
use protocol_cli::session::{Output, Session};
use protocol_cli::{candump, spec};
use protocol_dynamic::{Codec, Interpreter, Stream, parse_hex_located};
use protocol_runtime::Stats;
use protocol_spec::ir::Transport;

use super::{load_checked, pick_direction};
use crate::Format;

/// Arguments of `protocol decode`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The spec file.
    spec: PathBuf,
    /// The input: a binary file, or `-` for stdin (the default).
    #[arg(conflicts_with_all = ["serial", "candump", "can"])]
    input: Option<PathBuf>,
    /// The input is hex text (whitespace, `0x`, `,` and `:` are ignored).
    #[arg(long)]
    hex: bool,
    /// Read a live serial port (runs until interrupted, or until the port hangs up). Every
    /// frame and event carries the time its bytes were read.
    #[arg(long, value_name = "PORT", conflicts_with_all = ["candump", "can"])]
    serial: Option<String>,
    /// Baud rate of the serial port.
    #[arg(long, value_name = "N", default_value_t = 115_200, requires = "serial")]
    baud: u32,
    /// Read a Linux `candump -L` or `candump` log (the spec needs a CAN frame format).
    #[arg(long, value_name = "FILE")]
    candump: Option<PathBuf>,
    /// Read a live SocketCAN interface (`can0`, `vcan0`; Linux only), until interrupted (the
    /// spec needs a CAN frame format). Every frame and event carries its receive time.
    #[arg(long, value_name = "IFACE", conflicts_with = "candump")]
    can: Option<String>,
    /// Output format [default: table on a terminal, json otherwise].
    #[arg(long, value_enum)]
    format: Option<Format>,
    /// Print a summary at the end: frames per command, checksum failures, length rejections,
    /// bytes skipped, lost and reordered frames (a spec's frame counter), link efficiency (to
    /// stdout with `table`, to stderr with `json`).
    #[arg(long)]
    stats: bool,
    /// The frame format to look for [default: every command format of a link of several (as
    /// MAVLink 1 and 2), else the first of the spec with a matching transport].
    #[arg(long, value_name = "NAME")]
    frame: Option<String>,
    /// The direction of the frames, for a spec whose directions no header field tells
    /// (`given = true`): a direction named in the spec (`request`, `response`).
    #[arg(long, value_name = "NAME", conflicts_with = "session")]
    direction: Option<String>,
    /// Follow the spec's `[session]` through a capture of both ends of a half-duplex wire: a
    /// frame that follows a request expecting an answer is read as that answer (in the
    /// response direction of a spec whose header does not tell it), and each answer names the
    /// request it answers (`answers`, the request's `frame` number) and the round-trip time
    /// where frames carry times (`rtt_ms`); `--stats` counts the unanswered requests.
    #[arg(long)]
    session: bool,
}

/// Decodes the input.
pub fn run(args: &Args) -> Result<ExitCode> {
    let protocol = match load_checked(&args.spec)? {
        Ok(p) => p,
        Err(code) => return Ok(code),
    };
    if args.session && protocol.session.is_none() {
        return Err(miette!(
            "`--session`: spec `{}` has no `[session]` table, so no conversation to follow",
            protocol.name
        ));
    }
    let direction = pick_direction(&protocol, args.direction.as_deref(), !args.session)?;
    let interp = Interpreter::new(protocol);
    let codec = interp.codec().with_direction(direction);
    let output = match args.format {
        Some(Format::Table) => Output::Table,
        Some(Format::Json) => Output::Json,
        None if io::stdout().is_terminal() => Output::Table,
        None => Output::Json,
    };
    let can = args.candump.is_some() || args.can.is_some();
    let format = pick_format(&codec, args.frame.as_deref(), can)?;
    let stdout = io::stdout();
    let mut session = Session::new(&codec, format, output, io::BufWriter::new(stdout.lock()));
    if args.session {
        session.follow_conversation();
    }
    let decoded = if let Some(interface) = &args.can {
        let live = open_can(interface)?;
        decode_live_can(&mut session, live).map(|()| None)
    } else if let Some(path) = &args.candump {
        let text = spec::read_text("candump log", path)?;
        decode_candump(&mut session, &path.display().to_string(), &text).map(|()| None)
    } else {
        let mut input = open_input(args)?;
        // Without `--frame`, every command format of the link (MAVLink 1 and 2), each found by
        // its sync; with it, the one named.
        let link = args.frame.is_none() && !codec.protocol().link.is_empty();
        let decoder = if link {
            codec.link_stream()
        } else {
            codec.stream(format)
        };
        let (decoder, layout) = decoder
            .zip(codec.layout(format))
            .ok_or_else(|| miette!("no frame format {format}"))?;
        if layout.max_len > decoder.capacity() {
            eprintln!(
                "warning: frames longer than {} bytes (the format allows {}) are rejected as bad lengths",
                decoder.capacity(),
                layout.max_len
            );
        }
        stream(decoder, &mut input, &mut session).map(Some)
    }
    .and_then(|engine| session.flush().map(|()| engine));
    let engine = match decoded {
        Ok(engine) => engine,
        // The reader of the output went away (`| head`): not an error of ours.
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => return Ok(ExitCode::SUCCESS),
        Err(e) => return Err(e).into_diagnostic().wrap_err("decoding failed"),
    };
    if let Some(hint) = wrong_format_hint(&session, &codec, format, engine.as_ref(), args.hex) {
        eprintln!("{hint}");
    }
    session.finish();
    if args.stats {
        let summary = session.summary(engine.as_ref());
        let written = match output {
            Output::Table => writeln!(io::stdout(), "\n{summary}"),
            Output::Json => write!(io::stderr(), "{summary}"),
        };
        match written {
            Err(e) if e.kind() != io::ErrorKind::BrokenPipe => {
                return Err(e).into_diagnostic();
            }
            _ => {}
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// Inputs shorter than this get no hint: a few bytes of noise are no sign of a wrong format.
const HINT_ABOVE: u64 = 64;

/// A hint when nearly nothing of a sizeable input was in frames (under 10%): the capture is
/// probably of another link, another frame format, or hex text read as binary (not asked of
/// input read with `--hex`); or, when every candidate failed on its length or its check, the
/// spec's length or check rule is ([`rule_question`]).
fn wrong_format_hint(
    session: &Session<'_, '_, impl Write>,
    codec: &Codec<'_>,
    format: usize,
    engine: Option<&Stats>,
    hex: bool,
) -> Option<String> {
    let c = &session.counts;
    if c.input_bytes < HINT_ABOVE || c.frame_bytes.saturating_mul(10) >= c.input_bytes {
        return None;
    }
    let p = codec.protocol();
    let name = p.frames.get(format).map_or("?", |f| f.name.as_str());
    let lead = format!(
        "hint: {} of {} bytes decoded as `{name}` frames of {}",
        c.frame_bytes, c.input_bytes, p.name
    );
    if let Some(question) = engine.and_then(rule_question) {
        return Some(format!("{lead}: {question}"));
    }
    let others: Vec<&str> = p
        .frames
        .iter()
        .filter(|f| !matches!(f.transport, Transport::Can { .. }))
        .map(|f| f.name.as_str())
        .filter(|n| *n != name)
        .collect();
    let other = if others.is_empty() {
        String::new()
    } else {
        format!(
            ", another frame format (`--frame {}`)",
            others.join("` or `--frame ")
        )
    };
    let as_hex = if hex { "" } else { ", or hex text (`--hex`)" };
    Some(format!(
        "{lead}: is this a capture of that link{other}{as_hex}?"
    ))
}

/// The question when the frames' starts were found but every candidate failed on its length
/// or on a check (a candidate cut by the end of the input aside): the capture is likely of the
/// link, and the spec's length or check rule (its algorithm, what it covers, its byte order)
/// is the likely mistake. `None` when no candidate failed so, or another failed otherwise.
fn rule_question(s: &Stats) -> Option<String> {
    let checks = s.bad_checksum.saturating_add(s.bad_header_check);
    if s.bad_length.saturating_add(checks) == 0 || s.bad_header > 0 || s.bad_trailer > 0 {
        return None;
    }
    Some(format!(
        "every candidate failed on its length ({}) or its check ({checks}): is the length or \
         check rule right?",
        s.bad_length
    ))
}

/// The frame format to decode: `--frame NAME`, else the first with the input's transport.
pub(crate) fn pick_format(codec: &Codec<'_>, name: Option<&str>, can: bool) -> Result<usize> {
    let p = codec.protocol();
    let is_can = |t: Transport| matches!(t, Transport::Can { .. });
    if let Some(name) = name {
        let i = codec.format_index(name).ok_or_else(|| {
            let names: Vec<&str> = p.frames.iter().map(|f| f.name.as_str()).collect();
            miette!(
                "spec `{}` has no frame format `{name}` (it has: {})",
                p.name,
                names.join(", ")
            )
        })?;
        if is_can(p.frames[i].transport) != can {
            return Err(miette!(
                "frame format `{name}` is {} frame format; {}",
                if can { "not a CAN" } else { "a CAN" },
                if can {
                    "--candump and --can need a CAN one"
                } else {
                    "read it with --candump"
                }
            ));
        }
        return Ok(i);
    }
    p.frames
        .iter()
        .position(|f| is_can(f.transport) == can)
        .ok_or_else(|| {
            if can {
                miette!(
                    help = "a CAN frame format has `transport = \"can\"` in its `[frames.NAME]` table",
                    "spec `{}` has no CAN transport: --candump and --can need a frame format carried over CAN",
                    p.name
                )
            } else {
                miette!(
                    help = "use --candump FILE for a CAN log",
                    "spec `{}` has only CAN frame formats: a byte stream cannot be decoded",
                    p.name
                )
            }
        })
}

/// Where the bytes of a stream come from.
enum Input {
    /// All of it, in memory (a file, or hex text), with a progress bar for large inputs.
    Bytes {
        data: Vec<u8>,
        at: usize,
        bar: Option<ProgressBar>,
    },
    /// A stream read as it comes (stdin).
    Reader(Box<dyn Read>),
    /// A serial port, until it hangs up or SIGINT.
    Serial {
        port: Box<dyn serialport::SerialPort>,
        interrupted: Arc<AtomicBool>,
    },
}

/// Bytes per read: large enough for throughput, small enough for a live display.
const CHUNK: usize = 64 * 1024;

/// Inputs above this size get a progress bar (when stderr is a terminal).
const PROGRESS_ABOVE: usize = 4 * 1024 * 1024;

fn open_input(args: &Args) -> Result<Input> {
    if let Some(port) = &args.serial {
        let port = serialport::new(port, args.baud)
            .timeout(Duration::from_millis(100))
            .open()
            .into_diagnostic()
            .wrap_err_with(|| format!("cannot open serial port `{port}`"))?;
        let interrupted = Arc::new(AtomicBool::new(false));
        signal_hook::flag::register(signal_hook::consts::SIGINT, Arc::clone(&interrupted))
            .into_diagnostic()?;
        return Ok(Input::Serial { port, interrupted });
    }
    let path = args.input.as_ref().filter(|p| p.as_os_str() != "-");
    let raw = match (path, args.hex) {
        (None, false) => return Ok(Input::Reader(Box::new(io::stdin()))),
        (None, true) => {
            let mut text = Vec::new();
            io::stdin().read_to_end(&mut text).into_diagnostic()?;
            text
        }
        (Some(p), _) => spec::read("input", p)?,
    };
    let data = if args.hex {
        let name = path.map_or("stdin".into(), |p| p.display().to_string());
        let text = String::from_utf8(raw).map_err(|e| {
            miette!(
                "--hex input {name} is not text: byte {} is not UTF-8",
                e.utf8_error().valid_up_to()
            )
        })?;
        parse_hex_located(&text).map_err(|e| {
            miette!(
                "--hex input {name}:{}:{}: {} (expected pairs of hex digits; whitespace, `,`, `:` and `0x` are ignored)",
                e.line,
                e.column,
                e.what
            )
        })?
    } else {
        raw
    };
    let bar = (data.len() > PROGRESS_ABOVE && io::stderr().is_terminal()).then(|| {
        let bar = ProgressBar::new(data.len() as u64);
        if let Ok(style) =
            ProgressStyle::with_template("{bar:40} {bytes}/{total_bytes} {bytes_per_sec}")
        {
            bar.set_style(style);
        }
        bar
    });
    Ok(Input::Bytes { data, at: 0, bar })
}

impl Input {
    /// The next chunk; empty at the end of the input.
    fn next<'b>(&'b mut self, buf: &'b mut [u8]) -> io::Result<&'b [u8]> {
        match self {
            Input::Bytes { data, at, bar } => {
                let end = (*at + CHUNK).min(data.len());
                let chunk = data.get(*at..end).unwrap_or_default();
                *at = end;
                if let Some(bar) = bar {
                    bar.set_position(end as u64);
                    if end == data.len() {
                        bar.finish_and_clear();
                    }
                }
                Ok(chunk)
            }
            Input::Reader(r) => loop {
                match r.read(buf) {
                    Ok(n) => return Ok(buf.get(..n).unwrap_or_default()),
                    Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
                    Err(e) => return Err(e),
                }
            },
            Input::Serial { port, interrupted } => loop {
                if interrupted.load(Ordering::Relaxed) {
                    return Ok(&[]);
                }
                match port.read(buf) {
                    // A port that hangs up (a closed pty, an unplugged adapter: `serialport`
                    // reports POLLHUP as a broken pipe, a read after it as EIO) ends the input.
                    Ok(0) => return Ok(&[]),
                    Ok(n) => return Ok(buf.get(..n).unwrap_or_default()),
                    Err(e)
                        if matches!(
                            e.kind(),
                            io::ErrorKind::TimedOut | io::ErrorKind::Interrupted
                        ) => {}
                    Err(e)
                        if e.kind() == io::ErrorKind::BrokenPipe || e.raw_os_error() == Some(5) =>
                    {
                        return Ok(&[]);
                    }
                    Err(e) => return Err(e),
                }
            },
        }
    }

    /// Whether output should be flushed after every chunk (a live source).
    fn live(&self) -> bool {
        !matches!(self, Input::Bytes { .. })
    }

    /// Whether the items of a chunk carry the time it was read (a serial port; stdin may be
    /// a file, whose output must not change from run to run).
    fn stamped(&self) -> bool {
        matches!(self, Input::Serial { .. })
    }
}

/// Runs the stream decoder over the whole input; returns the engine's stats.
fn stream<W: Write>(
    mut decoder: Stream<'_>,
    input: &mut Input,
    session: &mut Session<'_, '_, W>,
) -> io::Result<protocol_runtime::Stats> {
    let mut buf = vec![0u8; CHUNK];
    let live = input.live();
    let stamped = input.stamped();
    loop {
        let mut chunk = input.next(&mut buf)?;
        if chunk.is_empty() {
            break;
        }
        session.fed(chunk.len());
        if stamped {
            session.received(SystemTime::now().duration_since(UNIX_EPOCH).ok());
        }
        while let Some(item) = decoder.next_item(&mut chunk) {
            session.item(item)?;
        }
        if live {
            session.flush()?;
        }
    }
    while let Some(item) = decoder.flush_item() {
        session.item(item)?;
    }
    Ok(*decoder.stats())
}

/// The live CAN input (Linux: SocketCAN).
#[cfg(target_os = "linux")]
type LiveCan = protocol_cli::socketcan::Live;
#[cfg(not(target_os = "linux"))]
type LiveCan = std::convert::Infallible;

#[cfg(target_os = "linux")]
fn open_can(interface: &str) -> Result<LiveCan> {
    LiveCan::open(interface)
        .into_diagnostic()
        .wrap_err_with(|| format!("cannot open CAN interface `{interface}`"))
}

#[cfg(not(target_os = "linux"))]
fn open_can(_interface: &str) -> Result<LiveCan> {
    Err(miette!(
        "--can reads SocketCAN interfaces, which only Linux has; replay a log with --candump"
    ))
}

/// Decodes the frames of a live CAN interface as they arrive, until SIGINT.
#[cfg(target_os = "linux")]
fn decode_live_can<W: Write>(
    session: &mut Session<'_, '_, W>,
    mut live: LiveCan,
) -> io::Result<()> {
    let mut errors = 0;
    let mut index = 0;
    while let Some(record) = live.next(&mut errors)? {
        let at = record
            .time
            .as_deref()
            .and_then(protocol_cli::export::time_ns);
        session.received(at.map(Duration::from_nanos));
        session.can(index, &record)?;
        session.flush()?;
        index += 1;
    }
    if errors > 0 {
        eprintln!("warning: {errors} CAN error frames skipped");
    }
    Ok(())
}

#[cfg(not(target_os = "linux"))]
fn decode_live_can<W: Write>(_: &mut Session<'_, '_, W>, live: LiveCan) -> io::Result<()> {
    match live {}
}

/// Decodes every record of a CAN log; lines that are not frames are reported on stderr.
fn decode_candump<W: Write>(
    session: &mut Session<'_, '_, W>,
    name: &str,
    text: &str,
) -> io::Result<()> {
    let (records, errors) = candump::parse(text);
    for (line, error) in &errors {
        eprintln!("warning: {name}:{line}: not a CAN frame: {error}");
    }
    for (index, (_, record)) in records.iter().enumerate() {
        session.can(index as u64, record)?;
    }
    Ok(())
}
