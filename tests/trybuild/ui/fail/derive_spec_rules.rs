// A derive's mistakes get the spec rules' diagnostics, all at once, each on its attribute or
// type: padding of 0 bytes, an empty array, a scale factor of 0, a scaled bool, and a Rust type
// that is not what the wire type decodes to.
#[derive(protocol_kit::Payload)]
struct Telemetry {
    #[payload(pad_before = 0)]
    id: u8,
    samples: [u16; 0],
    #[payload(scale = 0.0, raw = "i16")]
    speed: f32,
    #[payload(scale = 0.01)]
    armed: bool,
    #[payload(raw = "i24")]
    offset: u32,
}

fn main() {}
