"""Golden VESC packets written and decoded by pyvesc, for every command of `specs/vesc.toml`.

Writes `tests/vectors/vesc_pyvesc.json`: random messages of every command, in the direction the
command carries data (a host's command, a VESC's answer; COMM_FW_VERSION and COMM_GET_VALUES in
both, their requests being the bare command id). Each frame records the values pyvesc decodes
from the packet, under the spec's names and in the spec's shape, with the scale of every scaled
field, so a test can check a decoder against them within each scale's resolution.

Where the frames come from, per message (each frame's `provenance` says which):

* pyvesc's own messages (`SetDutyCycle`, `SetCurrent`, `SetCurrentBrake`, `SetRPM`,
  `SetPosition`, and `encode_request(GetValues)`), encoded by `pyvesc.encode` and decoded by
  `pyvesc.decode`: their layouts are the firmware's.
* Messages pyvesc 1.0.5 does not have, or has in a layout older than the firmware's
  (COMM_GET_VALUES's answer is the firmware-2 layout there, and id 10 is a firmware-2 command),
  declared here as pyvesc messages (its `VESCMessage` metaclass: an id and `(name, struct
  format, scalar)` fields) from the firmware's comm/commands.c, then encoded and decoded by
  pyvesc as its own: pyvesc packs, scales, frames and checks them.
* COMM_FW_VERSION's answer holds two NUL-terminated texts, which pyvesc's messages (at most one
  text, without a NUL) cannot describe: its payload is laid out here from comm/commands.c and
  framed by pyvesc's packet codec (`pyvesc.packet.codec.frame`), which writes the length, the CRC
  and the end byte, and unframed by it again.

Run with pyvesc installed (the version is written into the file):

    python3 -m venv .venv && .venv/bin/pip install pyvesc==1.0.5
    .venv/bin/python scripts/vesc_pyvesc_vectors.py
"""

from __future__ import annotations

import json
import random
import struct
from importlib.metadata import version
from pathlib import Path

import pyvesc
from pyvesc.messages.base import VESCMessage
from pyvesc.packet import codec

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "tests" / "vectors" / "vesc_pyvesc.json"
FRAMES_PER_MESSAGE = 6

# pyvesc 1.0.5 registers its firmware-2 `GetValues` (id 4) and `SetRotorPositionMode` (id 10,
# COMM_SET_HANDBRAKE in the firmware since); the firmware's messages of those ids replace them.
for stale in (4, 10):
    VESCMessage._msg_registry.pop(stale)


class Values(metaclass=VESCMessage):
    """COMM_GET_VALUES's answer, every field of the firmware's mask in order."""

    id = 4
    fields = [
        ("temp_fet", "h", 10),
        ("temp_motor", "h", 10),
        ("avg_motor_current", "i", 100),
        ("avg_input_current", "i", 100),
        ("avg_id", "i", 100),
        ("avg_iq", "i", 100),
        ("duty_cycle_now", "h", 1000),
        ("rpm", "i", 1),
        ("v_in", "h", 10),
        ("amp_hours", "i", 10000),
        ("amp_hours_charged", "i", 10000),
        ("watt_hours", "i", 10000),
        ("watt_hours_charged", "i", 10000),
        ("tachometer", "i", 1),
        ("tachometer_abs", "i", 1),
        ("fault", "B", 1),
        ("pid_pos_now", "i", 1000000),
        ("controller_id", "B", 1),
        ("temp_mos1", "h", 10),
        ("temp_mos2", "h", 10),
        ("temp_mos3", "h", 10),
        ("avg_vd", "i", 1000),
        ("avg_vq", "i", 1000),
        ("status", "B", 1),
    ]


class SetHandbrake(metaclass=VESCMessage):
    id = 10
    fields = [("current", "i", 1000)]


class SetServoPos(metaclass=VESCMessage):
    id = 12
    fields = [("pos", "h", 1000)]


class Alive(metaclass=VESCMessage):
    id = 30
    fields = []


class FwVersion(metaclass=VESCMessage):
    """COMM_FW_VERSION, as a request (the bare id)."""

    id = 0
    fields = []


