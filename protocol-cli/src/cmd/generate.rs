//! `protocol gen c SPEC -o DIR`: the C99 peer of a spec, a header and a source file
//! (`protocol_codegen::c`). A spec using a feature the C printer does not support yet is
//! refused with one line per feature, and nothing is written.

use std::path::Path;
use std::process::ExitCode;

use miette::{IntoDiagnostic, Result, WrapErr};

use super::{INVALID, load_checked};

/// Writes `NAME.h` and `NAME.c` into `dir` (created if missing).
pub fn c(spec: &Path, dir: &Path) -> Result<ExitCode> {
    let p = match load_checked(spec)? {
        Ok(p) => p,
        Err(code) => return Ok(code),
    };
    let files = match protocol_codegen::c::generate(&p) {
        Ok(files) => files,
        Err(refused) => {
            eprintln!(
                "{}: the C printer does not support {} feature{} of this spec yet:",
                spec.display(),
                refused.len(),
                if refused.len() == 1 { "" } else { "s" }
            );
            for line in refused {
                eprintln!("  - {line}");
            }
            return Ok(ExitCode::from(INVALID));
        }
    };
    std::fs::create_dir_all(dir)
        .into_diagnostic()
        .wrap_err_with(|| format!("cannot create `{}`", dir.display()))?;
    for (name, text) in [
        (&files.header_name, &files.header),
        (&files.source_name, &files.source),
    ] {
        let path = dir.join(name);
        std::fs::write(&path, text)
            .into_diagnostic()
            .wrap_err_with(|| format!("cannot write `{}`", path.display()))?;
        println!("{}", path.display());
    }
    Ok(ExitCode::SUCCESS)
}
