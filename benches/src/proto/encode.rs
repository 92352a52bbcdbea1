//! The prototype encoder: the body of the generated `Packet::encode` for the benchmark's two
//! messages, with the same steps in the same order (direction check, payload through the
//! runtime's `Writer`, header values, then sealing), changed in two places:
//!
//! 1. header values are written by an inlined copy of `WordField::write`: the `wire::*` fields
//!    are consts, so once the write is inlined it folds to a store at a fixed offset (the
//!    runtime's `WordField::write` and `write_uint` stay out of line, a call per field);
//! 2. sealing is [`seal`]: `FrameLayout::seal` with the layout a compile-time constant and the
//!    window checks of [`super::checks`] (the frame check is computed with the rest of the
//!    output buffer in reach);
//! 3. the generated `write_payload` (a `match` over every command, left out of line) is inlined
//!    by hand, as `#[inline]` on the generated method would let the compiler do: the `match`
//!    folds to the one payload's writes;
//! 4. the payload is written as codegen could emit it for a fixed-size struct: each field at a
//!    constant offset of one `&mut [u8; SIZE]`, instead of through `Writer`, which checks the
//!    room and advances a cursor for every field.

use protocol_runtime::EncodeError;
use protocol_runtime::layout::{ByteOrder, LengthRule, WordField};

use super::LayoutSource;
use crate::generated::{hflink, referee};

/// `WordField::write`, inlined (the value must fit the field's bits; the other bits of the word
/// are kept).
#[inline(always)]
fn write_word(f: &WordField, frame: &mut [u8], value: u64) -> Option<()> {
    let size = usize::from(f.size);
    let max = if f.width >= 64 {
        u64::MAX
    } else {
        (1u64 << f.width) - 1
    };
    if size == 0 || size > 8 || value > max {
        return None;
    }
    let at = f.at.resolve(frame.len())?;
    let word = frame.get_mut(at..at.checked_add(size)?)?;
    let mask = max << f.shift;
    let mut old = 0u64;
    for i in 0..size {
        let b = match f.order {
            ByteOrder::Big => word[i],
            ByteOrder::Little => word[size - 1 - i],
        };
        old = (old << 8) | u64::from(b);
    }
    let new = (old & !mask) | (value << f.shift);
    for i in 0..size {
        let b = (new >> (8 * (size - 1 - i))) as u8;
        match f.order {
            ByteOrder::Big => word[i] = b,
            ByteOrder::Little => word[size - 1 - i] = b,
        }
    }
    Some(())
}

/// `FrameLayout::seal` of the `len`-byte frame at the start of `buf`, with the layout a
/// constant and window checks (`buf` may run past the frame; nothing past it is written).
///
/// # Errors
///
/// As `FrameLayout::seal`.
#[inline(always)]
pub fn seal<L: LayoutSource>(buf: &mut [u8], len: usize) -> Result<(), EncodeError> {
    let layout = L::layout();
    let span = layout.header_span();
    let bare = layout.length.bare_len() == Some(len) && len >= span;
    let min = layout.min_len.max(span);
    if len < min && !bare {
        return Err(EncodeError::BufferTooSmall {
            needed: min,
            available: len,
        });
    }
    if len > layout.max_len {
        return Err(EncodeError::PayloadTooLarge {
            len,
            max: layout.max_len,
        });
    }
    let frame = buf.get_mut(..len).ok_or(EncodeError::ValueOutOfRange)?;
    let header = frame.get_mut(..span).ok_or(EncodeError::ValueOutOfRange)?;
    let sync = header
        .get_mut(..layout.sync.len())
        .ok_or(EncodeError::ValueOutOfRange)?;
    for (d, s) in sync.iter_mut().zip(layout.sync) {
        *d = *s;
    }
    match layout.length {
        LengthRule::Fixed(fixed) if fixed == len => {}
        LengthRule::Fixed(_) => return Err(EncodeError::ValueOutOfRange),
        LengthRule::Field { field, adjust } | LengthRule::FieldOrBare { field, adjust, .. } => {
            let value = i64::try_from(len)
                .ok()
                .and_then(|len| len.checked_sub(adjust))
                .and_then(|value| u64::try_from(value).ok())
                .ok_or(EncodeError::ValueOutOfRange)?;
            write_word(&field, header, value).ok_or(EncodeError::ValueOutOfRange)?;
        }
    }
    for c in layout.constants {
        write_word(&c.field, header, c.value).ok_or(EncodeError::ValueOutOfRange)?;
    }
    for c in L::header_checks() {
        store(c, buf, span)?;
    }
    if bare {
        return Ok(());
    }
    let frame = buf.get_mut(..len).ok_or(EncodeError::ValueOutOfRange)?;
    for m in layout.markers {
        m.write(frame).ok_or(EncodeError::ValueOutOfRange)?;
    }
    for c in L::frame_checks() {
        store(c, buf, len)?;
    }
    Ok(())
}

/// Computes a check of the `len`-byte frame at the start of `buf` and stores it.
#[inline(always)]
fn store(c: &super::checks::FastCheck, buf: &mut [u8], len: usize) -> Result<(), EncodeError> {
    let value = c
        .compute_exact(buf, len)
        .ok_or(EncodeError::ValueOutOfRange)?;
    let check = &c.check;
    let at = check.at.resolve(len).ok_or(EncodeError::ValueOutOfRange)?;
    let width = check.checksum.width();
    let field = WordField {
        at: protocol_runtime::layout::Pos::Start(at),
        size: width as u8,
        order: check.order,
        shift: 0,
        width: (8 * width) as u8,
    };
    let frame = buf.get_mut(..len).ok_or(EncodeError::ValueOutOfRange)?;
    write_word(&field, frame, value).ok_or(EncodeError::ValueOutOfRange)
}

