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

/// This project's frame of `packet` (any generated packet type), as an adapter's
/// `PeerAdapter::ours_write` returns it.
fn encoded<P: protocol::EncodePacket>(packet: &P) -> Result<Vec<u8>, String> {
    let mut buf = vec![0; packet.encoded_len()];
    let n = packet.encode_into(&mut buf).map_err(|e| e.to_string())?;
    buf.truncate(n);
    Ok(buf)
}
