//! Declares to rustc's `cfg` check the one `cfg` of this crate that no feature sets:
//! `protocol_ablate_early_truncation`, which only the benchmark scripts pass
//! (`RUSTFLAGS="--cfg protocol_ablate_early_truncation"`) to measure the decoder without its
//! early-truncation rule (`decoder/target.rs`). A measurement switch, not a feature: a feature
//! is part of the published crate's interface, and this one is never for use.
//!
//! A build script rather than the manifest's `[lints.rust]` table: the crate takes its lints
//! from the workspace (`lints.workspace = true`), which a member's manifest cannot extend.

fn main() {
    println!("cargo::rerun-if-changed=build.rs");
    println!("cargo::rustc-check-cfg=cfg(protocol_ablate_early_truncation)");
}
