#[derive(protocol_runtime::Payload)]
enum NotAStruct {
    A,
}

fn main() {}
