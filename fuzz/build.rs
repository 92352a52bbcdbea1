//! Writes `for_each_spec!` for the shared support code (`tests/tests/support/mod.rs`, which
//! includes it from `OUT_DIR`): the list of bundled specs of the registry
//! `tests/catalogue.toml`, as the tests crate's build script writes it.

#[path = "../tests/catalogue.rs"]
mod catalogue;

fn main() {
    println!("cargo:rerun-if-changed=../tests/catalogue.rs");
    println!("cargo:rerun-if-changed=../tests/catalogue.toml");
    let out = std::path::PathBuf::from(std::env::var("OUT_DIR").expect("OUT_DIR"));
    // The support code names spec paths from the tests crate (`../specs/`); the fuzz crate's
    // manifest directory is a sibling of it, so the same prefix leads to the root.
    let specs = catalogue::load().for_each_spec_macro("../");
    std::fs::write(out.join("for_each_spec.rs"), specs).expect("write for_each_spec.rs");
}
