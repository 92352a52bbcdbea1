//! CRSF (`tests/vectors/crsf.json`) against `crsf` 2.0 (tact1m4n3/crsf-rs).
//!
//! The peer decodes RC_CHANNELS_PACKED and LINK_STATISTICS; every other frame type it checks
//! (CRC-8/DVB-S2 over type and payload) and then reports as an unknown type, which confirms the
//! frame's framing and CRC. Its sync set is 0xC8, 0xEA, 0xEE and 0xEC (`PacketAddress`; the
//! vectors use 0xC8 and 0xEE, the random frames below all four); it lacks the broadcast 0x00.
//!
//! Random RC_CHANNELS_PACKED and LINK_STATISTICS frames cross both ways between the peer and the
//! code generated from `specs/crsf.toml`, as the same bytes. The peer keeps the wire integers
//! where the spec has physical values (channels in µs, RSSI in dBm): the adapter converts with
//! the specification's scales, which are exact in `f32` for every wire value.

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

// ---- Random messages both ways: the `crsf` crate and the generated CRSF codec ----

mod ours {
    protocol_kit::protocol!("../../specs/crsf.toml");
}

use crate::encoded;
use crsf::{LinkStatistics, PacketAddress, RcChannels};
use ours::crsf as spec;
use proptest::prelude::*;
use protocol_peers::harness::{PeerAdapter, assert_every_message_crosses};

/// A channel's pulse width in µs, from its 11-bit wire value (the specification's
/// `TICKS_TO_US`: `(x - 992) * 5 / 8 + 1500`).
fn us(ticks: u16) -> f32 {
    f32::from(ticks) * 0.625 + 880.0
}

/// A channel's 11-bit wire value, from its pulse width in µs.
fn ticks(us: f32) -> u16 {
    ((us - 880.0) / 0.625) as u16
}

/// An RSSI in dBm, from its wire value (dBm × -1).
fn dbm(wire: u8) -> f32 {
    -f32::from(wire)
}

/// An RSSI's wire value (dBm × -1), from dBm.
fn rssi_wire(dbm: f32) -> u8 {
    (-dbm) as u8
}

/// The `crsf` crate against the generated codec, over the two frame types the crate has
/// (RC_CHANNELS_PACKED and LINK_STATISTICS) and the four addresses it knows (`C8`, `EA`, `EE`,
/// `EC`: it has no broadcast address `00`, which the TBS specification lists and this spec
/// takes as a sync).
struct Crsf;

fn messages() -> BoxedStrategy<spec::Packet> {
    let address = prop_oneof![Just(0xC8u8), Just(0xEA), Just(0xEE), Just(0xEC)];
    let channels = prop::array::uniform16(0u16..=0x7FF).prop_map(|channels| {
        spec::Message::RcChannelsPacked(spec::RcChannels {
            channels: channels.map(us),
        })
    });
    let stats = (any::<[u8; 8]>(), any::<[i8; 2]>()).prop_map(|(u, [up_snr, down_snr])| {
        spec::Message::LinkStatistics(spec::LinkStatistics {
            up_rssi_ant1: dbm(u[0]),
            up_rssi_ant2: dbm(u[1]),
            up_link_quality: u[2],
            up_snr,
            active_antenna: u[3],
            rf_profile: u[4],
            up_rf_power: u[5],
            down_rssi: dbm(u[6]),
            down_link_quality: u[7],
            down_snr,
        })
    });
    (address, prop_oneof![channels, stats])
        .prop_map(|(address, message)| spec::Packet {
            header: spec::Header { address },
            message,
        })
        .boxed()
}

impl PeerAdapter for Crsf {
    type Message = spec::Packet;

    fn peer(&self) -> &'static str {
        "crsf 2.0"
    }

    fn messages(&self) -> BoxedStrategy<spec::Packet> {
        messages()
    }

    fn peer_write(&mut self, m: &spec::Packet) -> Result<Option<Vec<u8>>, String> {
        let address = PacketAddress::from_u8(m.header.address).ok_or("an address it lacks")?;
        let packet = match &m.message {
            spec::Message::RcChannelsPacked(c) => {
                Packet::RcChannels(RcChannels(c.channels.map(ticks)))
            }
            spec::Message::LinkStatistics(l) => Packet::LinkStatistics(LinkStatistics {
                uplink_rssi_1: rssi_wire(l.up_rssi_ant1),
                uplink_rssi_2: rssi_wire(l.up_rssi_ant2),
                uplink_link_quality: l.up_link_quality,
                uplink_snr: l.up_snr,
                active_antenna: l.active_antenna,
                rf_mode: l.rf_profile,
                uplink_tx_power: l.up_rf_power,
                downlink_rssi: rssi_wire(l.down_rssi),
                downlink_link_quality: l.down_link_quality,
                downlink_snr: l.down_snr,
            }),
            other => return Err(format!("not drawn: {other:?}")),
        };
        Ok(Some(packet.into_raw(address).data().to_vec()))
    }

    fn peer_read(
        &mut self,
        frame: &[u8],
        _like: &spec::Packet,
    ) -> Result<Option<spec::Packet>, String> {
        let mut parser = PacketParser::<1024>::new();
        parser.push_bytes(frame);
        let (address, packet) = parser
            .next_packet()
            .ok_or("no packet")?
            .map_err(|e| e.to_string())?;
        if parser.next_raw_packet().is_some() {
            return Err("more than one packet".into());
        }
        let message = match packet {
            Packet::RcChannels(c) => spec::Message::RcChannelsPacked(spec::RcChannels {
                channels: c.0.map(us),
            }),
            Packet::LinkStatistics(l) => spec::Message::LinkStatistics(spec::LinkStatistics {
                up_rssi_ant1: dbm(l.uplink_rssi_1),
                up_rssi_ant2: dbm(l.uplink_rssi_2),
                up_link_quality: l.uplink_link_quality,
                up_snr: l.uplink_snr,
                active_antenna: l.active_antenna,
                rf_profile: l.rf_mode,
                up_rf_power: l.uplink_tx_power,
                down_rssi: dbm(l.downlink_rssi),
                down_link_quality: l.downlink_link_quality,
                down_snr: l.downlink_snr,
            }),
            other => return Err(format!("{other:?}")),
        };
        Ok(Some(spec::Packet {
            header: spec::Header {
                address: address as u8,
            },
            message,
        }))
    }

    fn ours_write(&self, m: &spec::Packet) -> Result<Vec<u8>, String> {
        encoded(m)
    }

    fn ours_read(&self, frame: &[u8]) -> Result<spec::Packet, String> {
        spec::Packet::decode(frame).map_err(|e| e.to_string())
    }
}

#[test]
fn random_frames_cross_between_crsf_and_the_generated_codec() {
    assert_every_message_crosses(&mut Crsf, 2000, "crsf");
}
