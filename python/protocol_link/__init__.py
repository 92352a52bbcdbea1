"""Decode and encode the frames of a robot's serial or CAN link from its protocol spec.

``protocol_link`` is the run-time codec of the ``protocol`` project (``protocol-dynamic``)
for Python: the spec that generates the firmware's codec is loaded here, so a test script or
a log analysis reads frames exactly as the firmware writes them.

>>> import protocol_link
>>> spec = protocol_link.Spec.load("specs/mavlink.toml")        # doctest: +SKIP
>>> msg = spec.decode(frame_bytes)                               # doctest: +SKIP
>>> msg.name, msg.header.sysid, msg.payload.roll, msg.to_dict()  # doctest: +SKIP

The pieces:

* :class:`Spec` loads a spec (``Spec.load(path)``, ``Spec.from_str(text)``; a bad spec raises
  :class:`SpecError` with every error located and rendered), decodes one frame
  (``spec.decode(data)``, ``spec.decode_can(can_id, data)``) and encodes one
  (``spec.encode("ATTITUDE", roll=0.1, ..., header={...})``, errors raise
  :class:`EncodeError` naming the field).
* :class:`StreamDecoder` (``spec.stream()``) takes bytes in chunks of any size:
  ``feed(data)`` returns the :class:`Message` objects and :class:`Event` objects (rejected
  candidates, skipped bytes, frames without message) they complete; ``stats()`` is a dict.
* Readers: :func:`iter_file`, :func:`iter_bytes`, :func:`iter_candump`, :func:`iter_serial`
  (pyserial) and :func:`aiter_stream` (an ``asyncio.StreamReader``, with ``async for``).
* Columns: :func:`to_columns` (a dict of lists per command) and :func:`to_dataframe`
  (pandas).
"""

from ._native import (
    DecodeError,
    EncodeError,
    Event,
    Message,
    Record,
    Spec,
    SpecError,
    StreamDecoder,
)
from .columns import to_columns, to_dataframe
from .readers import aiter_stream, iter_bytes, iter_candump, iter_file, iter_serial, parse_candump_line

__all__ = [
    "DecodeError",
    "EncodeError",
    "Event",
    "Message",
    "Record",
    "Spec",
    "SpecError",
    "StreamDecoder",
    "aiter_stream",
    "iter_bytes",
    "iter_candump",
    "iter_file",
    "iter_serial",
    "parse_candump_line",
    "to_columns",
    "to_dataframe",
]
