//! `protocol gen wireshark SPEC -o DIR`: the Wireshark Lua dissector of a spec
//! (`protocol_codegen::wireshark`). A spec with a feature the dissector cannot express is
//! refused with one line per feature; what it shows less exactly than `decode` is listed on
//! stderr.

use std::path::Path;
use std::process::ExitCode;

use miette::{IntoDiagnostic, Result, WrapErr};

use super::{INVALID, load_checked};

/// Writes `NAME.lua` into `dir` (created if missing).
pub fn run(spec: &Path, dir: &Path) -> Result<ExitCode> {
    let p = match load_checked(spec)? {
        Ok(p) => p,
        Err(code) => return Ok(code),
    };
    let dissector = match protocol_codegen::wireshark::generate(&p) {
        Ok(d) => d,
        Err(refused) => {
            eprintln!(
                "{}: the Wireshark dissector cannot express {} feature{} of this spec:",
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
    for line in &dissector.degraded {
        eprintln!("note: {line}");
    }
    std::fs::create_dir_all(dir)
        .into_diagnostic()
        .wrap_err_with(|| format!("cannot create `{}`", dir.display()))?;
    let path = dir.join(&dissector.file_name);
    std::fs::write(&path, &dissector.text)
        .into_diagnostic()
        .wrap_err_with(|| format!("cannot write `{}`", path.display()))?;
    println!("{}", path.display());
    Ok(ExitCode::SUCCESS)
}
