protocol_kit::protocol!(spec = "specs/hflink.toml");

fn main() {}
