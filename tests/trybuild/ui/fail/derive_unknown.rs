// A derive the macro does not offer.
protocol_kit::protocol!("specs/hflink.toml", derive(serde, schemars));

fn main() {}
