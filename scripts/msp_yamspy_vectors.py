"""Golden MSP frames framed and parsed by YAMSPy, for the commands of `specs/msp.toml`.

Writes `tests/vectors/msp_yamspy.json`: for each command, random messages in v1 frames (ids below
255) and v2 frames. Requests are written by YAMSPy itself: `send_RAW_msg` (every read request,
empty) and its `send_RAW_RC` and `send_RAW_MOTORS` (the two writes, from random channel and
motor values). Replies, which YAMSPy only reads, have their payload laid out here from random
values in Betaflight's (or INAV's) order, are framed by `send_RAW_msg` (v1) or with YAMSPy's
`_crc8_dvb_s2` (v2 frames of ids below 256, which `send_RAW_msg` writes as v1 only), their
direction byte set to `>` (no check covers it), and are then read back by YAMSPy's
`receive_msg` and `process_recv_data`. Each frame records the payload in the spec's shape
(`payload`, what the script packed, a field the spec scales as its physical value: the wire
integer divided as `SCALED` says) and, under `yamspy`, what YAMSPy's parser read from the
bytes: `[spec path, YAMSPy's value, scale]`. Where the spec scales the field, YAMSPy's value
is in the spec's unit (YAMSPy's raw reading times the scale where YAMSPy keeps the integer)
and agrees with the spec's within half the scale; elsewhere the spec's wire value times
`scale` is YAMSPy's.

Run with YAMSPy installed (the version is written into the file):

    python3 -m venv .venv && .venv/bin/pip install yamspy==0.3.3
    .venv/bin/python scripts/msp_yamspy_vectors.py
"""

from __future__ import annotations

import json
import logging
import random
import struct
import tomllib
from importlib.metadata import version
from pathlib import Path

from yamspy import MSPy

ROOT = Path(__file__).resolve().parents[1]
SPEC = tomllib.loads((ROOT / "specs" / "msp.toml").read_text())
OUT = ROOT / "tests" / "vectors" / "msp_yamspy.json"
FRAMES_PER_COMMAND = 3
logging.disable(logging.CRITICAL)


class Wire:
    """A stand-in for YAMSPy's serial port: what it writes, and bytes for it to read."""

    def __init__(self) -> None:
        self.written = b""
        self.unread = b""

    def write(self, data) -> int:
        self.written = bytes(data)
        return len(data)

    def read(self, size: int = 1) -> bytes:
        out, self.unread = self.unread[:size], self.unread[size:]
        return out


def yamspy(inav: bool = False) -> tuple[MSPy, Wire]:
    board = MSPy(device="unused", logfilename=None, loglevel="CRITICAL")
    board.conn = Wire()
    board.INAV = inav
    board.CONFIG["apiVersion"] = "1.46.0"
    return board, board.conn


def v2_frame(direction: int, code: int, payload: bytes) -> bytes:
    body = bytes([0]) + struct.pack("<HH", code, len(payload)) + payload
    crc = 0
    for b in body:
        crc = MSPy._crc8_dvb_s2(crc, b)
    return b"$X" + bytes([direction]) + body + bytes([crc])


def framed(code: int, payload: bytes, direction: int, v2: bool) -> bytes:
    """The frame YAMSPy writes for `payload`, its direction byte set."""
    if v2 and code < 256:
        return v2_frame(direction, code, payload)
    board, wire = yamspy()
    board.send_RAW_msg(code, list(payload))
    return wire.written[:2] + bytes([direction]) + wire.written[3:]


def parsed(frame: bytes, inav: bool) -> MSPy:
    """YAMSPy after reading `frame` as a reply."""
    board, wire = yamspy(inav)
    wire.unread = frame
    handler = board.receive_msg()
    result = board.process_recv_data(handler)
    assert result >= 0 or result == -5, f"YAMSPy refuses {frame.hex()}: {result}"
    return board


# ---- Replies: random values, packed in the firmware's order ----


def u(rng, bits):
    return rng.getrandbits(bits)


def i(rng, bits):
    return rng.getrandbits(bits) - (1 << (bits - 1))


def text(rng, n):
    return "".join(rng.choice("ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789") for _ in range(n))


