// A derive the macro does not offer.
protocol::protocol!("specs/hflink.toml", derive(serde, schemars));

fn main() {}
