#[derive(protocol_kit::Payload)]
#[payload(endian = "big")]
struct Speed {
    left: i16,
}

fn main() {}
