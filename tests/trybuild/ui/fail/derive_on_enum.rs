#[derive(protocol::Payload)]
enum NotAStruct {
    A,
}

fn main() {}
