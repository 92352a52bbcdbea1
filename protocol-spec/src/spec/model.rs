//! The spec as written: a serde model that mirrors the TOML file one to one.
//!
//! Every value a diagnostic may point at is `Spanned`. Nothing is interpreted here: defaults,
//! names, sizes and references are resolved by `validate`, the only place that reports user
//! errors besides the TOML shape errors that deserialization itself finds.
//!
//! The `schemars` derives and attributes describe the model for the JSON Schema (`schema`,
//! the `schema` feature); without that feature they are not compiled.

use indexmap::IndexMap;
#[cfg(feature = "schema")]
use schemars::JsonSchema;
use serde::Deserialize;
#[cfg(feature = "schema")]
use std::collections::BTreeMap;
use toml::Spanned;

pub use super::registers::{RegisterDef, RegistersDef, SelectDef};
pub use super::session::{AnswersDef, ModesDef, PeriodicDef, ResultDef, SessionDef, WatchdogDef};

/// A spanned string.
pub type SStr = Spanned<String>;
/// A spanned integer (TOML integers are i64).
pub type SInt = Spanned<i64>;
/// An ordered map keyed by spanned names, in spec order.
pub type Named<T> = IndexMap<SStr, Spanned<T>>;

/// The whole spec file.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct SpecFile {
    /// `[protocol]`: name, version, documentation, default byte order.
    #[cfg_attr(feature = "schema", schemars(with = "ProtocolTable"))]
    pub protocol: Spanned<ProtocolTable>,
    /// `[constants]`: named integers usable where a count or value is expected.
    #[serde(default)]
    #[cfg_attr(feature = "schema", schemars(with = "BTreeMap<String, ConstantDef>"))]
    pub constants: Named<ConstantDef>,
    /// `[addresses]`: named addresses and address ranges.
    #[serde(default)]
    #[cfg_attr(feature = "schema", schemars(with = "BTreeMap<String, AddressDef>"))]
    pub addresses: Named<AddressDef>,
    /// `[checksums.NAME]`: custom checksum algorithms.
    #[serde(default)]
    #[cfg_attr(feature = "schema", schemars(with = "BTreeMap<String, ChecksumDef>"))]
    pub checksums: Named<ChecksumDef>,
    /// `[frames.NAME]`: frame formats.
    #[serde(default)]
    #[cfg_attr(feature = "schema", schemars(with = "BTreeMap<String, FrameDef>"))]
    pub frames: Named<FrameDef>,
    /// `[directions]`: how a decoder tells a request from a response.
    #[serde(default)]
    #[cfg_attr(feature = "schema", schemars(with = "BTreeMap<String, DirectionDef>"))]
    pub directions: Named<DirectionDef>,
    /// `[commands]`: one line per command.
    #[serde(default)]
    #[cfg_attr(feature = "schema", schemars(with = "BTreeMap<String, CommandDef>"))]
    pub commands: Named<CommandDef>,
    /// `[structs.NAME]`: payload structs.
    #[serde(default)]
    #[cfg_attr(feature = "schema", schemars(with = "BTreeMap<String, StructDef>"))]
    pub structs: Named<StructDef>,
    /// `[enums.NAME]`: enums.
    #[serde(default)]
    #[cfg_attr(feature = "schema", schemars(with = "BTreeMap<String, EnumDef>"))]
    pub enums: Named<EnumDef>,
    /// `[session]`: who answers whom (answers, matching, timeouts, retries, handshake,
    /// watchdog).
    #[cfg_attr(feature = "schema", schemars(with = "Option<SessionDef>"))]
    pub session: Option<Spanned<SessionDef>>,
    /// `[registers]`: the device's register map (a control table), which a command's
    /// `registers` selects runs of.
    #[cfg_attr(feature = "schema", schemars(with = "Option<RegistersDef>"))]
    pub registers: Option<Spanned<RegistersDef>>,
}

