// Every error of the spec, in one compile error.
protocol::protocol!("protocol-codegen/tests/invalid/many_errors_at_once.toml");

fn main() {}