def api_version(rng):
    v = [u(rng, 8) for _ in range(3)]
    y = lambda b: [["protocol_version", b.CONFIG["mspProtocolVersion"], 1]] + [
        [k, int(x), 1] for k, x in zip(["api_version_major", "api_version_minor"], b.CONFIG["apiVersion"].split(".")[:2])
    ]
    return dict(zip(["protocol_version", "api_version_major", "api_version_minor"], v)), bytes(v), y


def fc_variant(rng):
    ident = text(rng, 4)
    return {"identifier": ident}, ident.encode(), lambda b: [["identifier", b.CONFIG["flightControllerIdentifier"], None]]


def fc_version(rng):
    v = [u(rng, 8) for _ in range(3)]
    y = lambda b: [[k, int(x), 1] for k, x in zip(["major", "minor", "patch"], b.CONFIG["flightControllerVersion"].split("."))]
    return dict(zip(["major", "minor", "patch"], v)), bytes(v), y


def board_info(rng):
    names = [text(rng, rng.randint(0, 12)) for _ in range(3)]
    caps = rng.choice([0, 1, 2, 3, 9, 0x41, 0x4B])
    problems = rng.getrandbits(2)
    p = {
        "board_identifier": text(rng, 4),
        "hardware_revision": u(rng, 16),
        "board_type": rng.choice([0, 2]),
        "has_vcp": bool(caps & 1),
        "has_softserial": bool(caps & 2),
        "capability_bit_2": bool(caps & 4),
        "has_flash_bootloader": bool(caps & 8),
        "capability_bits_4_5": (caps >> 4) & 3,
        "supports_rx_bind": bool(caps & 0x40),
        "target_capabilities_reserved": caps >> 7,
        "target_name_length": len(names[0]),
        "target_name": names[0].encode().hex(),
        "board_name_length": len(names[1]),
        "board_name": names[1].encode().hex(),
        "manufacturer_id_length": len(names[2]),
        "manufacturer_id": names[2].encode().hex(),
        "signature": [u(rng, 8) for _ in range(32)],
        "mcu_type_id": u(rng, 8),
        "configuration_state": rng.randint(0, 1),
        "gyro_sample_rate": rng.choice([3200, 6400, 8000]),
        "acc_needs_calibration": bool(problems & 1),
        "motor_protocol_disabled": bool(problems & 2),
        "configuration_problems_reserved": 0,
        "spi_registered_device_count": u(rng, 8),
        "i2c_registered_device_count": u(rng, 8),
    }
    raw = p["board_identifier"].encode() + struct.pack("<HBB", p["hardware_revision"], p["board_type"], caps)
    for n in names:
        raw += bytes([len(n)]) + n.encode()
    raw += bytes(p["signature"]) + struct.pack(
        "<BBHIBB", p["mcu_type_id"], p["configuration_state"], p["gyro_sample_rate"], problems,
        p["spi_registered_device_count"], p["i2c_registered_device_count"],
    )

    def y(b):
        c = b.CONFIG
        return [
            ["board_identifier", c["boardIdentifier"], None],
            ["hardware_revision", c["boardVersion"], 1],
            ["board_type", c["boardType"], 1],
            ["target_name", c["targetName"].encode().hex(), None],
            ["board_name", c["boardName"].encode().hex(), None],
            ["manufacturer_id", c["manufacturerId"].encode().hex(), None],
            ["signature", c["signature"], None],
            ["mcu_type_id", c["mcuTypeId"], 1],
        ]

    return p, raw, y


def build_info(rng):
    date, time, rev = "Mar 14 2026", f"{rng.randint(0, 23):02}:{rng.randint(0, 59):02}:{rng.randint(0, 59):02}", text(rng, 7)
    options = bytes(u(rng, 8) for _ in range(rng.choice([0, 2, 6])))
    p = {"build_date": date, "build_time": time, "short_git_revision": rev, "build_options": options.hex()}
    return p, (date + time + rev).encode() + options, lambda b: [["build_date", b.CONFIG["buildInfo"][:11], None], ["build_time", b.CONFIG["buildInfo"][12:], None]]


def craft_name(rng):
    name = text(rng, rng.randint(1, 16))
    return {"name": name.encode().hex()}, name.encode(), lambda b: [["name", b.CONFIG["name"].encode().hex(), None]]


def feature_config(rng):
    m = u(rng, 32)
    return {"enabled_features": m}, struct.pack("<I", m), lambda b: [["enabled_features", b.FEATURE_CONFIG["featuremask"], 1]]


