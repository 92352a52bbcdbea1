//! `protocol report SPEC CAPTURE [-o FILE] [--frame NAME] [--direction NAME] [--plot NAMES]`:
//! the capture report, one self-contained HTML file (see `protocol_cli::report`), with the
//! signals `--plot` names (see `protocol_cli::signals`). This module owns reading the files and
//! the errors of `--plot`'s names.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use miette::{IntoDiagnostic, LabeledSpan, Result, WrapErr, miette};
use protocol_cli::export::{self, Capture};
use protocol_cli::signals::names::{Catalogue, Refusal};
use protocol_cli::signals::{self, BadName};
use protocol_cli::{report, spec};
use protocol_dynamic::Interpreter;

use super::{load_checked, pick_direction};

/// What to report on: the spec, the capture and how to read it.
pub struct Args<'a> {
    /// The spec file.
    pub spec: &'a Path,
    /// The capture (raw bytes).
    pub capture: &'a Path,
    /// Where to write the page (default: the capture's name with `.html`).
    pub output: Option<&'a Path>,
    /// The frame format to decode.
    pub frame: Option<&'a str>,
    /// The direction of the frames, as `decode --direction` has it: required for a spec whose
    /// directions no header field tells, refused for any other.
    pub direction: Option<&'a str>,
    /// The `--plot` arguments: names of signals, comma-separated.
    pub plot: &'a [String],
}

/// Writes the report.
pub fn run(args: &Args<'_>) -> Result<ExitCode> {
    let protocol = match load_checked(args.spec)? {
        Ok(p) => p,
        Err(code) => return Ok(code),
    };
    let direction = pick_direction(&protocol, args.direction, true)?;
    let catalogue = Catalogue::of(&protocol);
    let joined = args.plot.join(",");
    let chosen = if args.plot.is_empty() {
        None
    } else {
        Some(signals::parse(&catalogue, &joined).map_err(|bad| plot_error(&joined, &bad))?)
    };
    let data = spec::read("capture", args.capture)?;
    let interp = Interpreter::new(protocol);
    let codec = interp.codec().with_direction(direction);
    let format = match args.frame {
        Some(name) => codec
            .format_index(name)
            .ok_or_else(|| miette!("no frame format `{name}` in {}", args.spec.display()))?,
        None => 0,
    };
    let name = args.capture.file_name().map_or_else(
        || args.capture.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let not_a_stream =
        || miette!("frame format #{format} cannot decode a byte stream (a CAN format?)");
    let bytes = Capture::Bytes {
        data: &data,
        link: false,
    };
    let mut signals = signals::Collector::new(&catalogue, chosen.as_deref());
    export::each_frame(&codec, format, bytes, &mut |r| signals.add(&r))
        .map_err(|_| not_a_stream())?;
    let plot = signals.finish();
    let html = report::render(&codec, format, &data, &name, &plot).ok_or_else(not_a_stream)?;
    let path = args
        .output
        .map_or_else(|| args.capture.with_extension("html"), PathBuf::from);
    std::fs::write(&path, html)
        .into_diagnostic()
        .wrap_err_with(|| format!("cannot write `{}`", path.display()))?;
    eprintln!(
        "{}: {} bytes of capture reported, {} signals plotted",
        path.display(),
        data.len(),
        plot.series.len()
    );
    Ok(ExitCode::SUCCESS)
}

/// One error for every name of `--plot` that selects nothing, each underlined in the
/// argument, with the spec's closest names as help.
fn plot_error(arg: &str, bad: &[BadName]) -> miette::Report {
    let labels: Vec<LabeledSpan> = bad
        .iter()
        .map(|b| {
            let why = match b.refusal {
                Refusal::Unknown { .. } => "no such field",
                Refusal::NotNumeric => "names or text, not numbers",
            };
            LabeledSpan::at(b.at.clone(), why)
        })
        .collect();
    let help: Vec<String> = bad
        .iter()
        .map(|b| match &b.refusal {
            Refusal::Unknown { close } if close.is_empty() => format!(
                "`{}`: a name is COMMAND.payload.FIELD, COMMAND.header.FIELD, or payload.FIELD for every command that has it (`protocol doc SPEC` lists the fields)",
                b.name
            ),
            Refusal::Unknown { close } => {
                format!("`{}`: did you mean {}?", b.name, close.join(", "))
            }
            Refusal::NotNumeric => format!(
                "`{}` is an enum, text or bytes: only numbers and flags can be plotted",
                b.name
            ),
        })
        .collect();
    let names: Vec<&str> = bad.iter().map(|b| b.name.as_str()).collect();
    miette!(
        labels = labels,
        help = help.join("\n"),
        "--plot: {} cannot be plotted",
        names.join(", ")
    )
    .with_source_code(miette::NamedSource::new("--plot", arg.to_string()))
}
