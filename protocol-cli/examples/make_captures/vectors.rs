//! Captures of the specs whose traffic is made of their golden frames (`tests/vectors/`): CRSF,
//! UBX, iBUS, SBUS, MAVLink 1 and 2 mixed, Dynamixel 1.0 instruction packets, MSP v1, and the
//! commands of VESC, Feetech SCS/STS and LX-16A (the controller's side), SBP messages. Each
//! frame of a capture is a golden frame, or one whose payload bytes were changed at random and
//! the frame sealed again; either is kept only when the code `protocol!` generates decodes it
//! and encodes it back to the same bytes, so every frame is one the generated encoder writes.

use protocol_kit::FrameLayout;
use serde_json::Value;

use crate::{Rng, Stream};

protocol_kit::protocol!("../specs/crsf.toml");
protocol_kit::protocol!("../specs/ubx.toml");
protocol_kit::protocol!("../specs/ibus.toml");
protocol_kit::protocol!("../specs/sbus.toml");
protocol_kit::protocol!("../specs/mavlink.toml");
protocol_kit::protocol!("../specs/dynamixel1.toml");
protocol_kit::protocol!("../specs/msp.toml");
protocol_kit::protocol!("../specs/vesc.toml");
protocol_kit::protocol!("../specs/feetech.toml");
protocol_kit::protocol!("../specs/lx16a.toml");
protocol_kit::protocol!("../specs/sbp.toml");

/// Decodes a frame with generated code and encodes the packet again (`None` if it does not
/// decode or encode).
type Reencode = fn(&[u8]) -> Option<Vec<u8>>;

/// Generated `decode` then `encode`, into a buffer of the largest frame.
macro_rules! reencode {
    ($module:ident :: $packet:ident :: $decode:ident) => {
        |bytes: &[u8]| -> Option<Vec<u8>> {
            let packet = $module::$packet::$decode(bytes).ok()?;
            let mut buf = [0u8; $module::MAX_FRAME_LEN];
            let n = packet.encode(&mut buf).ok()?;
            Some(buf[..n].to_vec())
        }
    };
}

/// What a capture of golden frames is made of.
pub struct Spec {
    /// The capture's name (`examples/captures/NAME.bin`).
    pub name: &'static str,
    /// The vectors file (`tests/vectors/FILE.json`).
    vectors: &'static str,
    /// Which golden frames the capture carries (a format, a direction).
    keep: fn(&Value) -> bool,
    /// The layouts of the formats, each with the generated codec of its frames.
    formats: &'static [(&'static FrameLayout<'static>, Reencode)],
    /// The noise seed.
    seed: u64,
    /// Frames written.
    frames: usize,
    /// Whether frames are damaged (bit flips, cuts): not for a format without a check, where
    /// a damaged frame is still a frame.
    damage: bool,
}

fn any(_: &Value) -> bool {
    true
}

/// Every capture of golden frames.
pub const SPECS: &[Spec] = &[
    Spec {
        name: "crsf",
        vectors: "crsf",
        keep: any,
        formats: &[(&crsf::LAYOUT, reencode!(crsf::Packet::decode))],
        seed: 0x4352_5346_0001,
        frames: 300,
        damage: true,
    },
    Spec {
        name: "ubx",
        vectors: "ubx",
        keep: any,
        formats: &[(&ubx::LAYOUT, reencode!(ubx::Packet::decode))],
        seed: 0x5542_5800_0001,
        frames: 200,
        damage: true,
    },
    Spec {
        name: "ibus",
        vectors: "ibus",
        keep: any,
        formats: &[(&ibus::LAYOUT, reencode!(ibus::Packet::decode))],
        seed: 0x4942_5553_0001,
        frames: 200,
        damage: true,
    },
    Spec {
        name: "sbus",
        vectors: "sbus",
        keep: any,
        formats: &[(&sbus::LAYOUT, reencode!(sbus::Packet::decode))],
        seed: 0x5342_5553_0001,
        frames: 200,
        damage: false,
    },
    Spec {
        name: "mavlink",
        vectors: "mavlink",
        keep: any,
        formats: &[
            (&mavlink::LAYOUT, reencode!(mavlink::Packet::decode)),
            (&mavlink::V1_LAYOUT, reencode!(mavlink::V1Packet::decode)),
        ],
        seed: 0x4D41_564C_0001,
        frames: 300,
        damage: true,
    },
    Spec {
        name: "dynamixel1",
        vectors: "dynamixel_protocol1",
        keep: |f| f["packet"] == "instruction",
        formats: &[(
            &dynamixel1::LAYOUT,
            reencode!(dynamixel1::Packet::decode_request),
        )],
        seed: 0x4458_4C31_0001,
        frames: 300,
        damage: true,
    },
    Spec {
        name: "msp",
        vectors: "msp",
        keep: |f| f["version"] == "v1",
        formats: &[(&msp::LAYOUT, reencode!(msp::Packet::decode))],
        seed: 0x4D53_5000_0001,
        frames: 300,
        damage: true,
    },
    Spec {
        name: "vesc",
        vectors: "vesc_pyvesc",
        keep: |f| f["direction"] == "request",
        formats: &[(&vesc::LAYOUT, reencode!(vesc::Packet::decode_request))],
        seed: 0x5645_5343_0001,
        frames: 200,
        damage: true,
    },
    Spec {
        name: "feetech",
        vectors: "feetech_scservo",
        keep: |f| f["direction"] == "request",
        formats: &[(&feetech::LAYOUT, reencode!(feetech::Packet::decode_request))],
        seed: 0x5343_5300_0001,
        frames: 200,
        damage: true,
    },
    Spec {
        name: "lx16a",
        vectors: "lx16a_pylx16a",
        keep: |f| f["direction"] == "request",
        formats: &[(&lx16a::LAYOUT, reencode!(lx16a::Packet::decode_request))],
        seed: 0x4C58_3136_0001,
        frames: 200,
        damage: true,
    },
    Spec {
        name: "sbp",
        vectors: "sbp_libsbp",
        keep: any,
        formats: &[(&sbp::LAYOUT, reencode!(sbp::Packet::decode))],
        seed: 0x5342_5000_0001,
        frames: 200,
        damage: true,
    },
];

