//! Packets as the map of `direction` (given directions only), `command`, `header` and `payload`
//! (see the parent module), and commands as their names in the spec. A packet of a link of
//! several command formats (generated `AnyPacket`) is its format's packet with the format's
//! name first, as `format`.

use core::fmt;
use core::marker::PhantomData;

use serde::de::{self, DeserializeSeed, Deserializer, IgnoredAny, MapAccess, Visitor};
use serde::ser::{SerializeMap, Serializer};
use serde::{Deserialize, Serialize};

/// What a generated packet gives and takes for its `Serialize` and `Deserialize` impls (which
/// call [`serialize_packet`] and [`deserialize_packet`]).
pub trait SerdePacket: Sized {
    /// The header values.
    type Header: Serialize + for<'de> Deserialize<'de>;
    /// The message: it serializes as its payload alone.
    type Message: Serialize;
    /// The command enum.
    type Command: Copy;

    /// The command's name in the spec (`None` for an acknowledgement), the header and the
    /// message.
    fn parts(&self) -> (Option<&'static str>, &Self::Header, &Self::Message);
    /// The command of a spec name.
    fn command_named(name: &str) -> Option<Self::Command>;
    /// Reads the payload of `command` (`None`: no `command` key) sent with `header`.
    ///
    /// # Errors
    /// The deserializer's, and an error for a missing command or a header of no direction.
    fn payload<'de, D: Deserializer<'de>>(
        command: Option<Self::Command>,
        header: &Self::Header,
        d: D,
    ) -> Result<Self::Message, D::Error>;
    /// The packet of a header and a message.
    fn from_parts(header: Self::Header, message: Self::Message) -> Self;
    /// The names of the directions the decoder is given (`given = true` in the spec), in the
    /// spec's order; empty when the header tells the direction.
    const GIVEN_DIRECTIONS: &'static [&'static str] = &[];
    /// The packet's direction, for a spec whose decoder is given it.
    fn direction(&self) -> Option<&'static str> {
        None
    }
    /// Reads the payload of `command` sent with `header` in `direction` (an index into
    /// [`Self::GIVEN_DIRECTIONS`]; `None`: no `direction` key): [`Self::payload`] unless the
    /// spec's directions are given.
    ///
    /// # Errors
    /// Those of [`Self::payload`], and an error for a missing direction.
    fn payload_in<'de, D: Deserializer<'de>>(
        command: Option<Self::Command>,
        header: &Self::Header,
        direction: Option<usize>,
        d: D,
    ) -> Result<Self::Message, D::Error> {
        let _ = direction;
        Self::payload(command, header, d)
    }
}

/// Writes a packet as the map `direction` (when the decoder is given it), `command` (when it
/// has one), `header`, `payload`.
///
/// # Errors
/// The serializer's.
pub fn serialize_packet<P: SerdePacket, S: Serializer>(p: &P, s: S) -> Result<S::Ok, S::Error> {
    serialize_packet_in(p, None, s)
}

/// [`serialize_packet`] with the name of the packet's frame `format` first, when given (a
/// link's `AnyPacket`).
///
/// # Errors
/// The serializer's.
pub fn serialize_packet_in<P: SerdePacket, S: Serializer>(
    p: &P,
    format: Option<&str>,
    s: S,
) -> Result<S::Ok, S::Error> {
    let (command, header, message) = p.parts();
    let direction = p.direction();
    let len = [format.is_some(), command.is_some(), direction.is_some()]
        .into_iter()
        .filter(|&present| present)
        .count()
        .saturating_add(2);
    let mut map = s.serialize_map(Some(len))?;
    if let Some(name) = format {
        map.serialize_entry("format", name)?;
    }
    if let Some(name) = direction {
        map.serialize_entry("direction", name)?;
    }
    if let Some(name) = command {
        map.serialize_entry("command", name)?;
    }
    map.serialize_entry("header", header)?;
    map.serialize_entry("payload", message)?;
    map.end()
}

