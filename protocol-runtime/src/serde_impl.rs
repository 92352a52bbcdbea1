//! `Serialize` and `Deserialize` (the `serde` feature) for the runtime's value types, and the
//! helpers the impls of generated types call (`protocol!(..., derive(serde))`). `no_std` and
//! heap-free: nothing here buffers.
//!
//! The shape is that of the run-time codec's JSON (`protocol decode --format json`), so a
//! generated packet and the codec print the same JSON for the same frame:
//!
//! - [`Bytes`] is a lowercase hex string in a human-readable format, bytes otherwise;
//! - [`FixedStr`] is its text as a string when it is canonical (UTF-8 and only NUL bytes after
//!   it), else the array of its `N` bytes, so that every byte comes back;
//! - [`NulStr`] is its text as a string when it is UTF-8, else the array of its bytes (the NUL
//!   not included); [`Str`] the same;
//! - [`Group`] and arrays of any length ([`mod@array`]) are sequences;
//! - a spec enum is its variant's name in the spec, or its number when it has none
//!   ([`serialize_enum`], [`deserialize_enum`]);
//! - a packet is a map of `command` (the command's spec name; absent for an acknowledgement),
//!   `header` and `payload` ([`SerdePacket`]), after `direction` (the direction's name) in a
//!   spec whose decoder is given the direction; a command without payload has the empty map.
//!
//! Reading a packet needs `direction`, `command` and `header` before `payload` (the order every
//! serializer here writes), since the payload's type depends on them and nothing is buffered;
//! other keys (the codec's `offset`, `format`, `hex`, ...) are skipped, so a line of
//! `protocol decode --format json` reads as a generated packet.
//!
//! A value type added to the runtime gets its impls here: `Serialize` writing the codec's JSON
//! shape of the type, and `Deserialize` reading it back (usually a `Visitor` of a few methods).

use core::fmt;
use core::marker::PhantomData;

use serde::de::{self, Deserializer, IgnoredAny, MapAccess, SeqAccess, Visitor};
use serde::ser::{SerializeMap, SerializeSeq, SerializeTuple, Serializer};
use serde::{Deserialize, Serialize};

use crate::bytes::Bytes;
use crate::group::Group;
use crate::text::{FixedStr, NulStr};
use crate::unterminated::Str;

pub mod float;
mod packet;

pub use packet::{
    SerdeAnyPacket, SerdePacket, deserialize_any_packet, deserialize_name, deserialize_packet,
    packet_from_map, payload_error, serialize_name, serialize_packet, serialize_packet_in,
};

/// Bytes as lowercase hex, written straight into the serializer (no buffer).
struct Hex<'a>(&'a [u8]);

impl fmt::Display for Hex<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.iter().try_for_each(|b| write!(f, "{b:02x}"))
    }
}

/// The value of one hex digit.
fn nibble(c: u8) -> Option<u8> {
    match c {
        b'0'..=b'9' => Some(c.wrapping_sub(b'0')),
        b'a'..=b'f' => Some(c.wrapping_sub(b'a').wrapping_add(10)),
        b'A'..=b'F' => Some(c.wrapping_sub(b'A').wrapping_add(10)),
        _ => None,
    }
}

impl<const N: usize> Serialize for Bytes<N> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        if s.is_human_readable() {
            s.collect_str(&Hex(self.as_slice()))
        } else {
            s.serialize_bytes(self.as_slice())
        }
    }
}

struct BytesVisitor<const N: usize>;

