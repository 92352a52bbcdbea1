"""Agreement with pyubx2: random messages of every command of `specs/ubx.toml`, encoded by
pyubx2 and decoded by the package, and encoded by the package and parsed by pyubx2.

The spec and pyubx2 name fields differently (`h_msl` and `hMSL`) and give some a different
form, so fields are matched by their place in the payload, reserved ones left out: a scaled
field (pyubx2's `lon` in degrees) is compared as its raw integer, a bitfield word (read by
pyubx2 with `parsebitfield=0`, as bytes) as its little-endian value, an enum by its number.
pyubx2 encodes MON-VER's text fields at the length it is given, not padded, so MON-VER is
checked in the package-to-pyubx2 direction only; CFG-MSG is its 8-byte form (pyubx2's
definition of a set message)."""

from __future__ import annotations

import random

import pytest

from conftest import spec

pyubx2 = pytest.importorskip("pyubx2")
from pyubx2 import UBXMessage, UBXReader  # noqa: E402
from pyubx2.ubxtypes_get import UBX_PAYLOADS_GET  # noqa: E402
from pyubx2.ubxtypes_set import UBX_PAYLOADS_SET  # noqa: E402

COUNT = 2000

#: The spec's enums (`specs/ubx.toml`): a decoded enum is its variant's name.
ENUMS = {
    "NO_FIX": 0,
    "DEAD_RECKONING_ONLY": 1,
    "FIX_2D": 2,
    "FIX_3D": 3,
    "GPS_AND_DEAD_RECKONING": 4,
    "TIME_ONLY": 5,
    "UTC": 0,
    "GPS": 1,
    "GLONASS": 2,
    "BEIDOU": 3,
    "GALILEO": 4,
}

#: The spec's command, pyubx2's name and message mode (0: output of a receiver, 1: input).
MESSAGES = {
    "NAV_POSLLH": ("NAV-POSLLH", 0),
    "NAV_STATUS": ("NAV-STATUS", 0),
    "NAV_DOP": ("NAV-DOP", 0),
    "NAV_PVT": ("NAV-PVT", 0),
    "NAV_VELNED": ("NAV-VELNED", 0),
    "NAV_TIMEUTC": ("NAV-TIMEUTC", 0),
    "NAV_SAT": ("NAV-SAT", 0),
    "ACK_NAK": ("ACK-NAK", 0),
    "ACK_ACK": ("ACK-ACK", 0),
    "CFG_MSG": ("CFG-MSG", 1),
    "CFG_RATE": ("CFG-RATE", 1),
    "MON_VER": ("MON-VER", 0),
}


def definition(ubx_name: str, mode: int) -> dict:
    return (UBX_PAYLOADS_SET if mode else UBX_PAYLOADS_GET)[ubx_name]


def is_reserved(ubx_name: str, name: str) -> bool:
    # CFG-MSG's sixth rate is `reserved` in pyubx2 and the spec's `ports.rate[4]`.
    return name.startswith("reserved") and ubx_name != "CFG-MSG"


def leaves(ubx_name: str, defn: dict, counts: dict, suffix: str = ""):
    """pyubx2's fields in payload order: `(keyword, type, scale)`, groups expanded to
    `counts[group]` elements, reserved fields left out."""
    out = []
    for key, kind in defn.items():
        if isinstance(kind, tuple) and isinstance(kind[1], dict):
            if kind[0].startswith("X"):
                out.append((key[: -len("_bit")] + suffix, kind[0], 1))
            else:
                for i in range(1, counts[key] + 1):
                    out.extend(leaves(ubx_name, kind[1], counts, f"{suffix}_{i:02d}"))
        elif is_reserved(ubx_name, key):
            continue
        elif isinstance(kind, tuple):
            out.append((key + suffix, kind[0], kind[1]))
        else:
            out.append((key + suffix, kind, 1))
    return out


def random_raw(rng: random.Random, kind: str):
    """A random raw value of pyubx2 type `kind` (`U004`, `I002`, `X001`, `C030`)."""
    size = int(kind[1:])
    if kind[0] == "U":
        return rng.getrandbits(8 * size)
    if kind[0] == "I":
        return rng.getrandbits(8 * size) - (1 << (8 * size - 1))
    if kind[0] == "X":
        return rng.getrandbits(8 * size)
    return bytes(rng.choice(b"ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789=.-") for _ in range(rng.randint(0, size)))


def random_message(rng: random.Random, ubx_name: str, mode: int):
    """Group counts and `(keyword, type, scale, raw value)` of a random message."""
    defn = definition(ubx_name, mode)
    counts = {g: rng.randint(0, 12) for g, k in defn.items() if isinstance(k, tuple) and isinstance(k[1], dict) and not k[0].startswith("X")}
    fields = [(n, k, s, random_raw(rng, k)) for n, k, s in leaves(ubx_name, defn, counts)]
    count_fields = {defn[g][0]: n for g, n in counts.items()}
    fields = [(n, k, s, count_fields.get(n, v)) for n, k, s, v in fields]
    if ubx_name == "NAV-PVT":
        # The spec's `flags3` is one byte (bytes 79 to 83 are reserved): pyubx2's second
        # byte of it stays 0.
        fields = [(n, k, s, v & 0xFF if n == "flags3" else v) for n, k, s, v in fields]
    return counts, fields


