"""Agreement with sensirion-shdlc-driver: random SPS30 frames of `specs/shdlc.toml`, both ways.

Requests are the bytes the driver's `ShdlcSerialMosiFrameBuilder` writes for random commands
(from the script that writes `tests/vectors/shdlc_sensirion.json`, run here with seeds of its
own): the package decodes each to the script's values and encodes those values to the driver's
bytes. Responses are encoded by the package from random values and read by the driver's
`ShdlcSerialMisoFrameBuilder`, which checks their length, checksum and byte stuffing and must
read back the address, command, state and data the script laid out; the package decodes the
script's layout of the same response to those values."""

from __future__ import annotations

import random
import struct
import sys

import pytest

from conftest import ROOT, spec

pytest.importorskip("sensirion_shdlc_driver")
sys.path.insert(0, str(ROOT / "scripts"))
import shdlc_sensirion_vectors as driver  # noqa: E402

ROUNDS = 40


def agrees(ours, theirs, path: str = "") -> None:
    """Values equal, a float as the same f32 (the script keeps an f32's shortest decimal)."""
    if isinstance(theirs, dict):
        assert isinstance(ours, dict) and set(ours) == set(theirs), (path, ours, theirs)
        for key, value in theirs.items():
            agrees(ours[key], value, f"{path}.{key}")
    elif isinstance(theirs, float):
        assert struct.pack(">f", ours) == struct.pack(">f", theirs), (path, ours, theirs)
    else:
        assert ours == theirs, (path, ours, theirs)


def payload_of(message) -> dict:
    """A decoded message's payload, `{}` for a command that carries none."""
    return message.to_dict()["payload"] or {}


def test_the_package_reads_and_writes_the_drivers_requests():
    shdlc = spec("shdlc", direction="request")
    r = random.Random(0x5D1C_0001)
    names = set()
    for _ in range(ROUNDS):
        address = driver.byte(r)
        for name, cmd, payload, call in driver.requests(r):
            raw = driver.ShdlcSerialMosiFrameBuilder(address, cmd.id, cmd.data).to_bytes()
            ours = shdlc.decode(raw)
            assert ours.name == name, call
            assert ours.to_dict()["header"]["address"] == address, call
            agrees(payload_of(ours), payload or {}, name)
            again = shdlc.encode(name, payload, header={"address": address})
            assert again == raw, (call, again.hex(), raw.hex())
            names.add(name)
    assert names == set(shdlc.commands)


def test_the_driver_reads_the_packages_responses():
    shdlc = spec("shdlc", direction="response")
    r = random.Random(0x5D1C_0002)
    stuffed = 0
    for _ in range(ROUNDS):
        address = driver.byte(r)
        for name, cid, data, payload, how in driver.responses(r):
            state = r.choice([0x00, 0x80])
            frame = shdlc.encode(name, payload, header={"address": address, "state": state})
            assert driver.read_miso(frame) == (address, cid, state, data), (name, how)
            assert frame == driver.miso(address, cid, state, data), (name, how)
            ours = shdlc.decode(frame)
            assert ours.name == name and ours.to_dict()["header"]["state"] == state, how
            agrees(payload_of(ours), payload or {}, name)
            stuffed += 0x7D in frame[1:-1]
    assert stuffed > ROUNDS, f"{stuffed} responses with stuffed bytes"
