//! `protocol report SPEC CAPTURE [-o FILE] [--frame NAME] [--direction NAME]`: the capture
//! report, one self-contained HTML file (see `protocol_cli::report`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use miette::{IntoDiagnostic, Result, WrapErr, miette};
use protocol_cli::{report, spec};
use protocol_dynamic::Interpreter;

use super::{load_checked, pick_direction};

/// Writes the report to `output` (default: the capture's name with `.html`). `direction` names
/// the direction of the frames, as `decode --direction` does: required for a spec whose
/// directions no header field tells, refused for any other.
pub fn run(
    spec: &Path,
    capture: &Path,
    output: Option<&Path>,
    frame: Option<&str>,
    direction: Option<&str>,
) -> Result<ExitCode> {
    let protocol = match load_checked(spec)? {
        Ok(p) => p,
        Err(code) => return Ok(code),
    };
    let direction = pick_direction(&protocol, direction, true)?;
    let data = spec::read("capture", capture)?;
    let interp = Interpreter::new(protocol);
    let codec = interp.codec().with_direction(direction);
    let format = match frame {
        Some(name) => codec
            .format_index(name)
            .ok_or_else(|| miette!("no frame format `{name}` in {}", spec.display()))?,
        None => 0,
    };
    let name = capture.file_name().map_or_else(
        || capture.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let html = report::render(&codec, format, &data, &name).ok_or_else(|| {
        miette!("frame format #{format} cannot decode a byte stream (a CAN format?)")
    })?;
    let path = output.map_or_else(|| capture.with_extension("html"), PathBuf::from);
    std::fs::write(&path, html)
        .into_diagnostic()
        .wrap_err_with(|| format!("cannot write `{}`", path.display()))?;
    eprintln!(
        "{}: {} bytes of capture reported",
        path.display(),
        data.len()
    );
    Ok(ExitCode::SUCCESS)
}
