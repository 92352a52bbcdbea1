"""Golden SBP frames written and decoded by libsbp's Python package, for every command of
`specs/sbp.toml`.

Writes `tests/vectors/sbp_libsbp.json`: for each command, random messages (random field
values, random sender ids, random log texts of any length and any bytes) built with libsbp's
message classes, framed by their `to_binary()` and decoded again by `SBP.unpack` and
`sbp.table.dispatch`. Each frame records libsbp's decoded values under the spec's names and in
the spec's shape (a status word split into the spec's bit members, one bit as a boolean, a
member with an enum by its spec name; the DOPs scaled by the spec's 0.01, with the scale of
every scaled field), and a stream of the frames with garbage and a damaged copy of each.

Run with libsbp's Python installed (the version is written into the file):

    python3 -m venv .venv && .venv/bin/pip install sbp==6.5.2
    .venv/bin/python scripts/sbp_libsbp_vectors.py

Every spec command must name a libsbp class with the same message type, and every spec field
a libsbp field of the same name, so a name or id that drifts from libsbp's fails here.
"""

from __future__ import annotations

import json
import random
import struct
import tomllib
from pathlib import Path

import sbp
import sbp.imu
import sbp.logging
import sbp.navigation
import sbp.system
from sbp.msg import SBP
from sbp.table import dispatch

ROOT = Path(__file__).resolve().parents[1]
SPEC = tomllib.loads((ROOT / "specs" / "sbp.toml").read_text())
OUT = ROOT / "tests" / "vectors" / "sbp_libsbp.json"
FRAMES_PER_COMMAND = 4

#: The libsbp class of each spec command.
CLASSES = {
    "MSG_GPS_TIME": sbp.navigation.MsgGPSTime,
    "MSG_GPS_TIME_GNSS": sbp.navigation.MsgGPSTimeGnss,
    "MSG_UTC_TIME": sbp.navigation.MsgUtcTime,
    "MSG_UTC_TIME_GNSS": sbp.navigation.MsgUtcTimeGnss,
    "MSG_DOPS": sbp.navigation.MsgDops,
    "MSG_POS_ECEF": sbp.navigation.MsgPosECEF,
    "MSG_POS_ECEF_GNSS": sbp.navigation.MsgPosECEFGnss,
    "MSG_POS_LLH": sbp.navigation.MsgPosLLH,
    "MSG_POS_LLH_GNSS": sbp.navigation.MsgPosLLHGnss,
    "MSG_BASELINE_ECEF": sbp.navigation.MsgBaselineECEF,
    "MSG_BASELINE_NED": sbp.navigation.MsgBaselineNED,
    "MSG_VEL_ECEF": sbp.navigation.MsgVelECEF,
    "MSG_VEL_ECEF_GNSS": sbp.navigation.MsgVelECEFGnss,
    "MSG_VEL_NED": sbp.navigation.MsgVelNED,
    "MSG_VEL_NED_GNSS": sbp.navigation.MsgVelNEDGnss,
    "MSG_VEL_BODY": sbp.navigation.MsgVelBody,
    "MSG_AGE_CORRECTIONS": sbp.navigation.MsgAgeCorrections,
    "MSG_IMU_RAW": sbp.imu.MsgImuRaw,
    "MSG_IMU_AUX": sbp.imu.MsgImuAux,
    "MSG_LOG": sbp.logging.MsgLog,
    "MSG_STARTUP": sbp.system.MsgStartup,
    "MSG_HEARTBEAT": sbp.system.MsgHeartbeat,
}

#: construct's formats by the name libsbp's parsers give them.
FORMATS = {"Int8ul": "<B", "Int16ul": "<H", "Int32ul": "<I", "Int16sl": "<h", "Int32sl": "<i",
           "Float32l": "<f", "Float64l": "<d"}


def random_value(rng: random.Random, fmt: str):
    """A random value of a construct format: any integer of its width, any finite float."""
    if fmt in ("<f", "<d"):
        while True:
            raw = bytes(rng.getrandbits(8) for _ in range(struct.calcsize(fmt)))
            value = struct.unpack(fmt, raw)[0]
            if value == value and abs(value) != float("inf"):
                return value
    bits = 8 * struct.calcsize(fmt)
    value = rng.getrandbits(bits)
    if fmt[1].islower():
        value -= (value >> (bits - 1)) << bits
    return value


