//! Loading a spec file for a command, and showing what is wrong with it.
//!
//! This module owns the path shown in messages (as the user wrote it), which of the pipeline's
//! renderings a command prints, their JSON form for editors and CI, and "cannot read FILE",
//! the one error every command gives for a file it cannot read. The diagnostics and their
//! text come from [`protocol_spec::compile`] and [`protocol_spec::diag`], the pipeline
//! and renderer the macro uses, so a spec's error reads the same in both.

use std::fmt;
use std::path::Path;

use protocol_spec::diag::{self, Color, Diagnostic};
use protocol_spec::ir::Protocol;
use protocol_spec::source::SpecSource;
use serde_json::{Value, json};

/// A spec read from a file: its text, and the checked protocol or its errors.
pub struct Loaded {
    /// The text and the path shown in messages.
    pub source: SpecSource,
    /// The checked protocol, or every error found, sorted.
    pub result: Result<Protocol, Vec<Diagnostic>>,
}

/// Why a file (a spec, a capture, an input) could not even be read.
#[derive(Debug)]
pub struct ReadError {
    /// What the file is to the command: `spec`, `capture`, `input`, `candump log`.
    pub what: &'static str,
    /// The path as given.
    pub path: String,
    /// The I/O error.
    pub error: std::io::Error,
}

impl ReadError {
    /// The error reading `path`, which is the command's `what`.
    pub fn new(what: &'static str, path: &Path, error: std::io::Error) -> Self {
        ReadError {
            what,
            path: path.display().to_string(),
            error,
        }
    }

    /// The rendering every command prints: `error: cannot read WHAT `PATH`: REASON`.
    pub fn render(&self, color: bool) -> String {
        diag::render_read_error(self.what, &self.path, &self.error, None, paint(color))
    }
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&diag::read_error_message(
            self.what,
            &self.path,
            &self.error,
        ))
    }
}

impl std::error::Error for ReadError {}

impl miette::Diagnostic for ReadError {}

/// Reads a whole file that is the command's `what`.
///
/// # Errors
/// [`ReadError`] when it cannot be read.
pub fn read(what: &'static str, path: &Path) -> Result<Vec<u8>, ReadError> {
    std::fs::read(path).map_err(|error| ReadError::new(what, path, error))
}

/// Reads a whole text file that is the command's `what`.
///
/// # Errors
/// [`ReadError`] when it cannot be read or is not UTF-8.
pub fn read_text(what: &'static str, path: &Path) -> Result<String, ReadError> {
    std::fs::read_to_string(path).map_err(|error| ReadError::new(what, path, error))
}

/// Opens a file that is the command's `what` for reading.
///
/// # Errors
/// [`ReadError`] when it cannot be opened.
pub fn open(what: &'static str, path: &Path) -> Result<std::fs::File, ReadError> {
    std::fs::File::open(path).map_err(|error| ReadError::new(what, path, error))
}

/// Reads and checks the spec at `path`.
///
/// # Errors
/// [`ReadError`] when the file cannot be read; errors in the spec are in [`Loaded::result`].
pub fn load(path: &Path) -> Result<Loaded, ReadError> {
    let shown = path.display().to_string();
    let text = read_text("spec", path)?;
    let source = SpecSource::new(shown, text);
    let result = protocol_spec::compile(&source);
    Ok(Loaded { source, result })
}

/// Renders a spec's errors: the report the `protocol!` macro's compile error carries, byte for
/// byte ([`protocol_spec::diag::render_report`]), coloured when `color` is true.
pub fn render_errors(diagnostics: &[Diagnostic], source: &SpecSource, color: bool) -> String {
    diag::render_report(diagnostics, source, paint(color))
}

/// Renders lint warnings (no headline: the spec is valid), coloured when `color` is true.
pub fn render_warnings(diagnostics: &[Diagnostic], source: &SpecSource, color: bool) -> String {
    diag::render_all_styled(diagnostics, source, paint(color))
}

fn paint(color: bool) -> Color {
    if color { Color::Ansi } else { Color::Plain }
}

/// One diagnostic as JSON: file, 1-based line and column of its start and end, severity
/// (`error` or `warning`), message, help.
pub fn to_json(d: &Diagnostic, source: &SpecSource) -> Value {
    let span = source.clamp(d.span.clone());
    let (line, column) = source.line_col(span.start);
    let (end_line, end_column) = source.line_col(span.end);
    json!({
        "file": source.path,
        "line": line,
        "column": column,
        "end_line": end_line,
        "end_column": end_column,
        "severity": d.severity.as_str(),
        "message": d.message,
        "help": d.help,
    })
}
