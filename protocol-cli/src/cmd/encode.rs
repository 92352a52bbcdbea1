//! `protocol encode SPEC [INPUT|-] [--hex] [-o FILE] [--direction NAME]`: frame objects (JSON Lines, the shape
//! `decode --format json` prints) to frames. Event objects (`"event": ...`) are skipped, so
//! `decode --format json | encode` gives back every valid frame of the input.
//!
//! A line that is not a valid frame object gets an error naming its line and the offending
//! field, on stderr; nothing is written for it, the other lines are encoded, and the exit
//! status is 1.

use std::io::{self, BufRead, BufReader, IsTerminal, Read, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use miette::{IntoDiagnostic, Result, WrapErr};
use protocol_cli::candump::format_log;
use protocol_cli::spec;
use protocol_dynamic::{Encoded, Interpreter, Value, hex};
use protocol_spec::ir::Transport;

use super::{INVALID, load_checked, pick_direction};

/// Arguments of `protocol encode`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The spec file.
    spec: PathBuf,
    /// JSON Lines of frame objects: a file, or `-` for stdin (the default).
    input: Option<PathBuf>,
    /// Write one line of hex per frame instead of raw bytes (always on a terminal).
    #[arg(long)]
    hex: bool,
    /// Write to this file instead of stdout.
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// The direction of frame objects that name none, for a spec whose directions no header
    /// field tells (`given = true`): a direction named in the spec.
    #[arg(long, value_name = "NAME")]
    direction: Option<String>,
}

/// Encodes every line of the input.
pub fn run(args: &Args) -> Result<ExitCode> {
    let protocol = match load_checked(&args.spec)? {
        Ok(p) => p,
        Err(code) => return Ok(code),
    };
    let direction = pick_direction(&protocol, args.direction.as_deref(), false)?;
    let interp = Interpreter::new(protocol);
    let codec = interp.codec().with_direction(direction);
    let (name, reader): (String, Box<dyn Read>) =
        match args.input.as_ref().filter(|p| p.as_os_str() != "-") {
            Some(p) => (p.display().to_string(), Box::new(spec::open("input", p)?)),
            None => ("stdin".into(), Box::new(io::stdin())),
        };
    let (mut out, to_terminal): (Box<dyn Write>, bool) = match &args.output {
        Some(p) => (
            Box::new(io::BufWriter::new(
                std::fs::File::create(p)
                    .into_diagnostic()
                    .wrap_err_with(|| format!("cannot write `{}`", p.display()))?,
            )),
            false,
        ),
        None => (
            Box::new(io::BufWriter::new(io::stdout().lock())),
            io::stdout().is_terminal(),
        ),
    };
    // Raw bytes would garble a terminal.
    let as_hex = args.hex || to_terminal;
    let mut errors = 0usize;
    let mut can_time = 0u64;
    for (i, line) in BufReader::new(reader).lines().enumerate() {
        let line_no = i + 1;
        let line = line.into_diagnostic()?;
        if line.trim().is_empty() {
            continue;
        }
        let object: Value = match serde_json::from_str(&line) {
            Ok(v) => v,
            Err(e) => {
                eprintln!("error: {name}:{line_no}: not JSON: {e}");
                errors += 1;
                continue;
            }
        };
        // Events (bad checksums, skipped bytes...) carry no frame to encode.
        if object.get("event").is_some() {
            continue;
        }
        let encoded = match codec.encode(&object) {
            Ok(e) => e,
            Err(issue) => {
                eprintln!("error: {name}:{line_no}: {issue}; nothing written for this line");
                errors += 1;
                continue;
            }
        };
        let written = write_frame(
            &mut out,
            &codec.protocol().frames[encoded.format].transport,
            &encoded,
            as_hex,
            &mut can_time,
        );
        if let Err(e) = written {
            return closed_or(e);
        }
    }
    if let Err(e) = out.flush() {
        return closed_or(e);
    }
    if errors > 0 {
        eprintln!(
            "{errors} line{} not encoded",
            if errors == 1 { "" } else { "s" }
        );
        return Ok(ExitCode::from(INVALID));
    }
    Ok(ExitCode::SUCCESS)
}

/// Writes one frame: raw bytes, a hex line, or for a CAN frame a `candump -L` line (which
/// `decode --candump` reads back), timestamped 10 ms apart.
fn write_frame(
    out: &mut dyn Write,
    transport: &Transport,
    e: &Encoded,
    as_hex: bool,
    can_time: &mut u64,
) -> io::Result<()> {
    match (&e.can, transport) {
        (Some(can), Transport::Can { extended }) => {
            let time = format!("{}.{:06}", *can_time / 1_000_000, *can_time % 1_000_000);
            *can_time += 10_000;
            writeln!(
                out,
                "{}",
                format_log(&time, "can0", can.id, *extended, can.data())
            )
        }
        _ if as_hex => writeln!(out, "{}", hex(&e.bytes)),
        _ => out.write_all(&e.bytes),
    }
}

/// The reader of the output went away (`| head`): stop quietly; any other error is one.
fn closed_or(e: io::Error) -> Result<ExitCode> {
    if e.kind() == io::ErrorKind::BrokenPipe {
        Ok(ExitCode::SUCCESS)
    } else {
        Err(e).into_diagnostic()
    }
}
