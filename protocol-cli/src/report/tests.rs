//! What the page keeps of a long capture: counters for all of it, items for the bytes the hex
//! view shows.

use protocol_dynamic::Interpreter;
use protocol_runtime::Reject;
use protocol_spec::source::SpecSource;

use super::chart::Windows;
use super::{Entry, HEX_VIEW_MAX, decode};

fn hflink() -> Interpreter {
    let text = include_str!("../../../specs/hflink.toml");
    let source = SpecSource::new("hflink.toml", text);
    Interpreter::new(protocol_spec::compile(&source).expect("the bundled spec is valid"))
}

fn offset(e: &Entry) -> usize {
    match e {
        Entry::Frame { offset, .. }
        | Entry::Rejected { offset, .. }
        | Entry::Skipped { offset, .. } => *offset,
    }
}

#[test]
fn a_long_capture_is_counted_whole_and_kept_only_where_the_hex_view_shows_it() {
    let interp = hflink();
    let codec = interp.codec();
    let one = include_bytes!("../../../examples/captures/hflink.bin");
    let once = decode(&codec, 0, one).expect("a stream format");
    let copies = (3 * HEX_VIEW_MAX).div_ceil(one.len());
    let data = one.repeat(copies);
    let whole = decode(&codec, 0, &data).expect("a stream format");

    assert_eq!(whole.frames, once.frames * copies);
    assert_eq!(whole.stats.frames, once.stats.frames * copies as u64);
    assert!(!whole.shown.is_empty());
    assert!(whole.shown.iter().all(|e| offset(e) < HEX_VIEW_MAX));
    // Every item the view shows is kept, with its fields: the copies before the limit
    // account for as many items as a copy holds each.
    let before = HEX_VIEW_MAX / one.len();
    assert!(whole.shown.len() >= once.shown.len() * before);
    assert!(
        whole
            .shown
            .iter()
            .any(|e| matches!(e, Entry::Frame { spans, .. } if !spans.is_empty()))
    );
}

#[test]
fn a_rejection_past_the_hex_view_still_counts_in_its_window() {
    let mut w = Windows::new(6_000);
    w.rejected(5_999, Reject::BadChecksum);
    w.rejected(0, Reject::BadLength);
    assert_eq!(w.counts()[59], [1, 0, 0]);
    assert_eq!(w.counts()[0], [0, 1, 0]);
}

#[test]
fn a_skipped_run_gives_each_window_it_crosses_its_share() {
    // 600 bytes in windows of 10: a run of 25 from offset 5 covers 5 + 10 + 10.
    let mut w = Windows::new(600);
    w.skipped(5, 25);
    let c = w.counts();
    assert_eq!((c[0][2], c[1][2], c[2][2], c[3][2]), (5, 10, 10, 0));
    assert_eq!(c.iter().map(|x| x[2]).sum::<u64>(), 25);
}
