//! CRC_EXTRA: the byte MAVLink derives from a message's definition and folds into each frame's
//! CRC, so that a frame of one version of a message fails the check of another.
//!
//! This module owns that derivation alone: CRC-16/MCRF4XX (MAVLink's X.25) over the message
//! name and a space, then for each base field in wire order its C type and a space, its name
//! and a space, and for an array its length as one byte; the two bytes of the CRC XORed.
//! Extension fields do not take part, so appending one keeps the byte.

use crc::{CRC_16_MCRF4XX, Crc};

use super::model::Message;

/// The CRC_EXTRA byte of `message`.
pub fn crc_extra(message: &Message) -> u8 {
    const X25: Crc<u16> = Crc::<u16>::new(&CRC_16_MCRF4XX);
    let mut digest = X25.digest();
    digest.update(message.name.as_bytes());
    digest.update(b" ");
    for field in message.fields.iter().filter(|f| !f.extension) {
        digest.update(field.scalar.c_name().as_bytes());
        digest.update(b" ");
        digest.update(field.name.as_bytes());
        digest.update(b" ");
        if let Some(n) = field.array {
            // An array length is at most 255 (checked when the field is read).
            digest.update(&[n as u8]);
        }
    }
    let crc = digest.finalize();
    (crc & 0xFF) as u8 ^ (crc >> 8) as u8
}
