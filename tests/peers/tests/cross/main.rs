//! The peers' checks, in one test binary (one link of the peers instead of one per protocol).
//!
//! Each module takes one protocol: its golden vectors decoded by its crates.io peer, and the
//! random round trip of `protocol_peers::harness` between the peer and the code generated from
//! the protocol's spec.

mod crsf;
mod dynamixel1;
mod dynamixel2;
mod mavlink;
mod msp;
mod rc;
mod ublox;
mod values;
