#[derive(protocol_kit::Payload)]
struct Meter {
    #[payload(raw = "u24")]
    total: u16,
}

fn main() {}
