//! Every bundled spec and every feature fixture compiles under `deny(warnings, missing_docs)`.
#![deny(warnings, missing_docs)]

protocol_kit::protocol!("specs/hflink.toml");
protocol_kit::protocol!("specs/referee.toml");
protocol_kit::protocol!("specs/referee2018.toml");
protocol_kit::protocol!("specs/crsf.toml");
protocol_kit::protocol!("specs/scout.toml");
protocol_kit::protocol!("specs/mavlink.toml");
protocol_kit::protocol!("specs/roborts.toml");
protocol_kit::protocol!("specs/dynamixel.toml");
protocol_kit::protocol!("specs/dynamixel1.toml");
protocol_kit::protocol!("specs/ibus.toml");
protocol_kit::protocol!("specs/sbus.toml");
protocol_kit::protocol!("specs/sbp.toml");
protocol_kit::protocol!("specs/ubx.toml");
protocol_kit::protocol!("specs/msp.toml");
protocol_kit::protocol!("specs/dronecan.toml");
protocol_kit::protocol!("specs/vesc.toml");
protocol_kit::protocol!("specs/feetech.toml");
protocol_kit::protocol!("specs/lx16a.toml");
protocol_kit::protocol!("specs/shdlc.toml");
protocol_kit::protocol!("protocol-codegen/tests/features/bitfields_and_enums.toml");
protocol_kit::protocol!("protocol-codegen/tests/features/scaled_and_arrays.toml");
protocol_kit::protocol!("protocol-codegen/tests/features/two_field_key_and_custom_crc.toml");
protocol_kit::protocol!("protocol-codegen/tests/features/can_and_trailer_field.toml");
protocol_kit::protocol!("protocol-codegen/tests/features/can_id_members.toml");
protocol_kit::protocol!("protocol-codegen/tests/features/truncate_zeros.toml");
protocol_kit::protocol!("protocol-codegen/tests/features/text.toml");
protocol_kit::protocol!("protocol-codegen/tests/features/given_directions.toml");

fn main() {
    let _ = hflink::decoder();
    let _ = referee::decoder();
    let _ = scout::CanPacket::decode;
    let _ = roborts::decoder();
    let _ = dynamixel::feedback_decoder();
    let _ = dynamixel1::Packet::decode_response;
    let _ = told::Packet::decode_request;
    let _ = mavlink::decoder();
    let _ = truncated::decoder();
    let _ = ibus::decoder();
    let _ = sbus::Packet::decode;
    let _ = sbp::decoder();
    let _ = ubx::decoder();
    let _ = msp::decoder();
    let _ = msp::v2_decoder();
    let _ = dronecan::Packet::decode_can;
    let _ = canmembers::Packet::encode_can;
    let _ = vesc::Packet::decode_response;
    let _ = feetech::Packet::decode_response;
    let _ = lx16a::Packet::decode_response;
    let _ = shdlc::Packet::decode_response;
}
