//! Writes the `protocol!` line of every bundled spec this crate expands (those of the registry
//! `tests/catalogue.toml` that do not skip `no-std`), which `src/lib.rs` includes: a spec added
//! to the registry is built for the thumb target without an edit here.

#[path = "../catalogue.rs"]
mod catalogue;

fn main() {
    println!("cargo:rerun-if-changed=../catalogue.rs");
    println!("cargo:rerun-if-changed=../catalogue.toml");
    let catalogue = catalogue::load();
    let mut code = format!(
        "// @generated from {} by the build script.\n",
        catalogue::PATH
    );
    for e in catalogue.taking("no-std") {
        code.push_str(&format!(
            "protocol_kit::protocol!(\"../../specs/{}\");\n",
            e.file
        ));
    }
    let out = std::path::PathBuf::from(std::env::var("OUT_DIR").expect("OUT_DIR"));
    std::fs::write(out.join("specs.rs"), code).expect("write specs.rs");
}
