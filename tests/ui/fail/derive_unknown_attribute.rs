#[derive(protocol_runtime::Payload)]
#[payload(endian = "big")]
struct Speed {
    left: i16,
}

fn main() {}
