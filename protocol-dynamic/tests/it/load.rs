//! Loading a spec at run time: a good spec gives a codec, a bad one the pipeline's
//! diagnostics (rendered as the macro renders them), a missing file the I/O error.

use protocol_dynamic::{Interpreter, LoadError, Value};

fn spec_path(name: &str) -> String {
    format!("{}/../specs/{name}.toml", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn a_bundled_spec_loads_from_its_path_and_from_its_text() {
    let by_path = Interpreter::load(spec_path("hflink")).expect("hflink loads");
    let text = std::fs::read_to_string(spec_path("hflink")).expect("the spec reads");
    let by_text = Interpreter::from_text("specs/hflink.toml", text).expect("hflink loads");
    assert_eq!(by_path.protocol().name, "hflink");
    assert_eq!(by_path.protocol().commands, by_text.protocol().commands);
}

#[test]
fn a_bad_spec_gives_every_diagnostic_of_the_pipeline() {
    let text = std::fs::read_to_string(spec_path("hflink"))
        .expect("the spec reads")
        .replacen("\"sum-mod-255\"", "\"sum-mod-25\"", 1);
    let source = protocol_spec::source::SpecSource::new("specs/bad.toml", text.clone());
    let expected = protocol_spec::compile(&source).expect_err("the edit breaks the spec");
    match Interpreter::from_text("specs/bad.toml", text) {
        Err(e @ LoadError::Spec { .. }) => {
            let rendered = e.to_string();
            let LoadError::Spec { diagnostics, .. } = e else {
                unreachable!()
            };
            assert_eq!(diagnostics, expected);
            assert!(rendered.contains("--> specs/bad.toml:"), "{rendered}");
            assert!(rendered.contains(&expected[0].message), "{rendered}");
        }
        Err(other) => panic!("not a spec error: {other}"),
        Ok(_) => panic!("a bad spec loads"),
    }
}

#[test]
fn a_missing_file_is_a_read_error() {
    let missing = format!("{}/no-such-spec.toml", env!("CARGO_MANIFEST_DIR"));
    match Interpreter::load(&missing) {
        Err(LoadError::Read { path, error }) => {
            assert_eq!(path, missing);
            assert_eq!(error.kind(), std::io::ErrorKind::NotFound);
        }
        Err(other) => panic!("not a read error: {other}"),
        Ok(_) => panic!("a missing file loads"),
    }
}

#[test]
fn a_decoded_frame_holds_the_value_model() {
    let interp = Interpreter::load(spec_path("hflink")).expect("hflink loads");
    let codec = interp.codec();
    // SHAKING_HANDS from sender 1 to receiver 17, as docs/cli.md shows it.
    let frame =
        protocol_dynamic::parse_hex("ffff0111000d000000000000000000000000001f").expect("hex");
    let d = codec.parse(0, &frame).expect("a frame");
    assert_eq!(d.header["sender"], Value::UInt(1));
    assert_eq!(d.header["receiver"], Value::UInt(17));
    assert_eq!(d.payload["x"], Value::F32(0.0));
    let v = codec.frame_value(&d, 0, &frame);
    assert_eq!(v["command"], Value::from("SHAKING_HANDS"));
    assert_eq!(v["hex"], Value::Bytes(frame.clone()));
    assert_eq!(codec.encode(&v).expect("encodes").bytes, frame);
}
