//! The frame formats of the IR: transport, layout elements, header values, lengths, checks and
//! trailers, and the names generated code gives each format's items.

use super::{Algorithm, ByteOrder, Pos, Prim, Scalar, WordField};

/// How frames travel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Transport {
    /// A byte stream (UART, USB serial, TCP): frames are found by their sync bytes.
    Serial,
    /// CAN: a frame is an id and up to 8 data bytes. The frame's first two values are the
    /// virtual `can_id` (a big-endian `u32` word) and `dlc` (a `u8`), so checks may cover them;
    /// the data bytes follow.
    Can {
        /// 29-bit ids (CAN 2.0B) instead of 11-bit ones.
        extended: bool,
    },
}

/// Bytes of the virtual `can_id` + `dlc` prefix of a CAN frame.
pub const CAN_PREFIX_LEN: usize = 5;

/// A frame format.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// Name as written (snake_case).
    pub name: String,
    /// The Rust names of the frame format's items.
    pub names: FrameNames,
    /// How the frames travel.
    pub transport: Transport,
    /// Documentation.
    pub doc: String,
    /// Sync bytes at offset 0 (empty when `sync_set` is not).
    pub sync: Vec<u8>,
    /// The values of a sync from a set (a field with `one_of` as the first element): the
    /// frame's first header value, a `u8` at offset 0, holds one of them, and the decoder
    /// searches for any of them. Empty for a frame that starts with `sync`.
    pub sync_set: Vec<u8>,
    /// Bytes from the frame start to the payload (sync, header fields, header checks).
    pub header_len: usize,
    /// Bytes after the payload (frame checks, trailers).
    pub trailer_len: usize,
    /// Bytes a stream decoder needs before it knows a frame's length and has verified its
    /// header: through the sync, the length field, the flag that announces optional bytes,
    /// the constants and the header checks (fields after them, such as a command id, are part
    /// of what the length counts).
    pub decide_len: usize,
    /// Smallest payload.
    pub payload_min: usize,
    /// Largest payload.
    pub payload_max: usize,
    /// Header values (fields and bitfield members) in wire order.
    pub values: Vec<HeaderValue>,
    /// How the total frame length is known.
    pub length: Length,
    /// Indices into `values` of the dispatch key fields, in key order (empty: no dispatch).
    pub dispatch: Vec<usize>,
    /// Checks in the order they are verified on decode and computed on encode (header checks
    /// first, then frame checks in wire order).
    pub checks: Vec<Check>,
    /// Constant byte runs after the payload (trailers such as an end word).
    pub trailers: Vec<Trailer>,
    /// The wire elements in order, for docs and diagrams.
    pub elements: Vec<Element>,
    /// Acknowledgements: the index of the one-bit flag in `values` (role [`Role::Ack`]), and
    /// the bytes of an acknowledgement's header (the dispatch fields are absent).
    pub ack: Option<(usize, usize)>,
    /// Length of a bare header, when the frame may be the header alone.
    pub bare_len: Option<usize>,
    /// Byte stuffing of the payload: the pattern, and the byte inserted after it.
    pub stuffing: Option<(Vec<u8>, u8)>,
    /// Byte escaping of the whole frame between its flags (the sync and the last trailer).
    pub escape: Option<Escape>,
    /// Trailing-zero truncation of command payloads: the sender drops the zeros at the end of
    /// a payload (keeping its first byte), the receiver zero-fills it to its struct's size.
    pub truncate_zeros: bool,
    /// For a frame format without dispatch key: the struct (index into
    /// [`Protocol::structs`](super::Protocol::structs)) every frame carries.
    pub message: Option<usize>,
    /// What a whole decoded frame of this format holds, when it has a packet type.
    pub packet: PacketKind,
    /// False when the format carries payloads without their extension fields (a struct's
    /// [`Struct::base_size`](super::Struct::base_size) bytes).
    pub extensions: bool,
    /// The header value (index into [`Frame::values`]) that tells the direction, in a spec
    /// whose header tells its directions: set on the first format and on each format after it
    /// that carries the commands (the field of the same name).
    pub direction: Option<usize>,
    /// The commands (indices into [`Protocol::commands`](super::Protocol::commands)) this
    /// format carries: every command for the first format with a dispatch key; for a format with
    /// [`PacketKind::Commands`], those whose id fits its dispatch fields; else none.
    pub commands: Vec<usize>,
    /// Bytes at the end of the frame, after its checks and trailers, present when a header
    /// flag is set (the MAVLink 2 signature).
    pub flag_trailer: Option<FlagTrailer>,
    /// A wider length that a marker value of the length field announces (MSP v1 jumbo
    /// frames): its bytes follow the header, and the payload starts after them.
    pub length_extension: Option<LengthExtension>,
    /// The header value (index into `values`) that counts frames (`counter = true`): the
    /// sender adds one per frame, wrapping at its width. Decode-side statistics only (lost and
    /// reordered frames); no codec checks it.
    pub counter: Option<usize>,
    /// Where the spec declares the payload, for messages of generated code, which cannot
    /// point into the spec: `PATH:LINE:COL` and the line as written
    /// ([`crate::resources::payload_origin`]); set by [`crate::compile`], which knows the
    /// spec's path.
    pub payload_origin: String,
}

