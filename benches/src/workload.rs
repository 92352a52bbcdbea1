//! The benchmark's input: fixed-seed streams of HFLink and referee frames, clean or noisy, and
//! their ground truth (where every frame a correct decoder must return lies).
//!
//! What the streams hold:
//!
//! - HFLink: `FF FF sender receiver length(u16 BE) command payload sum%255`; `length` (command
//!   and payload) is `1 + min(a, b)` for `a`, `b` uniform in `0..120`, so frames are 8..=127
//!   bytes, 47.5 on average; sender and receiver are the PC (0x01) and the MCU (0x11), either
//!   way round; the command is one of the 27 ids.
//! - Referee: `A5 len(u16 LE) seq CRC8 | cmd(u16 LE) data CRC16`, `len` uniform in `1..=100`
//!   (frames of 59.5 bytes on average), `seq` counting up, `cmd` one of the 13 ids of 2019.
//! - Noisy: before each frame, with probability 10%, 0..32 random bytes (sync bytes included);
//!   with probability 5% the frame has one byte changed to another random value.
//!
//! The checks are computed here with the `crc` crate and plain byte loops, independently of the
//! decoders under test. A correct decoder returns exactly the untouched frames: the ground truth
//! is the list the generator made, and [`Workload::generate`] proves it with a slow reference
//! decoder (try every offset, resume one byte after a rejected start). Should the noise forge a
//! valid frame (a changed length byte whose new frame happens to sum right), the generator draws
//! the stream again with the next seed, so the seed in use is part of the workload's name.

use std::ops::Range;

/// Bytes of every benchmark stream (the last frame that fits ends the stream).
pub const STREAM_LEN: usize = 16 << 20;

/// Largest HFLink frame: 6 header bytes, 120 bytes of command and payload, the sum.
pub const HFLINK_MAX_FRAME: usize = 127;
/// Largest referee frame a receiver accepts: 7 header bytes, 118 data bytes, the CRC16.
pub const REFEREE_MAX_FRAME: usize = 127;
/// Largest `length` of an HFLink frame (command and payload).
pub const HFLINK_MAX_LENGTH: usize = 120;
/// Largest `data_length` of a referee frame.
pub const REFEREE_MAX_DATA: usize = 118;

/// The referee header's CRC-8: poly 0x31 reflected, register starting at 0xFF.
pub const REFEREE_CRC8: crc::Algorithm<u8> = crc::Algorithm {
    width: 8,
    poly: 0x31,
    init: 0xFF,
    refin: true,
    refout: true,
    xorout: 0x00,
    check: 0x0B,
    residue: 0x00,
};
/// The referee frame's CRC-16 (CRC-16/MCRF4XX).
pub const REFEREE_CRC16: crc::Algorithm<u16> = crc::CRC_16_MCRF4XX;

const CRC8: crc::Crc<u8> = crc::Crc::<u8>::new(&REFEREE_CRC8);
const CRC16: crc::Crc<u16> = crc::Crc::<u16>::new(&REFEREE_CRC16);

/// The 13 command ids of the referee's 2019 table.
const REFEREE_IDS: [u16; 13] = [
    0x0001, 0x0002, 0x0003, 0x0101, 0x0102, 0x0103, 0x0201, 0x0202, 0x0203, 0x0204, 0x0205, 0x0206,
    0x0207,
];

/// A protocol of the benchmark.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Protocol {
    /// HANDS-FREE HFLink (`specs/hflink.toml`).
    HfLink,
    /// RoboMaster referee system, 2019 (`specs/referee.toml`).
    Referee,
}

impl Protocol {
    /// Short name, as in benchmark ids.
    pub const fn name(self) -> &'static str {
        match self {
            Protocol::HfLink => "hflink",
            Protocol::Referee => "referee",
        }
    }
}

/// Whether a stream is clean or noisy.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Noise {
    /// Frames back to back.
    Clean,
    /// 10% of frames after 0..32 garbage bytes, 5% with one byte changed.
    Noisy,
}

impl Noise {
    /// Short name, as in benchmark ids.
    pub const fn name(self) -> &'static str {
        match self {
            Noise::Clean => "clean",
            Noise::Noisy => "noisy",
        }
    }
}

/// xorshift64*: a small deterministic generator, so that a seed names a stream forever.
#[derive(Debug, Clone)]
pub struct Rng(u64);

