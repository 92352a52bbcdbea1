//! Diagnostics: one error with its span and help, the accumulator every stage reports into,
//! and the one renderer of a spec's errors: the `protocol!` macro's compile error, every
//! `protocol` command that loads a spec, `protocol-dynamic`'s load error and the snapshot tests
//! all print [`render_report`] / [`render_all`], so one mistake reads the same, byte for byte,
//! wherever it is found.
//!
//! Every message points into the spec twice over: `--> path:line:col`, then the offending line
//! with a caret underline, then `= help:` with a fix. A file that cannot be read is
//! [`render_read_error`], in the same form.
//!
//! The renderer is this module's own rather than a crate's (annotate-snippets, miette): the
//! text is rustc's layout for a single-line span, which is all a spec diagnostic needs; the
//! macro crate builds it without a further dependency (it is compiled by every user of
//! `protocol!`); and its bytes are pinned by the diagnostics catalogue's snapshots, so a
//! renderer upgrade cannot change them unnoticed. Colour ([`Color::Ansi`]) is for a terminal
//! only; a compile error, a pipe and `NO_COLOR` get [`Color::Plain`].

use std::fmt::Write as _;
use std::ops::Range;

use crate::source::SpecSource;

/// How serious a diagnostic is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
pub enum Severity {
    /// The spec cannot be compiled.
    #[default]
    Error,
    /// The spec compiles, but something in it is likely a mistake or a risk (a lint).
    Warning,
}

impl Severity {
    /// `error` or `warning`, as rendered.
    pub fn as_str(self) -> &'static str {
        match self {
            Severity::Error => "error",
            Severity::Warning => "warning",
        }
    }
}

/// One error (or lint warning) in a spec.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Diagnostic {
    /// An error, or a lint's warning.
    pub severity: Severity,
    /// Byte range in the spec text (empty range: a point; `0..0` when the error is the whole
    /// file, e.g. a missing file).
    pub span: Range<usize>,
    /// What is wrong, one sentence without a final period.
    pub message: String,
    /// How to fix it.
    pub help: Option<String>,
}

/// Collects every error of a spec, so that all are reported at once.
#[derive(Debug, Default)]
pub struct Diagnostics {
    items: Vec<Diagnostic>,
}

impl Diagnostics {
    /// An empty accumulator.
    pub fn new() -> Self {
        Self::default()
    }

    /// Record an error. Returns it so a help line can be attached.
    pub fn error(&mut self, span: Range<usize>, message: impl Into<String>) -> &mut Diagnostic {
        self.items.push(Diagnostic {
            severity: Severity::Error,
            span,
            message: message.into(),
            help: None,
        });
        let last = self.items.len() - 1;
        &mut self.items[last]
    }

    /// Record a lint's warning. Returns it so a help line can be attached.
    pub fn warning(&mut self, span: Range<usize>, message: impl Into<String>) -> &mut Diagnostic {
        self.error(span, message).severity = Severity::Warning;
        let last = self.items.len() - 1;
        &mut self.items[last]
    }

    /// Add an already built diagnostic.
    pub fn push(&mut self, d: Diagnostic) {
        self.items.push(d);
    }

    /// The spans of the errors so far.
    pub fn spans(&self) -> Vec<Range<usize>> {
        self.items.iter().map(|d| d.span.clone()).collect()
    }

    /// True when nothing was reported.
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// Number of errors.
    pub fn len(&self) -> usize {
        self.items.len()
    }

    /// The errors sorted by position (then message), duplicates removed.
    pub fn into_sorted(mut self) -> Vec<Diagnostic> {
        self.items.sort_by(|a, b| {
            (a.span.start, a.span.end, &a.message).cmp(&(b.span.start, b.span.end, &b.message))
        });
        self.items.dedup();
        self.items
    }
}

impl Diagnostic {
    /// Attach a help line.
    pub fn help(&mut self, help: impl Into<String>) -> &mut Self {
        self.help = Some(help.into());
        self
    }

    /// Render as plain text: severity and message, location, quoted line with carets, help.
    pub fn render(&self, source: &SpecSource) -> String {
        self.render_styled(source, Color::Plain)
    }

