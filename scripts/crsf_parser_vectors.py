"""Golden CRSF frames written and parsed by crsf-parser, for the frame types it knows.

Writes `tests/vectors/crsf_parser.json`: random BATTERY_SENSOR, LINK_STATISTICS and
RC_CHANNELS_PACKED messages, framed by crsf-parser (`crsf_build_frame`, sync 0xC8, its CRC) and
parsed back by its `CRSFParser.parse_stream`, which checks the length and the CRC. Each frame
records the payload in the spec's shape (`payload`: a field the spec scales is its physical
value) and, under `peer`, what crsf-parser parsed from the bytes: `[spec path, crsf-parser's
value, scale]`. crsf-parser keeps the wire integers; where the spec scales a field, its value
is put in the spec's unit with the specification's scale, to agree within half the scale. crsf-parser's other types are left
out (see `left_out` in the file).

Run with crsf-parser installed (the version is written into the file):

    python3 -m venv .venv && .venv/bin/pip install crsf-parser==0.3.2
    .venv/bin/python scripts/crsf_parser_vectors.py
"""

from __future__ import annotations

import json
import random
from importlib.metadata import version
from pathlib import Path

from crsf_parser import CRSFParser, PacketValidationStatus
from crsf_parser.handling import crsf_build_frame
from crsf_parser.payloads import PacketsTypes

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "tests" / "vectors" / "crsf_parser.json"
FRAMES_PER_TYPE = 8

#: crsf-parser's field names, by the spec's.
BATTERY = {"voltage": "voltage", "current": "current", "capacity_used": "capacity", "remaining": "remaining"}
LINK = {
    "up_rssi_ant1": "uplink_rssi_ant_1", "up_rssi_ant2": "uplink_rssi_ant_2", "up_link_quality": "uplink_link_quality",
    "up_snr": "uplink_snr", "active_antenna": "diversity_active_antenna", "rf_profile": "rf_mode",
    "up_rf_power": "uplink_tx_power", "down_rssi": "downlink_rssi", "down_link_quality": "downlink_link_quality",
    "down_snr": "downlink_snr",
}


def parsed(frame: bytes):
    """crsf-parser's reading of `frame`: its payload, after its length and CRC checks."""
    out = []
    CRSFParser(lambda content, status: out.append((content, status))).parse_stream(bytearray(frame))
    assert len(out) == 1 and out[0][1] == PacketValidationStatus.VALID, out
    return out[0][0].payload


#: The fields the spec scales: the wire value to the spec's physical value (a scale that is
#: the reciprocal of an integer divides by it, as the generated code does), and the scale's step.
SCALED = {
    "voltage": (lambda v: v / 10, 0.1),
    "current": (lambda v: v / 10, 0.1),
    "up_rssi_ant1": (lambda v: v / -1, 1),
    "up_rssi_ant2": (lambda v: v / -1, 1),
    "down_rssi": (lambda v: v / -1, 1),
    "channels": (lambda v: v * 0.625 + 880, 0.625),
}


def physical(k, v):
    """The spec's value of field `k` whose wire value is `v`."""
    return SCALED[k][0](v) if k in SCALED else v


def peer(k, v):
    """crsf-parser's wire value `v` of field `k`, in the spec's unit, with its step."""
    return [k, physical(k.split(".")[0], v), SCALED.get(k.split(".")[0], (None, 1))[1]]


def battery(rng):
    p = {"voltage": rng.getrandbits(16), "current": rng.getrandbits(16), "capacity_used": rng.getrandbits(24), "remaining": rng.randint(0, 100)}
    frame = crsf_build_frame(PacketsTypes.BATTERY_SENSOR, {BATTERY[k]: v for k, v in p.items()})
    got = parsed(frame)
    return {k: physical(k, v) for k, v in p.items()}, frame, [peer(k, got[t]) for k, t in BATTERY.items()]


def link_statistics(rng):
    p = {
        "up_rssi_ant1": rng.getrandbits(8), "up_rssi_ant2": rng.getrandbits(8), "up_link_quality": rng.randint(0, 100),
        "up_snr": rng.randint(-128, 127), "active_antenna": rng.randint(0, 1), "rf_profile": rng.randint(0, 2),
        "up_rf_power": rng.randint(0, 6), "down_rssi": rng.getrandbits(8), "down_link_quality": rng.randint(0, 100),
        "down_snr": rng.randint(-128, 127),
    }
    frame = crsf_build_frame(PacketsTypes.LINK_STATISTICS, {LINK[k]: v for k, v in p.items()})
    got = parsed(frame)
    # Its enumerations parse to named integers: their integer is the wire value.
    return {k: physical(k, v) for k, v in p.items()}, frame, [peer(k, int(got[t])) for k, t in LINK.items()]


def rc_channels(rng):
    channels = [rng.getrandbits(11) for _ in range(16)]
    # crsf-parser's channel list is in reverse order (its first element is channel 16): it is
    # given reversed and read back reversed, so that the bytes carry channel 1 in the lowest
    # bits as the TBS specification writes them.
    frame = crsf_build_frame(PacketsTypes.RC_CHANNELS_PACKED, {"channels": channels[::-1]})
    got = list(parsed(frame)["channels"])[::-1]
    return {"channels": [physical("channels", c) for c in channels]}, frame, [peer(f"channels.{n}", v) for n, v in enumerate(got)]


TYPES = {"BATTERY_SENSOR": battery, "LINK_STATISTICS": link_statistics, "RC_CHANNELS_PACKED": rc_channels}


def main() -> None:
    rng = random.Random(0x435253)
    frames = []
    for name, make in TYPES.items():
        for n in range(FRAMES_PER_TYPE):
            payload, frame, peer = make(rng)
            frames.append({"name": f"{name.lower()}_{n}", "message": name, "hex": bytes(frame).hex(), "payload": payload, "peer": peer})
    out = {
        "protocol": "crsf",
        "source": {
            "generator": "scripts/crsf_parser_vectors.py",
            "crsf-parser": version("crsf-parser"),
            "what": "random messages of the frame types crsf-parser builds, framed by its crsf_build_frame and parsed back by its CRSFParser.parse_stream (length and CRC checked)",
            "payload": "the payload in the spec's shape, as protocol decode prints it",
            "peer": "[spec path, crsf-parser's value, scale]: crsf-parser's reading of the bytes",
            "left_out": {
                "HEARTBEAT": "crsf-parser declares a 1-byte payload; the TBS specification's origin address is an int16 (2 bytes)",
                "GPS, ATTITUDE, VIDEO_TRANSMITTER": "crsf-parser lists their types and sizes but has no payload layout to build or parse them",
            },
            "disagreements": [
                "RC_CHANNELS_PACKED: crsf-parser's channel list is in reverse order (its first element is the highest bits, channel 16); the frames here are built from the reversed list and compared reversed",
            ],
        },
        "frames": frames,
    }
    OUT.write_text(json.dumps(out, indent=1) + "\n")
    print(f"{len(frames)} frames -> {OUT.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
