protocol::protocol!(spec = "specs/hflink.toml");

fn main() {}