def status(rng):
    extra = bytes(u(rng, 8) for _ in range(rng.randint(0, 3)))
    p = {
        "cycle_time": u(rng, 16), "i2c_errors": u(rng, 16), "sensors": u(rng, 7), "flight_mode_flags": u(rng, 32),
        "current_pid_profile_index": rng.randint(0, 3), "average_system_load_percent": rng.randint(0, 100),
        "gyro_cycle_time": 0, "extra_flight_mode_flags_count": len(extra), "extra_flight_mode_flags": extra.hex(),
        "arming_disable_flags_count": 26, "arming_disable_flags": u(rng, 26), "config_state_flags": rng.randint(0, 1),
        "core_temp_celsius": rng.randint(20, 90), "control_rate_profile_count": 4,
    }
    raw = struct.pack("<HHHIBHH", *[p[k] for k in ["cycle_time", "i2c_errors", "sensors", "flight_mode_flags", "current_pid_profile_index", "average_system_load_percent", "gyro_cycle_time"]])
    raw += bytes([len(extra)]) + extra + struct.pack("<BIBHB", 26, p["arming_disable_flags"], p["config_state_flags"], p["core_temp_celsius"], 4)

    def y(b):
        c = b.CONFIG
        return [["cycle_time", c["cycleTime"], 1], ["i2c_errors", c["i2cError"], 1], ["sensors", c["activeSensors"], 1],
                ["flight_mode_flags", c["mode"], 1], ["current_pid_profile_index", c["profile"], 1]]

    return p, raw, y


def status_ex(rng):
    p, _, _ = status(rng)
    del p["gyro_cycle_time"]
    p = {**{k: p[k] for k in list(p)[:6]}, "pid_profile_count": 4, "current_control_rate_profile_index": rng.randint(0, 5), **{k: p[k] for k in list(p)[6:]}}
    extra = bytes.fromhex(p["extra_flight_mode_flags"])
    raw = struct.pack("<HHHIBHBB", *[p[k] for k in ["cycle_time", "i2c_errors", "sensors", "flight_mode_flags", "current_pid_profile_index", "average_system_load_percent", "pid_profile_count", "current_control_rate_profile_index"]])
    raw += bytes([len(extra)]) + extra + struct.pack("<BIBHB", 26, p["arming_disable_flags"], p["config_state_flags"], p["core_temp_celsius"], 4)

    def y(b):
        c = b.CONFIG
        return [["cycle_time", c["cycleTime"], 1], ["i2c_errors", c["i2cError"], 1], ["sensors", c["activeSensors"], 1],
                ["flight_mode_flags", c["mode"], 1], ["current_pid_profile_index", c["profile"], 1],
                ["average_system_load_percent", c["cpuload"], 1], ["pid_profile_count", c["numProfiles"], 1],
                ["current_control_rate_profile_index", c["rateProfile"], 1], ["extra_flight_mode_flags", bytes(c["flightModeFlags"]).hex(), None],
                ["arming_disable_flags_count", c["armingDisableCount"], 1], ["arming_disable_flags", c["armingDisableFlags"], 1]]

    return p, raw, y


def raw_imu(rng):
    names = [f"{s}_{a}" for s in ["acc", "gyro", "mag"] for a in "xyz"]
    v = [i(rng, 16) for _ in names]
    y = lambda b: [[n, x, 1] for n, x in zip(names, b.SENSOR_DATA["accelerometer"] + b.SENSOR_DATA["gyroscope"] + b.SENSOR_DATA["magnetometer"])]
    return dict(zip(names, v)), struct.pack("<9h", *v), y


def u16_list(name, key, count, lo, hi):
    def make(rng):
        v = [rng.randint(lo, hi) for _ in range(count(rng))]
        return {name: v}, struct.pack(f"<{len(v)}H", *v), lambda b: [[f"{name}.{n}", x, 1] for n, x in enumerate(key(b))]

    return make


def rc_channels(rng):
    v = [rng.randint(885, 2115) for _ in range(rng.randint(4, 18))]
    return {"channels": [{"value": x} for x in v]}, struct.pack(f"<{len(v)}H", *v), lambda b: [[f"channels.{n}.value", x, 1] for n, x in enumerate(b.RC["channels"])]


