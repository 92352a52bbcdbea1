//! Every decoder of the benchmark against the ground truth, on smaller streams of the same
//! workloads and at many chunk sizes; the encoders against each other. The benchmark repeats the
//! full-size checks before it times anything; these catch a broken decoder in `cargo test`.

use protocol_benches::encode;
use protocol_benches::floor::{CheckedWalk, Format, HfLinkFormat, LengthWalk, RefereeFormat};
use protocol_benches::hand::appending::{Appending, Early};
use protocol_benches::hand::{self, Staged};
use protocol_benches::port::{OneCallPerByte, hflink::HfLinkPort, referee::RefereePort};
use protocol_benches::verify::{Output, collect, compare, count, exact};
use protocol_benches::workload::{Noise, Protocol, Workload, reference_frames};
use protocol_benches::{ChunkDecoder, generated};

const LEN: usize = 256 << 10;
const CHUNKS: [usize; 6] = [1, 7, 64, 65, 1000, usize::MAX];

fn workloads() -> Vec<Workload> {
    let mut out = Vec::new();
    for protocol in [Protocol::HfLink, Protocol::Referee] {
        for (noise, seed) in [(Noise::Clean, 11), (Noise::Noisy, 12)] {
            out.push(Workload::generate(protocol, noise, LEN, seed));
        }
    }
    out
}

fn check_exact<D: ChunkDecoder>(name: &str, w: &Workload, make: impl Fn() -> D) {
    check_chunks(name, w, &CHUNKS, make);
}

fn check_chunks<D: ChunkDecoder>(name: &str, w: &Workload, chunks: &[usize], make: impl Fn() -> D) {
    for &chunk in chunks {
        let out = collect(&mut make(), &w.stream, chunk);
        if let Err(e) = exact(w, &out) {
            panic!("{name}, chunks of {chunk}: {e}");
        }
        assert_eq!(count(&mut make(), &w.stream, chunk).0, w.frames.len());
    }
}

#[test]
fn workloads_hold_exactly_their_untouched_frames() {
    for w in workloads() {
        assert_eq!(
            reference_frames(w.protocol, &w.stream),
            w.frames,
            "{}",
            w.name()
        );
        assert!(w.stream.len() > LEN - 200 && w.stream.len() <= LEN);
        let frames = w.frames.len() as f64;
        let mean = w.frame_lengths().iter().sum::<usize>() as f64 / frames;
        let expected = if w.protocol == Protocol::HfLink {
            47.5
        } else {
            59.5
        };
        assert!(
            (mean - expected).abs() < 1.0,
            "{}: mean frame {mean}",
            w.name()
        );
        if w.noise == Noise::Noisy {
            let covered: usize = w.frame_lengths().iter().sum();
            // 5% of the frames corrupt, and the garbage: roughly 5% + 0.1 * 15.5 / frame bytes.
            let lost = 1.0 - covered as f64 / w.stream.len() as f64;
            assert!((0.06..0.1).contains(&lost), "{}: {lost}", w.name());
        }
    }
}

#[test]
fn generated_decoders_return_exactly_the_untouched_frames() {
    for w in workloads() {
        match w.protocol {
            Protocol::HfLink => check_exact("generated", &w, generated::hflink_decoder),
            Protocol::Referee => check_exact("generated", &w, generated::referee_decoder),
        }
    }
}

#[test]
fn hand_written_decoders_return_exactly_the_untouched_frames() {
    for w in workloads() {
        match w.protocol {
            Protocol::HfLink => check_exact("hand", &w, Staged::<hand::hflink::HfLink>::default),
            Protocol::Referee => check_exact("hand", &w, Staged::<hand::referee::Referee>::default),
        }
    }
}

