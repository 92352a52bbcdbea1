"""Writes escaped_hdlc.json and escaped_slip.json: golden frames of the fixtures
protocol-codegen/tests/features/escaped_hdlc.toml and escaped_slip.toml, escaped by
independent implementations.

- HDLC-style escaping (7E, 7D, 11, 13 sent as 7D and the byte XOR 0x20) by the PyPI package
  `sensirion-shdlc-driver` (its MOSI frame builder's byte stuffing), and undone by its MISO
  frame builder's unstuffing; the FCS is CRC-16/IBM-SDLC, computed here from its catalogue
  parameters and checked against its check value.
- SLIP escaping (C0 sent as DB DC, DB as DB DD) by the PyPI package `sliplib` (`Driver.send`,
  with the leading END byte RFC 1055 advises), and the streams decoded back by its
  `Driver.receive`.

Run with both installed (their versions are written into the files):

    python3 -m venv .venv && .venv/bin/pip install sliplib==0.7.2 sensirion-shdlc-driver==1.0.2
    .venv/bin/python tests/vectors/escaped.py
"""

import json
import random
from importlib.metadata import version
from pathlib import Path

import sliplib
from sensirion_shdlc_driver.serial_frame_builder import (
    ShdlcSerialMisoFrameBuilder,
    ShdlcSerialMosiFrameBuilder,
)

HERE = Path(__file__).resolve().parent
RNG = random.Random(41)
RESERVED_HDLC = [0x7E, 0x7D, 0x11, 0x13]


def crc16_x25(data):
    """CRC-16/IBM-SDLC: poly 0x1021 reflected (0x8408), init 0xFFFF, xorout 0xFFFF."""
    crc = 0xFFFF
    for b in data:
        crc ^= b
        for _ in range(8):
            crc = (crc >> 1) ^ 0x8408 if crc & 1 else crc >> 1
    return crc ^ 0xFFFF


def crc8_smbus(data):
    """CRC-8/SMBUS: poly 0x07, init 0, no reflection, xorout 0."""
    crc = 0
    for b in data:
        crc ^= b
        for _ in range(8):
            crc = ((crc << 1) ^ 0x07) & 0xFF if crc & 0x80 else (crc << 1) & 0xFF
    return crc


assert crc16_x25(b"123456789") == 0x906E
assert crc8_smbus(b"123456789") == 0xF4


def byte(reserved):
    """A byte, half the time one the link reserves."""
    return RNG.choice(reserved) if RNG.random() < 0.5 else RNG.randrange(256)


def hdlc_frames():
    frames = []
    for i in range(12):
        kind = ["PING", "SET", "DATA"][i % 3]
        address = byte(RESERVED_HDLC)
        if kind == "PING":
            command, payload, fields = 0x11, b"", {}
        elif kind == "SET":
            value, flags = byte(RESERVED_HDLC) << 8 | byte(RESERVED_HDLC), byte(RESERVED_HDLC)
            command, payload = 0x7E, bytes([value >> 8, value & 0xFF, flags])
            fields = {"value": value, "flags": flags}
        else:
            data = bytes(byte(RESERVED_HDLC) for _ in range(RNG.randrange(33)))
            command, payload, fields = 0x02, data, {"bytes": list(data)}
        content = bytes([address, command, len(payload)]) + payload
        fcs = crc16_x25(content)
        content += bytes([fcs & 0xFF, fcs >> 8])
        stuffed = ShdlcSerialMosiFrameBuilder._stuff_data_bytes(bytearray(content))
        wire = bytes([0x7E]) + bytes(stuffed) + bytes([0x7E])
        unstuffed = ShdlcSerialMisoFrameBuilder._unstuff_data_bytes(bytearray(stuffed))
        assert bytes(unstuffed) == content
        frames.append({
            "name": f"{kind.lower()}_{i}",
            "hex": wire.hex(),
            "unescaped": (bytes([0x7E]) + content + bytes([0x7E])).hex(),
            "address": address,
            "command": kind,
            "fields": fields,
        })
    return frames