FAULTS = [
    "FAULT_CODE_NONE", "FAULT_CODE_OVER_VOLTAGE", "FAULT_CODE_UNDER_VOLTAGE", "FAULT_CODE_DRV",
    "FAULT_CODE_ABS_OVER_CURRENT", "FAULT_CODE_OVER_TEMP_FET", "FAULT_CODE_OVER_TEMP_MOTOR",
    "FAULT_CODE_GATE_DRIVER_OVER_VOLTAGE", "FAULT_CODE_GATE_DRIVER_UNDER_VOLTAGE",
    "FAULT_CODE_MCU_UNDER_VOLTAGE", "FAULT_CODE_BOOTING_FROM_WATCHDOG_RESET",
    "FAULT_CODE_ENCODER_SPI", "FAULT_CODE_ENCODER_SINCOS_BELOW_MIN_AMPLITUDE",
    "FAULT_CODE_ENCODER_SINCOS_ABOVE_MAX_AMPLITUDE", "FAULT_CODE_FLASH_CORRUPTION",
    "FAULT_CODE_HIGH_OFFSET_CURRENT_SENSOR_1", "FAULT_CODE_HIGH_OFFSET_CURRENT_SENSOR_2",
    "FAULT_CODE_HIGH_OFFSET_CURRENT_SENSOR_3", "FAULT_CODE_UNBALANCED_CURRENTS", "FAULT_CODE_BRK",
    "FAULT_CODE_RESOLVER_LOT", "FAULT_CODE_RESOLVER_DOS", "FAULT_CODE_RESOLVER_LOS",
    "FAULT_CODE_FLASH_CORRUPTION_APP_CFG", "FAULT_CODE_FLASH_CORRUPTION_MC_CFG",
    "FAULT_CODE_ENCODER_NO_MAGNET", "FAULT_CODE_ENCODER_MAGNET_TOO_STRONG",
    "FAULT_CODE_PHASE_FILTER", "FAULT_CODE_ENCODER_FAULT", "FAULT_CODE_LV_OUTPUT_FAULT",
]

I16 = (-(1 << 15), (1 << 15) - 1)
I32 = (-(1 << 31), (1 << 31) - 1)


def raw(rng: random.Random, fmt: str) -> int:
    lo, hi = {"h": I16, "i": I32}[fmt]
    # Mostly values of the size a controller reports, sometimes the type's extremes.
    pick = rng.random()
    if pick < 0.1:
        return lo
    if pick < 0.2:
        return hi
    return rng.randint(max(lo, -200_000), min(hi, 200_000))


def record(name, direction, command, payload, scales, packet, provenance):
    return {
        "name": name,
        "direction": direction,
        "command": command,
        "payload": payload,
        "scales": scales,
        "hex": packet.hex(),
        "provenance": provenance,
    }


def decoded(packet: bytes):
    msg, consumed = pyvesc.decode(packet)
    assert msg is not None and consumed == len(packet), packet.hex()
    return msg


def native(rng: random.Random, i: int) -> list[dict]:
    """pyvesc's own messages, whose layouts are the firmware's."""
    out = []
    # pyvesc 1.0.5 carries the duty cycle and the currents as the integers on the wire (duty
    # times 100000, milliamperes); the spec's physical value is that integer times its scale.
    for cls, command, field, spec_field, scale in [
        (pyvesc.SetDutyCycle, "COMM_SET_DUTY", "duty_cycle", "duty", 1e-5),
        (pyvesc.SetCurrent, "COMM_SET_CURRENT", "current", "current", 1e-3),
        (pyvesc.SetCurrentBrake, "COMM_SET_CURRENT_BRAKE", "current_brake", "current", 1e-3),
        (pyvesc.SetRPM, "COMM_SET_RPM", "rpm", "rpm", None),
    ]:
        packet = pyvesc.encode(cls(raw(rng, "i")))
        value = getattr(decoded(packet), field)
        payload = {spec_field: value * scale if scale else value}
        scales = {spec_field: scale} if scale else {}
        out.append(record(f"{command.lower()}_{i}", "request", command, payload, scales, packet,
                          f"pyvesc {version('pyvesc')}: encode({cls.__name__}), decode"))
    pos = raw(rng, "i") / 1e6
    packet = pyvesc.encode(pyvesc.SetPosition(pos))
    out.append(record(f"comm_set_pos_{i}", "request", "COMM_SET_POS",
                      {"pos": decoded(packet).pos}, {"pos": 1e-6}, packet,
                      f"pyvesc {version('pyvesc')}: encode(SetPosition), decode"))
    return out


def declared(rng: random.Random, i: int) -> list[dict]:
    """Firmware messages declared here as pyvesc messages, packed and decoded by pyvesc."""
    out = []
    how = f"pyvesc {version('pyvesc')}: a VESCMessage declared from the firmware's comm/commands.c, encode, decode"
    packet = pyvesc.encode(SetHandbrake(raw(rng, "i") / 1000))
    out.append(record(f"comm_set_handbrake_{i}", "request", "COMM_SET_HANDBRAKE",
                      {"current": decoded(packet).current}, {"current": 1e-3}, packet, how))
    packet = pyvesc.encode(SetServoPos(rng.randint(0, 1000) / 1000))
    out.append(record(f"comm_set_servo_pos_{i}", "request", "COMM_SET_SERVO_POS",
                      {"pos": decoded(packet).pos}, {"pos": 1e-3}, packet, how))
    packet = pyvesc.encode(Alive())
    out.append(record(f"comm_alive_{i}", "request", "COMM_ALIVE", {}, {}, packet, how))
    for cls, command in [(FwVersion, "COMM_FW_VERSION"), (pyvesc.GetValues, "COMM_GET_VALUES")]:
        packet = pyvesc.encode_request(cls)
        out.append(record(f"{command.lower()}_request_{i}", "request", command, {}, {}, packet,
                          f"pyvesc {version('pyvesc')}: encode_request"))
    out.append(values(rng, i, how))
    return out


