//! The robustness suites over every spec, one test binary: the property suite
//! ([`properties`]), fault injection ([`fault_injection`]), the resource bounds
//! ([`resource_bounds`]) and the fuzz corpus replayed on stable ([`fuzz_corpus`]).
//!
//! One binary because they share the harness in `support`, which expands every spec: as
//! separate binaries each compiled every spec's generated code again. (The no-allocation suite,
//! `no_alloc.rs`, stays a binary of its own: its counting allocator replaces the whole binary's
//! global allocator.)

#[path = "../support/mod.rs"]
mod support;

mod fault_injection;
mod fuzz_corpus;
mod properties;
mod resource_bounds;
