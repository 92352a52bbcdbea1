//! A packet carried inside another's payload (nested dispatch): a `bytes` field holds the
//! payload of the command whose id an earlier field of the same struct holds, as MSP v1's
//! command 255 carries an MSP v2 command and its payload. The carrying struct keeps the bytes
//! (so its size stays finite and no heap is needed); generated code reads them as a typed
//! message when asked ([`carried_command`]) and writes a message into them
//! ([`seal_carried`], [`carried_key`]), setting the key field from the message's command.

use crate::bytes::Bytes;
use crate::encoder::{MessagePayload, unknown_command};
use crate::error::{DecodeError, EncodeError, Place};
use crate::wire::Writer;

/// The command that the key field's value `key` names, found by the spec's `from_id`.
///
/// # Errors
///
/// [`DecodeError::UnknownCommand`] when `key` is not the id of a command: it does not fit the
/// id type, or no command has it.
///
/// ```
/// use protocol_runtime::{DecodeError, field::carried_command};
/// let from_id = |id: u8| (id == 7).then_some("SEVEN");
/// assert_eq!(carried_command(7u16, from_id), Ok("SEVEN"));
/// assert_eq!(carried_command(8u16, from_id), Err(DecodeError::UnknownCommand { key: 8 }));
/// assert_eq!(carried_command(263u16, from_id), Err(DecodeError::UnknownCommand { key: 263 }));
/// ```
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn carried_command<K: Into<u64>, I: TryFrom<u64>, C>(
    key: K,
    from_id: impl FnOnce(I) -> Option<C>,
) -> Result<C, DecodeError> {
    let key = key.into();
    I::try_from(key)
        .ok()
        .and_then(from_id)
        .ok_or(unknown_command(key))
}

/// The value of a key or size field of `bits` bits (in a Rust type `K`) that holds `value`.
///
/// # Errors
///
/// [`EncodeError::ValueOutOfRange`] when `value` does not fit `bits` bits: the command is not
/// one the carrying field can name, or its payload is longer than the size field counts.
///
/// ```
/// use protocol_runtime::field::carried_key;
/// assert_eq!(carried_key::<u16>(0x1003u16, 16), Ok(0x1003));
/// assert!(carried_key::<u8>(0x1003u16, 8).is_err());
/// assert!(carried_key::<u32>(1u32 << 24, 24).is_err());
/// ```
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn carried_key<K: TryFrom<u64>>(value: impl Into<u64>, bits: u32) -> Result<K, EncodeError> {
    let value = value.into();
    let out_of_range = EncodeError::ValueOutOfRange { place: Place::NONE };
    if bits < 64 && value >> bits != 0 {
        return Err(out_of_range);
    }
    K::try_from(value).map_err(|_| out_of_range)
}

/// The payload of `message` as the bytes of a carrying field of at most `N` bytes.
///
/// # Errors
///
/// The errors of writing the payload (a value that does not fit its field), and
/// [`EncodeError::ValueOutOfRange`] when the payload is longer than `N` bytes.
///
/// ```
/// use protocol_runtime::{Bytes, encoder::{CommandMessage, CommandPayload}, field::seal_carried};
///
/// #[derive(Clone, Copy)]
/// struct Seven;
/// impl protocol_runtime::encoder::CommandName for Seven {
///     fn command_name(&self) -> &'static str {
///         "SEVEN"
///     }
/// }
/// #[derive(Clone, Copy)]
/// struct Pair(u16);
/// impl protocol_runtime::Payload for Pair {
///     const SIZE: usize = 2;
///     fn write(&self, w: &mut protocol_runtime::Writer<'_>) -> protocol_runtime::EncodeResult {
///         w.put_u16_le(self.0)
///     }
///     fn read(r: &mut protocol_runtime::Reader<'_>) -> protocol_runtime::DecodeResult<Self> {
///         Ok(Pair(r.u16_le()?))
///     }
/// }
/// impl CommandPayload for Pair {
///     type Command = Seven;
///     const COMMAND: Seven = Seven;
/// }
/// let bytes: Bytes<4> = seal_carried(&CommandMessage(&Pair(0x0102))).expect("fits");
/// assert_eq!(bytes.as_slice(), &[0x02, 0x01]);
/// assert!(seal_carried::<1, _>(&CommandMessage(&Pair(0x0102))).is_err());
/// ```
pub fn seal_carried<const N: usize, M: MessagePayload>(
    message: &M,
) -> Result<Bytes<N>, EncodeError> {
    let out_of_range = EncodeError::ValueOutOfRange { place: Place::NONE };
    if message.payload_len() > N {
        return Err(out_of_range);
    }
    let mut buf = [0u8; N];
    let mut w = Writer::new(&mut buf);
    message.write_payload(&mut w)?;
    let len = w.position();
    Bytes::from_slice(buf.get(..len).unwrap_or_default()).ok_or(out_of_range)
}