/// `[protocol]`.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct ProtocolTable {
    /// Module name of the generated code (snake_case).
    #[cfg_attr(feature = "schema", schemars(with = "String"))]
    pub name: SStr,
    /// Free version string.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub version: Option<SStr>,
    /// Documentation (Markdown).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub doc: Option<SStr>,
    /// Default byte order of multi-byte fields: `"little"` (default) or `"big"`.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub byte_order: Option<SStr>,
}

/// A constant: `NAME = 12` or `NAME = { value = 12, doc = "..." }`.
///
/// Untagged enums buffer their input, so nothing inside them can be `Spanned`: the span of the
/// whole value is kept by the map entry.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(untagged)]
#[cfg_attr(
    feature = "schema",
    schemars(description = "A constant: `NAME = 12` or `NAME = { value = 12, doc = \"...\" }`.")
)]
pub enum ConstantDef {
    /// `NAME = 12`
    Bare(i64),
    /// `NAME = { value = 12, doc = "..." }`
    Full(ConstantFull),
}

/// The table form of a constant.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct ConstantFull {
    /// Value.
    pub value: i64,
    /// Documentation.
    pub doc: Option<String>,
}

/// An address set: `{ range = [lo, hi] }` or `{ value = v }`.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct AddressDef {
    /// Inclusive range.
    #[cfg_attr(feature = "schema", schemars(with = "Option<Vec<i64>>"))]
    pub range: Option<Spanned<Vec<SInt>>>,
    /// Single address.
    #[cfg_attr(feature = "schema", schemars(with = "Option<i64>"))]
    pub value: Option<SInt>,
    /// Documentation.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub doc: Option<SStr>,
}

/// A custom checksum algorithm.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct ChecksumDef {
    /// CRC parameters (Rocksoft model).
    #[cfg_attr(feature = "schema", schemars(with = "Option<CrcDef>"))]
    pub crc: Option<Spanned<CrcDef>>,
    /// Sum parameters: a sum of the bytes of a width, with a final xor.
    #[cfg_attr(feature = "schema", schemars(with = "Option<SumDef>"))]
    pub sum: Option<Spanned<SumDef>>,
    /// XOR parameters: the XOR of the bytes, starting from a constant.
    #[cfg_attr(feature = "schema", schemars(with = "Option<XorDef>"))]
    pub xor: Option<Spanned<XorDef>>,
    /// Lookup table slices of a CRC: 0, 1 or 16 (default 16).
    #[cfg_attr(feature = "schema", schemars(with = "Option<i64>"))]
    pub table: Option<SInt>,
    /// Documentation.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub doc: Option<SStr>,
}

/// A sum of the bytes, starting from `init`: modulo 2^`width`, then xored with `xorout` (all
/// ones: the one's complement of the sum, as Dynamixel Protocol 1.0 `~sum & 0xFF` and iBUS
/// `0xFFFF - sum`).
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct SumDef {
    /// 8 or 16.
    #[cfg_attr(feature = "schema", schemars(with = "i64"))]
    pub width: SInt,
    /// The value the sum starts from (default 0).
    #[cfg_attr(feature = "schema", schemars(with = "Option<i64>"))]
    pub init: Option<SInt>,
    /// Final XOR (default 0).
    #[cfg_attr(feature = "schema", schemars(with = "Option<i64>"))]
    pub xorout: Option<SInt>,
}

/// An 8-bit XOR of the bytes, starting from `init`.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct XorDef {
    /// The value the XOR starts from, 0 to 255.
    #[cfg_attr(feature = "schema", schemars(with = "i64"))]
    pub init: SInt,
}

/// CRC parameters in the Rocksoft model (as in the `crc` crate's `Algorithm`).
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct CrcDef {
    /// 1 to 64 bits; the check is stored in the fewest whole bytes that hold it.
    #[cfg_attr(feature = "schema", schemars(with = "i64"))]
    pub width: SInt,
    /// Polynomial, normal (MSB-first) form.
    #[cfg_attr(feature = "schema", schemars(with = "i64"))]
    pub poly: SInt,
    /// Initial register value, un-reflected.
    #[cfg_attr(feature = "schema", schemars(with = "i64"))]
    pub init: SInt,
    /// Reflect input bytes.
    #[cfg_attr(feature = "schema", schemars(with = "bool"))]
    pub refin: Spanned<bool>,
    /// Reflect the output.
    #[cfg_attr(feature = "schema", schemars(with = "bool"))]
    pub refout: Spanned<bool>,
    /// Final XOR.
    #[cfg_attr(feature = "schema", schemars(with = "i64"))]
    pub xorout: SInt,
    /// CRC of the ASCII bytes "123456789"; verified at expansion.
    #[cfg_attr(feature = "schema", schemars(with = "i64"))]
    pub check: SInt,
}