def pyubx2_keywords(fields):
    out = {}
    for name, kind, scale, raw in fields:
        if kind[0] == "X":
            out[name] = raw.to_bytes(int(kind[1:]), "little")
        elif scale != 1:
            out[name] = raw * scale
        else:
            out[name] = raw
    return out


def our_leaves(value):
    """The spec's values in payload order, structs and arrays flattened."""
    if isinstance(value, dict):
        return [leaf for v in value.values() for leaf in our_leaves(v)]
    if isinstance(value, list):
        return [leaf for v in value for leaf in our_leaves(v)]
    if value is None:
        return []
    return [value]


def same(kind: str, scale: float, ours, theirs) -> bool:
    if kind[0] == "X":
        return ours == int.from_bytes(theirs, "little")
    if kind[0] == "C":
        return ours == theirs.rstrip(b"\0").decode("ascii")
    if isinstance(ours, str):
        ours = ENUMS[ours]
    if scale != 1:
        return ours == round(theirs / scale)
    return ours == theirs


def compare(ubx_name: str, ours_payload: dict, parsed, expected_leaves):
    ours = our_leaves(ours_payload)
    assert len(ours) == len(expected_leaves), (ubx_name, ours, expected_leaves)
    for value, (name, kind, scale) in zip(ours, expected_leaves):
        theirs = getattr(parsed, name)
        assert same(kind, scale, value, theirs), (ubx_name, name, value, theirs)


def test_pyubx2_encodes_the_package_decodes():
    ubx = spec("ubx")
    rng = random.Random(0x5542_5801)
    names = [n for n in ubx.commands if n != "MON_VER"]
    checked = 0
    for _ in range(COUNT):
        command = rng.choice(names)
        ubx_name, mode = MESSAGES[command]
        counts, fields = random_message(rng, ubx_name, mode)
        frame = UBXMessage(ubx_name[:3], ubx_name, mode, parsebitfield=0, **pyubx2_keywords(fields)).serialize()
        parsed = UBXReader.parse(frame, msgmode=mode, parsebitfield=0)
        ours = ubx.decode(frame)
        assert ours.name == command
        compare(ubx_name, ours.to_dict()["payload"], parsed, [f[:3] for f in fields])
        checked += 1
    assert checked == COUNT


def fill(template, values):
    """The spec's payload `template` with its leaves replaced, in order, by `values`."""
    if isinstance(template, dict):
        return {k: fill(v, values) for k, v in template.items()}
    if isinstance(template, list):
        return [fill(v, values) for v in template]
    return next(values)


def template(command: str, counts: dict):
    """The shape of the spec's payload of `command` for these group counts."""
    if command == "MON_VER":
        n = counts["ext_grp"]
        return {"sw_version": 0, "hw_version": 0, "extension": [{"extension": 0}] * n}
    if command == "CFG_MSG":
        return {"msg_class": 0, "msg_id": 0, "rate": 0, "ports": {"rate": [0] * 5}}
    ubx_name, mode = MESSAGES[command]
    zero = [(n, k, s, 0 if k[0] != "C" else b"") for n, k, s in leaves(ubx_name, definition(ubx_name, mode), counts)]
    count_fields = {definition(ubx_name, mode)[g][0]: n for g, n in counts.items()}
    zero = [(n, k, s, count_fields.get(n, v)) for n, k, s, v in zero]
    frame = UBXMessage(ubx_name[:3], ubx_name, mode, parsebitfield=0, **pyubx2_keywords(zero)).serialize()
    return spec("ubx").decode(frame).to_dict()["payload"]


def test_the_package_encodes_pyubx2_decodes():
    ubx = spec("ubx")
    rng = random.Random(0x5542_5802)
    checked = 0
    for _ in range(COUNT):
        command = rng.choice(ubx.commands)
        ubx_name, mode = MESSAGES[command]
        counts, fields = random_message(rng, ubx_name, mode)
        if command == "MON_VER":
            counts = {"ext_grp": rng.randint(0, 10)}
            fields = [("swVersion", "C030", 1, random_raw(rng, "C030")), ("hwVersion", "C010", 1, random_raw(rng, "C010"))]
            fields += [(f"extension_{i:02d}", "C030", 1, random_raw(rng, "C030")) for i in range(1, counts["ext_grp"] + 1)]
        # The spec's text fields are strings.
        values = [raw.decode("ascii") if kind[0] == "C" else raw for _, kind, _, raw in fields]
        payload = fill(template(command, counts), iter(values))
        frame = ubx.encode(command, payload)
        parsed = UBXReader.parse(frame, msgmode=mode, parsebitfield=0)
        assert parsed.identity == ubx_name
        compare(ubx_name, payload, parsed, [f[:3] for f in fields])
        checked += 1
    assert checked == COUNT
