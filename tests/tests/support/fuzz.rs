//! The fuzz entry points. The `cargo fuzz` targets (`fuzz/fuzz_targets/`) call these on every
//! input, and `fuzz_corpus.rs` calls them on every file of the committed corpus, on stable, so
//! CI replays exactly what the fuzzers ran.

use std::collections::HashMap;
use std::sync::{Mutex, OnceLock};

use protocol_codegen::codegen::{RuntimePath, expand_pretty};
use protocol_codegen::diag::render_all;
use protocol_codegen::source::SpecSource;
use protocol_dynamic::{Interpreter, Value};

use super::stream::{assert_chunking_invariant, check_packet};
use super::{Rng, Source, Spec};

/// The stream decoder of `S` on arbitrary bytes: the first byte picks how the rest is cut into
/// chunks (0: byte by byte; otherwise a seeded mix of sizes up to a frame and a half). The
/// frames must not depend on the cut (but for the documented nested-frame case), and every
/// invariant of [`super::stream::run`] must hold. The rest is also given to `Packet::decode`.
pub fn stream<S: Spec>(data: &[u8]) {
    let Some((&mode, bytes)) = data.split_first() else {
        return;
    };
    let sizes = chunk_sizes(mode, S::MAX_FRAME_LEN);
    assert_chunking_invariant::<S>(bytes, &sizes);
    if let Ok(packet) = S::decode(bytes) {
        let frame = super::parse_wire(S::layouts()[S::format_of(bytes)], bytes)
            .expect("decoded bytes hold a frame");
        check_packet::<S>(&frame);
        let again = S::from_frame(&frame).expect("from_frame agrees with decode");
        super::stream::assert_same_packet(&packet, &again, &frame);
    }
}

/// Chunk sizes for a mode byte: 0 is byte by byte, anything else seeds a mix of sizes from 0
/// (an empty chunk) to `1.5 * max_frame`.
pub fn chunk_sizes(mode: u8, max_frame: usize) -> Vec<usize> {
    if mode == 0 {
        return vec![1];
    }
    let mut rng = Rng(u64::from(mode));
    (0..16)
        .map(|_| rng.below((max_frame + max_frame / 2 + 1) as u64) as usize)
        .collect()
}

/// The spec loader and validator on arbitrary text: diagnostics or a protocol, never a panic;
/// the diagnostics render, and a protocol that validates expands.
pub fn spec(data: &[u8]) {
    let text = String::from_utf8_lossy(data).into_owned();
    let source = SpecSource::new("specs/fuzz.toml", text);
    match protocol_codegen::compile(&source) {
        Ok(protocol) => {
            let code = expand_pretty(&protocol, &RuntimePath::default());
            assert!(
                code.contains(&format!("pub mod {}", protocol.name)) || code.contains("pub mod r#")
            );
        }
        Err(diagnostics) => {
            assert!(
                !diagnostics.is_empty(),
                "an invalid spec without a diagnostic"
            );
            let rendered = render_all(&diagnostics, &source);
            assert!(
                rendered.contains("error"),
                "diagnostics render to {rendered:?}"
            );
        }
    }
}

/// The interpreter of `S`'s spec, built once per process.
fn interpreter<S: Spec>() -> &'static Interpreter {
    static CACHE: OnceLock<Mutex<HashMap<&'static str, &'static Interpreter>>> = OnceLock::new();
    let mut cache = CACHE
        .get_or_init(Default::default)
        .lock()
        .expect("interpreter cache");
    cache.entry(S::NAME).or_insert_with(|| {
        let ir = super::model::model::<S>().ir.clone();
        Box::leak(Box::new(Interpreter::new(ir)))
    })
}

/// The run-time codec (`protocol_dynamic`) and the generated code of `S` on the same bytes (on a
/// link, as a frame of the format whose sync they start with):
/// neither panics, they accept and reject the same inputs, and what they accept they re-encode
/// to the same bytes (the codec's frame value going through its JSON form, as
/// `decode | encode` carries it).
pub fn interp<S: Spec>(data: &[u8]) {
    let interp = interpreter::<S>();
    let codec = interp.codec();
    let direction = S::DIRECTION.and_then(|d| codec.direction_index(d));
    let codec = codec.with_direction(direction);
    // On a link, the format whose sync the bytes start with (the IR's index of it).
    let format = super::model::model::<S>().format_for(data).format;
    let generated = S::decode(data);
    let interpreted = codec.parse(format, data);
    assert_eq!(
        generated.is_ok(),
        interpreted.is_ok(),
        "{}: generated {generated:?}, interpreter {interpreted:?} on {}",
        S::NAME,
        super::hex(data)
    );
    let (Ok(packet), Ok(decoded)) = (generated, interpreted) else {
        return;
    };
    let frame = super::parse_wire(S::layouts()[S::format_of(data)], data).expect("a decoded frame");
    let json = serde_json::to_value(codec.frame_value(&decoded, 0, &frame))
        .expect("a frame value has a JSON form");
    let object: Value = serde_json::from_value(json).expect("the JSON form reads back");
    let encoded = codec.encode(&object).unwrap_or_else(|e| {
        panic!(
            "{}: the interpreter does not re-encode {object}: {e:?}",
            S::NAME
        )
    });
    let bytes = packet.to_vec().expect("a decoded packet encodes");
    assert!(
        encoded.bytes == bytes,
        "{}: the interpreter encodes {object} to {}, generated code to {}",
        S::NAME,
        super::hex(&encoded.bytes),
        super::hex(&bytes)
    );
}

/// [`interp`] for the spec the first byte picks (in the order of `for_each_spec!`).
pub fn interp_any(data: &[u8]) {
    let Some((&pick, rest)) = data.split_first() else {
        return;
    };
    let mut targets: Vec<fn(&[u8])> = Vec::new();
    macro_rules! target {
        ($name:ident, $path:literal $(, $given:tt)*) => {
            targets.push(interp::<super::packet!($name $(, $given)*)>);
        };
    }
    super::for_each_spec!(target);
    targets[usize::from(pick) % targets.len()](rest);
}