impl<'de, const N: usize> Visitor<'de> for BytesVisitor<N> {
    type Value = Bytes<N>;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "at most {N} bytes, as a hex string")
    }

    fn visit_str<E: de::Error>(self, text: &str) -> Result<Bytes<N>, E> {
        let digits = text.as_bytes();
        if digits.len() % 2 != 0 || digits.len() / 2 > N {
            return Err(E::invalid_length(digits.len() / 2, &self));
        }
        let mut out = [0u8; N];
        for (slot, pair) in out.iter_mut().zip(digits.chunks_exact(2)) {
            let (hi, lo) = match pair {
                [hi, lo] => (nibble(*hi), nibble(*lo)),
                _ => (None, None),
            };
            *slot = hi
                .zip(lo)
                .map(|(hi, lo)| (hi << 4) | lo)
                .ok_or_else(|| E::invalid_value(de::Unexpected::Str(text), &self))?;
        }
        out.get(..digits.len() / 2)
            .and_then(Bytes::from_slice)
            .ok_or_else(|| E::invalid_length(digits.len() / 2, &self))
    }

    fn visit_bytes<E: de::Error>(self, bytes: &[u8]) -> Result<Bytes<N>, E> {
        Bytes::from_slice(bytes).ok_or_else(|| E::invalid_length(bytes.len(), &self))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Bytes<N>, A::Error> {
        let mut out = [0u8; N];
        let mut len = 0usize;
        while let Some(b) = seq.next_element::<u8>()? {
            let slot = out
                .get_mut(len)
                .ok_or_else(|| de::Error::invalid_length(len.saturating_add(1), &self))?;
            *slot = b;
            len = len.saturating_add(1);
        }
        out.get(..len)
            .and_then(Bytes::from_slice)
            .ok_or_else(|| de::Error::invalid_length(len, &self))
    }
}

impl<'de, const N: usize> Deserialize<'de> for Bytes<N> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        if d.is_human_readable() {
            d.deserialize_str(BytesVisitor)
        } else {
            d.deserialize_bytes(BytesVisitor)
        }
    }
}

impl<const N: usize> Serialize for FixedStr<N> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self.as_str() {
            Ok(text) if self.is_canonical() => s.serialize_str(text),
            _ => array::serialize(self.as_bytes(), s),
        }
    }
}

struct FixedStrVisitor<const N: usize>;

impl<'de, const N: usize> Visitor<'de> for FixedStrVisitor<N> {
    type Value = FixedStr<N>;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "a text of at most {N} bytes, or an array of {N} bytes")
    }

    fn visit_str<E: de::Error>(self, text: &str) -> Result<FixedStr<N>, E> {
        FixedStr::from_text(text).ok_or_else(|| E::invalid_length(text.len(), &self))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<FixedStr<N>, A::Error> {
        array::ArrayVisitor::<u8, N>(PhantomData)
            .visit_seq(seq)
            .map(FixedStr::from_bytes)
    }
}

impl<'de, const N: usize> Deserialize<'de> for FixedStr<N> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(FixedStrVisitor)
    }
}

/// `Option<[u8; N]>`, a header's flag trailer (a MAVLink 2 signature): its bytes as [`Bytes`]
/// are (a hex string in a human-readable format), `null` when the flag announces none.
pub mod trailer {
    use super::{Bytes, Deserialize, Deserializer, Serialize, Serializer, de};

    /// Serializes the bytes as [`Bytes`] does, or none.
    ///
    /// # Errors
    /// The serializer's.
    pub fn serialize<S: Serializer, const N: usize>(
        x: &Option<[u8; N]>,
        s: S,
    ) -> Result<S::Ok, S::Error> {
        x.as_ref()
            .and_then(|b| Bytes::<N>::from_slice(b))
            .serialize(s)
    }

    /// Reads what [`serialize`] writes: exactly `N` bytes, or none.
    ///
    /// # Errors
    /// Not bytes, or not `N` of them.
    pub fn deserialize<'de, D: Deserializer<'de>, const N: usize>(
        d: D,
    ) -> Result<Option<[u8; N]>, D::Error> {
        let Some(bytes) = Option::<Bytes<N>>::deserialize(d)? else {
            return Ok(None);
        };
        let exact: [u8; N] = bytes.as_slice().try_into().map_err(|_| {
            de::Error::invalid_length(bytes.as_slice().len(), &"exactly the trailer's bytes")
        })?;
        Ok(Some(exact))
    }
}

impl<const N: usize> Serialize for NulStr<N> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self.as_str() {
            Ok(text) => s.serialize_str(text),
            Err(_) => self.text().serialize(s),
        }
    }
}

struct NulStrVisitor<const N: usize>;

impl<'de, const N: usize> Visitor<'de> for NulStrVisitor<N> {
    type Value = NulStr<N>;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "a text of at most {N} bytes without NUL, or an array of such bytes"
        )
    }

    fn visit_str<E: de::Error>(self, text: &str) -> Result<NulStr<N>, E> {
        NulStr::from_text(text).ok_or_else(|| E::invalid_value(de::Unexpected::Str(text), &self))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<NulStr<N>, A::Error> {
        let (bytes, len) = text_bytes::<N, A>(seq, &self)?;
        let text = bytes.get(..len).unwrap_or_default();
        NulStr::from_text_bytes(text)
            .ok_or_else(|| de::Error::invalid_value(de::Unexpected::Bytes(text), &self))
    }
}