/// `[frames.NAME]`.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct FrameDef {
    /// Documentation.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub doc: Option<SStr>,
    /// The wire elements in order.
    #[cfg_attr(feature = "schema", schemars(with = "Vec<ElementDef>"))]
    pub layout: Spanned<Vec<Spanned<ElementDef>>>,
    /// Names of the fields that form the dispatch key, in key order.
    #[cfg_attr(feature = "schema", schemars(with = "Option<Vec<String>>"))]
    pub dispatch: Option<Spanned<Vec<SStr>>>,
    /// `"serial"` (default) or `"can"`.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub transport: Option<SStr>,
    /// For CAN: `"standard"` (11-bit ids, default) or `"extended"` (29-bit).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub can_id: Option<SStr>,
    /// For CAN: the identifier split into named members, lowest bit first, that together
    /// cover its 11 or 29 bits (DroneCAN's priority, message type and source node); each is a
    /// header value of the frame.
    #[cfg_attr(feature = "schema", schemars(with = "Option<Vec<BitDef>>"))]
    pub can_id_bits: Option<Spanned<Vec<Spanned<BitDef>>>>,
    /// Frames whose header matches this rule are acknowledgements: they carry no dispatch
    /// fields, and their payload is raw acknowledgement data.
    #[cfg_attr(feature = "schema", schemars(with = "Option<AckDef>"))]
    pub ack: Option<Spanned<AckDef>>,
    /// A frame may be the header alone (up to its header checks): no payload, no frame checks.
    #[cfg_attr(feature = "schema", schemars(with = "Option<bool>"))]
    pub bare_header: Option<Spanned<bool>>,
    /// Byte stuffing of the payload.
    #[cfg_attr(feature = "schema", schemars(with = "Option<StuffingDef>"))]
    pub stuffing: Option<Spanned<StuffingDef>>,
    /// Byte escaping of the whole frame between its flags (HDLC, PPP, SLIP): each reserved
    /// byte is sent as an escape byte and a substitute.
    #[cfg_attr(feature = "schema", schemars(with = "Option<EscapeDef>"))]
    pub escape: Option<Spanned<EscapeDef>>,
    /// The sender drops the trailing zero bytes of a command's payload (keeping at least one);
    /// the receiver zero-fills it to its struct's size.
    #[cfg_attr(feature = "schema", schemars(with = "Option<bool>"))]
    pub truncate_zeros: Option<Spanned<bool>>,
    /// For a frame format without dispatch key: the struct every frame carries.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub message: Option<SStr>,
    /// A serial frame format after the first that carries the commands too, each whose id fits
    /// its dispatch fields: another format of the same link (MAVLink 1 beside MAVLink 2).
    #[cfg_attr(feature = "schema", schemars(with = "Option<bool>"))]
    pub commands: Option<Spanned<bool>>,
    /// Whether the format carries the struct fields marked `extension` (default true); with
    /// `false`, a payload is its struct's fields before the first extension field.
    #[cfg_attr(feature = "schema", schemars(with = "Option<bool>"))]
    pub extensions: Option<Spanned<bool>>,
}

/// `stuffing = { after = [0xFF, 0xFF, 0xFD], insert = 0xFD }`.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct StuffingDef {
    /// The pattern after which the sender inserts a byte.
    #[cfg_attr(feature = "schema", schemars(with = "Vec<i64>"))]
    pub after: Spanned<Vec<SInt>>,
    /// The inserted byte.
    #[cfg_attr(feature = "schema", schemars(with = "i64"))]
    pub insert: SInt,
}

