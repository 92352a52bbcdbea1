protocol::protocol!("specs/does_not_exist.toml");

fn main() {}