/// The bytes of a text given as an array, collected on the stack (a text type of `N` bytes
/// has no heap to grow into): the buffer and how many it holds. One byte beyond `N` is already
/// too long, an error that `expected` describes.
fn text_bytes<'de, const N: usize, A: SeqAccess<'de>>(
    mut seq: A,
    expected: &dyn de::Expected,
) -> Result<([u8; N], usize), A::Error> {
    let mut bytes = [0u8; N];
    let mut len = 0;
    while let Some(b) = seq.next_element::<u8>()? {
        let slot = bytes
            .get_mut(len)
            .ok_or_else(|| de::Error::invalid_length(len.saturating_add(1), expected))?;
        *slot = b;
        len = len.saturating_add(1);
    }
    Ok((bytes, len))
}

impl<'de, const N: usize> Deserialize<'de> for NulStr<N> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(NulStrVisitor)
    }
}

impl<const N: usize> Serialize for Str<N> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self.as_str() {
            Ok(text) => s.serialize_str(text),
            Err(_) => self.text().serialize(s),
        }
    }
}

struct StrVisitor<const N: usize>;

impl<'de, const N: usize> Visitor<'de> for StrVisitor<N> {
    type Value = Str<N>;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "a text of at most {N} bytes, or an array of such bytes")
    }

    fn visit_str<E: de::Error>(self, text: &str) -> Result<Str<N>, E> {
        Str::from_text(text).ok_or_else(|| E::invalid_value(de::Unexpected::Str(text), &self))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Str<N>, A::Error> {
        let (bytes, len) = text_bytes::<N, A>(seq, &self)?;
        let text = bytes.get(..len).unwrap_or_default();
        Str::from_text_bytes(text)
            .ok_or_else(|| de::Error::invalid_value(de::Unexpected::Bytes(text), &self))
    }
}

impl<'de, const N: usize> Deserialize<'de> for Str<N> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(StrVisitor)
    }
}

impl<T: Copy + Default + Serialize, const N: usize> Serialize for Group<T, N> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut seq = s.serialize_seq(Some(self.len()))?;
        self.iter()
            .try_for_each(|item| seq.serialize_element(item))?;
        seq.end()
    }
}

struct GroupVisitor<T, const N: usize>(PhantomData<T>);

impl<'de, T: Copy + Default + Deserialize<'de>, const N: usize> Visitor<'de>
    for GroupVisitor<T, N>
{
    type Value = Group<T, N>;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "at most {N} elements")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Group<T, N>, A::Error> {
        let mut out = Group::new();
        while let Some(item) = seq.next_element()? {
            out.push(item)
                .map_err(|_| de::Error::invalid_length(N.saturating_add(1), &self))?;
        }
        Ok(out)
    }
}

impl<'de, T: Copy + Default + Deserialize<'de>, const N: usize> Deserialize<'de> for Group<T, N> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_seq(GroupVisitor(PhantomData))
    }
}

/// Arrays of any length as sequences (serde's own impls stop at 32 elements): the field
/// attribute `#[serde(with = "...::array")]` of generated arrays longer than that.
pub mod array {
    use super::*;

    /// Writes the array as a tuple of `N` elements (a JSON array).
    ///
    /// # Errors
    /// The serializer's.
    pub fn serialize<T: Serialize, S: Serializer, const N: usize>(
        items: &[T; N],
        s: S,
    ) -> Result<S::Ok, S::Error> {
        let mut tuple = s.serialize_tuple(N)?;
        items
            .iter()
            .try_for_each(|item| tuple.serialize_element(item))?;
        tuple.end()
    }

