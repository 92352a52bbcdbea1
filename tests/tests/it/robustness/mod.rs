//! The robustness suites over every spec, on the harness in `support`: the property suite
//! ([`properties`]), fault injection ([`fault_injection`]), the resource bounds
//! ([`resource_bounds`]) and the fuzz corpus replayed on stable ([`fuzz_corpus`]).

mod fault_injection;
mod fuzz_corpus;
mod properties;
mod resource_bounds;
