//! A generator of valid frames driven by a spec's checked IR: it knows every command, which
//! payload each direction carries, where the header values are and how a payload struct is laid
//! out, so it builds frames for any spec without naming its types (payload values: [`super::payload`]).
//!
//! The model assembles its frames through the runtime's packet rules ([`PacketRules`], lowered
//! from the IR as for generated code and the run-time codec), so the suites test the codecs on
//! the spec's frames rather than against a second copy of those rules; the rules themselves are
//! checked independently by the golden vectors the protocols' reference implementations wrote
//! and by the C peer, which executes the same plan in separately written C. What stays the
//! model's own is what to send: commands, directions, payload values and header values.
//!
//! *Canonical* frames are the ones the encoder itself produces (padding zero, booleans 0 or 1,
//! unused bits zero, enum values that exist): those must survive decode → encode byte for byte.
//! *Raw* frames only pass the frame checks (any header values, any payload length and bytes):
//! those must decode to a value or an error, never a panic.
//!
//! Every frame comes as it goes on the wire: escaped, for a format that escapes its frames
//! between flags (a decoder yields it unescaped: [`super::unescaped`]).

use std::collections::HashMap;
use std::sync::{Mutex, OnceLock};

use protocol_codegen::ir;
pub use protocol_codegen::layout::word_field;
use protocol_codegen::rules::{self as lowered, RulesPlan, lower_rules};
use protocol_codegen::source::SpecSource;
use protocol_kit::FrameLayout;
use protocol_kit::decoder::Probe;
use protocol_kit::encoder::write_header;
use protocol_kit::layout::{LengthRule, WordField};
use protocol_kit::rules::{Body, DirectionTest, PacketRules};

use super::payload::Ctx;
use super::{Source, Spec};

/// What a frame carries.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Carries {
    /// A command (index into the IR's commands).
    Command(usize),
    /// An acknowledgement: the ack flag set, no dispatch fields, any data.
    Ack,
    /// The one struct of a frame format without dispatch.
    Message,
}

/// One way a frame can be sent: a command in a direction with that direction's payload, an
/// acknowledgement, or the message of a frame format without dispatch.
#[derive(Debug, Clone, Copy)]
pub struct Choice {
    /// What the frame carries.
    pub carries: Carries,
    /// Index into the IR's directions (`None` when the spec has none).
    pub direction: Option<usize>,
    /// The payload struct (`None`: empty payload, or raw data for an acknowledgement).
    pub payload: Option<usize>,
}

/// A spec's IR, the generated layout of one of its frame formats and that format's packet
/// rules; on a link of several formats, the models of the others too.
///
/// The methods that build one frame build it in this model's format; [`canonical`],
/// [`try_canonical`] and [`raw`] first pick a format of the link at random (this one when the
/// link has one), so that the suites send frames of every format.
///
/// [`canonical`]: Self::canonical
/// [`try_canonical`]: Self::try_canonical
/// [`raw`]: Self::raw
pub struct Model {
    /// The checked protocol.
    pub ir: &'static ir::Protocol,
    /// The frame format (index into the IR's frames) this model builds.
    pub format: usize,
    /// The generated layout of that format (what the decoder runs on).
    pub layout: &'static FrameLayout<'static>,
    /// The format's packet rules, lowered from the IR ([`rules`](Self::rules)).
    plan: RulesPlan<'static>,
    /// The key fields the rules borrow.
    key: Vec<WordField>,
    /// The direction tests the rules borrow.
    directions: Vec<DirectionTest>,
    /// Every way a frame can be sent.
    pub choices: Vec<Choice>,
    /// The link's other formats, in the order of the decoder's `Frame::format` (empty when
    /// the spec is tested through one format).
    pub others: Vec<Model>,
}

/// The model of `S`, compiled once per process.
pub fn model<S: Spec>() -> &'static Model {
    static MODELS: OnceLock<Mutex<HashMap<&'static str, &'static Model>>> = OnceLock::new();
    let mut models = MODELS
        .get_or_init(Default::default)
        .lock()
        .expect("model cache");
    models
        .entry(S::NAME)
        .or_insert_with(|| Box::leak(Box::new(Model::of::<S>())))
}