/// `escape = { flag = 0x7E, escape = 0x7D, xor = 0x20, bytes = [0x7E, 0x7D] }` (HDLC: each
/// listed byte goes as the escape byte and the byte XOR `xor`) or `escape = { flag = 0xC0,
/// escape = 0xDB, map = [[0xC0, 0xDC], [0xDB, 0xDD]] }` (SLIP: each pair is a reserved byte and
/// its substitute).
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct EscapeDef {
    /// The byte that opens and closes every frame: the layout's sync and last trailer.
    #[cfg_attr(feature = "schema", schemars(with = "i64"))]
    pub flag: SInt,
    /// The byte that announces a substitute.
    #[cfg_attr(feature = "schema", schemars(with = "i64"))]
    pub escape: SInt,
    /// With `bytes`: the substitute of a reserved byte is the byte XOR this.
    #[cfg_attr(feature = "schema", schemars(with = "Option<i64>"))]
    pub xor: Option<SInt>,
    /// With `xor`: the reserved bytes (the flag and the escape byte among them).
    #[cfg_attr(feature = "schema", schemars(with = "Option<Vec<i64>>"))]
    pub bytes: Option<Spanned<Vec<SInt>>>,
    /// Instead of `xor` and `bytes`: pairs `[reserved, substitute]`.
    #[cfg_attr(feature = "schema", schemars(with = "Option<Vec<Vec<i64>>>"))]
    pub map: Option<Spanned<Vec<Spanned<Vec<SInt>>>>>,
}

/// `ack = { field = "is_ack", equals = 1 }`.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct AckDef {
    /// A one-bit header value.
    #[cfg_attr(feature = "schema", schemars(with = "String"))]
    pub field: SStr,
    /// Its value in acknowledgements.
    #[cfg_attr(feature = "schema", schemars(with = "i64"))]
    pub equals: SInt,
}

/// One element of a frame layout. Exactly one of `sync`, `field`, `payload`, `check`,
/// `trailer`, `optional` says what it is; validation checks the combination.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct ElementDef {
    /// Sync bytes (first element only).
    #[cfg_attr(feature = "schema", schemars(with = "Option<Vec<i64>>"))]
    pub sync: Option<Spanned<Vec<SInt>>>,
    /// A header field with this name.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub field: Option<SStr>,
    /// The payload, with its size bounds.
    #[cfg_attr(feature = "schema", schemars(with = "Option<PayloadDef>"))]
    pub payload: Option<Spanned<PayloadDef>>,
    /// A check with this algorithm (catalogue name, built-in, or `[checksums]` name).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub check: Option<SStr>,
    /// A constant byte run after the payload.
    #[cfg_attr(feature = "schema", schemars(with = "Option<Vec<i64>>"))]
    pub trailer: Option<Spanned<Vec<SInt>>>,
    /// Type of a field (`u8`, `u16be`, `u16le`, `u16`, ...).
    #[serde(rename = "type")]
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub ty: Option<SStr>,
    /// The field holds addresses of `[addresses]`.
    #[cfg_attr(feature = "schema", schemars(with = "Option<bool>"))]
    pub addresses: Option<Spanned<bool>>,
    /// The field is the frame's length and counts these elements (`"a..b"`, `"a"`, `"frame"`).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub length_of: Option<SStr>,
    /// The field must hold this value (a header field before the payload).
    #[cfg_attr(feature = "schema", schemars(with = "Option<i64>"))]
    pub value: Option<SInt>,
    /// The field, a `u8` and the layout's first element, is the sync: it holds one of these
    /// values, and a decoder searches for any of them (a CRSF device address).
    #[cfg_attr(feature = "schema", schemars(with = "Option<Vec<i64>>"))]
    pub one_of: Option<Spanned<Vec<SInt>>>,
    /// The field is split into bit members.
    #[cfg_attr(feature = "schema", schemars(with = "Option<Vec<BitDef>>"))]
    pub bits: Option<Spanned<Vec<Spanned<BitDef>>>>,
    /// Bytes a check covers (`"a..b"`, `"a"`, `"frame"`: everything before the check).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub over: Option<SStr>,
    /// Byte order of a check value (default: the protocol's).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub byte_order: Option<SStr>,
    /// A byte a check folds in after the bytes it covers: `"command"`, the `check_extra` each
    /// command declares (MAVLink's CRC_EXTRA).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub extra: Option<SStr>,
    /// Lookup table slices of a CRC check: 0, 1 or 16 (default: the CRC's, 16 for a
    /// catalogue CRC).
    #[cfg_attr(feature = "schema", schemars(with = "Option<i64>"))]
    pub table: Option<SInt>,
    /// Name of a check or trailer.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub name: Option<SStr>,
    /// Bytes at the end of the frame, after everything else, present when a one-bit header
    /// flag (`when`) is set: their name (the MAVLink 2 signature).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub optional: Option<SStr>,
    /// Bytes of an `optional` element.
    #[cfg_attr(feature = "schema", schemars(with = "Option<i64>"))]
    pub size: Option<SInt>,
    /// The one-bit header value whose being set makes an `optional` element present.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub when: Option<SStr>,
    /// The field is a wider length, present when the length field named here holds `marker`
    /// (MSP v1 jumbo frames).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub extends: Option<SStr>,
    /// With `extends`: the value of the length field that announces the wider length.
    #[cfg_attr(feature = "schema", schemars(with = "Option<i64>"))]
    pub marker: Option<SInt>,
    /// The field is a frame counter (a sequence number): the sender adds one per frame, wrapping at the
    /// field's width. Decoding tools count lost and reordered frames from it (statistics
    /// only: no codec checks it).
    #[cfg_attr(feature = "schema", schemars(with = "Option<bool>"))]
    pub counter: Option<Spanned<bool>>,
    /// The field belongs to the frames of this direction only (one given to the decoder): the
    /// other directions' frames do not have its bytes (Sensirion SHDLC's state byte, in a
    /// device's answers only).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub direction: Option<SStr>,

    /// Documentation.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub doc: Option<SStr>,
}

