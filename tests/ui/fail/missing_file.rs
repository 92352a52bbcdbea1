protocol_runtime::protocol!("specs/does_not_exist.toml");

fn main() {}
