protocol_kit::protocol!(inline = r#"
[protocol]
name = "inline"

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
GO = { id = 1, payload = "Go" }
"#);

fn main() {}
