//! Writes `examples/captures/`: a realistic capture per bundled spec, with noise, and the
//! ground truth of each (`NAME.truth.jsonl`: every frame written, intact or damaged, at its
//! offset). Run it from anywhere:
//!
//! ```sh
//! cargo run -p protocol-cli --example make_captures
//! ```
//!
//! Frames are built with the code `protocol!` generates, not with the interpreter, so a
//! capture decoded by `protocol decode` checks one codec against the other. The noise comes
//! from a seeded generator: the files are the same on every run and every machine (no
//! transcendental functions, whose last bits vary between C libraries).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

mod dynamixel;
mod dynamixel1;
mod hflink;
mod referee;
mod roborts;
mod scout;
mod vectors;

/// xorshift64*, seeded: the same noise on every run.
pub struct Rng(pub u64);

impl Rng {
    /// The next 64 random bits.
    pub fn bits(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// True with probability `percent` %.
    pub fn chance(&mut self, percent: u64) -> bool {
        self.bits() % 1000 < percent * 10
    }

    /// A number below `n`.
    pub fn below(&mut self, n: u64) -> u64 {
        self.bits() % n.max(1)
    }

    /// A small deterministic perturbation in `-amplitude..amplitude`.
    pub fn jitter(&mut self, amplitude: f32) -> f32 {
        (self.below(2001) as f32 - 1000.0) / 1000.0 * amplitude
    }
}

/// A triangle wave of period `period` between -1 and 1: smooth enough for a trajectory, and
/// exact on every machine.
pub fn wave(t: f32, period: f32) -> f32 {
    let phase = (t / period).fract();
    if phase < 0.5 {
        4.0 * phase - 1.0
    } else {
        3.0 - 4.0 * phase
    }
}

/// Lowercase hex of some bytes.
pub fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// Whether some bytes are a valid frame.
pub type IsFrame = Box<dyn Fn(&[u8]) -> bool>;

/// A byte stream under construction, with its ground truth.
pub struct Stream {
    /// The bytes of the capture.
    pub bytes: Vec<u8>,
    /// The ground truth: one JSON line per frame written.
    pub truth: String,
    /// The noise generator, also for the scenario's own jitter.
    pub rng: Rng,
    /// Percent of frames with a flipped bit, cut short, or preceded by line noise.
    flip: u64,
    cut: u64,
    noise: u64,
    /// Bytes of the sync word, sprinkled into line noise so that it looks like frame starts.
    sync: Vec<u8>,
    /// Bytes line noise does not contain (none unless [`Stream::undamaged`] says).
    avoid: Vec<u8>,
    /// Whether a damaged frame is still a valid frame (a bit no check covers): such a flip is
    /// made elsewhere, so that a frame recorded as damaged is rejected.
    valid: Option<IsFrame>,
    counts: [usize; 5],
}

const INTACT: usize = 0;
const FLIPPED: usize = 1;
const CUT: usize = 2;
const UNKNOWN: usize = 3;
const NOISE: usize = 4;

impl Stream {
    /// An empty stream with noise seeded by `seed`; `sync` is the sync word of its frames.
    pub fn new(seed: u64, sync: &[u8]) -> Self {
        Stream {
            bytes: Vec::new(),
            truth: String::new(),
            rng: Rng(seed),
            flip: 3,
            cut: 2,
            noise: 4,
            sync: sync.to_vec(),
            avoid: Vec::new(),
            valid: None,
            counts: [0; 5],
        }
    }

    /// No damaged frames, and line noise without the bytes of `avoid` (a format without a
    /// check: a damaged frame, or a frame start in the noise, would be a frame).
    pub fn undamaged(&mut self, avoid: &[u8]) {
        self.flip = 0;
        self.cut = 0;
        self.sync.clear();
        self.avoid = avoid.to_vec();
    }

    /// Tells which damaged frames are still valid frames.
    pub fn set_valid(&mut self, valid: IsFrame) {
        self.valid = Some(valid);
    }

    fn record(&mut self, kind: &str, offset: usize, frame: &[u8]) {
        let _ = writeln!(
            self.truth,
            "{{\"offset\":{offset},\"kind\":\"{kind}\",\"hex\":\"{}\"}}",
            hex(frame)
        );
    }

