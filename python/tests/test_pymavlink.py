"""Agreement with pymavlink: random messages of every command of `specs/mavlink.toml`,
MAVLink 2 and 1, encoded by pymavlink and decoded by the package, and encoded by the package
and parsed by pymavlink; every header value and field compared.

Names match (the spec spells fields as the MAVLink XML does). What differs in form only: a
`char[N]` field is text (a string or bytes up to the first NUL) in pymavlink and N bytes (NUL-padded) in the spec; an `f32` is
compared by its bits."""

from __future__ import annotations

import random
import string
import struct

import pytest

from conftest import spec

mavlink2 = pytest.importorskip("pymavlink.dialects.v20.common")
mavlink1 = pytest.importorskip("pymavlink.dialects.v10.common")

#: Random messages per direction and MAVLink version.
COUNTS = {"v2": 2000, "v1": 1000}

INT_RANGES = {
    "uint8_t": (0, 0xFF),
    "int8_t": (-0x80, 0x7F),
    "uint16_t": (0, 0xFFFF),
    "int16_t": (-0x8000, 0x7FFF),
    "uint32_t": (0, 0xFFFF_FFFF),
    "int32_t": (-0x8000_0000, 0x7FFF_FFFF),
    "uint64_t": (0, 0xFFFF_FFFF_FFFF_FFFF),
    "int64_t": (-0x8000_0000_0000_0000, 0x7FFF_FFFF_FFFF_FFFF),
}


def message_classes(dialect, names):
    return [dialect.mavlink_map[dialect_id(dialect, n)] for n in names]


def dialect_id(dialect, name):
    return getattr(dialect, f"MAVLINK_MSG_ID_{name}")


def layout(cls):
    """`(name, type, array length)` of each field, in declaration order (pymavlink lists array
    lengths in wire order)."""
    lengths = dict(zip(cls.ordered_fieldnames, cls.array_lengths))
    return [(name, kind, lengths[name]) for name, kind in zip(cls.fieldnames, cls.fieldtypes)]


def random_f32(rng: random.Random) -> float:
    while True:
        x = struct.unpack("<f", struct.pack("<I", rng.getrandbits(32)))[0]
        if x == x and abs(x) != float("inf"):
            return x


def random_scalar(rng: random.Random, kind: str):
    if kind == "float":
        return random_f32(rng)
    if kind == "double":
        while True:
            x = struct.unpack("<d", struct.pack("<Q", rng.getrandbits(64)))[0]
            if x == x and abs(x) != float("inf"):
                return x
    lo, hi = INT_RANGES[kind]
    return rng.randint(lo, hi)


def random_fields(rng: random.Random, cls, base_only: bool):
    """pymavlink's keyword values of a random message of `cls`."""
    values = {}
    skipped = extensions(cls) if base_only else set()
    for name, kind, n in layout(cls):
        if name in skipped:
            continue
        if kind == "char":
            size = rng.randint(0, n)
            values[name] = "".join(rng.choice(string.ascii_letters + string.digits + "_") for _ in range(size)).encode()
        elif n:
            values[name] = [random_scalar(rng, kind) for _ in range(n)]
        else:
            values[name] = random_scalar(rng, kind)
    return values


def zeroed(value):
    """A value of the same type and size, all zero."""
    if isinstance(value, bytes):
        return b""
    if isinstance(value, list):
        return [zeroed(v) for v in value]
    return type(value)(0)


def spec_value(kind: str, n: int, value):
    """The spec's form of a pymavlink value."""
    if kind == "char":
        return list(value + b"\0" * (n - len(value)))
    return value


def same(kind: str, ours, theirs) -> bool:
    if kind == "char":
        text = theirs if isinstance(theirs, str) else theirs.decode("ascii")
        return bytes(ours).split(b"\0")[0].decode("ascii") == text.split("\0")[0]
    if isinstance(theirs, (list, tuple)):
        return len(ours) == len(theirs) and all(same(kind, a, b) for a, b in zip(ours, theirs))
    if kind == "float":
        return struct.pack("<f", ours) == struct.pack("<f", theirs)
    return ours == theirs


def compare(cls, ours, theirs, fields):
    for name, kind in zip(cls.fieldnames, cls.fieldtypes):
        if name not in fields:
            continue
        assert same(kind, ours.payload[name], getattr(theirs, name)), (cls.msgname, name, ours.payload[name], getattr(theirs, name))


def extensions(cls) -> set:
    """Fields after the base fields (MAVLink 2 extensions): not sent in MAVLink 1."""
    v2 = mavlink2.mavlink_map[cls.id]
    v1 = mavlink1.mavlink_map.get(cls.id, v2)
    return set(v2.fieldnames) - set(v1.fieldnames)


@pytest.mark.parametrize("version", ["v2", "v1"])
def test_pymavlink_encodes_the_package_decodes(version):
    mav_spec = spec("mavlink")
    dialect = mavlink2 if version == "v2" else mavlink1
    classes = message_classes(dialect, mav_spec.commands)
    rng = random.Random(0x4D41_5600 + len(version))
    for i in range(COUNTS[version]):
        cls = rng.choice(classes)
        fields = random_fields(rng, cls, base_only=version == "v1")
        msg = cls(**fields)
        sysid, compid, seq = rng.randint(0, 255), rng.randint(0, 255), rng.randint(0, 255)
        mav = dialect.MAVLink(None, srcSystem=sysid, srcComponent=compid)
        mav.seq = seq
        frame = bytes(msg.pack(mav))
        ours = mav_spec.decode(frame)
        assert (ours.name, ours.format) == (cls.msgname, version)
        assert (ours.header.seq, ours.header.sysid, ours.header.compid) == (seq, sysid, compid)
        compare(cls, ours, msg, fields)
        if version == "v1":
            for name in extensions(cls):
                assert not any(ours.payload[name]) if isinstance(ours.payload[name], list) else ours.payload[name] == 0


@pytest.mark.parametrize("version", ["v2", "v1"])
def test_the_package_encodes_pymavlink_decodes(version):
    mav_spec = spec("mavlink")
    dialect = mavlink2 if version == "v2" else mavlink1
    classes = message_classes(dialect, mav_spec.commands)
    rng = random.Random(0x4D41_5610 + len(version))
    parser = dialect.MAVLink(None)
    parsed = 0
    for i in range(COUNTS[version]):
        cls = rng.choice(classes)
        fields = random_fields(rng, cls, base_only=version == "v1")
        # The spec's message has its extension fields in MAVLink 1 too (zero, not sent).
        full = mavlink2.mavlink_map[cls.id]
        zero = random_fields(random.Random(0), full, base_only=False)
        payload = {
            name: spec_value(kind, n, fields.get(name, zeroed(zero[name])))
            for name, kind, n in layout(full)
        }
        header = {"seq": rng.randint(0, 255), "sysid": rng.randint(0, 255), "compid": rng.randint(0, 255)}
        if version == "v2":
            header.update(compat_flags=0, signature=None)
        frame = mav_spec.encode(cls.msgname, payload, header=header, format=version)
        theirs = parser.parse_buffer(frame)
        assert theirs is not None and len(theirs) == 1, (cls.msgname, frame.hex())
        msg = theirs[0]
        assert msg.get_type() == cls.msgname
        assert (msg.get_seq(), msg.get_srcSystem(), msg.get_srcComponent()) == (
            header["seq"],
            header["sysid"],
            header["compid"],
        )
        sent = set(fields)
        compare(cls, mav_spec.decode(frame), msg, sent)
        parsed += 1
    assert parsed == COUNTS[version]