def raw_gps(rng):
    p = {"fix_type": rng.randint(0, 2), "num_sat": rng.randint(0, 30), "lat": rng.randint(-900000000, 900000000),
         "lon": rng.randint(-1800000000, 1800000000), "alt": u(rng, 16), "ground_speed": u(rng, 16), "ground_course": rng.randint(0, 3599)}
    raw = struct.pack("<BBiiHHH", *p.values())
    inav = rng.random() < 0.5
    p["dop"] = u(rng, 16) if inav else None
    if inav:
        raw += struct.pack("<H", p["dop"])

    def y(b):
        g = b.GPS_DATA
        # YAMSPy keeps these four integers: their scale makes them the spec's physical values.
        out = [["fix_type", g["fix"], 1], ["num_sat", g["numSat"], 1], ["lat", g["lat"] / 10**7, 1e-7], ["lon", g["lon"] / 10**7, 1e-7],
               ["alt", g["alt"], 1], ["ground_speed", g["speed"], 1], ["ground_course", g["ground_course"] / 10, 0.1]]
        return out + ([["dop", g["hdop"] / 100, 0.01]] if inav else [])

    return p, raw, y, inav


def comp_gps(rng):
    p = {"distance_to_home": u(rng, 16), "direction_to_home": rng.randint(0, 359), "update": rng.randint(0, 1)}
    g = lambda b: b.GPS_DATA
    y = lambda b: [["distance_to_home", g(b)["distanceToHome"], 1], ["direction_to_home", g(b)["directionToHome"], 1], ["update", g(b)["update"], 1]]
    return p, struct.pack("<HHB", *p.values()), y


def attitude(rng):
    p = {"roll": rng.randint(-1800, 1800), "pitch": rng.randint(-900, 900), "yaw": rng.randint(0, 359)}
    k = lambda b: b.SENSOR_DATA["kinematics"]
    return p, struct.pack("<hhh", *p.values()), lambda b: [["roll", k(b)[0], 0.1], ["pitch", k(b)[1], 0.1], ["yaw", k(b)[2], 1]]


def altitude(rng):
    p = {"altitude": i(rng, 32), "vario": i(rng, 16)}
    return p, struct.pack("<ih", *p.values()), lambda b: [["altitude", b.SENSOR_DATA["altitude"], 0.01]]


def analog(rng):
    p = {"battery_voltage": u(rng, 8), "mah_drawn": u(rng, 16), "rssi": rng.randint(0, 1023), "amperage": i(rng, 16), "battery_voltage_mv": u(rng, 16)}
    a = lambda b: b.ANALOG
    # YAMSPy reads the legacy voltage and then overwrites it with the 0.01 V one; its amperage
    # is signed, as Betaflight's.
    y = lambda b: [["mah_drawn", a(b)["mAhdrawn"], 1], ["rssi", a(b)["rssi"], 1], ["amperage", a(b)["amperage"], 0.01], ["battery_voltage_mv", a(b)["voltage"], 0.01]]
    return p, struct.pack("<BHHhH", *p.values()), y


def rc_tuning(rng):
    names = ["rc_rate", "rc_expo", "roll_rate", "pitch_rate", "yaw_rate", "dynamic_thr_pid", "throttle_mid", "throttle_expo", "dynamic_thr_breakpoint",
             "rc_yaw_expo", "rc_yaw_rate", "rc_pitch_rate", "rc_pitch_expo", "throttle_limit_type", "throttle_limit_percent",
             "roll_rate_limit", "pitch_rate_limit", "yaw_rate_limit", "rates_type"]
    fmt = "<BBBBBBBBHBBBBBBHHHB"
    v = [u(rng, 16) if c == "H" else u(rng, 8) for c in fmt[1:]]
    p = dict(zip(names, v))
    raw = struct.pack(fmt, *v)
    p["throttle_hover"] = u(rng, 8) if rng.random() < 0.5 else None
    if p["throttle_hover"] is not None:
        raw += bytes([p["throttle_hover"]])
    keys = {"rc_rate": "RC_RATE", "rc_expo": "RC_EXPO", "roll_rate": "roll_rate", "pitch_rate": "pitch_rate", "yaw_rate": "yaw_rate",
            "dynamic_thr_pid": "dynamic_THR_PID", "throttle_mid": "throttle_MID", "throttle_expo": "throttle_EXPO",
            "dynamic_thr_breakpoint": "dynamic_THR_breakpoint", "rc_yaw_expo": "RC_YAW_EXPO", "rc_yaw_rate": "rcYawRate",
            "rc_pitch_rate": "rcPitchRate", "rc_pitch_expo": "RC_PITCH_EXPO", "throttle_limit_type": "throttleLimitType",
            "throttle_limit_percent": "throttleLimitPercent", "roll_rate_limit": "roll_rate_limit", "pitch_rate_limit": "pitch_rate_limit",
            "yaw_rate_limit": "yaw_rate_limit"}
    scaled = {"dynamic_thr_breakpoint", "throttle_limit_type", "throttle_limit_percent", "roll_rate_limit", "pitch_rate_limit", "yaw_rate_limit"}
    return p, raw, lambda b: [[n, b.RC_TUNING[k], 1 if n in scaled else 0.01] for n, k in keys.items()]


