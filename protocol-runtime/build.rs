//! Tells the runtime whether it is compiled without optimisation (`opt-level = 0`, cargo's
//! default `dev` profile): cfg `protocol_opt0`.
//!
//! Forced inlining (`#[inline(always)]`) makes the optimised code small and fast: inlined
//! into generated code, a function sees the spec's static layout and folds to the few
//! instructions that layout needs. Without optimisation nothing folds, and forcing in the
//! dispatchers over every checksum and frame element copies all their arms into each caller,
//! nested: a firmware of one spec grows past a megabyte and does not link for a
//! microcontroller. So the runtime forces inlining only where the compiler optimises.

fn main() {
    println!("cargo::rustc-check-cfg=cfg(protocol_opt0)");
    println!("cargo::rerun-if-changed=build.rs");
    if std::env::var("OPT_LEVEL").is_ok_and(|level| level == "0") {
        println!("cargo::rustc-cfg=protocol_opt0");
    }
}
