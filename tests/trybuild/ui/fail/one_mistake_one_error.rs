// An unknown struct in a command line: exactly one error, not a cascade of unresolved types in
// generated code.
protocol_kit::protocol!(inline = r#"
[protocol]
name = "one"

[frames.main]
layout = [
  { sync = [0xAA] },
  { field = "len", type = "u8", length_of = "payload" },
  { field = "cmd", type = "u8" },
  { payload = { max = 8 } },
  { check = "sum8", over = "frame" },
]
dispatch = ["cmd"]

[commands]
GO = { id = 1, payload = "Speed" }
STOP = { id = 2 }

[structs.Sped]
fields = [{ name = "v", type = "i16" }]
"#);

fn main() {}
