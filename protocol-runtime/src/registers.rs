//! Register maps: a device's named registers at addresses (a servo's control table), and the
//! run of register bytes a request selects ([`Window`]: a READ's answer, a WRITE's data).
//!
//! The one rule of where a register's bytes lie in such a run is [`Window::cover`]; generated
//! code (a [`Register`] const per register of a spec's `[registers]`) and the run-time codec
//! both call it. What a register's value is (its type, scale and unit) is the spec's: the
//! generated `decode` functions and the run-time codec read it like a struct field.

/// A run of register bytes that starts at an address: what a READ's answer carries, or a
/// WRITE's data.
///
/// ```
/// use protocol_runtime::registers::{Cover, Window};
///
/// // A READ of 4 bytes from address 36, answered with them.
/// let w = Window::asked(36, 4, &[0x10, 0x02, 0x20, 0x00]);
/// assert_eq!(w.cover(36, 2), Cover::Whole(&[0x10, 0x02][..]));
/// assert_eq!(w.cover(39, 2), Cover::Part);
/// assert_eq!(w.cover(24, 1), Cover::Outside);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Window<'a> {
    start: u32,
    bytes: &'a [u8],
}

/// Where a register lies in a [`Window`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Cover<'a> {
    /// Every byte of it is in the window: these.
    Whole(&'a [u8]),
    /// Some of its bytes are, not all: the window starts or ends inside it.
    Part,
    /// None of its bytes are.
    Outside,
}

impl<'a> Window<'a> {
    /// The bytes `bytes`, the first at address `start`.
    #[must_use]
    pub const fn new(start: u32, bytes: &'a [u8]) -> Self {
        Window { start, bytes }
    }

    /// The run a request selected: `asked` bytes from `start`, of which `data` (its answer's
    /// bytes) holds the first; bytes of `data` beyond `asked` are no register's.
    #[must_use]
    pub fn asked(start: u32, asked: u64, data: &'a [u8]) -> Self {
        let n = usize::try_from(asked).map_or(data.len(), |a| a.min(data.len()));
        Window {
            start,
            bytes: data.get(..n).unwrap_or(data),
        }
    }

    /// The address of the first byte.
    #[must_use]
    pub const fn start(&self) -> u32 {
        self.start
    }

    /// The bytes.
    #[must_use]
    pub const fn bytes(&self) -> &'a [u8] {
        self.bytes
    }

    /// The address after the last byte.
    #[must_use]
    pub const fn end(&self) -> u64 {
        // Neither term exceeds 2^32 on any target this runs on, so the sum cannot wrap.
        (self.start as u64).saturating_add(self.bytes.len() as u64)
    }

    /// Where the register of `size` bytes at `address` lies in the window.
    #[must_use]
    pub fn cover(&self, address: u32, size: usize) -> Cover<'a> {
        let first = u64::from(address);
        let last = first.saturating_add(size as u64);
        let (start, end) = (u64::from(self.start), self.end());
        if last <= start || first >= end || size == 0 {
            return Cover::Outside;
        }
        if first < start || last > end {
            return Cover::Part;
        }
        let from = usize::try_from(first.saturating_sub(start)).unwrap_or(usize::MAX);
        match self.bytes.get(from..from.saturating_add(size)) {
            Some(b) => Cover::Whole(b),
            None => Cover::Part,
        }
    }
}

/// A register of a spec's `[registers]`: its name, address and size, and how its bytes give
/// its value (of type `T`). Generated code holds one as a `const` per register.
///
/// ```
/// use protocol_runtime::registers::{Register, Window};
///
/// const GOAL: Register<u16> =
///     Register::new("goal_position", 30, 2, |b| Some(u16::from_le_bytes([*b.first()?, *b.get(1)?])));
/// let written = Window::new(30, &[0x00, 0x02]);
/// assert_eq!(GOAL.read(written), Some(512));
/// assert_eq!(GOAL.decode(&[0x00]), None);
/// ```
#[derive(Debug, Clone, Copy)]
pub struct Register<T> {
    name: &'static str,
    address: u32,
    size: u8,
    value: fn(&[u8]) -> Option<T>,
}

impl<T> Register<T> {
    /// A register of `size` bytes at `address`, whose bytes `value` reads.
    #[must_use]
    pub const fn new(
        name: &'static str,
        address: u32,
        size: u8,
        value: fn(&[u8]) -> Option<T>,
    ) -> Self {
        Register {
            name,
            address,
            size,
            value,
        }
    }

    /// The spec's name.
    #[must_use]
    pub const fn name(&self) -> &'static str {
        self.name
    }

    /// The address of its first byte.
    #[must_use]
    pub const fn address(&self) -> u32 {
        self.address
    }

    /// Its bytes.
    #[must_use]
    pub const fn size(&self) -> usize {
        self.size as usize
    }

    /// The value of its bytes; `None` unless `bytes` is exactly [`size`](Self::size) long.
    #[must_use]
    pub fn decode(&self, bytes: &[u8]) -> Option<T> {
        if bytes.len() != self.size() {
            return None;
        }
        (self.value)(bytes)
    }

    /// Its value in `window`; `None` unless the window holds every byte of it.
    #[must_use]
    pub fn read(&self, window: Window<'_>) -> Option<T> {
        match window.cover(self.address, self.size()) {
            Cover::Whole(b) => self.decode(b),
            Cover::Part | Cover::Outside => None,
        }
    }
}

/// The value `read` reads from exactly `bytes`: what a generated register's `decode` runs.
/// `None` when `read` fails or leaves bytes unread.
///
/// ```
/// use protocol_runtime::registers::value;
///
/// assert_eq!(value(&[0x00, 0x08, 0, 0], |r| r.i32_le()), Some(2048));
/// assert_eq!(value(&[0x00, 0x08, 0], |r| r.u16_le()), None);
/// ```
pub fn value<'a, T>(
    bytes: &'a [u8],
    read: impl FnOnce(&mut crate::Reader<'a>) -> Result<T, crate::DecodeError>,
) -> Option<T> {
    let mut r = crate::Reader::new(bytes);
    let v = read(&mut r).ok()?;
    r.finish().ok()?;
    Some(v)
}
