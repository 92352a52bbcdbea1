#[derive(protocol::Payload)]
#[payload(endian = "big")]
struct Speed {
    left: i16,
}

fn main() {}