/// A wider length, right after the header, present when the length field holds a marker
/// value; it counts what the length field counts. A frame uses it exactly when the count does
/// not fit below the marker.
#[derive(Debug, Clone, PartialEq)]
pub struct LengthExtension {
    /// The wider length (index into [`Frame::values`], role [`Role::WideLength`]).
    pub value: usize,
    /// The length field's value that announces it.
    pub marker: u64,
    /// Its bytes.
    pub len: usize,
}

/// Bytes at the end of a frame present when a one-bit header flag is set: carried as they are
/// (a MAVLink 2 signature is not verified: that needs a key).
#[derive(Debug, Clone, PartialEq)]
pub struct FlagTrailer {
    /// Name (snake_case): the `Header` field that holds the bytes.
    pub name: String,
    /// Documentation.
    pub doc: String,
    /// The flag (index into [`Frame::values`], role [`Role::Flag`]).
    pub flag: usize,
    /// How many bytes.
    pub len: usize,
}

/// The packet type of a frame format: what a whole decoded frame holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PacketKind {
    /// No packet type of its own.
    None,
    /// The first frame format, with a dispatch key: a header and a command's message.
    Command,
    /// A serial frame format without dispatch key, in a spec whose first frame format has one:
    /// a header and the struct (index into [`Protocol::structs`](super::Protocol::structs))
    /// every frame carries.
    Message(usize),
    /// A CAN frame format other than the first, in a spec without directions whose first frame
    /// format has a dispatch key: a header and a command's message, the command found from the
    /// CAN id.
    Can,
    /// A serial frame format after the first that carries the commands too (`commands =
    /// true`): a header and a command's message, the command found from its own dispatch key.
    /// The link's decoder finds its frames beside the first format's.
    Commands,
}

impl Frame {
    /// Smallest total frame length (not counting a bare header): an acknowledgement without
    /// dispatch fields and with no data may be shorter than the smallest command frame.
    pub fn min_len(&self) -> usize {
        let command = self.header_len + self.payload_min + self.trailer_len;
        match self.ack {
            Some((_, ack_header_len)) => command.min(ack_header_len + self.trailer_len),
            None => command,
        }
    }
    /// Largest total frame length (with a flag trailer, if the frame has one).
    pub fn max_len(&self) -> usize {
        self.header_len
            + self.length_extension.as_ref().map_or(0, |e| e.len)
            + self.payload_max
            + self.trailer_len
            + self.flag_trailer_len()
    }
    /// Bytes of the flag trailer when present (0 without one).
    pub fn flag_trailer_len(&self) -> usize {
        self.flag_trailer.as_ref().map_or(0, |t| t.len)
    }
}

