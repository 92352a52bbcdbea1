"""Golden SHDLC frames of the SPS30's commands from sensirion-shdlc-driver, for `specs/shdlc.toml`.

Writes `tests/vectors/shdlc_sensirion.json`. The driver has a frame writer for one direction and
a frame reader for the other, as a host does, so:

* every request (a MOSI frame) is the bytes `ShdlcSerialMosiFrameBuilder.to_bytes()` writes for
  a command: the driver's own command classes where it has them (device information, version,
  device status, reset), its generic `ShdlcCommand` with the SPS30 datasheet's data for the
  others, with random values where a command takes one;
* every response (a MISO frame) is written here, the datasheet's layout with random values,
  and read by `ShdlcSerialMisoFrameBuilder` (which checks its length and checksum and undoes
  the byte stuffing); the address, command, state and data it reads are those written, and the
  values of the commands the driver interprets are the ones its `interpret_response` returns.

Random values reach every reserved byte (0x7E, 0x7D, 0x11, 0x13) often, so byte stuffing is in
most frames. Run with the driver installed (its version is written into the file):

    python3 -m venv .venv && .venv/bin/pip install sensirion-shdlc-driver==1.0.2
    .venv/bin/python scripts/shdlc_sensirion_vectors.py
"""

from __future__ import annotations

import json
import random
import struct
from importlib.metadata import version
from pathlib import Path

from sensirion_shdlc_driver.command import ShdlcCommand
from sensirion_shdlc_driver.commands.device_info import (
    ShdlcCmdGetProductType,
    ShdlcCmdGetSerialNumber,
)
from sensirion_shdlc_driver.commands.device_reset import ShdlcCmdDeviceReset
from sensirion_shdlc_driver.commands.device_version import ShdlcCmdGetVersion
from sensirion_shdlc_driver.commands.error_state import ShdlcCmdGetErrorState
from sensirion_shdlc_driver.serial_frame_builder import (
    ShdlcSerialMisoFrameBuilder,
    ShdlcSerialMosiFrameBuilder,
)

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "tests" / "vectors" / "shdlc_sensirion.json"
ROUNDS = 6
PEER = f"sensirion-shdlc-driver {version('sensirion-shdlc-driver')}"
RESERVED = [0x7E, 0x7D, 0x11, 0x13]

MEASURED = [
    "mass_pm1_0", "mass_pm2_5", "mass_pm4_0", "mass_pm10", "number_pm0_5", "number_pm1_0",
    "number_pm2_5", "number_pm4_0", "number_pm10", "typical_particle_size",
]


def byte(r: random.Random) -> int:
    """A random byte, a reserved one one time in three."""
    return r.choice(RESERVED) if r.random() < 0.33 else r.randrange(256)


def f32(r: random.Random) -> float:
    """A random f32, as its shortest decimal form (how a decoder prints an f32)."""
    exact = struct.pack(">f", r.uniform(0, 1000))
    for digits in range(1, 10):
        short = float(f"{struct.unpack('>f', exact)[0]:.{digits}g}")
        if struct.pack(">f", short) == exact:
            return short
    return struct.unpack(">f", exact)[0]


def generic(cid: int, data: list[int]) -> ShdlcCommand:
    """The driver's generic command with the datasheet's data."""
    return ShdlcCommand(cid, data, max_response_time=1.0)


def miso(address: int, cid: int, state: int, data: bytes) -> bytes:
    """A MISO frame as the datasheet lays it out: stuffed, its checksum over ADR..DATA."""
    inner = bytearray([address, cid, state, len(data)]) + data
    inner.append(~sum(inner) & 0xFF)
    out = bytearray([0x7E])
    for b in inner:
        out += bytes([0x7D, b ^ 0x20]) if b in RESERVED else bytes([b])
    out.append(0x7E)
    return bytes(out)


def read_miso(raw: bytes) -> tuple[int, int, int, bytes]:
    """The driver's reading of a MISO frame (it raises on a bad length or checksum)."""
    builder = ShdlcSerialMisoFrameBuilder()
    assert builder.add_data(raw)
    return builder.interpret_data()


def requests(r: random.Random) -> list[tuple[str, ShdlcCommand, dict, str]]:
    """(command, the driver's command, payload, what was called) of every request."""
    fmt = r.choice([0x03, 0x05])
    interval = r.choice([0, 604800, r.randrange(1 << 32), 0x7E7D1113])
    clear = r.choice([False, True])
    return [
        ("START_MEASUREMENT", generic(0x00, [0x01, fmt]),
         {"subcommand": 1, "output_format": fmt}, f"ShdlcCommand(0x00, [0x01, {fmt:#04x}])"),
        ("STOP_MEASUREMENT", generic(0x01, []), None, "ShdlcCommand(0x01, [])"),
        ("READ_MEASURED_VALUES", generic(0x03, []), None, "ShdlcCommand(0x03, [])"),
        ("SLEEP", generic(0x10, []), None, "ShdlcCommand(0x10, [])"),
        ("WAKE_UP", generic(0x11, []), None, "ShdlcCommand(0x11, [])"),
        ("START_FAN_CLEANING", generic(0x56, []), None, "ShdlcCommand(0x56, [])"),
        ("AUTO_CLEANING_INTERVAL", generic(0x80, [0x00]),
         {"subcommand": 0, "interval": None}, "ShdlcCommand(0x80, [0x00])"),
        ("AUTO_CLEANING_INTERVAL", generic(0x80, [0x00, *struct.pack(">I", interval)]),
         {"subcommand": 0, "interval": interval},
         f"ShdlcCommand(0x80, [0x00] + {interval} as a big-endian u32)"),
        ("DEVICE_INFORMATION", ShdlcCmdGetProductType(), {"subcommand": 0},
         "ShdlcCmdGetProductType()"),
        ("DEVICE_INFORMATION", ShdlcCmdGetSerialNumber(), {"subcommand": 3},
         "ShdlcCmdGetSerialNumber()"),
        ("READ_VERSION", ShdlcCmdGetVersion(), None, "ShdlcCmdGetVersion()"),
        ("READ_DEVICE_STATUS_REGISTER", ShdlcCmdGetErrorState(clear=clear),
         {"clear": int(clear)}, f"ShdlcCmdGetErrorState(clear={clear})"),
        ("DEVICE_RESET", ShdlcCmdDeviceReset(), None, "ShdlcCmdDeviceReset()"),
    ]