    /// Writes a frame, maybe damaged, maybe after line noise.
    pub fn frame(&mut self, frame: &[u8]) {
        if self.rng.chance(self.noise) {
            let n = 1 + self.rng.below(12) as usize;
            for _ in 0..n {
                let mut b = if !self.sync.is_empty() && self.rng.chance(25) {
                    self.sync[self.rng.below(self.sync.len() as u64) as usize]
                } else {
                    self.rng.bits() as u8
                };
                while self.avoid.contains(&b) {
                    b = self.rng.bits() as u8;
                }
                self.bytes.push(b);
            }
            self.counts[NOISE] += n;
        }
        let offset = self.bytes.len();
        if self.rng.chance(self.flip) {
            let mut damaged = frame.to_vec();
            let at = self.rng.below(damaged.len() as u64) as usize;
            damaged[at] ^= 1 << self.rng.below(8);
            while self.valid.as_ref().is_some_and(|valid| valid(&damaged)) {
                damaged = frame.to_vec();
                let at = self.rng.below(damaged.len() as u64) as usize;
                damaged[at] ^= 1 << self.rng.below(8);
            }
            self.bytes.extend_from_slice(&damaged);
            self.record("bit_flip", offset, &damaged);
            self.counts[FLIPPED] += 1;
        } else if self.rng.chance(self.cut) {
            let keep = 1 + self.rng.below(frame.len() as u64 - 1) as usize;
            self.bytes.extend_from_slice(&frame[..keep]);
            self.record("truncated", offset, &frame[..keep]);
            self.counts[CUT] += 1;
        } else {
            self.bytes.extend_from_slice(frame);
            self.record("frame", offset, frame);
            self.counts[INTACT] += 1;
        }
    }

    /// Writes a well-framed frame whose command the spec does not have.
    pub fn unknown(&mut self, frame: &[u8]) {
        let offset = self.bytes.len();
        self.bytes.extend_from_slice(frame);
        self.record("unknown_command", offset, frame);
        self.counts[UNKNOWN] += 1;
    }

    /// What was written, for the console.
    pub fn summary(&self) -> String {
        format!(
            "{} bytes: {} intact frames, {} with a flipped bit, {} cut short, {} unknown commands, {} bytes of line noise",
            self.bytes.len(),
            self.counts[INTACT],
            self.counts[FLIPPED],
            self.counts[CUT],
            self.counts[UNKNOWN],
            self.counts[NOISE]
        )
    }
}

fn write(dir: &Path, name: &str, bytes: &[u8]) {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
}

fn main() {
    let dir: PathBuf = [env!("CARGO_MANIFEST_DIR"), "..", "examples", "captures"]
        .iter()
        .collect();
    std::fs::create_dir_all(&dir).expect("creates examples/captures");
    let streams = [
        ("hflink", hflink::capture()),
        ("referee", referee::capture()),
        ("referee2018", referee::capture_2018()),
        ("roborts", roborts::capture()),
        ("dynamixel", dynamixel::capture()),
        ("dynamixel_feedback", dynamixel::feedback_capture()),
        ("dynamixel1_bus", dynamixel1::half_duplex_capture()),
    ];
    for (name, s) in streams {
        write(&dir, &format!("{name}.bin"), &s.bytes);
        write(&dir, &format!("{name}.truth.jsonl"), s.truth.as_bytes());
        println!("{name}.bin: {}", s.summary());
    }
    for spec in vectors::SPECS {
        let s = spec.capture();
        write(&dir, &format!("{}.bin", spec.name), &s.bytes);
        write(
            &dir,
            &format!("{}.truth.jsonl", spec.name),
            s.truth.as_bytes(),
        );
        println!("{}.bin: {}", spec.name, s.summary());
    }
    let (uart, can_log, can_truth, can_summary) = scout::captures();
    write(&dir, "scout.bin", &uart.bytes);
    write(&dir, "scout.truth.jsonl", uart.truth.as_bytes());
    println!("scout.bin: {}", uart.summary());
    write(&dir, "scout_can.log", can_log.as_bytes());
    write(&dir, "scout_can.truth.jsonl", can_truth.as_bytes());
    println!("scout_can.log: {can_summary}");
}