/// `{ payload = { min = 0, max = 119 } }`.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct PayloadDef {
    /// Smallest payload (default 0).
    #[cfg_attr(feature = "schema", schemars(with = "Option<i64>"))]
    pub min: Option<SInt>,
    /// Largest payload (required: a decoder's buffer is sized from it).
    #[cfg_attr(feature = "schema", schemars(with = "Option<i64>"))]
    pub max: Option<SInt>,
}

/// A bit member of a header field or struct field.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct BitDef {
    /// Name.
    #[cfg_attr(feature = "schema", schemars(with = "String"))]
    pub name: SStr,
    /// Number of bits.
    #[cfg_attr(feature = "schema", schemars(with = "i64"))]
    pub bits: SInt,
    /// Rust type (`bool`, `u8`, ..., or an enum name); default `bool` for one bit, else the
    /// smallest unsigned integer. In a payload, a signed type (`i8` ... `i64`) makes the member
    /// two's complement of its own width, sign-extended when read.
    #[serde(rename = "type")]
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub ty: Option<SStr>,
    /// In a payload: physical value = raw * scale (+ offset), as on a whole field.
    #[cfg_attr(feature = "schema", schemars(with = "Option<f64>"))]
    pub scale: Option<Spanned<f64>>,
    /// In a payload: added after scaling.
    #[cfg_attr(feature = "schema", schemars(with = "Option<f64>"))]
    pub offset: Option<Spanned<f64>>,
    /// In a payload: unit of the (physical) value, for docs.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub unit: Option<SStr>,
    /// In a header field before the payload: this member is the frame's length.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub length_of: Option<SStr>,
    /// In a header field before the payload: this member must hold this value.
    #[cfg_attr(feature = "schema", schemars(with = "Option<i64>"))]
    pub value: Option<SInt>,
    /// Documentation.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub doc: Option<SStr>,
}