def responses(r: random.Random) -> list[tuple[str, int, bytes, dict, str]]:
    """(command, id, data, payload, how the driver read it) of every response."""
    values = [f32(r) for _ in MEASURED]
    text = "".join(r.choice("0123456789ABCDEF") for _ in range(r.randrange(8, 17)))
    interval = r.randrange(1 << 32)
    ver = [byte(r) for _ in range(7)]
    reg, last = r.randrange(1 << 32), byte(r)
    version_read = ShdlcCmdGetVersion().interpret_response(bytes(ver))
    state_read = ShdlcCmdGetErrorState(clear=False).interpret_response(struct.pack(">IB", reg, last))
    assert state_read == (reg, last)
    assert (version_read.firmware.major, version_read.protocol.minor) == (ver[0], ver[6])
    text_read = ShdlcCmdGetSerialNumber().interpret_response((text + "\0").encode())
    assert text_read == text
    bits = {
        "bits_0_3": reg & 0xF, "fan_error": bool(reg >> 4 & 1), "laser_error": bool(reg >> 5 & 1),
        "bits_6_20": reg >> 6 & 0x7FFF, "speed_warning": bool(reg >> 21 & 1),
        "register_reserved": reg >> 22,
    }
    return [
        ("START_MEASUREMENT", 0x00, b"", None, "no data"),
        ("STOP_MEASUREMENT", 0x01, b"", None, "no data"),
        ("READ_MEASURED_VALUES", 0x03, struct.pack(">10f", *values),
         dict(zip(MEASURED, values)), "ten big-endian floats"),
        ("SLEEP", 0x10, b"", None, "no data"),
        ("WAKE_UP", 0x11, b"", None, "no data"),
        ("START_FAN_CLEANING", 0x56, b"", None, "no data"),
        ("AUTO_CLEANING_INTERVAL", 0x80, struct.pack(">I", interval), {"interval": interval},
         "the interval read"),
        ("AUTO_CLEANING_INTERVAL", 0x80, b"", {"interval": None}, "the answer to a write"),
        ("DEVICE_INFORMATION", 0xD0, (text + "\0").encode(), {"text": text},
         f"ShdlcCmdGetSerialNumber().interpret_response(...) == {text!r}"),
        ("READ_VERSION", 0xD1, bytes(ver), {
            "firmware_major": ver[0], "firmware_minor": ver[1], "firmware_debug": ver[2],
            "hardware_major": ver[3], "hardware_minor": ver[4], "shdlc_major": ver[5],
            "shdlc_minor": ver[6]}, "ShdlcCmdGetVersion().interpret_response(...)"),
        ("READ_DEVICE_STATUS_REGISTER", 0xD2, struct.pack(">IB", reg, last),
         {**bits, "last_error": last},
         f"ShdlcCmdGetErrorState(clear=False).interpret_response(...) == ({reg:#x}, {last})"),
        ("DEVICE_RESET", 0xD3, b"", None, "no data"),
    ]


def main() -> None:
    r = random.Random(0x5D1C)
    frames = []
    for round_ in range(ROUNDS):
        # The SPS30's address is 0; other SHDLC devices have others.
        address = 0 if round_ == 0 else byte(r)
        for i, (name, cmd, payload, call) in enumerate(requests(r)):
            raw = ShdlcSerialMosiFrameBuilder(address, cmd.id, cmd.data).to_bytes()
            frames.append({
                "name": f"{name.lower()}_request_{round_}_{i}",
                "direction": "request",
                "command": name,
                "header": {"address": address},
                "payload": {} if payload is None else payload,
                "scales": {},
                "hex": raw.hex(),
                "provenance": f"{PEER}: ShdlcSerialMosiFrameBuilder({address}, ...) of {call}",
            })
        for i, (name, cid, data, payload, how) in enumerate(responses(r)):
            # A state of 0 (no error) or the device-error flag: a frame with data.
            state = r.choice([0x00, 0x80])
            raw = miso(address, cid, state, data)
            assert read_miso(raw) == (address, cid, state, data)
            frames.append({
                "name": f"{name.lower()}_response_{round_}_{i}",
                "direction": "response",
                "command": name,
                "header": {"address": address, "state": state},
                "payload": {} if payload is None else payload,
                "scales": {},
                "hex": raw.hex(),
                "provenance": f"{PEER}: ShdlcSerialMisoFrameBuilder read it back ({how})",
            })
    doc = {
        "protocol": "shdlc",
        "source": {
            "generator": "scripts/shdlc_sensirion_vectors.py",
            "sensirion-shdlc-driver": version("sensirion-shdlc-driver"),
            "what": "requests the driver writes for the SPS30's commands (random values), and "
                    "responses laid out as the SPS30 datasheet says that the driver reads back",
        },
        "frames": frames,
    }
    OUT.write_text(json.dumps(doc, indent=1, ensure_ascii=False) + "\n")
    print(f"{len(frames)} frames -> {OUT.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