/// Reads a packet from a map with `direction` (for a spec whose decoder is given it),
/// `command` and `header` before `payload`; other keys are skipped.
///
/// # Errors
/// The deserializer's, and errors for an unknown command, a missing key or a payload before
/// its command or header.
pub fn deserialize_packet<'de, P: SerdePacket, D: Deserializer<'de>>(d: D) -> Result<P, D::Error> {
    d.deserialize_map(PacketVisitor::<P>(PhantomData))
}

/// Reads the rest of a packet's map, as [`deserialize_packet`] reads a whole one (for
/// [`SerdeAnyPacket::visit_format`], once the `format` key is read).
///
/// # Errors
/// As [`deserialize_packet`].
pub fn packet_from_map<'de, P: SerdePacket, A: MapAccess<'de>>(map: A) -> Result<P, A::Error> {
    PacketVisitor::<P>(PhantomData).visit_map(map)
}

/// What a link's generated `AnyPacket` (a packet of any of the link's command formats) gives
/// and takes for its `Serialize` and `Deserialize` impls (which call [`serialize_packet_in`]
/// and [`deserialize_any_packet`]): the map of its format's packet with `format`, the format's
/// name in the spec, first.
pub trait SerdeAnyPacket: Sized {
    /// The names of the link's command formats, in the order of the link's decoder.
    const FORMATS: &'static [&'static str];
    /// Reads the rest of the map as the packet of format `format` (an index into
    /// [`Self::FORMATS`]), with [`packet_from_map`].
    ///
    /// # Errors
    /// Those of [`packet_from_map`].
    fn visit_format<'de, A: MapAccess<'de>>(format: usize, map: A) -> Result<Self, A::Error>;
}

/// Reads a link's packet from a map with `format` before the packet's own keys (keys before it
/// that are not a packet's, such as `offset`, are skipped), then the format's packet.
///
/// # Errors
/// The deserializer's, and errors for a missing or unknown format, a packet key before it,
/// and those of [`deserialize_packet`].
pub fn deserialize_any_packet<'de, P: SerdeAnyPacket, D: Deserializer<'de>>(
    d: D,
) -> Result<P, D::Error> {
    d.deserialize_map(AnyPacketVisitor::<P>(PhantomData))
}

struct AnyPacketVisitor<P>(PhantomData<P>);

impl<'de, P: SerdeAnyPacket> Visitor<'de> for AnyPacketVisitor<P> {
    type Value = P;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a packet: a map of `format`, `command`, `header` and `payload`")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<P, A::Error> {
        while let Some(key) = map.next_key::<Key>()? {
            match key {
                Key::Format => {
                    let format = map
                        .next_value::<Name>()?
                        .index_in(P::FORMATS, "frame format")?;
                    return P::visit_format(format, map);
                }
                Key::Other => {
                    map.next_value::<IgnoredAny>()?;
                }
                Key::Direction | Key::Command | Key::Header | Key::Payload => {
                    return Err(de::Error::custom(
                        "a packet's key before `format`: the format must come first",
                    ));
                }
            }
        }
        Err(de::Error::missing_field("format"))
    }
}

struct PacketVisitor<P>(PhantomData<P>);

struct PayloadSeed<'a, P: SerdePacket> {
    command: Option<P::Command>,
    header: &'a P::Header,
    direction: Option<usize>,
}

impl<'de, P: SerdePacket> DeserializeSeed<'de> for PayloadSeed<'_, P> {
    type Value = P::Message;

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<P::Message, D::Error> {
        P::payload_in(self.command, self.header, self.direction, d)
    }
}