/// `request = { field = "sender", in = "master" }` or `{ field = "is_ack", equals = 0 }`: a
/// header field tells the direction; or `request = { given = true }`: the decoder is given it;
/// or `error = { field = "direction", equals = 0x21, empty = true }`: a direction whose frames
/// carry no payload.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct DirectionDef {
    /// Header field that tells the direction (on a link of several command formats: the field
    /// of this name in each format).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub field: Option<SStr>,
    /// No header field tells the direction: the decoding side is given it (a decoder per
    /// direction).
    #[cfg_attr(feature = "schema", schemars(with = "Option<bool>"))]
    pub given: Option<Spanned<bool>>,
    /// With `given`: every frame of this direction carries this struct in place of the
    /// dispatch key and the command's payload (a status packet that has no command).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub message: Option<SStr>,
    /// The field lies in this address set.
    #[serde(rename = "in")]
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub in_set: Option<SStr>,
    /// The field equals this value.
    #[cfg_attr(feature = "schema", schemars(with = "Option<i64>"))]
    pub equals: Option<SInt>,
    /// A direction besides `request` and `response` whose frames carry the header and no
    /// payload, whatever the command (MSP's error replies).
    #[cfg_attr(feature = "schema", schemars(with = "Option<bool>"))]
    pub empty: Option<Spanned<bool>>,
    /// Documentation.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub doc: Option<SStr>,
}

/// A command line: `NAME = { id = 1, request = "S", response = "T", doc = "..." }`.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct CommandDef {
    /// Key: an integer, or one integer per dispatch field.
    #[cfg_attr(feature = "schema", schemars(with = "IdDef"))]
    pub id: Spanned<IdDef>,
    /// Payload struct (specs without directions).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub payload: Option<SStr>,
    /// Payload struct of the request direction.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub request: Option<SStr>,
    /// Payload struct of the response direction.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub response: Option<SStr>,
    /// The command's CAN id, for specs with a CAN frame.
    #[cfg_attr(feature = "schema", schemars(with = "Option<i64>"))]
    pub can_id: Option<SInt>,
    /// The byte a check with `extra = "command"` folds in for this command (0 to 255).
    #[cfg_attr(feature = "schema", schemars(with = "Option<i64>"))]
    pub check_extra: Option<SInt>,
    /// The answer this command's request expects (as `[session] answer`).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub answer: Option<SStr>,
    /// This command's timeout in milliseconds (as `[session] timeout_ms`).
    #[cfg_attr(feature = "schema", schemars(with = "Option<i64>"))]
    pub timeout_ms: Option<SInt>,
    /// This command's retries (as `[session] retries`).
    #[cfg_attr(feature = "schema", schemars(with = "Option<i64>"))]
    pub retries: Option<SInt>,
    /// Values the answer repeats from this command's request under other names: each key a
    /// field of the request (header or payload), its value the answer's field that holds it.
    #[serde(rename = "match")]
    #[cfg_attr(
        feature = "schema",
        schemars(with = "Option<std::collections::BTreeMap<String, String>>")
    )]
    pub match_fields: Option<Spanned<IndexMap<SStr, SStr>>>,
    /// The value of the answer that says whether this command's request succeeded.
    #[cfg_attr(feature = "schema", schemars(with = "Option<ResultDef>"))]
    pub result: Option<Spanned<ResultDef>>,
    /// The ids that answer this command's request, once each: where the request lists them,
    /// and the answer's header field that names its sender.
    #[cfg_attr(feature = "schema", schemars(with = "Option<AnswersDef>"))]
    pub answers: Option<Spanned<AnswersDef>>,
    /// Request fields that select a run of `[registers]`, and the bytes (the request's data,
    /// the answer's) that hold their values.
    #[cfg_attr(feature = "schema", schemars(with = "Option<SelectDef>"))]
    pub registers: Option<Spanned<SelectDef>>,
    /// Documentation.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub doc: Option<SStr>,
}

/// A command id: `1` or `[0x03, 0x01]`.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(untagged)]
pub enum IdDef {
    /// One dispatch field.
    One(i64),
    /// Several dispatch fields, in the frame's `dispatch` order.
    Many(Vec<i64>),
}