#[test]
fn best_baseline_decoders_return_exactly_the_untouched_frames() {
    // The 2 KiB appending feed: chunks of 255 and 256 bytes straddle its choice between
    // appending and scanning in place; 1000 bytes after small chunks stage a frame's worth.
    let chunks = [1, 7, 64, 65, 255, 256, 1000, usize::MAX];
    for w in workloads() {
        match w.protocol {
            Protocol::HfLink => check_chunks(
                "best",
                &w,
                &chunks,
                Appending::<hand::hflink::HfLink>::default,
            ),
            Protocol::Referee => {
                let best = Appending::<hand::referee::RefereeClmul>::default;
                check_chunks("best", &w, &chunks, best);
                let slicing = Appending::<hand::referee::Referee>::default;
                check_chunks("best, slicing CRC", &w, &chunks, slicing);
                let crc_fast = Appending::<hand::referee::RefereeCrcFast>::default;
                check_chunks("best, crc-fast CRC", &w, &chunks, crc_fast);
            }
        }
    }
}

#[test]
fn best_baseline_with_the_rule_returns_exactly_the_untouched_frames() {
    let chunks = [1, 7, 64, 65, 255, 256, 1000, usize::MAX];
    for w in workloads() {
        match w.protocol {
            Protocol::HfLink => check_chunks(
                "best-early",
                &w,
                &chunks,
                Early::<hand::hflink::HfLink>::default,
            ),
            Protocol::Referee => {
                let early = Early::<hand::referee::RefereeClmul>::default;
                check_chunks("best-early", &w, &chunks, early);
            }
        }
    }
}

/// How many frames `decoder` has returned after each chunk of `chunk` bytes of `stream`.
fn frames_by_chunk<D: ChunkDecoder>(mut decoder: D, stream: &[u8], chunk: usize) -> Vec<usize> {
    let mut frames = 0;
    let mut after = Vec::new();
    for piece in stream.chunks(chunk) {
        decoder.feed(piece, &mut |_: &[u8]| frames += 1);
        after.push(frames);
    }
    after
}

#[test]
fn best_baseline_with_the_rule_returns_frames_when_the_generated_decoder_does() {
    // `best-early` times the rule against the generated decoder: the same frames at the same
    // moments. Without the rule (`best`), a frame inside a waiting candidate comes a chunk or
    // more later on the noisy streams, which the comparison must see.
    let mut later = 0;
    for w in workloads() {
        for chunk in [1, 7, 64, 65] {
            let (generated, early, best) = match w.protocol {
                Protocol::HfLink => (
                    frames_by_chunk(generated::hflink_decoder(), &w.stream, chunk),
                    frames_by_chunk(Early::<hand::hflink::HfLink>::default(), &w.stream, chunk),
                    frames_by_chunk(
                        Appending::<hand::hflink::HfLink>::default(),
                        &w.stream,
                        chunk,
                    ),
                ),
                Protocol::Referee => (
                    frames_by_chunk(generated::referee_decoder(), &w.stream, chunk),
                    frames_by_chunk(
                        Early::<hand::referee::RefereeClmul>::default(),
                        &w.stream,
                        chunk,
                    ),
                    frames_by_chunk(
                        Appending::<hand::referee::RefereeClmul>::default(),
                        &w.stream,
                        chunk,
                    ),
                ),
            };
            assert_eq!(generated, early, "{}, chunks of {chunk}", w.name());
            later += generated.iter().zip(&best).filter(|(g, b)| g != b).count();
        }
    }
    assert!(later > 0, "no frame came earlier with the rule");
}

/// Feeds `stream` to `decoder` in chunks of the sizes of `sizes`, in turn, and keeps every frame.
fn collect_alternating<D: ChunkDecoder>(mut decoder: D, stream: &[u8], sizes: &[usize]) -> Output {
    let mut out = Output::default();
    let mut sink = |frame: &[u8]| {
        out.bytes.extend_from_slice(frame);
        out.lengths.push(frame.len());
    };
    let mut rest = stream;
    for &n in sizes.iter().cycle() {
        if rest.is_empty() {
            break;
        }
        let (head, tail) = rest.split_at(n.min(rest.len()));
        decoder.feed(head, &mut sink);
        rest = tail;
    }
    decoder.finish(&mut sink);
    out
}

