//! Typed codecs for serial and CAN links, generated from a TOML spec: `no_std`, no allocation,
//! no panics, no `unsafe`.
//!
//! # Example
//!
//! A spec inline (a file is `protocol!("specs/NAME.toml")`, relative to the crate's
//! `Cargo.toml`): a frame is a sync byte, the payload's length, a command id, the payload and a
//! sum of every preceding byte.
//!
//! ```
//! protocol_kit::protocol!(inline = r#"
//! [protocol]
//! name = "lamp"
//!
//! [frames.main]
//! layout = [
//!   { sync = [0xAA] },
//!   { field = "len", type = "u8", length_of = "payload" },
//!   { field = "cmd", type = "u8" },
//!   { payload = { max = 8 } },
//!   { check = "sum8", over = "frame" },
//! ]
//! dispatch = ["cmd"]
//!
//! [commands]
//! SET_LEVEL = { id = 1, payload = "Level" }
//! PING = { id = 2 }
//!
//! [structs.Level]
//! fields = [
//!   { name = "brightness", type = "u8" },
//!   { name = "fade_ms", type = "u16" },
//! ]
//! "#);
//! use lamp::{Header, Level, Message, Packet};
//!
//! // Encode into a caller's buffer: no allocation, an error on a short buffer.
//! let packet = Packet {
//!     header: Header {},
//!     message: Message::SetLevel(Level { brightness: 200, fade_ms: 500 }),
//! };
//! let mut buf = [0u8; lamp::MAX_FRAME_LEN];
//! let n = packet.encode(&mut buf)?;
//! assert_eq!(buf[..n], [0xAA, 3, 1, 200, 0xF4, 0x01, 0x6B]);
//!
//! // Decode a stream arriving in pieces, after a stray byte.
//! let stream = [&[0x00][..], &buf[..2], &buf[2..n]].concat();
//! let mut decoder = lamp::decoder();
//! let mut decoded = Vec::new();
//! for mut chunk in stream.chunks(3) {
//!     while let Some(frame) = decoder.decode(&mut chunk) {
//!         decoded.push(Packet::from_frame(frame.bytes)?);
//!     }
//! }
//! assert_eq!(decoded, [packet]);
//! assert_eq!(decoder.stats().skipped_bytes, 1);
//! # Ok::<(), Box<dyn core::error::Error>>(())
//! ```
//!
//! # What it is
//!
//! A spec describes a link: how bytes are framed (sync bytes, a length field, checks,
//! trailers), which commands exist and what each carries. [`protocol!`] turns it into a module
//! of payload structs, enums, a `Command` table, a `Message` enum, `Packet::encode` and
//! `Packet::decode`, and a streaming decoder with a fixed buffer. [`derive@Payload`] gives a
//! hand-written struct the same wire encoding. Everything those need at run time is the
//! runtime re-exported here: frame layouts, the stream engine, checksums, cursors and errors.
//!
//! This crate is the one dependency to add; it holds no code of its own. The repository's
//! `docs/tutorial.md` goes from a new link to firmware, a capture and a checked change.
//!
//! # Naming this crate under another path
//!
//! Generated code reaches the runtime through `::protocol_kit`. A crate that re-exports this one
//! under another path says where: `protocol!(crate = ::my_link::protocol, "specs/x.toml")` and
//! `#[payload(crate = "::my_link::protocol")]` on a `#[derive(Payload)]` struct.
//!
//! # A handler
//!
//! Each side of a link gets a trait with one method per message it receives (`Handler`; with
//! directions, `RequestHandler` and `ResponseHandler`), each with a default, and a `dispatch`
//! function that calls them. A method whose request expects an answer (the spec's `[session]`)
//! returns it as a [`session::Reply`]; `dispatch` returns the answer's packet, addressed back.
//!
//! ```
//! protocol_kit::protocol!(inline = r#"
//! [protocol]
//! name = "lamp"
//!
//! [frames.main]
//! layout = [
//!   { sync = [0xAA] },
//!   { field = "len", type = "u8", length_of = "payload" },
//!   { field = "cmd", type = "u8" },
//!   { payload = { max = 8 } },
//!   { check = "sum8", over = "frame" },
//! ]
//! dispatch = ["cmd"]
//!
//! [session]
//! answer = "reply"
//!
//! [commands]
//! SET_LEVEL = { id = 1, payload = "Level" }
//! GET_LEVEL = { id = 2, payload = "Level" }
//! BLINK = { id = 3, answer = "none" }
//!
//! [structs.Level]
//! fields = [{ name = "brightness", type = "u8" }]
//! "#);
//! use protocol_kit::session::Reply;
//! use lamp::{Header, Level, Message, Packet};
//!
//! struct Lamp {
//!     level: u8,
//! }
//!
//! // BLINK is not written: its default does nothing.
//! impl lamp::Handler for Lamp {
//!     fn set_level(&mut self, _: &Header, level: &Level) -> Reply<Level> {
//!         self.level = level.brightness;
//!         Reply::Answer(*level)
//!     }
//!     fn get_level(&mut self, _: &Header, _: &Level) -> Reply<Level> {
//!         Reply::Answer(Level { brightness: self.level })
//!     }
//! }
//!
//! let mut lamp = Lamp { level: 0 };
//! let set = Packet { header: Header {}, message: Message::SetLevel(Level { brightness: 90 }) };
//! let answer = lamp::dispatch(&mut lamp, &set);
//! assert_eq!(answer, Some(set));
//! let get = Packet { header: Header {}, message: Message::GetLevel(Level { brightness: 0 }) };
//! let answer = lamp::dispatch(&mut lamp, &get).map(|p| p.message);
//! assert_eq!(answer, Some(Message::GetLevel(Level { brightness: 90 })));
//! assert_eq!(lamp::dispatch(&mut lamp, &Packet { header: Header {}, message: Message::Blink }), None);
//! ```
//!
//! # serde and defmt on generated types
//!
//! `protocol!("specs/x.toml", derive(serde, defmt))` (either or both) derives `serde`'s
//! `Serialize` and `Deserialize` and `defmt`'s `Format` on the generated structs, enums,
//! messages, headers and packets. It needs this crate's features of the same names, and no
//! `serde` or `defmt` dependency of the calling crate: generated code names the crates this one
//! re-exports (`protocol_kit::serde`, `protocol_kit::defmt`). defmt's logging macros name `defmt`, so a
//! firmware without a `defmt` dependency of its own writes `use protocol_kit::defmt;` first.
//!
//! The JSON is that of the run-time codec (`protocol decode --format json`): a packet is the map
//! of `command` (its name in the spec), `header` and `payload`; an enum is its variant's name in
//! the spec (its number when it has none); bytes are hex; a text is a string (its bytes when it
//! is not canonical); a non-finite float is `"inf"`, `"-inf"`, `"NaN"` or `"NaN(0x..)"`. A
//! packet reads `command` and `header` before `payload` (whose type they decide; nothing is
//! buffered) and skips other keys, so a line of `protocol decode` reads as a packet.
//!
//! # Features
//!
//! | feature | what it adds |
//! |---|---|
//! | `std` | reading frames from a `std::io::Read` |
//! | `embedded-io` | reading frames from an `embedded-io` reader |
//! | `embedded-io-async` | packets from an `embedded-io-async` reader (`io_async::PacketReader`) and written to a writer (`io_async::write_packet`); re-exports `embedded-io-async` and `embedded-io` at the versions they take |
//! | `embedded-can` | `CanFrame` as an `embedded_can::Frame`, `CanFrame::from_frame` and `CanFrame::to_frame` for a CAN driver's frames; re-exports `embedded-can` |
//! | `tokio` | `codec::PacketCodec`, a `tokio_util::codec` decoder and encoder of a spec's packets; re-exports `tokio-util` |
//! | `serde` | `Serialize` and `Deserialize` for [`Bytes`], [`FixedStr`], [`Group`], and for the generated types of a `protocol!(..., derive(serde))` call; `no_std`, heap-free; re-exports `serde` |
//! | `defmt` | `defmt::Format` for the runtime's value types, errors and events, and for the generated types of a `protocol!(..., derive(defmt))` call; re-exports `defmt` |
//! | `stage-input` | every input chunk staged in the decoder's buffer before it is scanned, as on targets without 64-bit pointers (where it is the default: less code); on hosts, to test that path |
//! | `crc-fast` | a host feature (needs `std`): the CRCs of more than 8 bytes that the `crc-fast` crate catalogues (CRC-16/MCRF4XX, CRC-32/ISO-HDLC, CRC-64/XZ, ...) computed by it, with carry-less multiplication behind its run-time CPU dispatch; the others, and every CRC without the feature, by slicing-by-16 tables. The frames are the same. Fewer instructions per CRC, but not faster on frames of a few dozen bytes on the hosts measured (`BENCHMARKS.md`) |
//! | `clmul` | a host feature (`no_std` too; Rust 1.89 or newer): in a build for an x86-64 CPU with carry-less multiplication (`RUSTFLAGS="-C target-cpu=native"` or `-C target-feature=+pclmulqdq`), reflected CRCs of up to 32 bits (CRC-16/MCRF4XX, CRC-32/ISO-HDLC, CRC-32C, ...) over more than 8 bytes folded 16 bytes at a time with `pclmulqdq`, without run-time CPU detection; without that target feature it changes nothing. The frames are the same. The referee's decoder at or above the best hand-written baseline's speed on whole streams (`BENCHMARKS.md`) |
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]

pub use protocol_macros::{Payload, protocol};
#[doc(inline)]
pub use protocol_runtime::*;
