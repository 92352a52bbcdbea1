protocol_runtime::protocol!(spec = "specs/hflink.toml");

fn main() {}
