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

/// Largest standard (11-bit) identifier.
pub const MAX_STANDARD_ID: u32 = 0x7FF;

/// Largest extended (29-bit) identifier.
pub const MAX_EXTENDED_ID: u32 = 0x1FFF_FFFF;

/// A classic CAN data frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct CanFrame {
    /// The identifier (11 or 29 bits).
    pub id: u32,
    /// Whether the identifier is an extended (29-bit) one. On the bus a standard and an
    /// extended frame with the same number are different frames; checks cover the number only.
    pub extended: bool,
    /// Number of data bytes (0 to 8).
    pub len: u8,
    /// The data; bytes past `len` are zero.
    pub data: [u8; 8],
}

impl CanFrame {
    /// A frame from an identifier and its data: a standard frame for an identifier of 11 bits,
    /// an extended one above ([`into_extended`](Self::into_extended) makes a small identifier
    /// extended).
    ///
    /// # Errors
    /// [`DecodeError::Frame`] with [`Reject::BadLength`] for more than 8 data bytes.
    pub fn new(id: u32, data: &[u8]) -> Result<Self, DecodeError> {
        let mut frame = CanFrame {
            id,
            extended: id > MAX_STANDARD_ID,
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

    /// The same frame with an extended identifier (a spec's `can_id = "extended"`).
    #[must_use]
    pub const fn into_extended(self) -> Self {
        CanFrame {
            extended: true,
            ..self
        }
    }

    /// The frame, if its identifier's kind is `extended` (a spec's `can_id`): on the bus a
    /// standard and an extended frame with the same number are different frames, so a frame of
    /// the other kind belongs to another protocol. Generated `<Name>Packet::decode` and
    /// `protocol-dynamic` both call this before anything else.
    ///
    /// # Errors
    /// [`DecodeError::Frame`] with [`Reject::BadHeader`] for a frame of the other kind.
    ///
    /// ```
    /// use protocol_runtime::{CanFrame, DecodeError, Reject};
    /// let standard = CanFrame::new(0x130, &[1, 2])?;
    /// assert_eq!(standard.of_kind(false), Ok(&standard));
    /// assert_eq!(standard.of_kind(true), Err(DecodeError::Frame(Reject::BadHeader)));
    /// # Ok::<(), DecodeError>(())
    /// ```
    pub fn of_kind(&self, extended: bool) -> Result<&Self, DecodeError> {
        if self.extended == extended {
            Ok(self)
        } else {
            Err(DecodeError::Frame(Reject::BadHeader))
        }
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
        let (prefix, data) =
            virt.split_first_chunk::<CAN_PREFIX_LEN>()
                .ok_or(EncodeError::ValueOutOfRange {
                    place: crate::error::Place::NONE,
                })?;
        let [a, b, c, d, _] = *prefix;
        CanFrame::new(u32::from_be_bytes([a, b, c, d]), data).map_err(|_| {
            EncodeError::ValueOutOfRange {
                place: crate::error::Place::NONE,
            }
        })
    }
}

#[cfg(feature = "embedded-can")]
mod embedded {
    //! [`CanFrame`] as an `embedded_can::Frame`, and conversions from and to the frame type of
    //! a CAN driver (any `embedded_can::Frame`: HAL drivers, `socketcan`).

    use embedded_can::{ExtendedId, Frame, Id, StandardId};

    use super::{CanFrame, MAX_EXTENDED_ID};

    impl CanFrame {
        /// The frame a driver received (any `embedded_can::Frame`). `None` for a remote frame
        /// or one of more than 8 bytes (a CAN FD frame): they carry no classic data.
        pub fn from_frame<F: Frame>(frame: &F) -> Option<Self> {
            if frame.is_remote_frame() {
                return None;
            }
            <CanFrame as Frame>::new(frame.id(), frame.data())
        }

        /// The frame as a driver's frame type, to send.
        pub fn to_frame<F: Frame>(&self) -> Option<F> {
            F::new(Frame::id(self), self.data())
        }
    }

    impl Frame for CanFrame {
        /// A data frame; `None` for more than 8 bytes.
        fn new(id: impl Into<Id>, data: &[u8]) -> Option<Self> {
            let (raw, extended) = match id.into() {
                Id::Standard(id) => (u32::from(id.as_raw()), false),
                Id::Extended(id) => (id.as_raw(), true),
            };
            let frame = CanFrame::new(raw, data).ok()?;
            Some(CanFrame { extended, ..frame })
        }

        /// `None`: a [`CanFrame`] is a data frame.
        fn new_remote(_id: impl Into<Id>, _dlc: usize) -> Option<Self> {
            None
        }

        fn is_extended(&self) -> bool {
            self.extended
        }

        fn is_remote_frame(&self) -> bool {
            false
        }

        /// The identifier; a standard one whose number does not fit 11 bits is reported as
        /// extended (the fields are public, so nothing else keeps them consistent).
        fn id(&self) -> Id {
            let standard = u16::try_from(self.id).ok().and_then(StandardId::new);
            match standard {
                Some(id) if !self.extended => Id::Standard(id),
                _ => Id::Extended(
                    ExtendedId::new(self.id & MAX_EXTENDED_ID).unwrap_or(ExtendedId::MAX),
                ),
            }
        }

        fn dlc(&self) -> usize {
            usize::from(self.len.min(8))
        }

        fn data(&self) -> &[u8] {
            CanFrame::data(self)
        }
    }

    #[cfg(test)]
    #[allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]
    mod tests {
        use super::*;

        /// A driver's frame type: data or remote, up to 8 bytes, as a HAL defines one.
        #[derive(Debug, PartialEq)]
        struct Driver {
            id: Id,
            remote: bool,
            data: [u8; 8],
            dlc: usize,
        }

        impl Frame for Driver {
            fn new(id: impl Into<Id>, data: &[u8]) -> Option<Self> {
                let mut d = [0; 8];
                d.get_mut(..data.len())?.copy_from_slice(data);
                Some(Driver {
                    id: id.into(),
                    remote: false,
                    data: d,
                    dlc: data.len(),
                })
            }
            fn new_remote(id: impl Into<Id>, dlc: usize) -> Option<Self> {
                Some(Driver {
                    id: id.into(),
                    remote: true,
                    data: [0; 8],
                    dlc,
                })
            }
            fn is_extended(&self) -> bool {
                matches!(self.id, Id::Extended(_))
            }
            fn is_remote_frame(&self) -> bool {
                self.remote
            }
            fn id(&self) -> Id {
                self.id
            }
            fn dlc(&self) -> usize {
                self.dlc
            }
            fn data(&self) -> &[u8] {
                &self.data[..self.dlc]
            }
        }

        #[test]
        fn standard_and_extended_ids_round_trip() {
            let std_id = Id::Standard(StandardId::new(0x151).unwrap());
            let ext_small = Id::Extended(ExtendedId::new(0x151).unwrap());
            let ext_big = Id::Extended(ExtendedId::new(0x18FF_50E5).unwrap());
            for id in [std_id, ext_small, ext_big] {
                let driver = Driver::new(id, &[1, 2, 3]).unwrap();
                let frame = CanFrame::from_frame(&driver).expect("a data frame");
                assert_eq!(frame.data(), [1, 2, 3]);
                assert_eq!(frame.is_extended(), matches!(id, Id::Extended(_)));
                assert_eq!(Frame::id(&frame), id);
                assert_eq!(frame.to_frame::<Driver>(), Some(driver));
            }
            // The same number, standard and extended: two frames.
            let a = CanFrame::from_frame(&Driver::new(std_id, &[]).unwrap()).unwrap();
            let b = CanFrame::from_frame(&Driver::new(ext_small, &[]).unwrap()).unwrap();
            assert_eq!(a.id, b.id);
            assert_ne!(a, b);
        }

        #[test]
        fn inferred_kind_and_inconsistent_fields() {
            assert!(!CanFrame::new(0x7FF, &[]).unwrap().extended);
            assert!(CanFrame::new(0x800, &[]).unwrap().extended);
            assert!(
                CanFrame::new(0x10, &[])
                    .unwrap()
                    .into_extended()
                    .is_extended()
            );
            let odd = CanFrame {
                id: 0x1234,
                extended: false,
                len: 0,
                data: [0; 8],
            };
            assert_eq!(
                Frame::id(&odd),
                Id::Extended(ExtendedId::new(0x1234).unwrap())
            );
        }

        #[test]
        fn remote_and_long_frames_are_refused() {
            let id = StandardId::new(0x10).unwrap();
            assert_eq!(
                CanFrame::from_frame(&Driver::new_remote(id, 2).unwrap()),
                None
            );
            assert_eq!(<CanFrame as Frame>::new(id, &[0; 9]), None);
            assert_eq!(CanFrame::new_remote(id, 0), None);
        }
    }
}