def pid(rng):
    v = [[u(rng, 8) for _ in range(3)] for _ in range(rng.randint(3, 5))]
    p = {"pids": [dict(zip("pid", t)) for t in v]}
    y = lambda b: [[f"pids.{n}.{k}", x, 1] for n, t in enumerate(b.PIDs) for k, x in zip("pid", t)]
    return p, bytes(sum(v, [])), y


def battery_state(rng):
    p = {"cell_count": rng.randint(0, 8), "capacity": u(rng, 16), "legacy_battery_voltage": u(rng, 8), "mah_drawn": u(rng, 16),
         "amperage": i(rng, 16), "battery_state": rng.randint(0, 4), "battery_voltage": u(rng, 16)}
    # YAMSPy reads no legacy voltage byte (Betaflight writes one after the capacity), so its
    # later fields are shifted by a byte: only the first two are its reading of Betaflight's.
    s = lambda b: b.BATTERY_STATE
    return p, struct.pack("<BHBHhBH", *p.values()), lambda b: [["cell_count", s(b)["cellCount"], 1], ["capacity", s(b)["capacity"], 1]]


def uid(rng):
    v = [u(rng, 32) for _ in range(3)]
    return {"uid": v}, struct.pack("<3I", *v), lambda b: [[f"uid.{n}", x, 1] for n, x in enumerate(b.CONFIG["uid"])]


def debug(rng):
    v = [i(rng, 16) for _ in range(4)]
    return {"debug": v}, struct.pack("<4h", *v), lambda b: [[f"debug.{n}", x, 1] for n, x in enumerate(b.SENSOR_DATA["debug"][:4])]


def box_names(rng):
    names = ";".join(text(rng, rng.randint(3, 10)) for _ in range(rng.randint(2, 20))) + ";"
    return {"names": names.encode().hex()}, names.encode(), lambda b: [["names", (";".join(b.AUX_CONFIG) + ";").encode().hex(), None]]


def inav_status(rng):
    p = {"cycle_time": u(rng, 16), "i2c_errors": u(rng, 16), "sensor_status": u(rng, 16), "cpu_load": rng.randint(0, 100),
         "config_profile": rng.randint(0, 2), "battery_profile": rng.randint(0, 2), "arming_flags": u(rng, 32), "active_modes": [u(rng, 32) for _ in range(4)]}
    raw = struct.pack("<HHHHBI4I", p["cycle_time"], p["i2c_errors"], p["sensor_status"], p["cpu_load"], p["battery_profile"] << 4 | p["config_profile"], p["arming_flags"], *p["active_modes"])
    p["mixer_profile"] = rng.randint(0, 1) if rng.random() < 0.5 else None
    if p["mixer_profile"] is not None:
        raw += bytes([p["mixer_profile"]])
    return p, raw, lambda b: []


