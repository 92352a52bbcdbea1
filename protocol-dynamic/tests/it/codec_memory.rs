//! A run-time codec owns everything it builds from a spec: loading and dropping thousands of
//! distinct specs leaves the heap as it found it. Measured with a counting global allocator
//! (`allocation-counter`, which counts the calling thread's allocations), so the figure is a
//! byte count, not a timing.
//!
//! The counting allocator is the global allocator of the whole test binary; it counts only the
//! thread inside `allocation_counter::measure`, so the tests running beside this one on other
//! threads neither add to its count nor see a difference.

use protocol_dynamic::{Interpreter, Value};
use protocol_runtime::checksum::Bitwise;

/// Specs loaded and dropped.
const SPECS: u32 = 3_000;

/// A MAVLink-1-like spec whose two commands fold in the bytes `a` and `b` (distinct specs give
/// distinct per-command byte tables), with a custom CRC starting from `init` (distinct specs
/// give distinct CRC parameters, as users' specs do) and a catalogue one.
fn spec(a: u8, b: u8, init: u16) -> String {
    let params = crc::Algorithm {
        width: 16,
        poly: 0x1021,
        init,
        refin: true,
        refout: true,
        xorout: 0,
        check: 0,
        residue: 0,
    };
    let check = Bitwise::<u16>::new(&params).checksum(b"123456789");
    format!(
        r#"
[protocol]
name = "extra"
byte_order = "little"

[checksums.mine]
crc = {{ width = 16, poly = 0x1021, init = {init:#06x}, refin = true, refout = true, xorout = 0x0000, check = {check:#06x} }}

[frames.v1]
layout = [
  {{ sync = [0xFE] }},
  {{ field = "length", type = "u8", length_of = "payload" }},
  {{ field = "msgid", type = "u8" }},
  {{ payload = {{ max = 16 }} }},
  {{ check = "mine", name = "crc", over = "length..payload", byte_order = "little", extra = "command" }},
  {{ check = "crc-16-umts", name = "crc2", over = "frame", byte_order = "big" }},
]
dispatch = ["msgid"]

[commands]
PING = {{ id = 0, payload = "Ping", check_extra = {a} }}
PONG = {{ id = 1, payload = "Ping", check_extra = {b} }}

[structs.Ping]
fields = [{{ name = "seq", type = "u32" }}]
"#
    )
}

/// Loads spec `i`, encodes a frame and decodes it back (so that every table the codec builds
/// is used), then drops the codec.
fn load_use_drop(i: u32) {
    let (a, b) = ((i % 256) as u8, (i / 256) as u8);
    let interp =
        Interpreter::from_text("extra.toml", spec(a, b, i as u16)).expect("the spec loads");
    let codec = interp.codec();
    let line = format!(r#"{{"command":"PONG","header":{{}},"payload":{{"seq":{i}}}}}"#);
    let object: Value = serde_json::from_str(&line).expect("a frame value");
    let frame = codec.encode(&object).expect("PONG encodes");
    let decoded = codec.parse(0, &frame.bytes).expect("PONG decodes");
    assert_eq!(decoded.payload["seq"], Value::UInt(u64::from(i)));
    // The extra byte is folded in: the frame of another spec's PONG differs in its check.
    let mut stream = codec.stream(0).expect("a stream");
    let mut input = frame.bytes.as_slice();
    assert!(stream.next_item(&mut input).is_some());
}

#[test]
fn loading_and_dropping_specs_returns_their_memory() {
    // Nothing is kept for the process: not even the first load is left out of the count.
    let info = allocation_counter::measure(|| {
        for i in 0..SPECS {
            load_use_drop(i);
        }
    });
    eprintln!(
        "{SPECS} specs: {} allocations, {} bytes allocated, {} bytes still held",
        info.count_total, info.bytes_total, info.bytes_current
    );
    assert!(info.count_total >= u64::from(SPECS), "the counter counts");
    assert_eq!(
        info.bytes_current, 0,
        "bytes still held after every codec is dropped"
    );
}
