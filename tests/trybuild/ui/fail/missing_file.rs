protocol_kit::protocol!("specs/does_not_exist.toml");

fn main() {}