def inav_analog(rng):
    p = {"battery_full_when_plugged_in": rng.random() < 0.5, "use_capacity_thresholds": rng.random() < 0.5, "battery_state": rng.randint(0, 3),
         "cell_count": rng.randint(0, 12), "voltage": u(rng, 16), "amperage": rng.randint(0, 0x7FFF), "power": u(rng, 32), "mah_drawn": u(rng, 32),
         "mwh_drawn": u(rng, 32), "battery_remaining_capacity": u(rng, 32), "battery_percentage": rng.randint(0, 100), "rssi": rng.randint(0, 1023)}
    flags = p["battery_full_when_plugged_in"] | p["use_capacity_thresholds"] << 1 | p["battery_state"] << 2 | p["cell_count"] << 4
    raw = bytes([flags]) + struct.pack("<HhIIIIBH", *[p[k] for k in list(p)[4:]])
    a = lambda b: b.ANALOG
    keys = {"battery_full_when_plugged_in": ("battery_full_when_plugged_in", None), "use_capacity_thresholds": ("use_capacity_thresholds", None),
            "battery_state": ("battery_state", 1), "cell_count": ("cell_count", 1), "voltage": ("voltage", 0.01), "amperage": ("amperage", 0.01),
            "power": ("power", 0.01), "mah_drawn": ("mAhdrawn", 1), "mwh_drawn": ("mWhdrawn", 1), "battery_remaining_capacity": ("battery_remaining_capacity", 1),
            "battery_percentage": ("battery_percentage", 1), "rssi": ("rssi", 1)}
    return p, raw, lambda b: [[n, a(b)[k], s] for n, (k, s) in keys.items()]


def inav_air_speed(rng):
    v = u(rng, 32)
    return {"air_speed": v}, struct.pack("<I", v), lambda b: []


REPLIES = {
    "API_VERSION": api_version, "FC_VARIANT": fc_variant, "FC_VERSION": fc_version, "BOARD_INFO": board_info,
    "BUILD_INFO": build_info, "NAME": craft_name, "FEATURE_CONFIG": feature_config, "STATUS": status,
    "RAW_IMU": raw_imu, "SERVO": u16_list("servos", lambda b: b.SERVO_DATA, lambda r: r.randint(1, 18), 750, 2250),
    "MOTOR": u16_list("motors", lambda b: b.MOTOR_DATA, lambda r: 8, 0, 2000), "RC": rc_channels, "RAW_GPS": raw_gps,
    "COMP_GPS": comp_gps, "ATTITUDE": attitude, "ALTITUDE": altitude, "ANALOG": analog, "RC_TUNING": rc_tuning, "PID": pid,
    "BOXNAMES": box_names, "BATTERY_STATE": battery_state, "STATUS_EX": status_ex, "UID": uid, "DEBUG": debug,
    "INAV_STATUS": inav_status, "INAV_ANALOG": inav_analog, "INAV_AIR_SPEED": inav_air_speed,
}
INAV = {"INAV_STATUS", "INAV_ANALOG", "INAV_AIR_SPEED"}

#: Commands YAMSPy cannot frame or that need a payload struct not laid out here, with why.
LEFT_OUT = {
    "V2_FRAME": "YAMSPy's send_RAW_msg writes neither format for command 255 (it tests `code < 255` and `code > 255`)",
    "COMMON_SETTING": "a setting's value bytes depend on the setting; msp.json holds INAV's frames",
    "COMMON_SET_SETTING": "as COMMON_SETTING",
    "SET_NAME": "YAMSPy has no writer for it; its payload is NAME's, which the replies cover",
}


#: The fields the spec scales, by command, and the integer that divides the wire value (the
#: reciprocal of the scale): the payload holds their physical values, as `protocol decode`
#: prints them.
SCALED = {
    "ATTITUDE": {"roll": 10, "pitch": 10},
    "ANALOG": {"battery_voltage": 10, "amperage": 100, "battery_voltage_mv": 100},
    "RAW_GPS": {"lat": 10**7, "lon": 10**7, "ground_course": 10, "dop": 100},
    "RC_TUNING": {k: 100 for k in ["rc_rate", "rc_expo", "roll_rate", "pitch_rate", "yaw_rate", "dynamic_thr_pid", "throttle_mid", "throttle_expo",
                                   "rc_yaw_expo", "rc_yaw_rate", "rc_pitch_rate", "rc_pitch_expo", "throttle_hover"]},
    "BATTERY_STATE": {"legacy_battery_voltage": 10, "amperage": 100, "battery_voltage": 100},
    "INAV_ANALOG": {"voltage": 100, "amperage": 100, "power": 100},
}


def physical(name, payload):
    """`payload` with the fields the spec scales divided into their physical values."""
    div = SCALED.get(name, {})
    return {k: v / div[k] if k in div and v is not None else v for k, v in payload.items()}