impl Rng {
    /// A generator from a seed (0 is mapped to another value: xorshift has no zero state).
    pub fn new(seed: u64) -> Self {
        Rng(if seed == 0 {
            0x9E37_79B9_7F4A_7C15
        } else {
            seed
        })
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// A value in `0..n` (`n > 0`).
    pub fn below(&mut self, n: u64) -> u64 {
        ((u128::from(self.next_u64()) * u128::from(n)) >> 64) as u64
    }

    /// A random byte.
    pub fn byte(&mut self) -> u8 {
        (self.next_u64() >> 56) as u8
    }

    /// True with probability `percent / 100`.
    pub fn percent(&mut self, percent: u64) -> bool {
        self.below(100) < percent
    }
}

/// A stream and the frames a correct decoder returns from it.
#[derive(Debug, Clone)]
pub struct Workload {
    /// The protocol of the frames.
    pub protocol: Protocol,
    /// Clean or noisy.
    pub noise: Noise,
    /// The seed the stream was drawn with.
    pub seed: u64,
    /// The bytes.
    pub stream: Vec<u8>,
    /// Where each untouched frame lies in `stream`, in order.
    pub frames: Vec<Range<usize>>,
}

impl Workload {
    /// The benchmark's workload for `protocol` and `noise`: [`STREAM_LEN`] bytes.
    pub fn standard(protocol: Protocol, noise: Noise) -> Self {
        Self::generate(
            protocol,
            noise,
            STREAM_LEN,
            Self::standard_seed(protocol, noise),
        )
    }

    /// The seed [`standard`](Self::standard) draws the workload from (the first one tried).
    pub const fn standard_seed(protocol: Protocol, noise: Noise) -> u64 {
        match (protocol, noise) {
            (Protocol::HfLink, Noise::Clean) => 0x4846_4C31,
            (Protocol::HfLink, Noise::Noisy) => 0x4846_4C32,
            (Protocol::Referee, Noise::Clean) => 0x5245_4631,
            (Protocol::Referee, Noise::Noisy) => 0x5245_4632,
        }
    }

    /// A stream of at most `len` bytes drawn from `seed` (or, if the noise forged a frame, from
    /// the first following seed whose stream holds exactly its untouched frames).
    ///
    /// # Panics
    ///
    /// If 100 seeds in a row all forge a frame (a bug in the generator).
    pub fn generate(protocol: Protocol, noise: Noise, len: usize, seed: u64) -> Self {
        for seed in seed..seed + 100 {
            let w = Self::draw(protocol, noise, len, seed);
            if reference_frames(protocol, &w.stream) == w.frames {
                return w;
            }
        }
        panic!("{protocol:?} {noise:?}: 100 seeds in a row forged a frame");
    }

    fn draw(protocol: Protocol, noise: Noise, len: usize, seed: u64) -> Self {
        let mut rng = Rng::new(seed);
        let mut stream = Vec::with_capacity(len);
        let mut frames = Vec::new();
        let mut frame = Vec::with_capacity(HFLINK_MAX_FRAME.max(REFEREE_MAX_FRAME));
        let mut garbage = Vec::with_capacity(32);
        let mut seq = 0u8;
        loop {
            garbage.clear();
            frame.clear();
            if noise == Noise::Noisy && rng.percent(10) {
                let n = rng.below(32);
                garbage.extend((0..n).map(|_| rng.byte()));
            }
            match protocol {
                Protocol::HfLink => hflink_frame(&mut rng, &mut frame),
                Protocol::Referee => {
                    referee_frame(&mut rng, seq, &mut frame);
                    seq = seq.wrapping_add(1);
                }
            }
            let corrupt = noise == Noise::Noisy && rng.percent(5);
            if corrupt {
                corrupt_one_byte(protocol, &mut rng, &mut frame);
            }
            if stream.len() + garbage.len() + frame.len() > len {
                break;
            }
            stream.extend_from_slice(&garbage);
            if !corrupt {
                frames.push(stream.len()..stream.len() + frame.len());
            }
            stream.extend_from_slice(&frame);
        }
        Workload {
            protocol,
            noise,
            seed,
            stream,
            frames,
        }
    }

    /// `protocol-noise`, as in benchmark ids.
    pub fn name(&self) -> String {
        format!("{}-{}", self.protocol.name(), self.noise.name())
    }

    /// The bytes of every frame of the ground truth, one after the other.
    pub fn frame_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(self.stream.len());
        for f in &self.frames {
            out.extend_from_slice(&self.stream[f.clone()]);
        }
        out
    }