/// `[structs.NAME]`.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct StructDef {
    /// Documentation.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub doc: Option<SStr>,
    /// Byte order of this struct's fields (default: the protocol's).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub byte_order: Option<SStr>,
    /// Fields in wire order.
    #[cfg_attr(feature = "schema", schemars(with = "Vec<FieldDef>"))]
    pub fields: Spanned<Vec<Spanned<FieldDef>>>,
}

/// A struct field, or `{ pad = N }`.
#[derive(Debug, Default, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct FieldDef {
    /// Field name.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub name: Option<SStr>,
    /// Type: primitive (`u16`, `i32be`, `u24le`, `u48`, `f16`, `f32`, `bool`), `char[N]` (N
    /// bytes of NUL-padded text), `cstr` (NUL-terminated text of at most `max` bytes), `str`
    /// (text of at most `max` bytes without a terminator, as `bytes`), `bitstream` (with
    /// `bits`: bytes read as one stream of bits, most significant bit first), struct or enum
    /// name.
    #[serde(rename = "type")]
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub ty: Option<SStr>,
    /// Fixed array length: an integer or a constant's name.
    #[cfg_attr(feature = "schema", schemars(with = "Option<CountDef>"))]
    pub count: Option<Spanned<CountDef>>,
    /// For `type = "bytes"` and `"str"`: the most bytes the field holds; with `repeat`: the
    /// most elements;
    /// for `type = "cstr"`: the most bytes of text, the NUL not counted.
    #[cfg_attr(feature = "schema", schemars(with = "Option<i64>"))]
    pub max: Option<SInt>,
    /// For `type = "bytes"`, `"str"` and `repeat` of a primitive: the name of an earlier integer field
    /// (of this struct, or of the struct that repeats this one) that holds the number of bytes
    /// or elements.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub size: Option<SStr>,
    /// The field is a group of elements of its type (a struct, or a primitive), repeated to
    /// the end of the payload, or as many times as `size` says.
    #[cfg_attr(feature = "schema", schemars(with = "Option<bool>"))]
    pub repeat: Option<Spanned<bool>>,
    /// The field may be absent: it is present when bytes remain in the payload.
    #[cfg_attr(feature = "schema", schemars(with = "Option<bool>"))]
    pub optional: Option<Spanned<bool>>,
    /// The field is present only when a bit of an earlier unsigned integer field of the
    /// struct is set: `{ field = "flags", bit = 3 }`.
    #[cfg_attr(feature = "schema", schemars(with = "Option<WhenDef>"))]
    pub when: Option<Spanned<WhenDef>>,
    /// With `repeat` of a primitive or an enum: the name of an earlier unsigned integer field
    /// of the struct whose set bits count the elements (one element per set bit).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub mask: Option<SStr>,
    /// With `type = "bytes"`: the bytes are the payload of the command whose id this earlier
    /// unsigned integer field of the struct holds (a packet carried in this one).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub carries: Option<SStr>,
    /// Padding bytes (written as zero, ignored when read).
    #[cfg_attr(feature = "schema", schemars(with = "Option<i64>"))]
    pub pad: Option<SInt>,
    /// Bit members of an integer field (lowest bit first), or of a `bitstream` (first bit
    /// first).
    #[cfg_attr(feature = "schema", schemars(with = "Option<Vec<BitDef>>"))]
    pub bits: Option<Spanned<Vec<Spanned<BitDef>>>>,
    /// A bit-packed array: `count` unsigned elements of `bits` bits each, back to back, in
    /// the bit order `order`.
    #[cfg_attr(feature = "schema", schemars(with = "Option<PackedDef>"))]
    pub packed: Option<Spanned<PackedDef>>,
    /// With `bits`, the bits above the members: `"keep"` (default: held in a member named
    /// `<field>_reserved`, so that decoding then encoding gives the same bytes) or `"zero"`
    /// (reserved-zero: written as zero, ignored when read).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub reserved: Option<SStr>,
    /// Physical value = raw * scale (+ offset), for an integer or a float on the wire.
    #[cfg_attr(feature = "schema", schemars(with = "Option<f64>"))]
    pub scale: Option<Spanned<f64>>,
    /// Added after scaling.
    #[cfg_attr(feature = "schema", schemars(with = "Option<f64>"))]
    pub offset: Option<Spanned<f64>>,
    /// `"nearest"` (default) or `"truncate"`: how encoding turns a physical value into a raw
    /// integer (a float on the wire keeps the quotient).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub rounding: Option<SStr>,
    /// `[min, max]`: physical values are clamped into this range before encoding.
    #[cfg_attr(feature = "schema", schemars(with = "Option<Vec<f64>>"))]
    pub clamp: Option<Spanned<Vec<Spanned<f64>>>>,
    /// With `type = "bool"`: the wire byte 0 means `true` (an active-low flag); `true` is
    /// written as 0 and `false` as 1.
    #[cfg_attr(feature = "schema", schemars(with = "Option<bool>"))]
    pub invert: Option<Spanned<bool>>,
    /// Unit of the (physical) value, for docs.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub unit: Option<SStr>,
    /// The field is a check value over earlier fields of this struct: a built-in checksum, a
    /// CRC of the catalogue, or a `[checksums]` entry (a CRC inside the payload).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub check: Option<SStr>,
    /// With `check`: the fields it covers, `"a..b"` (a run, both ends included) or `"a"`.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub over: Option<SStr>,
    /// With a CRC `check`: constant bytes it covers before the fields (the frame type a CRSF
    /// command's inner CRC starts with).
    #[cfg_attr(feature = "schema", schemars(with = "Option<Vec<i64>>"))]
    pub prefix: Option<Spanned<Vec<SInt>>>,
    /// With `check`: byte order of the check value (default: the struct's).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub byte_order: Option<SStr>,
    /// The field was appended by a later revision of the struct: it and the fields after it
    /// are not carried by a frame format with `extensions = false`.
    #[cfg_attr(feature = "schema", schemars(with = "Option<bool>"))]
    pub extension: Option<Spanned<bool>>,
    /// Documentation.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub doc: Option<SStr>,
    /// The Rust type a `#[derive(Payload)]` field declares (its element type, for an array);
    /// never in a spec file.
    #[serde(skip)]
    #[cfg_attr(feature = "schema", schemars(skip))]
    pub rust: Option<SStr>,
}