#[test]
fn best_baseline_survives_alternating_chunk_sizes() {
    // Small chunks leave bytes pending when a large one comes, and the buffer fills and is
    // compacted: every combination in one stream.
    let sizes = [3usize, 300, 64, 64, 64, 700, 255, 1, 256, 100];
    for w in workloads() {
        let out = match w.protocol {
            Protocol::HfLink => collect_alternating(
                Appending::<hand::hflink::HfLink>::default(),
                &w.stream,
                &sizes,
            ),
            Protocol::Referee => {
                let d = Appending::<hand::referee::RefereeClmul>::default();
                collect_alternating(d, &w.stream, &sizes)
            }
        };
        if let Err(e) = exact(&w, &out) {
            panic!("{}: {e}", w.name());
        }
    }
}

#[test]
fn generated_decoders_reading_their_layout_by_reference_agree() {
    // The same engine with the layout read through a reference (the interpreter's way):
    // the compile-time layout must change the speed only.
    for w in workloads() {
        match w.protocol {
            Protocol::HfLink => check_exact("by-ref", &w, generated::hflink_decoder_by_ref),
            Protocol::Referee => check_exact("by-ref", &w, generated::referee_decoder_by_ref),
        }
    }
}

#[test]
fn ports_return_every_clean_frame_and_lose_some_noisy_ones() {
    for w in workloads() {
        for chunk in [1, 64, usize::MAX] {
            let out = match w.protocol {
                Protocol::HfLink => collect(&mut HfLinkPort::default(), &w.stream, chunk),
                Protocol::Referee => collect(&mut RefereePort::default(), &w.stream, chunk),
            };
            let loss = compare(&w, &out);
            assert_eq!(loss.extra, 0, "{}", w.name());
            match w.noise {
                Noise::Clean => assert_eq!(loss.lost, 0, "{}", w.name()),
                // The originals lose the frame after a stray sync byte or a truncated frame.
                Noise::Noisy => assert!(
                    loss.lost > 0 && loss.lost * 100 < w.frames.len(),
                    "{}: {loss}",
                    w.name()
                ),
            }
        }
    }
}

#[test]
fn ports_called_once_per_byte_return_what_the_fused_ports_return() {
    for w in workloads() {
        for chunk in [1, 64, usize::MAX] {
            let (fused, per_byte) = match w.protocol {
                Protocol::HfLink => (
                    collect(&mut HfLinkPort::default(), &w.stream, chunk),
                    collect(
                        &mut OneCallPerByte::<HfLinkPort>::default(),
                        &w.stream,
                        chunk,
                    ),
                ),
                Protocol::Referee => (
                    collect(&mut RefereePort::default(), &w.stream, chunk),
                    collect(
                        &mut OneCallPerByte::<RefereePort>::default(),
                        &w.stream,
                        chunk,
                    ),
                ),
            };
            assert!(fused.frames() > 0);
            assert_eq!(fused, per_byte, "{}, chunks of {chunk}", w.name());
        }
    }
}

#[test]
fn floors_return_exactly_the_frames_of_clean_streams() {
    for w in workloads().into_iter().filter(|w| w.noise == Noise::Clean) {
        match w.protocol {
            Protocol::HfLink => {
                check_exact("floor", &w, LengthWalk::<HfLinkFormat>::default);
                check_exact("floor-checked", &w, CheckedWalk::<HfLinkFormat>::default);
            }
            Protocol::Referee => {
                check_exact("floor", &w, LengthWalk::<RefereeFormat>::default);
                check_exact("floor-checked", &w, CheckedWalk::<RefereeFormat>::default);
            }
        }
    }
}

