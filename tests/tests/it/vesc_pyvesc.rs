//! VESC packets written and decoded by pyvesc (`tests/vectors/vesc_pyvesc.json`, made by
//! `scripts/vesc_pyvesc_vectors.py`): random messages of every command of `specs/vesc.toml`,
//! in the directions that carry them.
//!
//! The generated code and the run-time codec, each given the frame's direction, decode every
//! packet to pyvesc's values (a scaled field within half its scale, every other value equal)
//! and encode pyvesc's values back to the packet's bytes; a stream of the packets with noise
//! and damaged packets between them yields exactly the good packets, in both.

use crate::peer_frames;

peer_frames::directed_link!(vesc, "../specs/vesc.toml");

#[test]
fn every_pyvesc_packet_decodes_to_its_values_and_encodes_to_its_bytes() {
    let frames = peer_frames::frames("vesc_pyvesc.json");
    let (covered, without_command) = check_every_frame(&frames);
    assert_eq!(
        covered,
        all_commands(),
        "every command of the spec has pyvesc packets"
    );
    assert_eq!(without_command, 0, "every packet carries its command");
    assert_eq!(frames.len(), 72, "every vector was checked");
}

#[test]
fn a_noisy_stream_yields_exactly_the_good_packets() {
    check_noisy_streams(&peer_frames::frames("vesc_pyvesc.json"));
}
