//! A prototype of the runtime changes that would bring the generated decoder to the speed of the
//! hand-written one, measured in the benchmark next to the real generated decoder. Nothing here
//! is used by the real generated code; `BENCHMARKS.md` describes the changes it stands for.
//!
//! The prototype engine ([`stream::ProtoDecoder`]) is a copy of the runtime's `StreamDecoder`
//! and `FrameLayout::probe_within` (same rules: the search, the order of the checks, the
//! one-byte resynchronisation, the early truncation of a candidate that holds a valid frame, the
//! stats), run on the generated `LAYOUT` statics themselves, with three changes:
//!
//! 1. **The layout is a compile-time constant.** The runtime's decoder keeps `&FrameLayout` in
//!    a field and interprets it for every candidate (loops over the checks, `Pos` resolution,
//!    `WordField` reads, a `match` on the algorithm). Here the decoder is generic over a
//!    zero-sized [`LayoutSource`] whose `layout()` returns the generated static, so every
//!    layout read folds to a constant and the interpretation compiles away.
//! 2. **Window checks** ([`checks`]): a masked fixed-window sum, and slicing-by-16 CRCs with
//!    no byte-wise loop, computed with the rest of the input in reach.
//! 3. **Small-chunk staging** (`STAGE` in [`stream`]): a chunk that arrives while a candidate is
//!    pending is appended to the buffer whole and the buffer scanned contiguously, instead of
//!    completing the candidate with exactly the bytes it needs and returning to the chunk.
//!
//! Each change can be switched on alone, so the benchmark measures what each one buys.

pub mod checks;
pub mod encode;
pub mod stream;

use protocol_runtime::FrameLayout;

use crate::generated::{hflink, referee};
use checks::{Fast, FastCheck, Slices, sum_or_runtime};

/// A frame format known at compile time: what generated code would hand the engine.
pub trait LayoutSource {
    /// The frame format.
    fn layout() -> &'static FrameLayout<'static>;
    /// Its header checks, with the way to compute each.
    fn header_checks() -> &'static [FastCheck];
    /// Its frame checks, with the way to compute each.
    fn frame_checks() -> &'static [FastCheck];
    /// Whether a chunk that arrives while a candidate is pending is appended whole.
    const STAGE: bool;
    /// Whether a pending candidate is searched for a complete valid frame every time the input
    /// runs out (the runtime's rule; off only to measure what it costs).
    const EARLY_TRUNCATION: bool = true;
}

/// The checks of `layout`, computed as the runtime computes them today.
const fn runtime_checks<const N: usize>(
    checks: &'static [protocol_runtime::layout::Check<'static>],
) -> [FastCheck; N] {
    let mut out = [FastCheck {
        check: checks[0],
        fast: Fast::Runtime,
    }; N];
    let mut i = 0;
    while i < N {
        out[i] = FastCheck {
            check: checks[i],
            fast: Fast::Runtime,
        };
        i += 1;
    }
    out
}

static HFLINK_RUNTIME: [FastCheck; 1] = runtime_checks(hflink::LAYOUT.frame_checks);
static HFLINK_FAST: [FastCheck; 1] = [sum_or_runtime(hflink::LAYOUT.frame_checks[0])];

static REFEREE_HEADER_RUNTIME: [FastCheck; 1] = runtime_checks(referee::LAYOUT.header_checks);
static REFEREE_FRAME_RUNTIME: [FastCheck; 1] = runtime_checks(referee::LAYOUT.frame_checks);
/// The referee's CRC-8 (poly 0x31 reflected, register from 0xFF) by slicing.
static REFEREE_CRC8: Slices = Slices::new(8, 0x31, 0xFF, true, true, 0);
/// CRC-16/MCRF4XX by slicing-by-16.
static REFEREE_CRC16: Slices = Slices::new(16, 0x1021, 0xFFFF, true, true, 0);
static REFEREE_HEADER_FAST: [FastCheck; 1] = [FastCheck {
    check: referee::LAYOUT.header_checks[0],
    fast: Fast::Crc(&REFEREE_CRC8),
}];
static REFEREE_FRAME_FAST: [FastCheck; 1] = [FastCheck {
    check: referee::LAYOUT.frame_checks[0],
    fast: Fast::Crc(&REFEREE_CRC16),
}];

macro_rules! source {
    ($(#[$doc:meta])* $name:ident, $layout:expr, $header:expr, $frame:expr, $stage:expr) => {
        source!($(#[$doc])* $name, $layout, $header, $frame, $stage, true);
    };
    ($(#[$doc:meta])* $name:ident, $layout:expr, $header:expr, $frame:expr, $stage:expr, $early:expr) => {
        $(#[$doc])*
        pub struct $name;
        impl LayoutSource for $name {
            #[inline(always)]
            fn layout() -> &'static FrameLayout<'static> {
                &$layout
            }
            #[inline(always)]
            fn header_checks() -> &'static [FastCheck] {
                &$header
            }
            #[inline(always)]
            fn frame_checks() -> &'static [FastCheck] {
                &$frame
            }
            const STAGE: bool = $stage;
            const EARLY_TRUNCATION: bool = $early;
        }
    };
}

source!(
    /// HFLink, change 1 only.
    HfConst, hflink::LAYOUT, [], HFLINK_RUNTIME, false
);
source!(
    /// HFLink, changes 1 and 2.
    HfFast, hflink::LAYOUT, [], HFLINK_FAST, false
);
source!(
    /// HFLink, changes 1, 2 and 3.
    HfStaged, hflink::LAYOUT, [], HFLINK_FAST, true
);
source!(
    /// HFLink, changes 1, 2 and 3, without the early truncation rule (to measure its cost).
    HfStagedLazy, hflink::LAYOUT, [], HFLINK_FAST, true, false
);
source!(
    /// Referee, change 1 only.
    RefConst, referee::LAYOUT, REFEREE_HEADER_RUNTIME, REFEREE_FRAME_RUNTIME, false
);
source!(
    /// Referee, changes 1 and 2.
    RefFast, referee::LAYOUT, REFEREE_HEADER_FAST, REFEREE_FRAME_FAST, false
);
source!(
    /// Referee, changes 1, 2 and 3.
    RefStaged, referee::LAYOUT, REFEREE_HEADER_FAST, REFEREE_FRAME_FAST, true
);
source!(
    /// Referee, changes 1, 2 and 3, without the early truncation rule (to measure its cost).
    RefStagedLazy, referee::LAYOUT, REFEREE_HEADER_FAST, REFEREE_FRAME_FAST, true, false
);

/// The prototype HFLink decoder with all three changes (the same rules as the runtime's).
pub type HfLinkProto = ProtoStaged<HfStaged, { hflink::MAX_FRAME_LEN }>;
/// The prototype referee decoder with all three changes (the same rules as the runtime's).
pub type RefereeProto = ProtoStaged<RefStaged, { referee::MAX_FRAME_LEN }>;

/// Frames of at most `N` bytes in a buffer of `N` bytes (changes 1 and 2).
pub type Proto<L, const N: usize> = stream::ProtoDecoder<L, N, N>;
/// Frames of at most `N` bytes in a buffer with room for a pending frame, a small chunk, and a
/// check window past them.
pub type ProtoStaged<L, const N: usize> = stream::ProtoDecoder<L, N, 512>;