    /// Render as text, with ANSI colours when `color` says so (the same text otherwise).
    pub fn render_styled(&self, source: &SpecSource, color: Color) -> String {
        let span = source.clamp(self.span.clone());
        let (line, col) = source.line_col(span.start);
        let level = match self.severity {
            Severity::Error => Paint::Error,
            Severity::Warning => Paint::Warning,
        };
        let mut out = String::new();
        let _ = writeln!(
            out,
            "{}{}",
            color.paint(level, self.severity.as_str()),
            color.paint(Paint::Bold, &format!(": {}", self.message))
        );
        let _ = writeln!(
            out,
            "  {} {}:{}:{}",
            color.paint(Paint::Gutter, "-->"),
            source.path,
            line,
            col
        );
        if !source.text.is_empty() {
            let text = source.line_text(line);
            let gutter = line.to_string();
            let pad = " ".repeat(gutter.len());
            // Underline up to the end of the span or of the line, at least one caret.
            let line_chars = text.chars().count();
            let (end_line, end_col) = source.line_col(span.end);
            let last_col = if end_line == line {
                end_col
            } else {
                line_chars + 1
            };
            let width = last_col.saturating_sub(col).max(1);
            let bar = color.paint(Paint::Gutter, &format!("{pad} |"));
            let _ = writeln!(out, "{bar}");
            let _ = writeln!(
                out,
                "{} {text}",
                color.paint(Paint::Gutter, &format!("{gutter} |"))
            );
            let _ = writeln!(
                out,
                "{bar} {}{}",
                " ".repeat(col.saturating_sub(1)),
                color.paint(level, &"^".repeat(width))
            );
        }
        if let Some(help) = &self.help {
            let _ = writeln!(out, "  {} {help}", color.paint(Paint::Bold, "= help:"));
        }
        out
    }
}

/// Whether rendered text carries ANSI colours.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Color {
    /// No escape codes: compile errors, pipes, files, `NO_COLOR`.
    #[default]
    Plain,
    /// rustc's colours, for a terminal.
    Ansi,
}

/// The roles text plays in a rendering, each with its colour.
#[derive(Debug, Clone, Copy)]
enum Paint {
    Error,
    Warning,
    Gutter,
    Bold,
}

impl Color {
    fn paint(self, role: Paint, text: &str) -> String {
        let code = match (self, role) {
            (Color::Plain, _) => return text.to_string(),
            (Color::Ansi, Paint::Error) => "1;31",
            (Color::Ansi, Paint::Warning) => "1;33",
            (Color::Ansi, Paint::Gutter) => "1;34",
            (Color::Ansi, Paint::Bold) => "1",
        };
        format!("\x1b[{code}m{text}\x1b[0m")
    }
}

/// Render a list of diagnostics, separated by blank lines.
pub fn render_all(diagnostics: &[Diagnostic], source: &SpecSource) -> String {
    render_all_styled(diagnostics, source, Color::Plain)
}

/// [`render_all`], with colours when `color` says so.
pub fn render_all_styled(diagnostics: &[Diagnostic], source: &SpecSource, color: Color) -> String {
    diagnostics
        .iter()
        .map(|d| d.render_styled(source, color))
        .collect::<Vec<_>>()
        .join("\n")
}

/// A spec's errors as one report: `N errors in spec PATH`, a blank line, then every
/// diagnostic. The `protocol!` macro's compile error and every `protocol` command that loads
/// the spec print exactly this text (plain, or coloured on a terminal).
pub fn render_report(diagnostics: &[Diagnostic], source: &SpecSource, color: Color) -> String {
    let n = diagnostics.len();
    let headline = format!(
        "{n} error{} in spec {}",
        if n == 1 { "" } else { "s" },
        source.path
    );
    format!(
        "{}\n\n{}",
        color.paint(Paint::Bold, &headline),
        render_all_styled(diagnostics, source, color)
    )
}

/// A file that cannot be read, in the form of a spec diagnostic: `error: cannot read WHAT
/// `PATH`: REASON`, and the help when there is one. `what` is `spec`, `capture`, `input`...
pub fn render_read_error(
    what: &str,
    path: &str,
    error: &std::io::Error,
    help: Option<&str>,
    color: Color,
) -> String {
    let mut out = format!(
        "{}{}\n",
        color.paint(Paint::Error, "error"),
        color.paint(
            Paint::Bold,
            &format!(": {}", read_error_message(what, path, error))
        )
    );
    if let Some(help) = help {
        let _ = writeln!(out, "  {} {help}", color.paint(Paint::Bold, "= help:"));
    }
    out
}

/// The one sentence saying a file cannot be read: `cannot read WHAT `PATH`: REASON`.
pub fn read_error_message(what: &str, path: &str, error: &std::io::Error) -> String {
    format!("cannot read {what} `{path}`: {error}")
}

/// The closest candidate to a misspelled name, if one is close enough to suggest.
pub fn did_you_mean<'a>(
    name: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> Option<&'a str> {
    let normalized = normalize(name);
    candidates
        .into_iter()
        .map(|c| (edit_distance(&normalized, &normalize(c)), c))
        .filter(|(d, c)| *d <= (c.len().max(name.len()) / 3).max(1))
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

fn normalize(s: &str) -> String {
    s.chars()
        .filter(|c| !matches!(c, '-' | '_' | '/' | ' '))
        .flat_map(char::to_lowercase)
        .collect()
}

/// Edit distance counting a swap of two adjacent characters as one edit (optimal string
/// alignment), since transposed letters are the most common typo.
fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let mut d = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    for (j, cell) in d[0].iter_mut().enumerate() {
        *cell = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut v = (d[i - 1][j] + 1)
                .min(d[i][j - 1] + 1)
                .min(d[i - 1][j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                v = v.min(d[i - 2][j - 2] + 1);
            }
            d[i][j] = v;
        }
    }
    d[a.len()][b.len()]
}