/// `when = { field = "flags", bit = 3 }`: the bit of a mask field that announces a field.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct WhenDef {
    /// An earlier unsigned integer field of the struct (the mask).
    #[cfg_attr(feature = "schema", schemars(with = "String"))]
    pub field: SStr,
    /// The bit, counted from the least significant bit of the mask's value (0 first).
    #[cfg_attr(feature = "schema", schemars(with = "i64"))]
    pub bit: SInt,
}

/// `packed = { bits = 11, order = "lsb-first" }`: the elements of a bit-packed array.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct PackedDef {
    /// Bits of each element, 1 to 32.
    #[cfg_attr(feature = "schema", schemars(with = "i64"))]
    pub bits: SInt,
    /// `"lsb-first"` (bit 0 of byte 0 first, as CRSF and SBUS) or `"msb-first"`.
    #[cfg_attr(feature = "schema", schemars(with = "String"))]
    pub order: SStr,
}

/// An array count: `8` or `"SERVO_COUNT"`.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(untagged)]
pub enum CountDef {
    /// Literal.
    Literal(i64),
    /// A constant's name.
    Constant(String),
}

/// `[enums.NAME]`.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct EnumDef {
    /// Wire type (`u8`, `u16be`, ...).
    #[serde(rename = "type")]
    #[cfg_attr(feature = "schema", schemars(with = "String"))]
    pub ty: SStr,
    /// `"reject"` (default) or `"keep"`.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub unknown: Option<SStr>,
    /// Documentation.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub doc: Option<SStr>,
    /// Variants: `NAME = 1` or `NAME = { value = 1, doc = "..." }`.
    #[cfg_attr(feature = "schema", schemars(with = "BTreeMap<String, ConstantDef>"))]
    pub values: Named<ConstantDef>,
}
