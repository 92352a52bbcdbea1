//! The specs the random spec comparisons found failing, shrunk and kept (`tests/random_specs/`,
//! each saying what it tests): each goes through the checks of the random batch
//! (`random_specs.rs`), and has a test of what failed.

use protocol_kit::{Bytes, EncodeError};

use crate::random_specs::check;

expand_spec!(ack_and_can, "random_specs/ack_and_can.toml");

#[test]
fn kept_random_specs_agree_in_generated_rust_and_the_run_time_codec() {
    assert_eq!(
        check::<ack_and_can::Packet>(62),
        crate::random_specs::FRAMES
    );
}

/// A spec with acknowledgements and a CAN format: the CAN packet encodes a command by its CAN
/// id and refuses an acknowledgement, which has no command and so no CAN id.
#[test]
fn a_can_packet_encodes_a_command_and_refuses_an_acknowledgement() {
    use ack_and_can::{CanHeader, CanPacket, Message, P0};
    let packet = CanPacket {
        header: CanHeader {},
        message: Message::C0(P0 { v: 0x2A }),
    };
    let can = packet.encode().expect("a command with a CAN id encodes");
    assert_eq!(CanPacket::decode(&can), Ok(packet));
    let ack = CanPacket {
        header: CanHeader {},
        message: Message::Ack(Bytes::from_slice(&[1]).expect("fits")),
    };
    assert!(matches!(
        ack.encode(),
        Err(EncodeError::ValueOutOfRange { .. })
    ));
}
