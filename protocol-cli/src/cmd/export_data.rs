//! `protocol export csv|mcap SPEC [INPUT] [--hex] [--candump FILE] [--frame NAME]
//! [--direction NAME] -o OUT`: a capture decoded as `protocol decode` decodes it, written as
//! CSV tables or an MCAP file (see `protocol_cli::export`). This module owns the arguments
//! and reading the input.

use std::path::PathBuf;
use std::process::ExitCode;

use miette::{IntoDiagnostic, Result, WrapErr, miette};
use protocol_cli::export::{self, Capture, Record};
use protocol_cli::{candump, spec};
use protocol_dynamic::{Interpreter, parse_hex};
use protocol_spec::ir::Protocol;

use super::decode::pick_format;
use super::{load_checked, pick_direction};

/// The arguments of `export csv` and `export mcap`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The spec file.
    spec: PathBuf,
    /// The capture: a binary file of raw serial bytes.
    #[arg(required_unless_present = "candump", conflicts_with = "candump")]
    input: Option<PathBuf>,
    /// The input is hex text (whitespace, `0x`, `,` and `:` are ignored).
    #[arg(long)]
    hex: bool,
    /// Read a `candump -L` or `candump` log instead (the spec needs a CAN frame format).
    #[arg(long, value_name = "FILE", conflicts_with = "hex")]
    candump: Option<PathBuf>,
    /// The frame format to look for, as `decode --frame`.
    #[arg(long, value_name = "NAME")]
    frame: Option<String>,
    /// The direction of the frames, as `decode --direction`.
    #[arg(long, value_name = "NAME")]
    direction: Option<String>,
    /// The link's bit rate, for the times of frames of a byte stream (MCAP log times; ten
    /// bits a byte).
    #[arg(long, value_name = "N", default_value_t = 115_200,
          value_parser = clap::value_parser!(u32).range(1..))]
    baud: u32,
    /// Where to write: a directory for `csv` (one `COMMAND.csv` per command), a file for
    /// `mcap`.
    #[arg(short, long)]
    output: PathBuf,
}

/// The spec and the decoded frames of the input.
fn decode(args: &Args) -> Result<std::result::Result<(Protocol, Vec<Record>), ExitCode>> {
    let protocol = match load_checked(&args.spec)? {
        Ok(p) => p,
        Err(code) => return Ok(Err(code)),
    };
    let direction = pick_direction(&protocol, args.direction.as_deref(), true)?;
    let interp = Interpreter::new(protocol.clone());
    let codec = interp.codec().with_direction(direction);
    let format = pick_format(&codec, args.frame.as_deref(), args.candump.is_some())?;
    let records = if let Some(log) = &args.candump {
        let text = spec::read_text("candump log", log)?;
        let (frames, errors) = candump::parse(&text);
        for (line, error) in &errors {
            eprintln!(
                "warning: {}:{line}: not a CAN frame: {error}",
                log.display()
            );
        }
        let frames: Vec<candump::CanRecord> = frames.into_iter().map(|(_, r)| r).collect();
        export::decode_capture(&codec, format, Capture::Can(&frames))
    } else {
        let path = args.input.as_ref().ok_or_else(|| miette!("no input"))?;
        let raw = spec::read("input", path)?;
        let data = if args.hex {
            parse_hex(&String::from_utf8_lossy(&raw))
                .ok_or_else(|| miette!("--hex input {} is not hex", path.display()))?
        } else {
            raw
        };
        let link = args.frame.is_none() && !protocol.link.is_empty();
        export::decode_capture(&codec, format, Capture::Bytes { data: &data, link })
    }
    .into_diagnostic()
    .wrap_err("decoding failed")?;
    Ok(Ok((protocol, records)))
}

/// `export csv`: one CSV file per command in the output directory.
pub fn csv_run(args: &Args) -> Result<ExitCode> {
    let records = match decode(args)? {
        Ok((_, records)) => records,
        Err(code) => return Ok(code),
    };
    let written = export::csv::write_dir(&records, &args.output)
        .into_diagnostic()
        .wrap_err_with(|| format!("cannot write into `{}`", args.output.display()))?;
    for (path, frames) in &written {
        eprintln!("{}: {frames} frames", path.display());
    }
    eprintln!("{} frames in {} files", records.len(), written.len());
    Ok(ExitCode::SUCCESS)
}

/// `export mcap`: one MCAP file, a channel per command.
pub fn mcap_run(args: &Args) -> Result<ExitCode> {
    let (protocol, records) = match decode(args)? {
        Ok(decoded) => decoded,
        Err(code) => return Ok(code),
    };
    let clock = if args.candump.is_some() {
        export::mcap::Clock::Records
    } else {
        export::mcap::Clock::Baud(args.baud)
    };
    let file = std::fs::File::create(&args.output)
        .into_diagnostic()
        .wrap_err_with(|| format!("cannot write `{}`", args.output.display()))?;
    let written = export::mcap::write(&protocol, &records, clock, std::io::BufWriter::new(file))
        .into_diagnostic()
        .wrap_err_with(|| format!("cannot write `{}`", args.output.display()))?;
    eprintln!(
        "{}: {} frames on {} channels",
        args.output.display(),
        records.len(),
        written.len()
    );
    Ok(ExitCode::SUCCESS)
}
