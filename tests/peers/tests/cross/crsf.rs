//! CRSF (`tests/vectors/crsf.json`) against `crsf` 2.0 (tact1m4n3/crsf-rs).
//!
//! The peer decodes RC_CHANNELS_PACKED and LINK_STATISTICS; every other frame type it checks
//! (CRC-8/DVB-S2 over type and payload) and then reports as an unknown type, which confirms the
//! frame's framing and CRC. Its sync set is 0xC8, 0xEA and 0xEE (the vectors use 0xC8 and 0xEE).

use crate::values::{V, assert_fields};
use crsf::{Packet, PacketError, PacketParser};
use protocol_peers::{expected_frames, frame_bytes, frames, hex, load_vectors, name, uint};

/// What the peer makes of the next frame: its fields, or `Err(type)` for a type it only checks.
fn next(parser: &mut PacketParser<1024>) -> Option<Result<Vec<(&'static str, V)>, u8>> {
    use V::I;
    loop {
        return match parser.next_packet()? {
            Ok((_, Packet::RcChannels(ch))) => Some(Ok(vec![(
                "channels",
                V::List(ch.0.iter().map(|&c| c.into()).collect()),
            )])),
            Ok((_, Packet::LinkStatistics(l))) => Some(Ok(vec![
                ("up_rssi_ant1", I(l.uplink_rssi_1.into())),
                ("up_rssi_ant2", I(l.uplink_rssi_2.into())),
                ("up_link_quality", I(l.uplink_link_quality.into())),
                ("up_snr", I(l.uplink_snr.into())),
                ("active_antenna", I(l.active_antenna.into())),
                ("rf_profile", I(l.rf_mode.into())),
                ("up_rf_power", I(l.uplink_tx_power.into())),
                ("down_rssi", I(l.downlink_rssi.into())),
                ("down_link_quality", I(l.downlink_link_quality.into())),
                ("down_snr", I(l.downlink_snr.into())),
            ])),
            Ok((_, other)) => panic!("no vector has {other:?}"),
            Err(PacketError::UnknownType { raw_type }) => Some(Err(raw_type)),
            // A rejected candidate: the peer drops it and goes on.
            Err(_) => continue,
        };
    }
}

#[test]
fn every_frame_decodes_or_checks_in_crsf() {
    let v = load_vectors("crsf.json");
    let (mut decoded, mut checked) = (0, 0);
    for frame in frames(&v) {
        let mut parser = PacketParser::<1024>::new();
        parser.push_bytes(&frame_bytes(frame));
        match parser.next_packet() {
            Some(Ok(_)) => {
                let mut parser = PacketParser::<1024>::new();
                parser.push_bytes(&frame_bytes(frame));
                let got = next(&mut parser).expect("a packet").expect("decoded");
                assert_fields(name(frame), &got, &frame["fields"]);
                decoded += 1;
            }
            Some(Err(PacketError::UnknownType { raw_type })) => {
                assert_eq!(u64::from(raw_type), uint(frame, "type"), "{}", name(frame));
                checked += 1;
            }
            other => panic!("{}: {other:?}", name(frame)),
        }
    }
    println!("crsf: {decoded} frames decoded to their fields, {checked} CRC-checked only");
    assert_eq!(decoded + checked, frames(&v).len());
    assert_eq!(decoded, 6);
}

/// The peer consumes a rejected candidate whole (a bad CRC, or a length that runs into the next
/// frame) instead of resuming one byte after its start, so it may lose frames the rule keeps:
/// what it yields must be the expected frames in order, some possibly missing.
#[test]
fn the_stream_yields_expected_frames_in_crsf() {
    let v = load_vectors("crsf.json");
    for stream in v["streams"].as_array().expect("streams") {
        let mut parser = PacketParser::<1024>::new();
        parser.push_bytes(&hex(stream["hex"].as_str().expect("hex")));
        let mut seen = Vec::new();
        while let Some(item) = next(&mut parser) {
            seen.push(format!("{item:?}"));
        }
        let wanted: Vec<String> = expected_frames(stream)
            .iter()
            .map(|(_, b)| {
                let mut p = PacketParser::<1024>::new();
                p.push_bytes(b);
                format!("{:?}", next(&mut p).expect("a frame"))
            })
            .collect();
        let mut rest = wanted.iter();
        for s in &seen {
            assert!(
                rest.any(|w| w == s),
                "{}: {s} out of order or unexpected",
                stream["name"]
            );
        }
        println!(
            "crsf: {} of {} expected frames from the peer",
            seen.len(),
            wanted.len()
        );
        assert!(!seen.is_empty());
    }
}