def slip_frames():
    sliplib.config.USE_LEADING_END_BYTE = True
    frames = []
    for i in range(12):
        kind = ["HELLO", "READING", "TEXT"][i % 3]
        reserved = [0xC0, 0xDB, 0xDC, 0xDD]
        if kind == "HELLO":
            command, payload, fields = 0xC0, b"", {}
        elif kind == "READING":
            sensor = byte(reserved)
            value = int.from_bytes(bytes(byte(reserved) for _ in range(4)), "little", signed=True)
            command = 0xDB
            payload = bytes([sensor]) + value.to_bytes(4, "little", signed=True)
            fields = {"sensor": sensor, "value": value}
        else:
            text = bytes(byte(reserved) for _ in range(RNG.randrange(65)))
            command, payload, fields = 0x01, text, {"text": list(text)}
        content = bytes([command, len(payload)]) + payload
        content += bytes([crc8_smbus(content)])
        wire = sliplib.Driver().send(content)
        assert wire[0] == 0xC0 and wire[-1] == 0xC0
        assert sliplib.decode(wire[1:-1]) == content
        frames.append({
            "name": f"{kind.lower()}_{i}",
            "hex": wire.hex(),
            "unescaped": (bytes([0xC0]) + content + bytes([0xC0])).hex(),
            "command": kind,
            "fields": fields,
        })
    return frames


def damaged(wire, flag, escape, i):
    """A copy of `wire` damaged as a line damages frames: a bad escape, a flipped byte, a cut."""
    bad = bytearray(wire)
    if i % 3 == 0:
        bad[1:2] = bytes([escape, 0x01])
    elif i % 3 == 1:
        bad[len(bad) // 2] ^= 0x01 if bad[len(bad) // 2] not in (flag ^ 1, escape ^ 1) else 0x02
    else:
        del bad[len(bad) // 2:]
    return bytes(bad)


def stream(frames, flag, escape, shared):
    """Garbage, then each frame after a damaged copy of another; with `shared`, frames whose
    opening flag is the previous frame's closing one (sent with END after each frame only)."""
    out = bytes([0x00, 0x55, escape])
    expected = []
    for i, f in enumerate(frames):
        wire = bytes.fromhex(f["hex"])
        if shared and i > 0 and i % 2 == 0:
            expected.append({"offset": len(out) - 1, "hex": f["unescaped"]})
            out += wire[1:]
            continue
        out += damaged(bytes.fromhex(frames[(i + 1) % len(frames)]["hex"]), flag, escape, i)
        expected.append({"offset": len(out), "hex": f["unescaped"]})
        out += wire
    return out, expected


def write(name, frames, flag, escape, source):
    streams = []
    for shared in (False, True):
        data, expected = stream(frames, flag, escape, shared)
        streams.append({
            "name": "shared_flags" if shared else "garbage_and_damaged_copies",
            "hex": data.hex(),
            "expected_frames": expected,
        })
    if name == "escaped_slip":
        # sliplib's own stream decoder finds the same good frames (and drops the damaged ones
        # whose escapes break; those with a bad check it hands on: the check is the spec's).
        for s in streams:
            driver = sliplib.Driver()
            driver.receive(bytes.fromhex(s["hex"]))
            driver.receive(b"")
            got = []
            while True:
                try:
                    message = driver.get(block=False)
                except sliplib.ProtocolError:
                    continue
                if not message:
                    break
                got.append(message)
            wanted = [bytes.fromhex(e["hex"])[1:-1] for e in s["expected_frames"]]
            assert all(w in got for w in wanted)
    (HERE / f"{name}.json").write_text(json.dumps({
        "protocol": name,
        "source": source,
        "frames": frames,
        "streams": streams,
    }, indent=1) + "\n")


write("escaped_hdlc", hdlc_frames(), 0x7E, 0x7D, {
    "repos": [f"sensirion-shdlc-driver {version('sensirion-shdlc-driver')} (PyPI): "
              "ShdlcSerialMosiFrameBuilder._stuff_data_bytes escapes, "
              "ShdlcSerialMisoFrameBuilder._unstuff_data_bytes unescapes"],
    "check": "CRC-16/IBM-SDLC of address..payload, little-endian (computed in the script "
             "from the catalogue parameters, check value 0x906E)",
    "framing": "7E, address, command, length, payload, FCS, 7E; 7E 7D 11 13 escaped",
    "how": "random messages of every command, reserved bytes in every field half the time; "
           "`unescaped` is the frame as the decoder yields it",
    "spec": "protocol-codegen/tests/features/escaped_hdlc.toml",
})
write("escaped_slip", slip_frames(), 0xC0, 0xDB, {
    "repos": [f"sliplib {version('sliplib')} (PyPI): Driver.send with the leading END, "
              "decode, Driver.receive"],
    "check": "CRC-8/SMBUS of kind..payload (computed in the script, check value 0xF4)",
    "framing": "C0, kind, size, payload, CRC, C0; C0 as DB DC, DB as DB DD",
    "how": "random messages of every command, reserved bytes in every field half the time; "
           "`unescaped` is the frame as the decoder yields it",
    "spec": "protocol-codegen/tests/features/escaped_slip.toml",
})