/// The Rust names of a frame format's items. The first (default) frame format's items have
/// the plain names (`Header`, `Decoder`, ...); another's carry its PascalCase name
/// (`ScoutHeader`, `ScoutDecoder`, ...), and its consts its upper-case name (`SCOUT_`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FrameNames {
    /// PascalCase of the frame name (`scout` -> `Scout`).
    pub pascal: String,
    /// Prefix of the frame's consts and statics: empty for the first frame, else `NAME_`.
    pub const_prefix: String,
    /// The struct of the header values a sender sets.
    pub header: String,
    /// The type of a whole decoded frame.
    pub packet: String,
    /// The type of the frame's layout.
    pub layout: String,
    /// The stream decoder type.
    pub decoder: String,
    /// The function that makes a stream decoder.
    pub decoder_fn: String,
    /// The `FrameLayout` static (`LAYOUT`, `SCOUT_CAN_LAYOUT`).
    pub layout_static: String,
    /// The `PacketRules` static (`RULES`, `SCOUT_CAN_RULES`).
    pub rules_static: String,
    /// The size consts (`MAX_FRAME_LEN`, `SCOUT_CAN_HEADER_LEN`, ...).
    pub sizes: FrameSizeNames,
    /// The `wire` const of each header value, in the order of [`Frame::values`].
    pub wire: Vec<String>,
}

/// The names of a frame format's size consts.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FrameSizeNames {
    /// Largest frame.
    pub max_frame_len: String,
    /// Smallest frame.
    pub min_frame_len: String,
    /// Largest payload.
    pub max_payload_len: String,
    /// Smallest payload.
    pub min_payload_len: String,
    /// Bytes before the payload.
    pub header_len: String,
    /// Bytes after the payload.
    pub trailer_len: String,
    /// The stream decoder's buffer.
    pub decoder_buffer_len: String,
}

/// One element of a frame layout, for docs.
#[derive(Debug, Clone, PartialEq)]
pub enum Element {
    /// Sync bytes.
    Sync(Vec<u8>),
    /// A header word (index of its first value in `Frame::values`; `len` values share it).
    Word {
        /// Name of the word (field name).
        name: String,
        /// Where the word is.
        at: Pos,
        /// Wire type.
        scalar: Scalar,
        /// Indices into `Frame::values`.
        values: Vec<usize>,
    },
    /// The payload.
    Payload,
    /// A check (index into `Frame::checks`).
    Check(usize),
    /// A trailer (index into `Frame::trailers`).
    Trailer(usize),
    /// The flag trailer ([`Frame::flag_trailer`]), last.
    FlagTrailer,
}

/// A value stored in the header: a whole field, or some bits of a header word.
#[derive(Debug, Clone, PartialEq)]
pub struct HeaderValue {
    /// Name (snake_case).
    pub name: String,
    /// Documentation.
    pub doc: String,
    /// Where the word is: from the start for header values, back from the end for values
    /// after the payload (such as a rolling counter before the checksum).
    pub at: Pos,
    /// The word on the wire.
    pub word: Scalar,
    /// Lowest bit of the value in the word (0 for a whole field).
    pub shift: u32,
    /// Number of bits (8 * size for a whole field).
    pub width: u32,
    /// Rust type of the value.
    pub prim: Prim,
    /// What the value is for.
    pub role: Role,
}

/// What a header value is for.
#[derive(Debug, Clone, PartialEq)]
pub enum Role {
    /// Set by the user, exposed in the generated `Header` struct.
    User {
        /// True when the spec marks the field as holding addresses of `[addresses]`.
        addresses: bool,
    },
    /// The length field (see [`Frame::length`]); computed on encode.
    Length,
    /// Part of the dispatch key; set from the command on encode.
    Dispatch,
    /// Must equal this value; written on encode, checked on decode.
    Const(u64),
    /// The acknowledgement flag: equals the value when the frame is an acknowledgement; set by
    /// the codec from the message.
    Ack(u64),
    /// The flag of the frame's flag trailer ([`Frame::flag_trailer`]): set when the trailer is
    /// present; set by the codec from the header's trailer.
    Flag,
    /// The wider length of a [`LengthExtension`]: computed on encode, present only when the
    /// length field holds the marker.
    WideLength,
}

/// How the total length of a frame is known.
#[derive(Debug, Clone, PartialEq)]
pub enum Length {
    /// Every frame has the same length.
    Fixed(usize),
    /// `total = value + adjust`, where `value` is the header value at index `value`.
    Field {
        /// Index into `Frame::values`.
        value: usize,
        /// Added to the field value to give the total frame length (may be negative).
        adjust: i64,
    },
}