def values(rng: random.Random, i: int, how: str) -> dict:
    args = []
    for name, fmt, scalar in Values.fields:
        if fmt == "B":
            n = rng.randrange(len(FAULTS)) if name == "fault" else rng.randrange(256 if name == "controller_id" else 4)
            args.append(n)
        else:
            args.append(raw(rng, fmt) / scalar)
    packet = pyvesc.encode(Values(*args))
    msg = decoded(packet)
    payload, scales = {}, {}
    for name, fmt, scalar in Values.fields:
        value = getattr(msg, name)
        if name == "fault":
            payload[name] = FAULTS[int(value)]
        elif name == "status":
            # The status byte's bit members are fields of the struct, as the spec's `bits` make them.
            payload["timeout"] = bool(int(value) & 1)
            payload["kill_switch"] = bool(int(value) & 2)
            payload["status_reserved"] = int(value) >> 2
        elif scalar == 1:
            payload[name] = int(value)
        else:
            payload[name] = value
            scales[name] = 1 / scalar
    return record(f"comm_get_values_{i}", "response", "COMM_GET_VALUES", payload, scales, packet, how)


def fw_version(rng: random.Random, i: int) -> dict:
    hw = rng.choice(["60", "75_300", "410", "STORMCORE_100D", "UBOX_SINGLE_100"])
    fw_name = rng.choice(["", "", "beta", "custom-build"])
    uuid = [rng.randrange(256) for _ in range(12)]
    values = {
        "fw_version_major": rng.choice([5, 6]),
        "fw_version_minor": rng.randrange(100),
        "hw_name": hw,
        "uuid": uuid,
        "pairing_done": rng.random() < 0.5,
        "fw_test_version_number": rng.choice([0, 0, rng.randrange(1, 40)]),
        "hw_type": 0,
        "custom_config_count": rng.randrange(3),
        "has_phase_filters": rng.random() < 0.5,
        "qml_ui_hw": rng.randrange(3),
        "qml_ui_app": rng.randrange(3),
        "nrf_flags": rng.randrange(4),
        "fw_name": fw_name,
    }
    payload = (
        bytes([0, values["fw_version_major"], values["fw_version_minor"]])
        + hw.encode() + b"\0" + bytes(uuid)
        + bytes([int(values["pairing_done"]), values["fw_test_version_number"], values["hw_type"],
                 values["custom_config_count"], int(values["has_phase_filters"]), values["qml_ui_hw"],
                 values["qml_ui_app"], values["nrf_flags"]])
        + fw_name.encode() + b"\0"
    )
    packet = codec.frame(payload)
    unframed, consumed = codec.unframe(packet)
    assert unframed == payload and consumed == len(packet)
    return record(f"comm_fw_version_{i}", "response", "COMM_FW_VERSION", values, {}, packet,
                  f"payload laid out from the firmware's comm/commands.c; framed and unframed by pyvesc "
                  f"{version('pyvesc')} (pyvesc.packet.codec)")


def main() -> None:
    rng = random.Random(0x56_45_53_43)
    frames = []
    for i in range(FRAMES_PER_MESSAGE):
        frames += native(rng, i)
        frames += declared(rng, i)
        frames.append(fw_version(rng, i))
    doc = {
        "protocol": "vesc",
        "source": {
            "generator": "scripts/vesc_pyvesc_vectors.py",
            "pyvesc": version("pyvesc"),
            "what": "random messages of every command of specs/vesc.toml in the directions that carry them; "
            "each frame's provenance says whether the message is pyvesc's own, declared from the firmware's "
            "comm/commands.c as a pyvesc message, or (COMM_FW_VERSION's answer) laid out from commands.c "
            "and framed by pyvesc's packet codec",
            "payload": "pyvesc's decoded values under the spec's names: scaled fields in physical units "
            "(pyvesc 1.0.5's SetDutyCycle, SetCurrent and SetCurrentBrake carry the wire integer, recorded "
            "times the spec's scale), the fault code by its mc_fault_code name, status bits as booleans",
            "scales": "the spec's scale of every scaled field: a decoder's value is within half of it",
        },
        "frames": frames,
    }
    OUT.write_text(json.dumps(doc, indent=1) + "\n")
    print(f"{len(frames)} frames -> {OUT.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
