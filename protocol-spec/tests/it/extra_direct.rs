//! A per-command byte table (MAVLink's CRC_EXTRA) as validation splits it: the ids below 256
//! read from a table indexed by id, the others searched among sorted pairs. On the bundled
//! MAVLink specs (12 messages, and the 234 of the common dialect, whose ids run past 256), the
//! runtime's check built from the split finds the same byte for every id up to 2^17 (the
//! largest is 12,920) as a binary search of all the pairs.

use std::path::Path;

use protocol_runtime::checksum::{Checksum, Extra, fill_direct};
use protocol_spec::ir::{CheckExtra, DIRECT_KEYS};
use protocol_spec::source::SpecSource;

/// The per-command byte tables of every check of the bundled spec `name`.
fn extras(name: &str) -> Vec<CheckExtra> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../specs")
        .join(name);
    let text = std::fs::read_to_string(&path).expect("bundled spec");
    let ir = protocol_spec::compile(&SpecSource::new(format!("specs/{name}"), text))
        .unwrap_or_else(|_| panic!("{name} compiles"));
    let extras: Vec<CheckExtra> = ir
        .frames
        .iter()
        .flat_map(|f| &f.checks)
        .filter_map(|c| c.extra.clone())
        .collect();
    assert!(!extras.is_empty(), "{name} has a check with CRC_EXTRA");
    extras
}

/// The id at the key's place (MAVLink 2's `msgid` at covered byte 6, v1's at byte 4) in
/// otherwise zero bytes.
fn covered_with(extra: &CheckExtra, id: u32) -> [u8; 16] {
    let mut covered = [0u8; 16];
    let protocol_spec::ir::Pos::Start(at) = extra.key.at else {
        panic!("a key counted from the first covered byte");
    };
    let size = usize::from(extra.key.size);
    covered[at..at + size].copy_from_slice(&id.to_le_bytes()[..size]);
    covered
}

/// Checks the split of every byte table of `name`; returns the number of pairs searched.
fn split_agrees_with_the_search(name: &str) -> usize {
    let mut searched_pairs = 0;
    for extra in extras(name) {
        searched_pairs += extra.searched_pairs().len();
        let below: Vec<u32> = extra
            .bytes
            .iter()
            .map(|&(id, _)| id)
            .filter(|&id| id < DIRECT_KEYS)
            .collect();
        assert_eq!(extra.direct, below.last().map_or(0, |&id| id as usize + 1));
        assert_eq!(
            [extra.direct_pairs(), extra.searched_pairs()].concat(),
            extra.bytes,
            "{name}: the split keeps every pair, in order"
        );
        let mut direct = vec![0u16; extra.direct];
        fill_direct(&mut direct, extra.direct_pairs());
        let crc = Checksum::Sum8;
        let split = Extra {
            crc,
            key: extra.key,
            direct: &direct,
            bytes: extra.searched_pairs(),
        };
        let searched = Extra {
            crc,
            key: extra.key,
            direct: &[],
            bytes: &extra.bytes,
        };
        let mut found = 0;
        let top = ((1u32 << (8 * u32::from(extra.key.size).min(3))) - 1).min(0x1_FFFF);
        for id in 0..=top {
            let covered = covered_with(&extra, id);
            let byte = searched.byte(&covered);
            assert_eq!(split.byte(&covered), byte, "{name}: id {id}");
            found += usize::from(byte.is_some());
        }
        let reachable = extra.bytes.iter().filter(|&&(id, _)| id <= top).count();
        assert_eq!(found, reachable, "{name}: every id's byte is found");
    }
    searched_pairs
}

#[test]
fn the_twelve_messages_split_as_searched() {
    // Ids 0 to 253: all in the table.
    assert_eq!(split_agrees_with_the_search("mavlink.toml"), 0);
}

#[test]
fn the_common_dialect_splits_as_searched() {
    // MAVLink 2's ids from 256 on are searched.
    assert!(split_agrees_with_the_search("mavlink-common.toml") > 0);
}