    /// The length of every frame of the ground truth.
    pub fn frame_lengths(&self) -> Vec<usize> {
        self.frames.iter().map(|f| f.len()).collect()
    }
}

/// Appends one random HFLink frame.
fn hflink_frame(rng: &mut Rng, out: &mut Vec<u8>) {
    let length = 1 + rng.below(120).min(rng.below(120)) as usize;
    let (sender, receiver) = if rng.below(2) == 0 {
        (0x01, 0x11)
    } else {
        (0x11, 0x01)
    };
    out.extend_from_slice(&[0xFF, 0xFF, sender, receiver]);
    out.extend_from_slice(&(length as u16).to_be_bytes());
    out.push(rng.below(27) as u8);
    out.extend((1..length).map(|_| rng.byte()));
    out.push(hflink_sum(out));
}

/// The HFLink check: the sum of the bytes modulo 255.
pub fn hflink_sum(bytes: &[u8]) -> u8 {
    (bytes.iter().map(|&b| u64::from(b)).sum::<u64>() % 255) as u8
}

/// Appends one random referee frame with sequence number `seq`.
fn referee_frame(rng: &mut Rng, seq: u8, out: &mut Vec<u8>) {
    let data = 1 + rng.below(100) as usize;
    out.push(0xA5);
    out.extend_from_slice(&(data as u16).to_le_bytes());
    out.push(seq);
    out.push(CRC8.checksum(out));
    let cmd = REFEREE_IDS[rng.below(REFEREE_IDS.len() as u64) as usize];
    out.extend_from_slice(&cmd.to_le_bytes());
    out.extend((0..data).map(|_| rng.byte()));
    let crc = CRC16.checksum(out);
    out.extend_from_slice(&crc.to_le_bytes());
}

/// The referee header check of `header` (4 bytes).
pub fn referee_crc8(header: &[u8]) -> u8 {
    CRC8.checksum(header)
}

/// The referee frame check of `bytes`.
pub fn referee_crc16(bytes: &[u8]) -> u16 {
    CRC16.checksum(bytes)
}

/// Changes one byte of `frame` to another value. HFLink's sum modulo 255 cannot see a 0x00
/// turned into 0xFF (or back): such a change would leave a valid frame, so it is not drawn.
fn corrupt_one_byte(protocol: Protocol, rng: &mut Rng, frame: &mut [u8]) {
    let at = rng.below(frame.len() as u64) as usize;
    let old = frame[at];
    loop {
        let new = rng.byte();
        let invisible =
            protocol == Protocol::HfLink && (old ^ new) == 0xFF && (old == 0 || new == 0);
        if new != old && !invisible {
            frame[at] = new;
            return;
        }
    }
}

/// The length of the valid frame starting at `bytes[0]`, if one does, by the plainest reading
/// of the frame format (byte loops and the `crc` crate).
pub fn valid_frame_at(protocol: Protocol, bytes: &[u8]) -> Option<usize> {
    match protocol {
        Protocol::HfLink => {
            let header = bytes.get(..6)?;
            if header[0] != 0xFF || header[1] != 0xFF {
                return None;
            }
            let length = usize::from(u16::from_be_bytes([header[4], header[5]]));
            if !(1..=HFLINK_MAX_LENGTH).contains(&length) {
                return None;
            }
            let frame = bytes.get(..length + 7)?;
            let (body, sum) = frame.split_at(length + 6);
            (hflink_sum(body) == sum[0]).then_some(frame.len())
        }
        Protocol::Referee => {
            let header = bytes.get(..5)?;
            if header[0] != 0xA5 || referee_crc8(&header[..4]) != header[4] {
                return None;
            }
            let data = usize::from(u16::from_le_bytes([header[1], header[2]]));
            if data > REFEREE_MAX_DATA {
                return None;
            }
            let frame = bytes.get(..data + 9)?;
            let (body, crc) = frame.split_at(data + 7);
            (referee_crc16(body) == u16::from_le_bytes([crc[0], crc[1]])).then_some(frame.len())
        }
    }
}

/// The frames of `stream` by the stream rule of the specs: a frame at every offset where one
/// is valid; after a frame, continue at its end; after anything else, at the next byte.
pub fn reference_frames(protocol: Protocol, stream: &[u8]) -> Vec<Range<usize>> {
    let mut frames = Vec::new();
    let mut at = 0;
    while at < stream.len() {
        match valid_frame_at(protocol, &stream[at..]) {
            Some(len) => {
                frames.push(at..at + len);
                at += len;
            }
            None => at += 1,
        }
    }
    frames
}
