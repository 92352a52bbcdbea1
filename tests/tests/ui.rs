//! Compile tests (trybuild): a spec's errors are compile errors on the spec-path literal that
//! quote the spec; every spec's generated code compiles under `deny(warnings, missing_docs)`.

#[test]
fn ui() {
    // The cases name specs relative to the repository root; trybuild builds them in a crate of
    // its own, so tell the macro where the root is.
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    #[allow(unsafe_code)]
    // SAFETY: set before trybuild starts any thread or child process; nothing else in this test
    // binary reads the environment concurrently.
    unsafe {
        std::env::set_var("PROTOCOL_SPEC_DIR", root);
    }
    let t = trybuild::TestCases::new();
    t.pass("ui/pass/*.rs");
    t.compile_fail("ui/fail/*.rs");
}