/// A check: a checksum or CRC over a range of the frame, stored in the frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Check {
    /// Name (snake_case, defaults to the algorithm kind).
    pub name: String,
    /// Documentation.
    pub doc: String,
    /// The algorithm, as the runtime describes it: backends print or execute it as it is.
    pub algorithm: Algorithm,
    /// How the algorithm is named.
    pub naming: CheckNaming,
    /// A byte folded in after the covered bytes, picked by the command.
    pub extra: Option<CheckExtra>,
    /// Where the check value is stored.
    pub at: Pos,
    /// Bytes of the stored check value.
    pub size: usize,
    /// Byte order of the stored value.
    pub endian: ByteOrder,
    /// First byte covered.
    pub from: Pos,
    /// One past the last byte covered.
    pub to: Pos,
    /// True when the check is inside the header: it is verified before the length is trusted.
    pub header: bool,
}

/// The byte a check folds in after the bytes it covers, one per command (MAVLink's
/// CRC_EXTRA): the runtime's [`Extra`](protocol_runtime::checksum::Extra) without its CRC.
#[derive(Debug, Clone, PartialEq)]
pub struct CheckExtra {
    /// The header value (index into [`Frame::values`]) whose value is the key: the frame's one
    /// dispatch field.
    pub value: usize,
    /// Where the key sits, from the first covered byte.
    pub key: WordField,
    /// `(command id, byte)` of every command, sorted by id.
    pub bytes: Vec<(u32, u8)>,
    /// The ids below this are looked up in a table indexed by id (the runtime's
    /// [`Extra::direct`](protocol_runtime::checksum::Extra::direct)), the others searched
    /// among the pairs: one more than the largest id below [`DIRECT_KEYS`], 0 for none.
    pub direct: usize,
}

/// Keys a per-command byte table may index directly: a table of 256 two-byte entries (512
/// bytes) at most, which covers a one-byte id and MAVLink's first 256 messages.
pub const DIRECT_KEYS: u32 = 256;

impl CheckExtra {
    /// The pairs whose ids the direct table holds (ids below [`direct`](Self::direct)).
    pub fn direct_pairs(&self) -> &[(u32, u8)] {
        &self.bytes[..self.searched_from()]
    }

    /// The pairs searched by id (ids from [`direct`](Self::direct) on).
    pub fn searched_pairs(&self) -> &[(u32, u8)] {
        &self.bytes[self.searched_from()..]
    }

    /// Index of the first pair not in the direct table (the pairs are sorted by id).
    fn searched_from(&self) -> usize {
        self.bytes
            .partition_point(|&(id, _)| usize::try_from(id).is_ok_and(|id| id < self.direct))
    }
}

/// The names of a check's algorithm: what docs show, and the Rust items a CRC is printed with.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CheckNaming {
    /// The name docs show: `sum-mod-255`, `CRC-16/UMTS`, or the `[checksums]` name of a
    /// custom algorithm.
    pub display: String,
    /// True for an algorithm defined under `[checksums]`.
    pub custom: bool,
    /// For a catalogue CRC, the `crc` crate's constant (`CRC_16_UMTS`).
    pub crc_constant: Option<String>,
    /// For a CRC, the `static` its table lives in (`CRC_TABLE`, `SCOUT_CRC_TABLE`).
    pub table_static: Option<String>,
    /// For a check with a per-command extra byte, the `static` of its runtime `Extra`
    /// (`CRC_EXTRA`).
    pub extra_static: Option<String>,
}

/// A constant byte run after the payload.
#[derive(Debug, Clone, PartialEq)]
pub struct Trailer {
    /// Name (snake_case).
    pub name: String,
    /// Documentation.
    pub doc: String,
    /// Where it starts.
    pub at: Pos,
    /// The bytes.
    pub bytes: Vec<u8>,
}

/// The byte escaping of a frame format: between the flags that open and close a frame, each
/// reserved byte goes as `escape` and its substitute. Lengths and checks count and cover the
/// bytes before escaping.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Escape {
    /// The byte that opens and closes every frame.
    pub flag: u8,
    /// The byte that announces a substitute.
    pub escape: u8,
    /// Each reserved byte and its substitute, in the spec's order (the XOR form lowered to
    /// its pairs).
    pub pairs: Vec<[u8; 2]>,
    /// The XOR form's value, when the spec gives one (for docs).
    pub xor: Option<u8>,
}
