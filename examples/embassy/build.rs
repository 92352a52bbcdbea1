//! Build script: links the binaries with cortex-m-rt's `link.x`, and gives the QEMU binary
//! (feature `mps2`) its memory map, `memory-mps2.x`, as the `memory.x` that `link.x` includes.
//! The STM32F4 binary's `memory.x` comes from `embassy-stm32` (its `memory-x` feature).

use std::path::PathBuf;

fn main() {
    println!("cargo:rustc-link-arg-bins=-Tlink.x");
    println!("cargo:rerun-if-changed=memory-mps2.x");
    if std::env::var_os("CARGO_FEATURE_MPS2").is_some() {
        let out = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
        std::fs::copy("memory-mps2.x", out.join("memory.x")).expect("copy memory-mps2.x");
        println!("cargo:rustc-link-search={}", out.display());
    }
}
