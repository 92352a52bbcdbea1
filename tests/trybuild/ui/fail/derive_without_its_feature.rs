// `derive(serde)` and `derive(defmt)` with a `protocol` dependency that lacks the features of
// those names: the first errors name the missing features (the unresolved paths follow).
protocol_kit::protocol!(
    derive(serde, defmt),
    inline = r#"
[protocol]
name = "lamp"

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
SET_LEVEL = { id = 1, payload = "Level" }

[structs.Level]
fields = [{ name = "brightness", type = "u8" }]
"#
);

fn main() {}
