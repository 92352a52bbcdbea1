//! Loading a spec at run time: its text through [`protocol_spec::compile`], the pipeline the
//! `protocol!` macro runs, so a bad spec gives the macro's diagnostics.

use std::fmt;
use std::path::Path;

use protocol_spec::diag::{Color, Diagnostic, read_error_message, render_report};
use protocol_spec::source::SpecSource;

use crate::Interpreter;

/// Why a spec could not be loaded.
#[derive(Debug)]
pub enum LoadError {
    /// The file could not be read.
    Read {
        /// The path as given.
        path: String,
        /// The I/O error.
        error: std::io::Error,
    },
    /// The spec has errors.
    Spec {
        /// The spec's text and the path its messages show.
        source: SpecSource,
        /// Every error found, sorted.
        diagnostics: Vec<Diagnostic>,
    },
}

impl fmt::Display for LoadError {
    /// For a spec with errors: the report the macro and the CLI print (`N errors in spec
    /// PATH`, then every diagnostic: `--> path:line:col`, the line, a caret underline, the help).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LoadError::Read { path, error } => {
                f.write_str(&read_error_message("spec", path, error))
            }
            LoadError::Spec {
                source,
                diagnostics,
            } => f.write_str(render_report(diagnostics, source, Color::Plain).trim_end()),
        }
    }
}

impl std::error::Error for LoadError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            LoadError::Read { error, .. } => Some(error),
            LoadError::Spec { .. } => None,
        }
    }
}

impl Interpreter {
    /// Loads and checks a spec's text; `path` is the name its messages show.
    ///
    /// # Errors
    /// [`LoadError::Spec`] with every error of the spec.
    pub fn from_text(path: impl Into<String>, text: impl Into<String>) -> Result<Self, LoadError> {
        let source = SpecSource::new(path, text);
        match protocol_spec::compile(&source) {
            Ok(protocol) => Ok(Interpreter::new(protocol)),
            Err(diagnostics) => Err(LoadError::Spec {
                source,
                diagnostics,
            }),
        }
    }

    /// Reads, loads and checks the spec at `path`.
    ///
    /// # Errors
    /// [`LoadError::Read`] when the file cannot be read, else as
    /// [`from_text`](Self::from_text).
    pub fn load(path: impl AsRef<Path>) -> Result<Self, LoadError> {
        let path = path.as_ref();
        let shown = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|error| LoadError::Read {
            path: shown.clone(),
            error,
        })?;
        Interpreter::from_text(shown, text)
    }
}
