//! Ports of the C originals' receivers: byte-at-a-time state machines, written from the
//! descriptions in the protocol fact sheet (no original code was copied). They are the "as the
//! robots do it today" baseline.
//!
//! Each keeps the original's behaviour, including its losses: no rescan after a failed
//! candidate, so a stray sync byte or a truncated frame costs the next valid frame too. Where
//! the original has undefined behaviour (writing past its buffer), the port stops the candidate
//! instead; the module of each protocol lists such differences.

pub mod hflink;
pub mod referee;
