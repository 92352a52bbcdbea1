//! Compile tests (trybuild): a spec's errors are compile errors on the spec-path literal that
//! quote the spec; every spec's generated code compiles under `deny(warnings, missing_docs)`.

use std::io::IsTerminal;

#[test]
fn ui() {
    // The cases name specs relative to the repository root; trybuild builds them in a crate of
    // its own, so tell the macro where the root is.
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
    let plain = !std::io::stderr().is_terminal();
    #[allow(unsafe_code)]
    // SAFETY: set before trybuild starts any thread or child process; nothing else in this test
    // binary reads the environment concurrently.
    unsafe {
        std::env::set_var("PROTOCOL_SPEC_DIR", root);
        // trybuild colours its report unless `NO_COLOR` is set, terminal or not.
        if plain {
            std::env::set_var("NO_COLOR", "1");
        }
    }
    let t = trybuild::TestCases::new();
    t.pass("ui/pass/*.rs");
    t.compile_fail("ui/fail/*.rs");
}
