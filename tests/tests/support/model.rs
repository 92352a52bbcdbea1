//! A generator of valid frames driven by a spec's checked IR: it knows every command, which
//! payload each direction carries, where the header values are and how a payload struct is laid
//! out, so it builds frames for any spec without naming its types (payload values: [`super::payload`]).
//!
//! *Canonical* frames are the ones the encoder itself produces (padding zero, booleans 0 or 1,
//! unused bits zero, enum values that exist): those must survive decode → encode byte for byte.
//! *Raw* frames only pass the frame checks (any header values, any payload length and bytes):
//! those must decode to a value or an error, never a panic.

use std::collections::HashMap;
use std::sync::{Mutex, OnceLock};

use protocol::FrameLayout;
use protocol::decoder::Probe;
use protocol::layout::LengthRule;
use protocol::layout::WordField;
use protocol::stuffing::Stuffing;
use protocol_codegen::ir;
pub use protocol_codegen::layout::word_field;
use protocol_codegen::source::SpecSource;

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

/// A spec's IR and the generated layout of one of its frame formats; on a link of several
/// formats, the models of the others too.
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
    pub ir: ir::Protocol,
    /// The frame format (index into the IR's frames) this model builds.
    pub format: usize,
    /// The generated layout of that format (what the decoder runs on).
    pub layout: &'static FrameLayout<'static>,
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
    /// Compiles the spec of `S`.
    ///
    /// # Panics
    /// If the spec does not compile (it compiled for `protocol!` already).
    pub fn of<S: Spec>() -> Model {
        let source = SpecSource::new(S::PATH, S::TEXT);
        let ir = protocol_codegen::compile(&source)
            .unwrap_or_else(|e| panic!("{} does not compile: {e:?}", S::PATH));
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
            .map(|(&format, layout)| Model::of_format::<S>(ir.clone(), format, layout))
            .collect();
        let mut first = models.remove(0);
        first.others = models;
        first
    }

    /// The model of frame format `format` of `ir`, whose generated layout is `layout`.
    fn of_format<S: Spec>(
        ir: ir::Protocol,
        format: usize,
        layout: &'static FrameLayout<'static>,
    ) -> Model {
        let f = &ir.frames[format];
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
            choices,
            others: Vec::new(),
        }
    }

    /// The frame format this model builds.
    pub fn frame(&self) -> &ir::Frame {
        &self.ir.frames[self.format]
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

    /// Bytes before the payload of a frame of `choice`.
    fn header_len(&self, choice: Choice) -> usize {
        match (choice.carries, self.frame().ack) {
            (Carries::Ack, Some((_, len))) => len,
            _ => self.frame().header_len,
        }
    }

    /// The most (unstuffed) payload bytes a frame of `choice` can carry.
    fn payload_room(&self, choice: Choice) -> usize {
        let f = self.frame();
        f.max_len() - self.header_len(choice) - f.trailer_len
    }

    /// Fixed payload bytes of a choice (the largest size for a variable struct).
    pub fn payload_len(&self, choice: Choice) -> usize {
        choice.payload.map_or(0, |s| self.ir.structs[s].size)
    }

    /// A random choice.
    pub fn choose(&self, src: &mut impl Source) -> Choice {
        self.choices[src.below(self.choices.len() as u64) as usize]
    }

    /// A canonical frame for a random choice. A choice whose frame the layout refuses (see
    /// [`try_canonical`](Self::try_canonical)) is replaced by another.
    ///
    /// # Panics
    /// If the layout refuses every frame tried.
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
        panic!("the layout refuses every frame tried: {last:?}")
    }

    /// A canonical frame for a random choice, or why the layout refused to seal it (a frame
    /// the spec allows but the layout's bounds exclude).
    pub fn try_canonical(&self, src: &mut impl Source) -> Result<Vec<u8>, Refused> {
        self.pick(src).try_canonical_here(src)
    }

    /// [`try_canonical`](Self::try_canonical) in this model's format.
    pub fn try_canonical_here(&self, src: &mut impl Source) -> Result<Vec<u8>, Refused> {
        let choice = self.choose(src);
        self.canonical_for(src, choice)
    }

    /// A canonical frame for `choice`: its payload is what the encoder writes for some value.
    pub fn canonical_for(&self, src: &mut impl Source, choice: Choice) -> Result<Vec<u8>, Refused> {
        let room = self.payload_room(choice);
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
            if self.stuffed(&payload).len() <= room {
                break;
            }
        }
        // A format without extension fields sends a payload's base fields only.
        if let (false, Carries::Command(_), Some(base)) = (
            self.frame().extensions,
            choice.carries,
            choice.payload.and_then(|s| self.ir.structs[s].base_size),
        ) {
            payload.truncate(base);
        }
        // With trailing-zero truncation, the encoder sends the payload without its trailing
        // zeros (keeping its first byte).
        if self.frame().truncate_zeros && matches!(choice.carries, Carries::Command(_)) {
            payload.truncate(protocol::zeros::trimmed_len(&payload));
        }
        self.try_build(src, choice, &payload)
    }

    /// The payload as sent: stuffed, if the frame format stuffs.
    pub fn stuffed(&self, payload: &[u8]) -> Vec<u8> {
        let Some((after, insert)) = &self.frame().stuffing else {
            return payload.to_vec();
        };
        let rule = Stuffing {
            after,
            insert: *insert,
        };
        let mut buf = payload.to_vec();
        buf.resize(2 * payload.len() + 1, 0);
        let n = rule
            .stuff_in_place(&mut buf, payload.len())
            .expect("room to stuff");
        buf.truncate(n);
        buf
    }

    /// A frame of `choice` whose (unstuffed) payload is `payload`, any bytes: header values
    /// set, payload stuffed, sealed.
    ///
    /// # Panics
    /// If the layout refuses to seal it (a payload outside the format's bounds).
    pub fn build(&self, src: &mut impl Source, choice: Choice, payload: &[u8]) -> Vec<u8> {
        self.try_build(src, choice, payload)
            .unwrap_or_else(|e| panic!("{e:?}"))
    }

    /// [`build`](Self::build), or why the layout refused to seal the frame.
    pub fn try_build(
        &self,
        src: &mut impl Source,
        choice: Choice,
        payload: &[u8],
    ) -> Result<Vec<u8>, Refused> {
        let f = self.frame();
        let ack = choice.carries == Carries::Ack;
        let header_len = self.header_len(choice);
        let payload = self.stuffed(payload);
        let bare = ack && payload.is_empty() && f.bare_len.is_some();
        let trailer = if bare { 0 } else { f.trailer_len };
        // A wider length moves the payload behind it; a flag trailer follows everything.
        let short = header_len + payload.len() + trailer;
        let header_len = header_len + self.layout.extension_for(short);
        let flagged = f
            .flag_trailer
            .as_ref()
            .filter(|_| src.one_in(2))
            .map(|t| src.bytes(t.len));
        let body = header_len + payload.len() + trailer;
        let mut frame = vec![0u8; body + flagged.as_ref().map_or(0, Vec::len)];
        if let Some(bytes) = &flagged {
            frame[body..].copy_from_slice(bytes);
        }
        for (i, v) in f.values.iter().enumerate() {
            let value = match &v.role {
                ir::Role::Const(c) => *c,
                ir::Role::Length | ir::Role::WideLength => continue,
                ir::Role::Flag => u64::from(flagged.is_some()),
                ir::Role::Dispatch => match choice.carries {
                    Carries::Command(c) => {
                        let k = f
                            .dispatch
                            .iter()
                            .position(|&d| d == i)
                            .expect("dispatch value");
                        self.ir.commands[c].id[k]
                    }
                    _ => continue,
                },
                ir::Role::Ack(flag) if ack => *flag,
                ir::Role::Ack(flag) => !flag & word_field(v).max_value(),
                ir::Role::User { .. } => self.user_value(src, choice, i, v),
            };
            if bare && matches!(v.at, ir::Pos::End(_)) {
                continue;
            }
            word_field(v)
                .write(&mut frame, value)
                .expect("header value fits");
        }
        frame[header_len..header_len + payload.len()].copy_from_slice(&payload);
        self.layout.seal(&mut frame).map_err(|error| Refused {
            choice,
            len: frame.len(),
            error,
        })?;
        Ok(self.checked(frame))
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
        // A wider length moves the payload behind it; a flag trailer follows everything.
        let short = f.header_len + len + f.trailer_len;
        let header_len = f.header_len + self.layout.extension_for(short);
        let flagged = f
            .flag_trailer
            .as_ref()
            .filter(|_| src.one_in(2))
            .map(|t| t.len);
        let mut frame = vec![0u8; short + header_len - f.header_len + flagged.unwrap_or(0)];
        // A check that folds in a per-command byte verifies only the frames of known commands.
        let known_key = f.checks.iter().any(|c| c.extra.is_some()) && !self.ir.commands.is_empty();
        let command = src.below(self.ir.commands.len().max(1) as u64) as usize;
        for (i, v) in f.values.iter().enumerate() {
            let field = word_field(v);
            let value = match v.role {
                ir::Role::Length | ir::Role::WideLength => continue,
                ir::Role::Flag => u64::from(flagged.is_some()),
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
        let end = header_len + len;
        let payload = src.bytes(len);
        frame[header_len..end].copy_from_slice(&payload);
        self.layout.seal(&mut frame).expect("seal");
        self.checked(frame)
    }

    /// Checks that a sealed frame is a valid frame of the layout.
    fn checked(&self, frame: Vec<u8>) -> Vec<u8> {
        assert_eq!(
            self.layout.probe(&frame),
            Probe::Frame(frame.len()),
            "sealed frame is valid"
        );
        frame
    }

    /// A value of the first frame's sync set.
    fn sync_value(&self, src: &mut impl Source) -> u64 {
        let set = &self.frame().sync_set;
        let k = src.range(0, set.len() as u64 - 1) as usize;
        u64::from(set[k])
    }

    /// A header value set by the user: the direction's range or value for the field that
    /// tells the direction, a value of the sync set for a sync from a set, anything that fits
    /// otherwise.
    fn user_value(
        &self,
        src: &mut impl Source,
        choice: Choice,
        index: usize,
        v: &ir::HeaderValue,
    ) -> u64 {
        if let Some(d) = choice.direction {
            // A rule names a header value of the first format; a link's other formats carry
            // the field of the same name.
            let first = &self.ir.frames[0].values;
            let here = |value: usize| {
                first
                    .get(value)
                    .is_some_and(|x| x.name == self.frame().values[index].name)
            };
            match self.ir.directions[d].rule {
                ir::DirectionRule::InSet { value, set } if here(value) => {
                    let set = &self.ir.addresses[set];
                    return src.range(set.first, set.last);
                }
                ir::DirectionRule::Equals { value, equals } if here(value) => return equals,
                _ => {}
            }
        }
        if index == 0 && !self.frame().sync_set.is_empty() {
            return self.sync_value(src);
        }
        src.next_u64() & word_field(v).max_value()
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

/// A frame the spec allows but the generated layout refuses to seal.
#[derive(Debug, Clone)]
pub struct Refused {
    /// What the frame carried.
    pub choice: Choice,
    /// Its length.
    pub len: usize,
    /// What `seal` said.
    pub error: protocol::EncodeError,
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
