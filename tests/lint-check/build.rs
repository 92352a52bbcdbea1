//! Expands every spec of `specs/` into `$OUT_DIR/specs.rs`, as plain source: clippy skips code
//! that comes out of a proc macro, so `protocol!` would hide generated code from its lints.

use std::path::Path;

use protocol_codegen::codegen::{RuntimePath, expand_pretty};
use protocol_codegen::diag::render_all;
use protocol_codegen::source::SpecSource;

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let dir = root.join("specs");
    println!("cargo::rerun-if-changed={}", dir.display());
    let mut specs: Vec<_> = std::fs::read_dir(&dir)
        .expect("specs/")
        .map(|e| e.expect("spec entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    specs.sort();
    let mut out = String::new();
    for path in specs {
        println!("cargo::rerun-if-changed={}", path.display());
        let name = path.file_name().expect("file name").to_string_lossy();
        let text = std::fs::read_to_string(&path).expect("spec text");
        let source = SpecSource::new(format!("specs/{name}"), text);
        match protocol_codegen::compile(&source) {
            Ok(protocol) => out.push_str(&expand_pretty(&protocol, &RuntimePath::default())),
            Err(diagnostics) => panic!("{}", render_all(&diagnostics, &source)),
        }
    }
    let dest = Path::new(&std::env::var("OUT_DIR").expect("OUT_DIR")).join("specs.rs");
    std::fs::write(dest, out).expect("write specs.rs");
}
