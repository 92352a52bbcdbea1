//! CAN frames: an identifier and up to 8 data bytes. A spec's CAN frame format is described by
//! an ordinary [`FrameLayout`](crate::FrameLayout) over a *virtual frame*: the identifier as a
//! big-endian `u32`, the data length, then the data. Checks may then cover the identifier and
//! the length (as the AgileX Scout CAN checksum does), and the same engine verifies and seals
//! CAN and serial frames.

use crate::decoder::Reject;
use crate::error::{DecodeError, EncodeError};

/// Bytes of the virtual prefix: the identifier (4) and the data length (1).
pub const CAN_PREFIX_LEN: usize = 5;

/// Bytes of the longest virtual frame (prefix and 8 data bytes).
pub const CAN_VIRTUAL_LEN: usize = CAN_PREFIX_LEN + 8;

/// A classic CAN data frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct CanFrame {
    /// The identifier (11 or 29 bits).
    pub id: u32,
    /// Number of data bytes (0 to 8).
    pub len: u8,
    /// The data; bytes past `len` are zero.
    pub data: [u8; 8],
}

impl CanFrame {
    /// A frame from an identifier and its data.
    ///
    /// # Errors
    /// [`DecodeError::Frame`] with [`Reject::BadLength`] for more than 8 data bytes.
    pub fn new(id: u32, data: &[u8]) -> Result<Self, DecodeError> {
        let mut frame = CanFrame {
            id,
            len: 0,
            data: [0; 8],
        };
        let slot = frame
            .data
            .get_mut(..data.len())
            .ok_or(DecodeError::Frame(Reject::BadLength))?;
        slot.copy_from_slice(data);
        frame.len = data.len() as u8;
        Ok(frame)
    }

    /// The data bytes.
    pub fn data(&self) -> &[u8] {
        self.data.get(..usize::from(self.len)).unwrap_or(&self.data)
    }

    /// Write the virtual frame (identifier, length, data) into `buf`; returns its bytes.
    pub fn to_virtual<'b>(&self, buf: &'b mut [u8; CAN_VIRTUAL_LEN]) -> &'b [u8] {
        let len = usize::from(self.len.min(8));
        let [a, b, c, d] = self.id.to_be_bytes();
        let mut out = [0u8; CAN_VIRTUAL_LEN];
        out[0] = a;
        out[1] = b;
        out[2] = c;
        out[3] = d;
        out[4] = len as u8;
        for (dst, src) in out
            .iter_mut()
            .skip(CAN_PREFIX_LEN)
            .zip(self.data.iter().take(len))
        {
            *dst = *src;
        }
        *buf = out;
        let n = CAN_PREFIX_LEN.wrapping_add(len);
        let all: &'b [u8] = buf;
        all.get(..n).unwrap_or(all)
    }

    /// The frame held by a sealed virtual frame.
    ///
    /// # Errors
    /// [`EncodeError::ValueOutOfRange`] if `virt` is shorter than the prefix or holds more than
    /// 8 data bytes.
    pub fn from_virtual(virt: &[u8]) -> Result<Self, EncodeError> {
        let (prefix, data) = virt
            .split_first_chunk::<CAN_PREFIX_LEN>()
            .ok_or(EncodeError::ValueOutOfRange)?;
        let [a, b, c, d, _] = *prefix;
        CanFrame::new(u32::from_be_bytes([a, b, c, d]), data)
            .map_err(|_| EncodeError::ValueOutOfRange)
    }
}