/// The frames the two floors return on `stream` fed in `chunk`-byte chunks: unchecked, checked.
fn floor_frames(protocol: Protocol, stream: &[u8], chunk: usize) -> (Output, Output) {
    fn both<F: Format>(stream: &[u8], chunk: usize) -> (Output, Output) {
        (
            collect(&mut LengthWalk::<F>::default(), stream, chunk),
            collect(&mut CheckedWalk::<F>::default(), stream, chunk),
        )
    }
    match protocol {
        Protocol::HfLink => both::<HfLinkFormat>(stream, chunk),
        Protocol::Referee => both::<RefereeFormat>(stream, chunk),
    }
}

#[test]
fn the_checked_floor_drops_a_frame_whose_check_fails() {
    for protocol in [Protocol::HfLink, Protocol::Referee] {
        let w = Workload::generate(protocol, Noise::Clean, 4096, 5);
        let mut stream = w.stream.clone();
        // The last byte of the second frame: HFLink's sum, the referee's CRC-16 (lengths stay).
        let second = w.frames[1].clone();
        stream[second.end - 1] ^= 0x01;
        for chunk in [1, 64, usize::MAX] {
            let (unchecked, checked) = floor_frames(protocol, &stream, chunk);
            assert_eq!(unchecked.frames(), w.frames.len(), "{protocol:?}");
            assert_eq!(checked.frames(), w.frames.len() - 1, "{protocol:?}");
            assert_ne!(checked.iter().nth(1), Some(&stream[second.clone()]));
        }
    }
}

#[test]
fn a_stray_sync_byte_costs_the_port_the_next_frame_but_not_the_others() {
    let w = Workload::generate(Protocol::HfLink, Noise::Clean, 1000, 3);
    let first = w.frames[0].clone();
    let mut stream = vec![0xFF];
    stream.extend_from_slice(&w.stream);
    let port = collect(&mut HfLinkPort::default(), &stream, usize::MAX);
    let hand = collect(
        &mut Staged::<hand::hflink::HfLink>::default(),
        &stream,
        usize::MAX,
    );
    assert_eq!(hand.frames(), w.frames.len());
    assert_eq!(port.frames(), w.frames.len() - 1);
    assert_ne!(port.iter().next(), Some(&w.stream[first]));
}

#[test]
fn encoders_write_the_same_frames() {
    let n = 10_000;
    let g = encode::encode_all(n, |b, i| {
        generated::encode_system_info(b, 0x11, 0x01, encode::system_info(i)).unwrap_or(0)
    });
    let h = encode::encode_all(n, |b, i| {
        hand::hflink::encode_system_info(b, 0x11, 0x01, encode::system_info(i)).unwrap_or(0)
    });
    assert_eq!(g.len(), n as usize * hand::hflink::SYSTEM_INFO_FRAME);
    assert!(g == h);
    assert_eq!(
        count(&mut generated::hflink_decoder(), &g, 100).0,
        n as usize
    );

    let g = encode::encode_all(n, |b, i| {
        generated::encode_robot_pos(b, i as u8, encode::robot_pos(i)).unwrap_or(0)
    });
    let h = encode::encode_all(n, |b, i| {
        hand::referee::encode_robot_pos(b, i as u8, encode::robot_pos(i)).unwrap_or(0)
    });
    assert_eq!(g.len(), n as usize * hand::referee::ROBOT_POS_FRAME);
    assert!(g == h);
    assert_eq!(
        count(&mut generated::referee_decoder(), &g, 100).0,
        n as usize
    );
}

#[test]
fn wrapping_encoder_reuses_its_buffer() {
    let mut buf = vec![0u8; encode::BUFFER];
    let total = encode::encode_wrapping(&mut buf, 100_000, |b, i| {
        hand::hflink::encode_system_info(b, 0x11, 0x01, encode::system_info(i)).unwrap_or(0)
    });
    assert_eq!(total, 100_000 * hand::hflink::SYSTEM_INFO_FRAME);
}
