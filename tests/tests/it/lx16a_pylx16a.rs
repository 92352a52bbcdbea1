//! LX-16A packets from pylx16a (`tests/vectors/lx16a_pylx16a.json`, made by
//! `scripts/lx16a_pylx16a_vectors.py`): the commands pylx16a writes for random calls of its
//! methods, every command of `specs/lx16a.toml`, and the servo's answers to its read commands,
//! as pylx16a reads them.
//!
//! The generated code and the run-time codec, each given the packet's direction, decode every
//! packet to pylx16a's values (an angle within half a unit of 0.24°, every other value equal)
//! and encode them back to the packet's bytes; a stream of the packets with noise and damaged
//! packets between them yields exactly the good packets, in both.

use crate::peer_frames;

peer_frames::directed_link!(lx16a, "../specs/lx16a.toml");

#[test]
fn every_pylx16a_packet_decodes_to_its_values_and_encodes_to_its_bytes() {
    let frames = peer_frames::frames("lx16a_pylx16a.json");
    let (covered, without_command) = check_every_frame(&frames);
    assert_eq!(
        covered,
        all_commands(),
        "every command of the spec has pylx16a packets"
    );
    assert_eq!(without_command, 0, "every packet carries its command");
    assert_eq!(frames.len(), 144, "every vector was checked");
}

#[test]
fn a_noisy_stream_yields_exactly_the_good_packets() {
    check_noisy_streams(&peer_frames::frames("lx16a_pylx16a.json"));
}
