//! The C peer (`protocol gen c`): a C99 header and source file per spec, printed from the IR.
//!
//! Like the Rust expansion, this backend decides nothing: every size, offset, byte order,
//! length rule and check comes from the IR through the plans the Rust backends print and the
//! run-time codec builds: the frame rules from [`crate::layout::lower_layout`], the packet rules
//! (what a format carries, its key, acknowledgements, directions, stuffing, truncation) from
//! [`crate::rules::lower_rules`]. What the C printer does not support yet is refused by
//! [`unsupported`] with one line per feature, before anything is printed: a spec gets correct
//! C or a clear error, never wrong code.
//!
//! The generated code needs nothing beyond the C standard headers and never allocates:
//!
//! * a struct (fixed-width types) per payload struct, an integer type and constants per enum,
//!   a header struct, a command enum and a packet struct (`header`, `packet`);
//! * a reader and a writer per payload struct, with explicit byte order (shifts), never
//!   relying on struct layout or packing (`payload`; each field kind in its module of `kinds`,
//!   with `fields`, `values`, `prelude`);
//! * the frame rules: each check's algorithm (sums, bitwise or table CRCs from the IR's
//!   parameters), the probe of a candidate, a decoder of one frame's bytes and an encoder per
//!   command into the caller's buffer (`frame`, `checks`);
//! * the stream decoders, with the runtime engine's rules over a fixed buffer (`engine`);
//! * a reader of the packet a carrying field carries (`carried`);
//! * optionally (`<PREFIX>_WITH_FORMAT`), a text form of a packet, with `snprintf` (`format`).
//!
//! A spec with several frame formats gets the items of a format (sizes, header and packet
//! types, decoder, encoders, stream decoder, text form) once per format, those of a format
//! after the first with the format's name in their prefix (`mavlink_v1_decode`), as the Rust
//! side has a packet per format; the structs, enums and commands are shared.
//!
//! The code every spec needs (byte readers, the stream engine) is printed into each source
//! file as `static` functions, not shipped as a shared `protocol_rt.h`: the two files of a
//! spec are all a firmware vendors, two specs linked into one firmware cannot clash, and the
//! engine's constants (sync bytes, buffer size) are compile-time constants of that file.
//!
//! The C is written as the C it prints, with `${name}` holes for a spec's values, filled by
//! `template`'s `fill!`: the code every spec gets in template files (`templates/*.c`, `.h`),
//! the parts a spec shapes in raw strings beside the Rust that loops over its items. A filler
//! of a few lines rather than a template engine keeps those loops in Rust, where the other
//! printers have theirs, and puts no template language between the reader and the C.
//!
//! Each module uses only modules after it in this order, so no two import each other:
//! `header`, `packet`, `engine`, `lookups`, `format`, `frame` (its `probe`, `decode`,
//! `encode`, then `rules`, then `wire`), `carried`, `payload`, `fields`, `values`, `checks`, `scale`,
//! `prelude`, `support`, `shape`, `names`, `template`. The main lines: `header` → `packet`;
//! `payload` → `fields` → `values` → `prelude`, `scale`; the printers → `shape` → `names`.

mod carried;
mod checks;
mod engine;
mod fields;
mod format;
mod frame;
mod header;
mod kinds;
mod lookups;
mod members;
mod names;
mod packet;
mod payload;
mod prelude;
mod scale;
mod shape;
mod support;
mod template;
mod values;

pub use carried::{carried_format, carried_reader};
pub use support::unsupported;

use protocol_runtime::DecodeError;

use crate::ir::Protocol;

/// The name, lower case, of the `ERR_` code the printed C returns for a frame on which the
/// runtime (generated Rust, the run-time codec) returns `e`: the correspondence that tests
/// comparing the C with the Rust codec hold it to (`HFLINK_ERR_PAYLOAD_LENGTH` for
/// `PayloadLength`). Every framing verdict is the C's one `ERR_FRAME`.
pub fn error_name(e: &DecodeError) -> &'static str {
    match e {
        DecodeError::PayloadLength { .. } => "payload_length",
        DecodeError::InvalidEnum { .. } => "invalid_enum",
        DecodeError::UnknownCommand { .. } => "unknown_command",
        DecodeError::UnknownDirection => "unknown_direction",
        DecodeError::SizeMismatch { .. } => "size_mismatch",
        DecodeError::Unterminated { .. } => "unterminated",
        DecodeError::PayloadCheck { .. } => "payload_check",
        DecodeError::ValueOutOfRange { .. } => "outside_clamp",
        DecodeError::InvalidStuffing => "invalid_stuffing",
        _ => "frame",
    }
}

/// The two files of a spec's C code.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CFiles {
    /// File name of the header (`hflink.h`).
    pub header_name: String,
    /// The header.
    pub header: String,
    /// File name of the source (`hflink.c`).
    pub source_name: String,
    /// The source.
    pub source: String,
}

/// The C code of a spec, or every feature of the spec the C printer does not support (one
/// line each).
///
/// # Errors
/// The unsupported features, when there are any.
pub fn generate(p: &Protocol) -> Result<CFiles, Vec<String>> {
    let refused = unsupported(p);
    if !refused.is_empty() {
        return Err(refused);
    }
    let n = names::Names::new(p);
    let header = header::header(p, &n);
    let mut source = String::new();
    source.push_str(&prelude::source_prelude(p, &n));
    source.push_str(&lookups::lookups(p, &n));
    source.push_str(&checks::checks(p, &n));
    source.push_str(&checks::payload_checks(p, &n));
    source.push_str(&payload::payloads(p, &n));
    source.push_str(&frame::frame(p, &n));
    source.push_str(&carried::readers(p, &n));
    source.push_str(&engine::engine(p, &n));
    source.push_str(&format::format(p, &n));
    Ok(CFiles {
        header_name: format!("{}.h", p.name),
        header,
        source_name: format!("{}.c", p.name),
        source,
    })
}