    /// Reads exactly `N` elements (`N` > 0).
    ///
    /// # Errors
    /// The deserializer's, and a length error for fewer or more than `N` elements.
    pub fn deserialize<'de, T: Copy + Deserialize<'de>, D: Deserializer<'de>, const N: usize>(
        d: D,
    ) -> Result<[T; N], D::Error> {
        d.deserialize_tuple(N, ArrayVisitor(PhantomData))
    }

    pub(super) struct ArrayVisitor<T, const N: usize>(pub(super) PhantomData<T>);

    impl<'de, T: Copy + Deserialize<'de>, const N: usize> Visitor<'de> for ArrayVisitor<T, N> {
        type Value = [T; N];

        fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            write!(f, "an array of {N} elements")
        }

        fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<[T; N], A::Error> {
            // The first element fills the array (no `Default` needed), the others follow. The
            // arrays this reads have elements (longer than serde's own impls take).
            let Some(first) = seq.next_element::<T>()? else {
                return Err(de::Error::invalid_length(0, &self));
            };
            let mut out = [first; N];
            for (i, slot) in out.iter_mut().enumerate().skip(1) {
                *slot = seq
                    .next_element()?
                    .ok_or_else(|| de::Error::invalid_length(i, &self))?;
            }
            if seq.next_element::<IgnoredAny>()?.is_some() {
                return Err(de::Error::invalid_length(N.saturating_add(1), &self));
            }
            Ok(out)
        }
    }
}

/// An empty payload: the empty map.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Empty;

impl Serialize for Empty {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_map(Some(0))?.end()
    }
}

impl<'de> Deserialize<'de> for Empty {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct EmptyVisitor;
        impl<'de> Visitor<'de> for EmptyVisitor {
            type Value = Empty;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("an empty map")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Empty, A::Error> {
                match map.next_key::<IgnoredAny>()? {
                    None => Ok(Empty),
                    Some(_) => Err(de::Error::invalid_length(1, &self)),
                }
            }
            fn visit_unit<E: de::Error>(self) -> Result<Empty, E> {
                Ok(Empty)
            }
        }
        d.deserialize_any(EmptyVisitor)
    }
}

/// Writes a spec enum: its variant's name when `value` is in `names`, else its number `raw`.
///
/// # Errors
/// The serializer's.
pub fn serialize_enum<E: PartialEq, R: Serialize, S: Serializer>(
    s: S,
    names: &[(&'static str, E)],
    value: &E,
    raw: R,
) -> Result<S::Ok, S::Error> {
    match names.iter().find(|(_, v)| v == value) {
        Some((name, _)) => s.serialize_str(name),
        None => raw.serialize(s),
    }
}

/// Reads a spec enum: a variant's name from `names`, or a number that `from_raw` accepts.
///
/// # Errors
/// The deserializer's, and an error for a name not in `names` or a number `from_raw` refuses.
pub fn deserialize_enum<'de, D, E, R, F>(
    d: D,
    names: &'static [(&'static str, E)],
    from_raw: F,
) -> Result<E, D::Error>
where
    D: Deserializer<'de>,
    E: Copy,
    R: TryFrom<i128>,
    F: Fn(R) -> Option<E>,
{
    d.deserialize_any(EnumVisitor {
        names,
        from_raw,
        raw: PhantomData,
    })
}

struct EnumVisitor<E: 'static, R, F> {
    names: &'static [(&'static str, E)],
    from_raw: F,
    raw: PhantomData<R>,
}

impl<E: Copy, R: TryFrom<i128>, F: Fn(R) -> Option<E>> EnumVisitor<E, R, F> {
    fn number<Er: de::Error>(self, n: i128) -> Result<E, Er> {
        R::try_from(n)
            .ok()
            .and_then(&self.from_raw)
            .ok_or_else(|| Er::custom(format_args!("{n} is no value of the enum")))
    }
}

impl<'de, E: Copy, R: TryFrom<i128>, F: Fn(R) -> Option<E>> Visitor<'de> for EnumVisitor<E, R, F> {
    type Value = E;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a variant's name or a number")
    }

    fn visit_str<Er: de::Error>(self, name: &str) -> Result<E, Er> {
        self.names
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, v)| *v)
            .ok_or_else(|| Er::custom(format_args!("no variant `{name}`")))
    }

    fn visit_u64<Er: de::Error>(self, n: u64) -> Result<E, Er> {
        self.number(i128::from(n))
    }

    fn visit_i64<Er: de::Error>(self, n: i64) -> Result<E, Er> {
        self.number(i128::from(n))
    }
}
