"""Agreement with pyubx2: random messages of every command of `specs/ubx.toml`, framed and
decoded by pyubx2, decoded by the package to pyubx2's values and encoded by the package from
them to pyubx2's bytes.

The frames and pyubx2's values in the spec's names and shape come from the script that writes
`tests/vectors/ubx_pyubx2.json` (`scripts/ubx_pyubx2_vectors.py`), run here with seeds of its
own: a scaled field agrees within half its scale, every other value exactly (bit members,
enumerations by name, texts, bytes)."""

from __future__ import annotations

import random
import sys

import pytest

from conftest import ROOT, spec

pytest.importorskip("pyubx2")
sys.path.insert(0, str(ROOT / "scripts"))
import ubx_pyubx2_vectors as pyubx2_frames  # noqa: E402

PER_COMMAND = 40

#: The spec's `bytes` fields: `bytes` in the package, hex text in the script's records.
BYTES_FIELDS = {"cfg_data", "message"}


def agrees(ours, theirs, path: str, scales: dict) -> None:
    if isinstance(theirs, dict):
        assert isinstance(ours, dict) and set(ours) == set(theirs), (path, ours, theirs)
        for key, value in theirs.items():
            agrees(ours[key], value, f"{path}.{key}" if path else key, scales)
    elif isinstance(theirs, list):
        assert isinstance(ours, list) and len(ours) == len(theirs), (path, ours, theirs)
        for o, t in zip(ours, theirs):
            agrees(o, t, path, scales)
    elif path.rsplit(".", 1)[-1] in BYTES_FIELDS:
        assert ours == bytes.fromhex(theirs), (path, ours, theirs)
    elif path in scales:
        assert abs(ours - theirs) <= scales[path] / 2 + abs(theirs) * 1e-12, (path, ours, theirs)
    else:
        assert ours == theirs and type(ours) is type(theirs), (path, ours, theirs)


def for_package(value, key: str = ""):
    """A record's payload as the package's encoder takes it (bytes fields as `bytes`)."""
    if isinstance(value, dict):
        return {k: for_package(v, k) for k, v in value.items()}
    if isinstance(value, list):
        return [for_package(v, key) for v in value]
    if key in BYTES_FIELDS:
        return bytes.fromhex(value)
    return value


def test_pyubx2_frames_decode_to_its_values():
    ubx = spec("ubx")
    frames = pyubx2_frames.random_frames(random.Random(0x5542_5801), PER_COMMAND)
    for record in frames:
        ours = ubx.decode(bytes.fromhex(record["hex"]))
        assert ours.name == record["message"], record["name"]
        payload = ours.to_dict()["payload"]
        agrees(payload, record["payload"], "", record["scales"])
        for main, (theirs, (_, hp)) in record.get("pyubx2_sums", {}).items():
            assert abs(payload[main] + payload[hp] - theirs) <= record["scales"][hp] / 2 + abs(theirs) * 1e-12
    assert {r["message"] for r in frames} == set(ubx.commands)


def test_the_package_encodes_pyubx2_values_to_its_bytes():
    ubx = spec("ubx")
    frames = pyubx2_frames.random_frames(random.Random(0x5542_5802), PER_COMMAND)
    for record in frames:
        frame = ubx.encode(record["message"], for_package(record["payload"]))
        assert frame == bytes.fromhex(record["hex"]), record["name"]
    assert len(frames) > PER_COMMAND * len(ubx.commands)