impl<'de, P: SerdePacket> Visitor<'de> for PacketVisitor<P> {
    type Value = P;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a packet: a map of `command`, `header` and `payload`")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<P, A::Error> {
        let mut command = None;
        let mut header = None;
        let mut message = None;
        let mut direction = None;
        while let Some(key) = map.next_key::<Key>()? {
            match key {
                Key::Direction if !P::GIVEN_DIRECTIONS.is_empty() => {
                    let name = map.next_value::<Name>()?;
                    direction = Some(name.index_in(P::GIVEN_DIRECTIONS, "direction")?);
                }
                Key::Command => {
                    let name = map.next_value::<Name>()?;
                    let c = P::command_named(name.as_str()).ok_or_else(|| {
                        de::Error::custom(format_args!("no command `{}`", name.as_str()))
                    })?;
                    command = Some(c);
                }
                Key::Header => header = Some(map.next_value::<P::Header>()?),
                Key::Payload => {
                    let header = header.as_ref().ok_or_else(|| {
                        de::Error::custom("`payload` before `header`: the header must come first")
                    })?;
                    message = Some(map.next_value_seed(PayloadSeed::<P> {
                        command,
                        header,
                        direction,
                    })?);
                }
                Key::Format | Key::Direction | Key::Other => {
                    map.next_value::<IgnoredAny>()?;
                }
            }
        }
        match (header, message) {
            (Some(header), Some(message)) => Ok(P::from_parts(header, message)),
            (None, _) => Err(de::Error::missing_field("header")),
            (_, None) => Err(de::Error::missing_field("payload")),
        }
    }
}

/// A key of a packet's map.
enum Key {
    Format,
    Direction,
    Command,
    Header,
    Payload,
    Other,
}

impl<'de> Deserialize<'de> for Key {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct KeyVisitor;
        impl Visitor<'_> for KeyVisitor {
            type Value = Key;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a key")
            }
            fn visit_str<E: de::Error>(self, key: &str) -> Result<Key, E> {
                Ok(match key {
                    "format" => Key::Format,
                    "direction" => Key::Direction,
                    "command" => Key::Command,
                    "header" => Key::Header,
                    "payload" => Key::Payload,
                    _ => Key::Other,
                })
            }
        }
        d.deserialize_identifier(KeyVisitor)
    }
}

/// A command name of up to 64 bytes, copied (a borrowed `&str` is not available from every
/// deserializer, and no heap is).
struct Name(crate::bytes::Bytes<64>);

impl Name {
    fn as_str(&self) -> &str {
        core::str::from_utf8(self.0.as_slice()).unwrap_or_default()
    }

    /// The name's place in `names`, or an error that there is no `what` of the name.
    fn index_in<E: de::Error>(&self, names: &[&str], what: &str) -> Result<usize, E> {
        let name = self.as_str();
        names
            .iter()
            .position(|n| *n == name)
            .ok_or_else(|| E::custom(format_args!("no {what} `{name}`")))
    }
}

impl<'de> Deserialize<'de> for Name {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct NameVisitor;
        impl Visitor<'_> for NameVisitor {
            type Value = Name;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a command's name")
            }
            fn visit_str<E: de::Error>(self, name: &str) -> Result<Name, E> {
                crate::bytes::Bytes::from_slice(name.as_bytes())
                    .map(Name)
                    .ok_or_else(|| E::custom(format_args!("no command `{name}`")))
            }
        }
        d.deserialize_str(NameVisitor)
    }
}

/// Writes a command as its name in the spec.
///
/// # Errors
/// The serializer's.
pub fn serialize_name<S: Serializer>(s: S, name: &str) -> Result<S::Ok, S::Error> {
    s.serialize_str(name)
}

/// Reads a command from its name in the spec.
///
/// # Errors
/// The deserializer's, and an error for a name `named` does not know.
pub fn deserialize_name<'de, D: Deserializer<'de>, C>(
    d: D,
    named: impl Fn(&str) -> Option<C>,
) -> Result<C, D::Error> {
    let name = Name::deserialize(d)?;
    named(name.as_str())
        .ok_or_else(|| de::Error::custom(format_args!("no command `{}`", name.as_str())))
}

/// An error of a payload's deserializer: a header that matches no direction of the spec, or
/// a payload with no command in a spec without acknowledgements.
pub fn payload_error<E: de::Error>(what: &'static str) -> E {
    E::custom(what)
}
