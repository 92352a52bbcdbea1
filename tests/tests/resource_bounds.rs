//! Resource bounds: a spec's decoder is its frame buffer plus a small constant, the same for
//! every spec, and nothing else grows with the buffer. (That it never holds more than the buffer,
//! whatever the input, is checked after every call by the property and fault suites.)

mod support;

use std::mem::{align_of, size_of};

use protocol_runtime::StreamDecoder;
use support::{Dec, Spec};

/// Bytes of a decoder beyond its buffer (of a buffer size that needs no padding).
const OVERHEAD: usize = size_of::<StreamDecoder<'static, 0>>();

/// The most a decoder may take beyond its buffer: the layout reference, the pending range, the
/// position and the counters.
const MAX_OVERHEAD: usize = 160;

// Checked when the test compiles.
const _: () = assert!(OVERHEAD <= MAX_OVERHEAD, "the decoder's overhead grew");

/// The size of a decoder with an `n`-byte buffer, by the rule: overhead plus the buffer,
/// rounded up to the decoder's alignment.
fn expected(n: usize) -> usize {
    OVERHEAD + n.next_multiple_of(align_of::<StreamDecoder<'static, 0>>())
}

#[test]
fn overhead_is_small_and_independent_of_the_buffer() {
    eprintln!("decoder overhead: {OVERHEAD} bytes");
    assert_eq!(size_of::<StreamDecoder<'static, 1>>(), expected(1));
    assert_eq!(size_of::<StreamDecoder<'static, 64>>(), expected(64));
    assert_eq!(size_of::<StreamDecoder<'static, 127>>(), expected(127));
    assert_eq!(size_of::<StreamDecoder<'static, 4096>>(), expected(4096));
}

fn bounds<S: Spec>() {
    let size = size_of::<S::Decoder>();
    assert_eq!(
        <S::Decoder as Dec>::CAPACITY,
        S::MAX_FRAME_LEN,
        "{}: the buffer holds one frame",
        S::NAME
    );
    assert_eq!(
        size,
        expected(S::MAX_FRAME_LEN),
        "{}: decoder of {size} bytes",
        S::NAME
    );
    eprintln!(
        "{}: decoder {size} bytes = {OVERHEAD} + buffer {} (padded)",
        S::NAME,
        S::MAX_FRAME_LEN
    );
}

macro_rules! bounds_suite {
    ($name:ident, $path:literal) => {
        #[test]
        fn $name() {
            bounds::<support::$name::Packet>();
        }
    };
}

support::for_each_spec!(bounds_suite);
