"""Where frames come from: a capture file, bytes in memory, a CAN log, a serial port, an
asyncio stream. Each reader feeds a :class:`~protocol_link.StreamDecoder` (or, for a CAN log,
decodes record by record) and yields :class:`~protocol_link.Message` objects, and with
``events=True`` the :class:`~protocol_link.Event` objects too, in stream order.

This module owns the inputs only; finding and decoding frames is the codec's.
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any, AsyncIterator, Iterable, Iterator, NamedTuple, Optional, Union

from ._native import Event, Message, Spec

if TYPE_CHECKING:
    import asyncio

Item = Union[Message, Event]

#: Bytes read at a time from a file or a stream.
CHUNK = 64 * 1024


def _keep(items: Iterable[Item], events: bool) -> Iterator[Item]:
    if events:
        yield from items
    else:
        for item in items:
            if isinstance(item, Message):
                yield item


def iter_bytes(spec: Spec, data: bytes, *, format: Optional[str] = None, events: bool = False) -> Iterator[Item]:
    """The messages (and with ``events=True`` the events) of a byte string."""
    stream = spec.stream(format=format)
    yield from _keep(stream.feed(data), events)
    yield from _keep(stream.flush(), events)


def iter_file(
    spec: Spec,
    path: Union[str, "os.PathLike[str]"],
    *,
    format: Optional[str] = None,
    events: bool = False,
    chunk_size: int = CHUNK,
) -> Iterator[Item]:
    """The messages (and with ``events=True`` the events) of a binary capture file, read in
    chunks of ``chunk_size`` bytes, as ``protocol decode FILE`` finds them."""
    stream = spec.stream(format=format)
    with open(path, "rb") as f:
        while True:
            chunk = f.read(chunk_size)
            if not chunk:
                break
            yield from _keep(stream.feed(chunk), events)
    yield from _keep(stream.flush(), events)


class CanRecord(NamedTuple):
    """One frame of a CAN log."""

    time: Optional[str]
    interface: str
    can_id: int
    extended: bool
    remote: bool
    fd: bool
    data: bytes


_FLAG_BITS = 0xE000_0000


def _parse_id(text: str) -> tuple[int, bool]:
    raw = int(text, 16)
    extended = len(text) > 3
    can_id = raw & ~_FLAG_BITS
    if can_id > (0x1FFF_FFFF if extended else 0x7FF):
        raise ValueError(f"CAN id `{text}` is out of range")
    return can_id, extended


def _parse_log_frame(interface: str, frame: str, time: Optional[str]) -> CanRecord:
    id_text, sep, rest = frame.partition("#")
    if not sep:
        raise ValueError(f"expected ID#DATA, got `{frame}`")
    can_id, extended = _parse_id(id_text)
    fd = rest.startswith("#")
    if fd:
        rest = rest[2:]
    elif rest[:1] in ("R", "r"):
        return CanRecord(time, interface, can_id, extended, True, False, b"")
    return CanRecord(time, interface, can_id, extended, False, fd, bytes.fromhex(rest.replace(".", "")))


def _parse_plain(rest: str, time: Optional[str]) -> CanRecord:
    words = rest.split()
    if len(words) < 3:
        raise ValueError("expected INTERFACE ID [LENGTH] DATA")
    interface, id_text, len_text = words[:3]
    can_id, extended = _parse_id(id_text)
    if not (len_text.startswith("[") and len_text.endswith("]")):
        raise ValueError(f"expected [length], got `{len_text}`")
    digits = len_text[1:-1]
    length = int(digits)
    fd = len(digits) == 2 or length > 8
    if words[3:4] == ["remote"]:
        return CanRecord(time, interface, can_id, extended, True, fd, b"")
    data = bytes(int(w, 16) for w in words[3 : 3 + length])
    if len(data) != length:
        raise ValueError(f"length says {length} bytes, the line has {len(data)}")
    return CanRecord(time, interface, can_id, extended, False, fd, data)


def parse_candump_line(line: str) -> Optional[CanRecord]:
    """One line of a Linux ``candump -L`` log (``(1700000000.5) can0 151#0001007B``) or of
    ``candump``'s default output (``  can0  151   [4]  00 01 00 7B``, with or without a
    timestamp in front); ``None`` for a blank line or a ``#`` comment. Raises ``ValueError``
    for a line that is no CAN frame."""
    line = line.strip()
    if not line or line.startswith("#"):
        return None
    time = None
    if line.startswith("("):
        end = line.find(")")
        if end < 0:
            raise ValueError("unclosed timestamp parenthesis")
        time, line = line[1:end].strip(), line[end + 1 :].strip()
    words = line.split()
    if len(words) >= 2 and "#" in words[1]:
        return _parse_log_frame(words[0], words[1], time)
    return _parse_plain(line, time)


def iter_candump(
    spec: Spec,
    source: Union[str, "os.PathLike[str]", Iterable[str]],
    *,
    format: Optional[str] = None,
    events: bool = False,
) -> Iterator[Item]:
    """The messages (and with ``events=True`` the events) of a CAN log, a path or an iterable
    of lines, as ``protocol decode --candump FILE`` reports them: each message's ``offset`` is
    its record's index in the log. Lines that are no CAN frame raise ``ValueError`` naming the
    line."""
    if isinstance(source, (str, os.PathLike)):
        with open(source, encoding="utf-8") as f:
            yield from iter_candump(spec, f.readlines(), format=format, events=events)
        return
    index = 0
    for number, line in enumerate(source, 1):
        try:
            record = parse_candump_line(line)
        except ValueError as e:
            raise ValueError(f"line {number}: not a CAN frame: {e}") from None
        if record is None:
            continue
        item = spec.read_can(
            record.can_id,
            record.data,
            extended=record.extended,
            offset=index,
            remote=record.remote,
            fd=record.fd,
            format=format,
        )
        index += 1
        if events or isinstance(item, Message):
            yield item


def iter_serial(
    spec: Spec,
    port: Any,
    baudrate: int = 115200,
    *,
    format: Optional[str] = None,
    events: bool = False,
    timeout: float = 0.1,
) -> Iterator[Item]:
    """The messages (and with ``events=True`` the events) of a serial port, as they arrive,
    until the port closes. ``port`` is a device name (opened with pyserial, which must be
    installed: ``pip install pyserial``) or an open object with ``read(n)``."""
    if isinstance(port, str):
        try:
            import serial  # type: ignore[import-not-found]
        except ImportError as e:
            raise ImportError("iter_serial needs pyserial: pip install pyserial") from e
        with serial.Serial(port, baudrate, timeout=timeout) as handle:
            yield from iter_serial(spec, handle, format=format, events=events)
        return
    stream = spec.stream(format=format)
    while True:
        waiting = getattr(port, "in_waiting", 0) or 1
        try:
            chunk = port.read(waiting)
        except OSError:
            break
        if chunk is None:
            break
        if chunk:
            yield from _keep(stream.feed(chunk), events)
        elif not getattr(port, "is_open", False):
            break
    yield from _keep(stream.flush(), events)


async def aiter_stream(
    spec: Spec,
    reader: "asyncio.StreamReader",
    *,
    format: Optional[str] = None,
    events: bool = False,
    chunk_size: int = CHUNK,
) -> AsyncIterator[Item]:
    """``async for msg in aiter_stream(spec, reader)``: the messages (and with ``events=True``
    the events) of an ``asyncio.StreamReader`` (a TCP connection, a pipe, a serial port opened
    with pyserial-asyncio), until it ends."""
    stream = spec.stream(format=format)
    while True:
        chunk = await reader.read(chunk_size)
        if not chunk:
            break
        for item in _keep(stream.feed(chunk), events):
            yield item
    for item in _keep(stream.flush(), events):
        yield item