/// A `READ_SYSTEM_INFO` response, as [`crate::generated::encode_system_info`] writes it.
///
/// # Errors
///
/// As the generated encoder.
#[inline]
pub fn encode_system_info(
    buf: &mut [u8],
    sender: u8,
    receiver: u8,
    info: [f32; 5],
) -> Result<usize, EncodeError> {
    use hflink::{HEADER_LEN, Message, Response, SystemInfo, TRAILER_LEN};
    let [
        system_time,
        cpu_temperature,
        cpu_usage,
        battery_voltage,
        power_remain,
    ] = info;
    let message = Message::Response(Response::ReadSystemInfo(SystemInfo {
        system_time,
        cpu_temperature,
        cpu_usage,
        battery_voltage,
        power_remain,
    }));
    // The generated body, step by step.
    let matches = match &message {
        Message::Request(_) => (1u8..=16).contains(&sender),
        Message::Response(_) => (17u8..=64).contains(&sender),
    };
    if !matches {
        return Err(EncodeError::ValueOutOfRange);
    }
    let needed = HEADER_LEN + message.payload_len() + TRAILER_LEN;
    let available = buf.len();
    if available < needed {
        return Err(EncodeError::BufferTooSmall { needed, available });
    }
    let region = buf
        .get_mut(HEADER_LEN..available.saturating_sub(TRAILER_LEN))
        .ok_or(EncodeError::BufferTooSmall { needed, available })?;
    // Changes 3 and 4: `write_payload` inlined (its `match` folds away), and the payload
    // written as codegen could emit it for a fixed-size struct: every field at a constant
    // offset of one `&mut [u8; SIZE]`, bounds-checked once.
    let mut written = 0;
    if let Message::Response(Response::ReadSystemInfo(info)) = &message {
        let out = region
            .first_chunk_mut::<20>()
            .ok_or(EncodeError::BufferTooSmall { needed, available })?;
        let fields = [
            info.system_time,
            info.cpu_temperature,
            info.cpu_usage,
            info.battery_voltage,
            info.power_remain,
        ];
        for (dst, v) in out.chunks_exact_mut(4).zip(fields) {
            dst.copy_from_slice(&v.to_le_bytes());
        }
        written = 20;
    }
    let total = HEADER_LEN + written + TRAILER_LEN;
    let frame = buf.get_mut(..total).ok_or(EncodeError::BufferTooSmall {
        needed: total,
        available,
    })?;
    write_word(&hflink::wire::SENDER, frame, u64::from(sender))
        .ok_or(EncodeError::ValueOutOfRange)?;
    write_word(&hflink::wire::RECEIVER, frame, u64::from(receiver))
        .ok_or(EncodeError::ValueOutOfRange)?;
    write_word(
        &hflink::wire::COMMAND,
        frame,
        u64::from(message.command().id()),
    )
    .ok_or(EncodeError::ValueOutOfRange)?;
    seal::<super::HfFast>(buf, total)?;
    Ok(total)
}

/// A `GAME_ROBOT_POS` frame, as [`crate::generated::encode_robot_pos`] writes it.
///
/// # Errors
///
/// As the generated encoder.
#[inline]
pub fn encode_robot_pos(buf: &mut [u8], seq: u8, pos: [f32; 4]) -> Result<usize, EncodeError> {
    use referee::{GameRobotPos, HEADER_LEN, Message, TRAILER_LEN};
    let [x, y, z, yaw] = pos;
    let message = Message::GameRobotPos(GameRobotPos { x, y, z, yaw });
    let needed = HEADER_LEN + message.payload_len() + TRAILER_LEN;
    let available = buf.len();
    if available < needed {
        return Err(EncodeError::BufferTooSmall { needed, available });
    }
    let region = buf
        .get_mut(HEADER_LEN..available.saturating_sub(TRAILER_LEN))
        .ok_or(EncodeError::BufferTooSmall { needed, available })?;
    // Changes 3 and 4, as for HFLink.
    let mut written = 0;
    if let Message::GameRobotPos(p) = &message {
        let out = region
            .first_chunk_mut::<16>()
            .ok_or(EncodeError::BufferTooSmall { needed, available })?;
        for (dst, v) in out.chunks_exact_mut(4).zip([p.x, p.y, p.z, p.yaw]) {
            dst.copy_from_slice(&v.to_le_bytes());
        }
        written = 16;
    }
    let total = HEADER_LEN + written + TRAILER_LEN;
    let frame = buf.get_mut(..total).ok_or(EncodeError::BufferTooSmall {
        needed: total,
        available,
    })?;
    write_word(&referee::wire::SEQ, frame, u64::from(seq)).ok_or(EncodeError::ValueOutOfRange)?;
    write_word(
        &referee::wire::CMD_ID,
        frame,
        u64::from(message.command().id()),
    )
    .ok_or(EncodeError::ValueOutOfRange)?;
    seal::<super::RefFast>(buf, total)?;
    Ok(total)
}
