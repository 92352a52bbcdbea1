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
mod msp_errors;
mod msp_yamspy;
mod rc;
mod sbp;
mod ublox;
mod values;

/// This project's frame of `packet` (any generated packet type), as an adapter's
/// `PeerAdapter::ours_write` returns it.
fn encoded<P: protocol_kit::EncodePacket>(packet: &P) -> Result<Vec<u8>, String> {
    let mut buf = vec![0; packet.encoded_len()];
    let n = packet.encode_into(&mut buf).map_err(|e| e.to_string())?;
    buf.truncate(n);
    Ok(buf)
}

/// The packet of the first frame in `bytes`, as the integrations decode a stream: through the
/// runtime's `PacketDecoder` over `layout` (a link's `AnyLayout` finds every format's frames).
/// Bytes before a frame are skipped; a rejected candidate or a frame that holds no packet is
/// the error.
fn packet_of<L, const N: usize>(layout: L, bytes: &[u8]) -> Result<L::Packet, String>
where
    L: protocol_kit::PacketLayout<Error = protocol_kit::DecodeError>,
{
    let mut decoder = protocol_kit::PacketDecoder::<L, N>::new(layout);
    let mut input = bytes;
    let events = core::iter::from_fn(|| decoder.next_packet(&mut input));
    let mut events: Vec<_> = events.collect();
    events.extend(core::iter::from_fn(|| decoder.flush_packet()));
    for event in events {
        match event {
            protocol_kit::PacketEvent::Packet { packet, .. } => return Ok(packet),
            protocol_kit::PacketEvent::Invalid { error, .. } => return Err(error.to_string()),
            _ => {}
        }
    }
    Err("no frame found".into())
}