def reply_frames(rng, name, cmd, frames):
    for n in range(FRAMES_PER_COMMAND):
        made = REPLIES[name](rng)
        payload, raw, peer = made[:3]
        payload = physical(name, payload)
        inav = made[3] if len(made) > 3 else name in INAV
        for v2 in ([True] if cmd["id"] > 255 else [False, True]):
            frame = framed(cmd["id"], raw, 0x3E, v2)
            board = parsed(frame, inav)
            frames.append({
                "name": f"{name.lower()}_{'v2' if v2 else 'v1'}_{n}", "message": name, "id": cmd["id"], "direction": "response",
                "version": "v2" if v2 else "v1", "hex": frame.hex(), "payload": payload, "yamspy": peer(board),
            })


def request_frames(rng, name, cmd, frames):
    board, wire = yamspy()
    if name == "SET_RAW_RC":
        for n in range(FRAMES_PER_COMMAND):
            v = [rng.randint(885, 2115) for _ in range(rng.randint(4, 18))]
            board.send_RAW_RC(v)
            frames.append({"name": f"set_raw_rc_v1_{n}", "message": name, "id": cmd["id"], "direction": "request", "version": "v1",
                           "hex": wire.written.hex(), "payload": {"channels": [{"value": x} for x in v]}, "yamspy": []})
    elif name == "SET_MOTOR":
        for n in range(FRAMES_PER_COMMAND):
            v = [rng.randint(1000, 2000) for _ in range(8)]
            board.send_RAW_MOTORS(v)
            frames.append({"name": f"set_motor_v1_{n}", "message": name, "id": cmd["id"], "direction": "request", "version": "v1",
                           "hex": wire.written.hex(), "payload": {"motors": v}, "yamspy": []})
    else:
        board.send_RAW_msg(cmd["id"], [])
        frames.append({"name": f"{name.lower()}_request", "message": name, "id": cmd["id"], "direction": "request",
                       "version": "v2" if cmd["id"] > 255 else "v1", "hex": wire.written.hex(), "payload": {}, "yamspy": []})


def main() -> None:
    rng = random.Random(0x4D5350)
    frames: list[dict] = []
    for name, cmd in SPEC["commands"].items():
        if name in LEFT_OUT:
            continue
        if "request" in cmd or name in REPLIES:
            request_frames(rng, name, cmd, frames)
        if name in REPLIES:
            reply_frames(rng, name, cmd, frames)
    out = {
        "protocol": "msp",
        "source": {
            "generator": "scripts/msp_yamspy_vectors.py",
            "yamspy": version("yamspy"),
            "what": "requests written by YAMSPy (send_RAW_msg, send_RAW_RC, send_RAW_MOTORS); replies laid out from random values in Betaflight's or INAV's order, framed by YAMSPy's send_RAW_msg (v1) or with its _crc8_dvb_s2 (v2), direction set to '>', and read back by YAMSPy's receive_msg and process_recv_data",
            "payload": "the payload in the spec's shape, as protocol decode prints it (bytes as hex, texts as strings, bit members by name)",
            "yamspy": "[spec path, YAMSPy's value, scale]: YAMSPy's reading of the bytes; where the spec scales the field, YAMSPy's value in the spec's unit, within half the scale of the spec's physical value; elsewhere the spec's raw value times scale is YAMSPy's value (scale null: compared as they are, texts as hex)",
            "left_out": LEFT_OUT,
            "disagreements": [
                "MSP_BATTERY_STATE: YAMSPy 0.3.3 reads no legacy voltage byte after the capacity (Betaflight writes one), so its mAhDrawn, amperage, batteryState and voltage are read a byte early; only cell_count and capacity are compared",
                "MSP_ANALOG: YAMSPy overwrites the legacy 0.1 V voltage with the 0.01 V one; the legacy byte is not compared",
                "MSP2_INAV_ANALOG: YAMSPy reads the amperage unsigned, INAV writes it signed; the vectors hold non-negative amperages",
                "MSP2_INAV_STATUS and MSP2_INAV_AIR_SPEED: YAMSPy has no reader for them; their frames are YAMSPy-framed and CRC-checked only",
            ],
        },
        "frames": frames,
    }
    OUT.write_text(json.dumps(out, indent=1, ensure_ascii=False) + "\n")
    print(f"{len(frames)} frames -> {OUT.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