impl Model {
    /// Compiles the spec of `S`. The IR lives for the process (the rules borrow it), as the
    /// model does in [`model`].
    ///
    /// # Panics
    /// If the spec does not compile (it compiled for `protocol!` already).
    pub fn of<S: Spec>() -> Model {
        let source = SpecSource::new(S::PATH, S::TEXT);
        let ir: &'static ir::Protocol = Box::leak(Box::new(
            protocol_codegen::compile(&source)
                .unwrap_or_else(|e| panic!("{} does not compile: {e:?}", S::PATH)),
        ));
        // The formats the decoder finds: the link's (in its order), or the first alone.
        let formats = if ir.link.is_empty() {
            vec![0]
        } else {
            ir.link.clone()
        };
        let layouts = S::layouts();
        assert!(
            layouts.len() <= formats.len(),
            "{}: more layouts than formats",
            S::NAME
        );
        let mut models: Vec<Model> = formats
            .iter()
            .zip(layouts)
            .map(|(&format, layout)| Model::of_format::<S>(ir, format, layout))
            .collect();
        let mut first = models.remove(0);
        first.others = models;
        first
    }

    /// The model of frame format `format` of `ir`, whose generated layout is `layout`.
    fn of_format<S: Spec>(
        ir: &'static ir::Protocol,
        format: usize,
        layout: &'static FrameLayout<'static>,
    ) -> Model {
        let f = &ir.frames[format];
        let plan = lower_rules(ir, f);
        let mut choices = Vec::new();
        if let Some(s) = f.message {
            choices.push(Choice {
                carries: Carries::Message,
                direction: None,
                payload: Some(s),
            });
        }
        // The commands this format carries (a link's wider format may carry more).
        for (command, c) in ir
            .commands
            .iter()
            .enumerate()
            .filter(|(ci, _)| f.message.is_none() && f.commands.contains(ci))
        {
            let carries = Carries::Command(command);
            if ir.directions.is_empty() {
                let payload = c.payloads.first().copied().flatten();
                choices.push(Choice {
                    carries,
                    direction: None,
                    payload,
                });
            } else {
                // A decoder given its direction reads only the frames of that direction.
                let decoded =
                    S::DIRECTION.and_then(|d| ir.directions.iter().position(|x| x.name == d));
                for direction in
                    (0..ir.directions.len()).filter(|&d| decoded.is_none_or(|x| x == d))
                {
                    let payload = c.payloads.get(direction).copied().flatten();
                    choices.push(Choice {
                        carries,
                        direction: Some(direction),
                        payload,
                    });
                }
            }
        }
        if f.ack.is_some() {
            choices.push(Choice {
                carries: Carries::Ack,
                direction: None,
                payload: None,
            });
        }
        Model {
            ir,
            format,
            layout,
            key: plan.key_fields(),
            directions: plan.direction_tests(),
            plan,
            choices,
            others: Vec::new(),
        }
    }

    /// The frame format this model builds.
    pub fn frame(&self) -> &ir::Frame {
        &self.ir.frames[self.format]
    }

    /// The packet rules of this model's format, on its generated layout.
    pub fn rules(&self) -> PacketRules<'_> {
        self.plan.rules(self.layout, &self.key, &self.directions)
    }

    /// This format and the link's others, in the decoder's order.
    pub fn formats(&self) -> impl Iterator<Item = &Model> {
        std::iter::once(self).chain(&self.others)
    }

    /// A format of the link at random (this one when the link has one: no choice is drawn).
    pub fn pick(&self, src: &mut impl Source) -> &Model {
        if self.others.is_empty() {
            return self;
        }
        match src.below(1 + self.others.len() as u64) as usize {
            0 => self,
            k => &self.others[k - 1],
        }
    }

    /// The format whose sync `bytes` start with (this one if none).
    pub fn format_for(&self, bytes: &[u8]) -> &Model {
        self.formats()
            .find(|m| super::starts_as(m.layout, bytes))
            .unwrap_or(self)
    }

    /// The longest frame of any format.
    pub fn max_len(&self) -> usize {
        self.formats().map(|m| m.layout.max_len).max().unwrap_or(0)
    }

    /// Fixed payload bytes of a choice (the largest size for a variable struct).
    pub fn payload_len(&self, choice: Choice) -> usize {
        choice.payload.map_or(0, |s| self.ir.structs[s].size)
    }

    /// A random choice.
    pub fn choose(&self, src: &mut impl Source) -> Choice {
        self.choices[src.below(self.choices.len() as u64) as usize]
    }

    /// A canonical frame for a random choice. A choice whose frame the rules refuse (see
    /// [`try_canonical`](Self::try_canonical)) is replaced by another.
    ///
    /// # Panics
    /// If the rules refuse every frame tried.
    pub fn canonical(&self, src: &mut impl Source) -> Vec<u8> {
        self.pick(src).canonical_here(src)
    }

    /// [`canonical`](Self::canonical) in this model's format.
    pub fn canonical_here(&self, src: &mut impl Source) -> Vec<u8> {
        let mut last = None;
        for _ in 0..16 {
            match self.try_canonical_here(src) {
                Ok(frame) => return frame,
                Err(e) => last = Some(e),
            }
        }
        panic!("the rules refuse every frame tried: {last:?}")
    }

    /// A canonical frame for a random choice, or why the rules refused to assemble it (a frame
    /// the spec allows but the layout's bounds exclude).
    pub fn try_canonical(&self, src: &mut impl Source) -> Result<Vec<u8>, Refused> {
        self.pick(src).try_canonical_here(src)
    }

    /// [`try_canonical`](Self::try_canonical) in this model's format.
    pub fn try_canonical_here(&self, src: &mut impl Source) -> Result<Vec<u8>, Refused> {
        let choice = self.choose(src);
        self.canonical_for(src, choice)
    }

    /// A canonical frame for `choice`: its payload is what the encoder writes for some value,
    /// sent as the rules send it (for a format without extension fields, the fields before
    /// them).
    pub fn canonical_for(&self, src: &mut impl Source, choice: Choice) -> Result<Vec<u8>, Refused> {
        let rules = self.rules();
        let key = self.key_values(choice);
        let carried = choice
            .payload
            .and_then(|s| self.ir.structs[s].base_size)
            .filter(|_| !self.frame().extensions);
        let body = self.body(choice, &key, carried);
        let room = match choice.carries {
            Carries::Ack => rules.ack_max(),
            _ => rules.max_payload,
        };
        // Stuffing may lengthen the payload: retry with smaller variable parts if it no longer
        // fits (rare: the pattern must occur in random bytes).
        let mut payload = Vec::new();
        for attempt in 0..4 {
            let budget = room >> attempt;
            payload.clear();
            match (choice.carries, choice.payload) {
                (Carries::Ack, _) => {
                    let n = src.len(budget);
                    payload = src.bytes(n);
                }
                (_, Some(s)) => {
                    self.canonical_struct(src, s, budget, &mut Ctx::default(), &mut payload)
                }
                (_, None) => {}
            }
            if rules.wire_len(&body, &payload) <= room {
                break;
            }
        }
        self.assemble(src, choice, &rules, &body, &payload)
    }

    /// A frame of `choice` whose payload is `payload` as it is, any bytes (not cut to the
    /// carried fields, trailing zeros kept): header values set, payload stuffed, sealed.
    ///
    /// # Panics
    /// If the rules refuse to assemble it (a payload outside the format's bounds).
    pub fn build(&self, src: &mut impl Source, choice: Choice, payload: &[u8]) -> Vec<u8> {
        self.try_build(src, choice, payload)
            .unwrap_or_else(|e| panic!("{e:?}"))
    }

    /// [`build`](Self::build), or why the rules refused to assemble the frame.
    pub fn try_build(
        &self,
        src: &mut impl Source,
        choice: Choice,
        payload: &[u8],
    ) -> Result<Vec<u8>, Refused> {
        // The format's rules, except that the payload is sent whole: a payload the encoder
        // would trim is one the decoder must read too.
        let rules = PacketRules {
            truncate_zeros: false,
            ..self.rules()
        };
        let key = self.key_values(choice);
        let body = self.body(choice, &key, None);
        self.assemble(src, choice, &rules, &body, payload)
    }

    /// What a frame of `choice` carries, as the rules take it: `key` its key's values,
    /// `carried` the payload bytes a format without extension fields sends.
    fn body<'k>(&self, choice: Choice, key: &'k [u64], carried: Option<usize>) -> Body<'k> {
        match choice.carries {
            Carries::Command(_) => Body::Command {
                key,
                carried,
                direction: choice.direction,
            },
            Carries::Ack => Body::Ack,
            Carries::Message => Body::Struct {
                start: self.plan.header_len,
            },
        }
    }

    /// The key's values of a frame of `choice`: the command's id, or its CAN id in a format
    /// keyed by the CAN identifier (none for a frame without command).
    fn key_values(&self, choice: Choice) -> Vec<u64> {
        let Carries::Command(c) = choice.carries else {
            return Vec::new();
        };
        let command = &self.ir.commands[c];
        match self.plan.carries {
            lowered::Carries::CanCommand => command.can_id.into_iter().collect(),
            _ => command.id.clone(),
        }
    }

    /// The frame `rules` assemble for `body` with `payload`, header values chosen for `choice`
    /// and, half the time, a flag trailer; checked by the layout.
    fn assemble(
        &self,
        src: &mut impl Source,
        choice: Choice,
        rules: &PacketRules<'_>,
        body: &Body<'_>,
        payload: &[u8],
    ) -> Result<Vec<u8>, Refused> {
        let flagged = self
            .frame()
            .flag_trailer
            .as_ref()
            .filter(|_| src.one_in(2))
            .map(|t| src.bytes(t.len));
        let flag_len = flagged.as_ref().map_or(0, Vec::len);
        let len = rules.frame_len(body, rules.wire_len(body, payload), flag_len);
        // Room for a trailer past the frame: `assemble` asks for it before it knows that an
        // acknowledgement without data is a bare header. An escaped frame may take twice its
        // bytes on the wire.
        let room = len + rules.trailer_len;
        let mut frame = vec![
            0u8;
            if self.layout.escape.is_some() {
                2 * room
            } else {
                room
            }
        ];
        let mut aside = vec![0u8; payload.len()];
        let assembled = rules.assemble(
            &mut frame,
            &mut aside,
            body,
            || len,
            flag_len,
            |w| w.put_bytes(payload),
            |frame| self.header_values(src, choice, flagged.as_deref(), frame),
        );
        match assembled {
            Ok(n) => {
                frame.truncate(n);
                Ok(self.checked(frame))
            }
            Err(error) => Err(Refused { choice, len, error }),
        }
    }

    /// Writes the header values a sender sets into `frame`: a value of the direction's test
    /// for the field that tells the direction of `choice`, a value of the sync set for a sync
    /// from a set, any value that fits for the others; the flag of a flag trailer and its
    /// bytes.
    fn header_values(
        &self,
        src: &mut impl Source,
        choice: Choice,
        flagged: Option<&[u8]>,
        frame: &mut [u8],
    ) -> Result<(), protocol_kit::EncodeError> {
        let test = choice.direction.and_then(|d| self.directions.get(d));
        for (i, v) in self.frame().values.iter().enumerate() {
            let field = word_field(v);
            let value = match (&v.role, test) {
                (
                    ir::Role::User { .. },
                    Some(&DirectionTest::InRange {
                        field: f,
                        first,
                        last,
                    }),
                ) if f == field => src.range(first, last),
                (ir::Role::User { .. }, Some(&DirectionTest::Equals { field: f, value }))
                    if f == field =>
                {
                    value
                }
                (ir::Role::User { .. }, _) if i == 0 && !self.frame().sync_set.is_empty() => {
                    self.sync_value(src)
                }
                (ir::Role::User { .. }, _) => src.next_u64() & field.max_value(),
                (ir::Role::Flag, _) => u64::from(flagged.is_some()),
                // The layout and the rules write the others.
                _ => continue,
            };
            write_header(frame, field, value)?;
        }
        if let Some(bytes) = flagged {
            let at = frame.len() - bytes.len();
            frame[at..].copy_from_slice(bytes);
        }
        Ok(())
    }

    /// A frame that passes every check but is otherwise random: any header values (an unknown
    /// command, an address in no direction's range, the ack flag), any payload length and
    /// bytes (unstuffed: possibly invalid stuffing).
    pub fn raw(&self, src: &mut impl Source) -> Vec<u8> {
        self.pick(src).raw_here(src)
    }

    /// [`raw`](Self::raw) in this model's format.
    pub fn raw_here(&self, src: &mut impl Source) -> Vec<u8> {
        let f = self.frame();
        // Half of them carry a real command with random payload bytes of its size: those reach
        // the payload decoders (an unknown command stops at the dispatch).
        if src.one_in(2) {
            let choice = self.choose(src);
            let st = choice.payload.map(|s| &self.ir.structs[s]);
            let len = st.map_or(0, |st| st.min_size + src.len(st.size - st.min_size));
            let payload = src.bytes(len);
            if let Ok(frame) = self.try_build(src, choice, &payload) {
                return frame;
            }
        }
        let len = f.payload_min + src.len(f.payload_max - f.payload_min);
        self.raw_with_payload_len(src, len)
    }

    /// [`raw`](Self::raw) with a payload of `len` bytes.
    pub fn raw_with_payload_len(&self, src: &mut impl Source, len: usize) -> Vec<u8> {
        let f = self.frame();
        let flagged = f
            .flag_trailer
            .as_ref()
            .filter(|_| src.one_in(2))
            .map_or(0, |t| t.len);
        // The length of a frame with that payload after the header; every byte after the
        // header is random, and sealing writes a wider length, the checks and the markers.
        let payload = Body::Struct {
            start: f.header_len,
        };
        let mut frame = vec![0u8; self.rules().frame_len(&payload, len, flagged)];
        let after = src.bytes(frame.len() - f.header_len);
        frame[f.header_len..].copy_from_slice(&after);
        // A format whose dispatch fields are narrower than some ids (MAVLink 1's one-byte id)
        // carries only the commands whose ids fit them.
        let fits = |c: &ir::Command| {
            f.dispatch
                .iter()
                .zip(&c.id)
                .all(|(&d, &id)| id <= word_field(&f.values[d]).max_value())
        };
        let carried: Vec<usize> = (0..self.ir.commands.len())
            .filter(|&c| fits(&self.ir.commands[c]))
            .collect();
        // A check that folds in a per-command byte verifies only the frames of known commands.
        let known_key = f.checks.iter().any(|c| c.extra.is_some()) && !carried.is_empty();
        let pick = src.below(carried.len().max(1) as u64) as usize;
        let command = carried.get(pick).copied().unwrap_or(0);
        for (i, v) in f.values.iter().enumerate() {
            let field = word_field(v);
            let value = match v.role {
                ir::Role::Length | ir::Role::WideLength => continue,
                ir::Role::Flag => u64::from(flagged > 0),
                ir::Role::Const(c) if !src.one_in(8) => c,
                ir::Role::Dispatch if known_key => {
                    let k = f
                        .dispatch
                        .iter()
                        .position(|&d| std::ptr::eq(&f.values[d], v));
                    self.ir.commands[command].id[k.expect("dispatch value")]
                }
                // A sync from a set: the frame is found only with a value of the set.
                ir::Role::User { .. } if i == 0 && !f.sync_set.is_empty() => self.sync_value(src),
                _ => src.next_u64() & field.max_value(),
            };
            field.write(&mut frame, value).expect("header value fits");
        }
        self.layout.seal(&mut frame).expect("seal");
        if let Some(escape) = self.layout.escape {
            let len = frame.len();
            frame.resize(2 * len, 0);
            let n = escape
                .escape_in_place(&mut frame, len)
                .expect("room to escape");
            frame.truncate(n);
        }
        self.checked(frame)
    }

    /// Checks that a sealed frame, as it goes on the wire, is one valid frame of the layout
    /// (escaped whole, for a format that escapes its frames).
    fn checked(&self, wire: Vec<u8>) -> Vec<u8> {
        let frame = super::unescaped(self.layout, &wire);
        assert_eq!(
            self.layout.probe(&frame),
            Probe::Frame(frame.len()),
            "sealed frame is valid"
        );
        if let Some(escape) = self.layout.escape {
            assert_eq!(
                escape.escaped_len(&frame),
                wire.len(),
                "an escaped frame holds no flag before its last byte"
            );
        }
        wire
    }

    /// A value of the first frame's sync set.
    fn sync_value(&self, src: &mut impl Source) -> u64 {
        let set = &self.frame().sync_set;
        let k = src.range(0, set.len() as u64 - 1) as usize;
        u64::from(set[k])
    }
}

/// A sync as it stands on the wire: the `pick`-th value (modulo their number) of a sync set, if
/// the layout has one, then the sync bytes.
pub fn sync_word(layout: &FrameLayout<'_>, pick: usize) -> Vec<u8> {
    let set = layout.sync_set;
    let lead = set.get(pick % set.len().max(1)).copied();
    lead.into_iter()
        .chain(layout.sync.iter().copied())
        .collect()
}

/// A frame the spec allows but the packet rules refuse to assemble (the layout's bounds exclude
/// it).
#[derive(Debug, Clone)]
pub struct Refused {
    /// What the frame carried.
    pub choice: Choice,
    /// Its length.
    pub len: usize,
    /// What `assemble` said.
    pub error: protocol_kit::EncodeError,
}

/// The length field of the layout, with the adjustment (`None` for fixed-length frames).
pub fn length_field(layout: &FrameLayout<'_>) -> Option<(WordField, i64)> {
    match layout.length {
        LengthRule::Field { field, adjust }
        | LengthRule::FieldOrBare { field, adjust, .. }
        | LengthRule::Conditional { field, adjust, .. } => Some((field, adjust)),
        LengthRule::Fixed(_) => None,
    }
}
