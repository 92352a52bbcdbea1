#[derive(protocol_kit::Payload)]
enum NotAStruct {
    A,
}

fn main() {}
