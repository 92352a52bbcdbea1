// Generated types are real types: a READ request carries no payload.
protocol_kit::protocol!("specs/hflink.toml");

fn main() {
    let _ = hflink::Request::ReadSystemInfo(hflink::ChassisCoord::default());
}