/// Lowercase hex back to bytes.
fn unhex(text: &str) -> Vec<u8> {
    (0..text.len())
        .step_by(2)
        .map(|i| u8::from_str_radix(&text[i..i + 2], 16).expect("hex"))
        .collect()
}

/// Whether `bytes` start with the sync of `layout` (a value of its sync set first, if any).
fn starts_as(layout: &FrameLayout<'_>, bytes: &[u8]) -> bool {
    let rest = if layout.sync_set.is_empty() {
        bytes
    } else {
        match bytes.split_first() {
            Some((b, rest)) if layout.sync_set.contains(b) => rest,
            _ => return false,
        }
    };
    rest.starts_with(layout.sync)
}

impl Spec {
    /// The format of a frame: its layout and codec.
    fn format(&self, frame: &[u8]) -> Option<(&'static FrameLayout<'static>, Reencode)> {
        self.formats
            .iter()
            .copied()
            .find(|(layout, _)| starts_as(layout, frame))
    }

    /// Whether `frame` is a valid frame that generated code decodes and encodes back to it.
    fn written_by_generated_code(&self, frame: &[u8]) -> bool {
        self.format(frame).is_some_and(|(layout, reencode)| {
            layout.is_valid_frame(frame) && reencode(frame).as_deref() == Some(frame)
        })
    }

    /// Whether `frame`, damaged, still passes the checks of some format: a damage the decoder
    /// cannot see (a bit no check covers).
    fn still_valid(&self, frame: &[u8]) -> bool {
        self.formats.iter().any(|(l, _)| l.is_valid_frame(frame))
    }

    /// The golden frames of the capture that generated code writes byte for byte.
    fn golden(&self) -> Vec<Vec<u8>> {
        let path = [
            env!("CARGO_MANIFEST_DIR"),
            "..",
            "tests",
            "vectors",
            &format!("{}.json", self.vectors),
        ]
        .iter()
        .collect::<std::path::PathBuf>();
        let text =
            std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let vectors: Value = serde_json::from_str(&text).expect("vectors are JSON");
        let golden: Vec<Vec<u8>> = vectors["frames"]
            .as_array()
            .expect("frames")
            .iter()
            .filter(|f| (self.keep)(f))
            .filter_map(|f| f["hex"].as_str().map(unhex))
            .filter(|frame| self.written_by_generated_code(frame))
            .collect();
        assert!(
            golden.len() >= 4,
            "{}: {} golden frames the generated code writes",
            self.name,
            golden.len()
        );
        golden
    }

    /// A golden frame with some payload bytes changed and the frame sealed again, if generated
    /// code writes the result byte for byte.
    fn varied(&self, rng: &mut Rng, golden: &[u8]) -> Option<Vec<u8>> {
        let (layout, _) = self.format(golden)?;
        let start = layout.header_span();
        let mut frame = golden.to_vec();
        if frame.len() <= start {
            return None;
        }
        for _ in 0..1 + rng.below(4) {
            let at = start + rng.below((frame.len() - start) as u64) as usize;
            frame[at] = rng.bits() as u8;
        }
        layout.seal(&mut frame).ok()?;
        self.written_by_generated_code(&frame).then_some(frame)
    }

    /// The capture: golden frames and varied ones, in a seeded order, with noise.
    pub fn capture(&'static self) -> Stream {
        let golden = self.golden();
        // Noise bytes never start a frame of a format without a check.
        let syncs: Vec<u8> = self
            .formats
            .iter()
            .flat_map(|(l, _)| l.sync_set.iter().chain(l.sync.first()).copied())
            .collect();
        let mut s = Stream::new(self.seed, &syncs);
        if !self.damage {
            s.undamaged(&syncs);
        }
        let spec = self;
        s.set_valid(Box::new(move |frame: &[u8]| spec.still_valid(frame)));
        for _ in 0..self.frames {
            let pick = &golden[s.rng.below(golden.len() as u64) as usize];
            let frame = if s.rng.chance(50) {
                self.varied(&mut s.rng, pick)
                    .unwrap_or_else(|| pick.clone())
            } else {
                pick.clone()
            };
            s.frame(&frame);
        }
        s
    }
}
