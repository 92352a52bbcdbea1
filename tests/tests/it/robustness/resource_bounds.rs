//! Resource bounds: a spec's decoder is its frame buffer plus a small constant, the same for
//! every spec, and nothing else grows with the buffer. (That it never holds more than the buffer,
//! whatever the input, is checked after every call by the property and fault suites.)

use std::mem::{align_of, size_of};

use crate::support::{Dec, Spec};
use protocol_kit::layout::LayoutRef;
use protocol_kit::{FrameLayout, StreamDecoder};

/// A layout known at compile time, as generated code names it: a zero-sized type.
#[derive(Clone, Copy)]
struct Static;
impl LayoutRef for Static {
    fn layout(&self) -> &FrameLayout<'_> {
        &crate::support::hflink::LAYOUT
    }
}

/// A decoder of a layout built at run time (the run-time codec): a reference to it.
type ByRef<const N: usize> = StreamDecoder<&'static FrameLayout<'static>, N>;
/// A decoder of a generated layout.
type ByType<const N: usize> = StreamDecoder<Static, N>;

/// Bytes of a generated decoder beyond its buffer (of a buffer size that needs no padding).
const OVERHEAD: usize = size_of::<ByType<0>>();

/// The most a decoder may take beyond its buffer: the layout reference, the pending range, the
/// position and the counters.
const MAX_OVERHEAD: usize = 160;

// Checked when the test compiles.
const _: () = assert!(OVERHEAD <= MAX_OVERHEAD, "the decoder's overhead grew");
// A generated layout costs no bytes; a reference costs one pointer.
const _: () = assert!(size_of::<ByRef<0>>() == OVERHEAD + size_of::<usize>());

/// The size of a generated decoder with an `n`-byte buffer, by the rule: overhead plus the
/// buffer, rounded up to the decoder's alignment.
fn expected(n: usize) -> usize {
    OVERHEAD + n.next_multiple_of(align_of::<ByType<0>>())
}

#[test]
fn overhead_is_small_and_independent_of_the_buffer() {
    eprintln!("decoder overhead: {OVERHEAD} bytes");
    assert_eq!(size_of::<ByType<1>>(), expected(1));
    assert_eq!(size_of::<ByType<64>>(), expected(64));
    assert_eq!(size_of::<ByType<127>>(), expected(127));
    assert_eq!(size_of::<ByType<4096>>(), expected(4096));
    assert_eq!(
        size_of::<ByRef<4096>>(),
        expected(4096) + size_of::<usize>()
    );
}

fn bounds<S: Spec>() {
    let size = size_of::<S::Decoder>();
    // The buffer: one frame, a staged chunk as large again (at least 64 bytes), and a
    // 128-byte checksum window, rounded up to 64 bytes; on hosts (these tests' targets, with
    // 64-bit pointers) at least 2 KiB.
    let rule = ((2 * S::MAX_FRAME_LEN).max(S::MAX_FRAME_LEN + 64) + 128).next_multiple_of(64);
    let host = if cfg!(target_pointer_width = "64") {
        rule.max(2048)
    } else {
        rule
    };
    assert_eq!(S::DECODER_BUFFER_LEN, host, "{}", S::NAME);
    assert_eq!(
        <S::Decoder as Dec>::CAPACITY,
        S::DECODER_BUFFER_LEN,
        "{}: the buffer is the one the rule gives",
        S::NAME
    );
    assert_eq!(
        size,
        expected(S::DECODER_BUFFER_LEN),
        "{}: decoder of {size} bytes",
        S::NAME
    );
    eprintln!(
        "{}: decoder {size} bytes = {OVERHEAD} + buffer {} (frames up to {})",
        S::NAME,
        S::DECODER_BUFFER_LEN,
        S::MAX_FRAME_LEN
    );
}

macro_rules! bounds_suite {
    ($name:ident, $path:literal $(, $given:tt)*) => {
        #[test]
        fn $name() {
            bounds::<crate::support::packet!($name $(, $given)*)>();
        }
    };
}

crate::support::for_each_spec!(bounds_suite);
