//! The runtime of codecs generated from protocol specs: `no_std`, no allocation, no panics.
//!
//! A spec describes a serial or CAN link: how bytes are framed, how a frame is checked, which
//! commands exist and what each carries. The `protocol!` macro turns it into payload structs, a
//! command table and a `Message` enum; this crate holds everything those need at run time, once:
//!
//! - [`layout`]: a frame format as data ([`FrameLayout`]): sync bytes, length rule, constants,
//!   header and frame checks, trailing markers;
//! - [`decoder`]: the one stream engine ([`StreamDecoder`]) that finds the frames of any layout in
//!   chunks of bytes, zero-copy, resynchronising one byte after any rejected candidate, and
//!   counting what it dropped ([`Stats`]);
//! - [`encoder`]: sealing a frame written in place ([`FrameLayout::seal`]) and the [`Payload`]
//!   trait of payload structs;
//! - [`field`]: field semantics (scaling, rounding, clamping, enum policy, bit members,
//!   sized bytes, optional fields and repeated groups), shared by generated code and the
//!   run-time codec;
//! - [`wire`]: the cursors payload code reads and writes with ([`Reader`], [`Writer`]);
//! - [`checksum`]: sums, xor and CRCs ([`Checksum`]);
//! - [`error`]: [`DecodeError`] and [`EncodeError`].
//!
//! Users depend on the `protocol` crate, which re-exports this one and the macros; generated
//! code names this crate's items through `protocol::__private`. This crate does not depend on
//! the macros, so the code generator can use its types (byte order, positions, check
//! algorithms, frame layouts) as its own vocabulary.
//!
//! # Features
//!
//! | feature | what it adds |
//! |---|---|
//! | `std` | reading frames from a `std::io::Read` |
//! | `embedded-io` | reading frames from an `embedded-io` reader |
//! | `stage-input` | every input chunk staged in the decoder's buffer before it is scanned, as on targets without 64-bit pointers (where it is the default: less code); on hosts, to test that path. Frames and stats are the same either way; only whether a frame borrows the caller's input changes |
//!
//! # Example
//!
//! A layout written by hand (generated code writes the same `static`): HFLink frames are
//! `FF FF sender receiver length(u16 BE) command payload sum`, where `length` counts the command
//! and the payload and `sum` is the sum of every preceding byte modulo 255.
//!
//! ```
//! use protocol_runtime::layout::{ByteOrder, Check, LengthRule, Pos, WordField};
//! use protocol_runtime::{Checksum, Event, FrameLayout, StreamDecoder};
//!
//! static HFLINK: FrameLayout<'static> = FrameLayout {
//!     sync: &[0xFF, 0xFF],
//!     header_len: 6,
//!     min_len: 8,
//!     max_len: 127,
//!     length: LengthRule::Field {
//!         field: WordField { at: Pos::Start(4), size: 2, order: ByteOrder::Big, shift: 0, width: 16 },
//!         adjust: 7,
//!     },
//!     constants: &[],
//!     header_checks: &[],
//!     frame_checks: &[Check {
//!         checksum: Checksum::SumMod255,
//!         from: Pos::Start(0),
//!         to: Pos::End(1),
//!         at: Pos::End(1),
//!         order: ByteOrder::Big,
//!     }],
//!     markers: &[],
//! };
//!
//! // Encode: write the user's fields in place, let the layout fill in the rest.
//! let mut frame = [0u8; 8];
//! frame[2..4].copy_from_slice(&[0x11, 0x01]); // sender, receiver
//! HFLINK.seal(&mut frame)?;
//! assert_eq!(frame, [0xFF, 0xFF, 0x11, 0x01, 0x00, 0x01, 0x00, 0x13]);
//!
//! // Decode a stream: a stray byte, a corrupt frame, then the frame cut in two chunks.
//! let mut corrupt = frame;
//! corrupt[6] = 0x05;
//! let stream = [&[0x42][..], &corrupt, &frame[..3], &frame[3..]].concat();
//! let mut decoder = StreamDecoder::<_, 128>::new(&HFLINK);
//! let mut events = Vec::new();
//! for mut chunk in stream.chunks(11) {
//!     while let Some(event) = decoder.next_event(&mut chunk) {
//!         events.push(match event {
//!             Event::Frame(f) => format!("frame at {}: {:02x?}", f.offset, f.bytes),
//!             other => format!("{other:?}"),
//!         });
//!     }
//! }
//! assert_eq!(events, [
//!     "Skipped { offset: 0, len: 1 }",
//!     "Rejected { offset: 1, reason: BadChecksum }",
//!     "Skipped { offset: 2, len: 7 }",
//!     "frame at 9: [ff, ff, 11, 01, 00, 01, 00, 13]",
//! ]);
//! assert_eq!(decoder.stats().bad_checksum, 1);
//! # Ok::<(), protocol_runtime::EncodeError>(())
//! ```
#![no_std]
#![forbid(unsafe_code)]
#![deny(
    missing_docs,
    clippy::indexing_slicing,
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    clippy::arithmetic_side_effects
)]

#[cfg(feature = "std")]
extern crate std;

pub mod bytes;
pub mod can;
pub mod checksum;
pub mod decoder;
pub mod encoder;
pub mod error;
pub mod field;
pub mod group;
#[cfg(any(feature = "std", feature = "embedded-io"))]
pub mod io;
pub mod layout;
pub mod stuffing;
pub mod wire;

pub use bytes::Bytes;
pub use can::CanFrame;
pub use checksum::Checksum;
pub use decoder::{Event, Frame, Reject, Stats, StreamDecoder};
pub use encoder::{Payload, PayloadVisitor};
pub use error::{DecodeError, DecodeResult, EncodeError, EncodeResult};
pub use group::Group;
pub use layout::FrameLayout;
pub use wire::{Reader, Writer};

/// Everything generated code names, under one path. Not a public API: it changes with the
/// code generator.
#[doc(hidden)]
pub mod __private {
    pub use crate::{
        bytes::*, can::*, checksum::*, decoder::*, encoder::*, error::*, field::*, group::*,
        layout::*, stuffing::*, wire::*,
    };
    pub use core;
    pub use core::option::Option::{self, None, Some};
    pub use core::result::Result::{self, Err, Ok};
    pub use crc;
}
