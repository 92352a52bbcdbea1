// Every error of the spec, in one compile error.
protocol_kit::protocol!("protocol-codegen/tests/invalid/many_errors_at_once.toml");

// A misspelled key in the frame layout, a command, a struct, an enum and a checksum: five
// errors, none hiding another, in the text `protocol check` prints for the same spec.
protocol_kit::protocol!("protocol-codegen/tests/invalid/every_table_reports_at_once.toml");

fn main() {}
