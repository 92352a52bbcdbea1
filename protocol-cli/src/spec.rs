//! Loading a spec file for a command, and showing what is wrong with it.
//!
//! This module owns the path shown in messages (as the user wrote it), the miette rendering of
//! the pipeline's [`Diagnostic`]s (file:line:col, the quoted line, the underline, the help) and
//! their JSON form for editors and CI. The diagnostics themselves come from
//! [`protocol_codegen::compile`], the same pipeline the macro runs.

use std::fmt;
use std::path::Path;

use miette::{GraphicalReportHandler, GraphicalTheme, LabeledSpan, NamedSource, SourceSpan};
use protocol_codegen::diag::{Diagnostic, Severity};
use protocol_codegen::ir::Protocol;
use protocol_codegen::source::SpecSource;
use serde_json::{Value, json};

/// A spec read from a file: its text, and the checked protocol or its errors.
pub struct Loaded {
    /// The text and the path shown in messages.
    pub source: SpecSource,
    /// The checked protocol, or every error found, sorted.
    pub result: Result<Protocol, Vec<Diagnostic>>,
}

/// Why a spec file could not even be read.
#[derive(Debug)]
pub struct ReadError {
    /// The path as given.
    pub path: String,
    /// The I/O error.
    pub error: std::io::Error,
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "cannot read spec `{}`: {}", self.path, self.error)
    }
}

impl std::error::Error for ReadError {}

/// Reads and checks the spec at `path`.
///
/// # Errors
/// [`ReadError`] when the file cannot be read; errors in the spec are in [`Loaded::result`].
pub fn load(path: &Path) -> Result<Loaded, ReadError> {
    let shown = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|error| ReadError {
        path: shown.clone(),
        error,
    })?;
    let source = SpecSource::new(shown, text);
    let result = protocol_codegen::compile(&source);
    Ok(Loaded { source, result })
}

/// A pipeline diagnostic as a miette diagnostic, with the spec as its source code.
#[derive(Debug)]
pub struct SpecDiagnostic {
    severity: Severity,
    message: String,
    help: Option<String>,
    span: SourceSpan,
    source: NamedSource<String>,
}

impl SpecDiagnostic {
    /// Wraps `d`, which points into `source`.
    pub fn new(d: &Diagnostic, source: &SpecSource) -> Self {
        let span = source.clamp(d.span.clone());
        SpecDiagnostic {
            severity: d.severity,
            message: d.message.clone(),
            help: d.help.clone(),
            span: (span.start, span.end - span.start).into(),
            source: NamedSource::new(source.path.clone(), source.text.clone())
                .with_language("TOML"),
        }
    }
}

impl fmt::Display for SpecDiagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for SpecDiagnostic {}

impl miette::Diagnostic for SpecDiagnostic {
    fn severity(&self) -> Option<miette::Severity> {
        Some(match self.severity {
            Severity::Error => miette::Severity::Error,
            Severity::Warning => miette::Severity::Warning,
        })
    }

    fn help<'a>(&'a self) -> Option<Box<dyn fmt::Display + 'a>> {
        self.help
            .as_ref()
            .map(|h| Box::new(h) as Box<dyn fmt::Display + 'a>)
    }

    fn source_code(&self) -> Option<&dyn miette::SourceCode> {
        Some(&self.source)
    }

    fn labels(&self) -> Option<Box<dyn Iterator<Item = LabeledSpan> + '_>> {
        Some(Box::new(std::iter::once(LabeledSpan::new_with_span(
            Some("here".into()),
            self.span,
        ))))
    }
}

/// Renders diagnostics as text: the message, `[file:line:col]`, the quoted spec lines with the
/// offending span underlined, and the help. Colours only when `color` is true.
pub fn render(diagnostics: &[Diagnostic], source: &SpecSource, color: bool) -> String {
    let theme = if color {
        GraphicalTheme::unicode()
    } else {
        GraphicalTheme::unicode_nocolor()
    };
    let handler = GraphicalReportHandler::new_themed(theme)
        .with_context_lines(1)
        .with_width(100);
    let mut out = String::new();
    for d in diagnostics {
        let wrapped = SpecDiagnostic::new(d, source);
        if handler.render_report(&mut out, &wrapped).is_err() {
            // The renderer writes into a String, which cannot fail; keep the plain form anyway.
            out.push_str(&d.render(source));
        }
        out.push('\n');
    }
    out
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
