// The spec has one mistake (an unknown checksum): one error, on the path literal, quoting the
// spec's line and column.
protocol_kit::protocol!("protocol-codegen/tests/invalid/unknown_checksum.toml");

fn main() {}