def random_message(rng: random.Random, cls):
    values = {"sender": rng.getrandbits(16)}
    for sub in cls._parser.subcons:
        kind = type(sub.subcon).__name__
        if kind == "GreedyBytes":
            # Log text: mostly printable ASCII, now and then any byte (a NUL, invalid UTF-8).
            n = rng.randint(0, 254 - 1)
            values[sub.name] = bytes(
                rng.getrandbits(8) if rng.random() < 0.05 else rng.randint(0x20, 0x7E) for _ in range(n))
        else:
            values[sub.name] = random_value(rng, sub.subcon.fmtstr)
    return cls(**values)


def enum_name(enum: str, value: int):
    for name, v in SPEC["enums"][enum]["values"].items():
        if v == value:
            return name
    return value


def spec_payload(struct_name: str, parsed, scales: dict) -> dict:
    """libsbp's decoded values in the spec's shape."""
    out = {}
    for field in SPEC["structs"][struct_name]["fields"]:
        name = field["name"]
        value = getattr(parsed, name)
        if "bits" in field:
            shift = 0
            for m in field["bits"]:
                part = (value >> shift) & ((1 << m["bits"]) - 1)
                if "type" in m:
                    out[m["name"]] = enum_name(m["type"], part)
                else:
                    out[m["name"]] = bool(part) if m["bits"] == 1 else part
                shift += m["bits"]
            width = {"u8": 8, "u16": 16, "u32": 32}[field["type"]]
            if shift < width:
                out[f"{name}_reserved"] = value >> shift
        elif field["type"] == "str":
            try:
                out[name] = value.decode("utf-8")
            except UnicodeDecodeError:
                out[name] = list(value)
        elif field["type"] in SPEC["enums"]:
            out[name] = enum_name(field["type"], value)
        elif "scale" in field:
            scales[name] = field["scale"]
            out[name] = round(value * field["scale"], 12)
        elif field["type"] == "f32":
            out[name] = f32_text(value)
        else:
            out[name] = value
    return out


def f32_text(value: float) -> float:
    """The shortest decimal that reads back as the same `f32`, as the codec prints it."""
    bits = struct.pack("<f", value)
    for digits in range(1, 18):
        shortest = float(f"{value:.{digits}g}")
        if struct.pack("<f", shortest) == bits:
            return shortest
    return value


def frames(rng: random.Random) -> list[dict]:
    out = []
    for command, cmd in SPEC["commands"].items():
        cls = CLASSES[command]
        for i in range(FRAMES_PER_COMMAND):
            raw = random_message(rng, cls).to_binary()
            parsed = dispatch(SBP.unpack(raw))
            assert type(parsed) is cls and parsed.msg_type == cmd["id"], (command, parsed)
            scales = {}
            out.append({
                "name": f"{command.lower()}_{i}",
                "message": command,
                "hex": raw.hex(),
                "header": {"msg_type": parsed.msg_type, "sender": parsed.sender},
                "payload": spec_payload(cmd["payload"], parsed, scales),
                "scales": scales,
            })
    assert {f["message"] for f in out} == set(SPEC["commands"]), "every command has frames"
    return out


def stream(rng: random.Random, good: list[dict]) -> dict:
    """Garbage (stray preambles among it), then each frame after a copy with a flipped bit."""
    data = bytes([0x55, 0x00, 0x55, 0x13])
    expected = []
    for f in good:
        b = bytes.fromhex(f["hex"])
        bad = bytearray(b)
        bad[rng.randrange(1, len(bad))] ^= 1 << rng.randrange(8)
        data += bytes(bad)
        expected.append({"offset": len(data), "hex": f["hex"]})
        data += b
    return {"name": "garbage_and_damaged_copies", "hex": data.hex(), "expected_frames": expected}


def main() -> None:
    rng = random.Random(0x53_42_50)
    good = frames(rng)
    doc = {
        "protocol": "sbp",
        "source": {
            "generator": "scripts/sbp_libsbp_vectors.py",
            "sbp": sbp.__version__,
            "what": "random messages of every command of specs/sbp.toml, built with libsbp's Python message "
            "classes, framed by to_binary() and decoded by SBP.unpack and sbp.table.dispatch",
            "payload": "libsbp's decoded values under the spec's names: status words split into the spec's bit "
            "members (one bit a boolean, an enum member by its spec name), DOPs scaled by the spec's 0.01 "
            "(scales: the scale of each scaled field), log text a string when it is UTF-8, else its bytes",
        },
        "frames": good,
        "streams": [stream(rng, good)],
    }
    OUT.write_text(json.dumps(doc, indent=1) + "\n")
    print(f"{len(good)} frames of {len(SPEC['commands'])} commands -> {OUT.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
