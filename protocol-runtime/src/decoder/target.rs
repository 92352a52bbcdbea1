//! The decoder's target and build switches, one constant each, read by its other modules in
//! place of a `cfg!` of their own. What each switch changes, what sets it and why: the
//! [module docs](super#target-and-build-switches).
//!
//! Each is a `cfg!` evaluated at compile time: a branch on it folds away exactly as a branch on
//! the `cfg!` written at the site does, so a build carries one side of every switch and tests
//! nothing at run time.

/// A host: a target with 64-bit pointers, where the decoder trades code size for speed.
/// Otherwise (microcontrollers, and 32-bit hosts with them) the smaller code.
pub(super) const HOST: bool = cfg!(target_pointer_width = "64");

/// Whether the caller's chunk is scanned in place while nothing is pending (frames found whole
/// there borrow it) rather than staged in the buffer first: on hosts, unless the `stage-input`
/// feature selects staging.
pub(super) const SCAN_IN_PLACE: bool = HOST && !cfg!(feature = "stage-input");

/// Whether the early-truncation rule is in force: in every build but the benchmarks' ablated
/// one (`--cfg protocol_ablate_early_truncation`, a measurement that is never for use).
pub(super) const EARLY_TRUNCATION: bool = !cfg!(protocol_ablate_early_truncation);
