//! Shared build script of the footprint firmware: puts `memory.x` where the linker finds it and
//! links with cortex-m-rt's `link.x` (so that the build works from any directory, without a
//! `.cargo/config.toml`).

use std::path::PathBuf;

fn main() {
    let out = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    let memory = PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").expect("cargo sets it"))
        .join("../memory.x");
    std::fs::copy(&memory, out.join("memory.x")).expect("copy memory.x");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed={}", memory.display());
    println!("cargo:rustc-link-arg=-Tlink.x");
}
