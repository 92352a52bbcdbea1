"""Golden LX-16A packets from pylx16a, for every command of `specs/lx16a.toml`.

Writes `tests/vectors/lx16a_pylx16a.json`. pylx16a talks to a serial port (its class attribute
`LX16A._controller`); here that is a fake port that records the packets pylx16a writes and, to
every read command, answers as a servo would, with a packet of random values. So:

* every command packet is the bytes pylx16a writes for a random call of one of its methods
  (`move`, `move_start`, `move_stop`, `set_id`, `set_angle_offset`, `set_angle_limits`,
  `set_vin_limits`, `set_temp_limit`, `motor_mode`, `servo_mode`, `enable_torque`,
  `disable_torque`, `led_power_on`, `led_power_off`, `set_led_error_triggers`, and the `get_*`
  and `is_*` methods that poll the servo);
* every answer is read by pylx16a's `_read_packet` (which checks its checksum) and the value
  its method returns is the packet's recorded value, in the spec's units.

Run with pylx16a installed (the version is written into the file):

    python3 -m venv .venv && .venv/bin/pip install pylx16a==1.1.1
    .venv/bin/python scripts/lx16a_pylx16a_vectors.py
"""

from __future__ import annotations

import json
import random
from importlib.metadata import version
from pathlib import Path

from pylx16a.lx16a import LX16A

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "tests" / "vectors" / "lx16a_pylx16a.json"
ROUNDS = 3
PEER = f"pylx16a {version('pylx16a')}"

#: The spec's command names.
NAMES = {
    1: "SERVO_MOVE_TIME_WRITE", 2: "SERVO_MOVE_TIME_READ", 7: "SERVO_MOVE_TIME_WAIT_WRITE",
    8: "SERVO_MOVE_TIME_WAIT_READ", 11: "SERVO_MOVE_START", 12: "SERVO_MOVE_STOP",
    13: "SERVO_ID_WRITE", 14: "SERVO_ID_READ", 17: "SERVO_ANGLE_OFFSET_ADJUST",
    18: "SERVO_ANGLE_OFFSET_WRITE", 19: "SERVO_ANGLE_OFFSET_READ", 20: "SERVO_ANGLE_LIMIT_WRITE",
    21: "SERVO_ANGLE_LIMIT_READ", 22: "SERVO_VIN_LIMIT_WRITE", 23: "SERVO_VIN_LIMIT_READ",
    24: "SERVO_TEMP_MAX_LIMIT_WRITE", 25: "SERVO_TEMP_MAX_LIMIT_READ", 26: "SERVO_TEMP_READ",
    27: "SERVO_VIN_READ", 28: "SERVO_POS_READ", 29: "SERVO_OR_MOTOR_MODE_WRITE",
    30: "SERVO_OR_MOTOR_MODE_READ", 31: "SERVO_LOAD_OR_UNLOAD_WRITE",
    32: "SERVO_LOAD_OR_UNLOAD_READ", 33: "SERVO_LED_CTRL_WRITE", 34: "SERVO_LED_CTRL_READ",
    35: "SERVO_LED_ERROR_WRITE", 36: "SERVO_LED_ERROR_READ",
}

#: The values a servo answers each read command with: random, of the protocol's ranges.
ANSWERS = {
    2: lambda r: [*le(r.randrange(1001)), *le(r.randrange(30001))],
    8: lambda r: [*le(r.randrange(1001)), *le(r.randrange(30001))],
    14: lambda r: [r.randrange(254)],
    19: lambda r: [r.randint(-125, 125) & 0xFF],
    21: lambda r: [*le(r.randrange(500)), *le(r.randrange(500, 1001))],
    23: lambda r: [*le(r.randrange(4500, 8000)), *le(r.randrange(8000, 12001))],
    25: lambda r: [r.randrange(50, 101)],
    26: lambda r: [r.randrange(10, 90)],
    27: lambda r: [*le(r.randrange(4500, 12001))],
    # pylx16a reads the position as unsigned: the servo's positions within its range.
    28: lambda r: [*le(r.randrange(1001))],
    30: lambda r: [r.randrange(2), 0, *le(r.randint(-1000, 1000) & 0xFFFF)],
    32: lambda r: [r.randrange(2)],
    34: lambda r: [r.randrange(2)],
    36: lambda r: [r.randrange(8)],
}


def le(n: int) -> tuple[int, int]:
    return n & 0xFF, n >> 8


def checksum(body: list[int]) -> int:
    return ~sum(body) & 0xFF


class FakeServoPort:
    """The serial port pylx16a writes to: it records each packet and answers read commands."""

    def __init__(self, rng: random.Random) -> None:
        self.rng = rng
        self.timeout = 0.02
        self.write_timeout = 0.02
        self.sent: list[bytes] = []
        self.answers: list[bytes] = []
        self.incoming = bytearray()

    def write(self, packet: bytes) -> int:
        self.sent.append(bytes(packet))
        servo, command = packet[2], packet[4]
        if command in ANSWERS:
            params = ANSWERS[command](self.rng)
            body = [servo, len(params) + 3, command, *params]
            answer = bytes([0x55, 0x55, *body, checksum(body)])
            self.answers.append(answer)
            self.incoming += answer
        return len(packet)

    def read(self, n: int) -> bytes:
        data = bytes(self.incoming[:n])
        del self.incoming[:n]
        return data

    def flushInput(self) -> None:
        self.incoming.clear()

    reset_input_buffer = flushInput

    def reset_output_buffer(self) -> None:
        pass

    def close(self) -> None:
        pass


def request(packet: bytes, fields: dict, scales: dict, call: str) -> dict:
    command = packet[4]
    return {
        "name": "",
        "direction": "request",
        "command": NAMES[command],
        "header": {"id": packet[2]},
        "payload": fields,
        "scales": scales,
        "hex": packet.hex(),
        "provenance": f"{PEER}: {call}, written to a fake port",
    }


def response(packet: bytes, fields: dict, scales: dict, call: str) -> dict:
    return {
        **request(packet, fields, scales, call),
        "direction": "response",
        "provenance": f"{PEER}: the answer to {call}, read by _read_packet from a fake port",
    }


ANGLE = {"angle": 0.24}


def round_of(rng: random.Random, port: FakeServoPort) -> list[dict]:
    out: list[dict] = []
    # The constructor polls the servo: every read command pylx16a has, but the temperature,
    # voltage and move readers, which are called below.
    servo_id = rng.randrange(254)
    servo = LX16A(servo_id, disable_torque=rng.random() < 0.5)

    def last() -> bytes:
        return port.sent[-1]

    def write(call: str, fn, *args, fields: dict, scales: dict | None = None):
        before = len(port.sent)
        fn(*args)
        assert len(port.sent) == before + 1, call
        out.append(request(last(), fields, scales or {}, call))

    def read(call: str, fn, fields_of, scales: dict | None = None):
        before, answers = len(port.sent), len(port.answers)
        value = fn()
        assert len(port.sent) == before + 1 and len(port.answers) == answers + 1, call
        out.append(request(last(), {}, {}, call))
        out.append(response(port.answers[-1], fields_of(value), scales or {}, call))

    # A state in which pylx16a moves the servo: torque on, servo mode, the whole range.
    write("enable_torque()", servo.enable_torque, fields={"load": True})
    write("servo_mode()", servo.servo_mode, fields={"mode": "SERVO", "speed": 0})
    write("set_angle_limits(0, 240)", servo.set_angle_limits, 0, 240,
          fields={"min_angle": 0, "max_angle": 240.0}, scales={"min_angle": 0.24, "max_angle": 0.24})
    angle, time = rng.randrange(1001), rng.randrange(30001)
    for wait in (False, True):
        write(f"move({angle * 0.24}, {time}, wait={wait})", lambda: servo.move(angle * 0.24, time, wait=wait),
              fields={"angle": angle * 0.24, "time": time}, scales=ANGLE)
    write("move_start()", servo.move_start, fields={})
    read("get_last_instant_move_hw()", servo.get_last_instant_move_hw,
         lambda v: {"angle": v[0], "time": v[1]}, ANGLE)
    read("get_last_delayed_move_hw()", servo.get_last_delayed_move_hw,
         lambda v: {"angle": v[0], "time": v[1]}, ANGLE)
    read("get_physical_angle()", servo.get_physical_angle, lambda v: {"pos": v}, {"pos": 0.24})
    read("get_temp()", servo.get_temp, lambda v: {"temp": v})
    read("get_vin()", servo.get_vin, lambda v: {"vin": v})
    read("get_id(poll_hardware=True)", lambda: servo.get_id(True), lambda v: {"id": v})
    read("get_angle_offset(poll_hardware=True)", lambda: servo.get_angle_offset(True),
         lambda v: {"offset": v}, {"offset": 0.24})
    read("get_angle_limits(poll_hardware=True)", lambda: servo.get_angle_limits(True),
         lambda v: {"min_angle": v[0], "max_angle": v[1]}, {"min_angle": 0.24, "max_angle": 0.24})
    read("get_vin_limits(poll_hardware=True)", lambda: servo.get_vin_limits(True),
         lambda v: {"min_vin": v[0], "max_vin": v[1]})
    read("get_temp_limit(poll_hardware=True)", lambda: servo.get_temp_limit(True),
         lambda v: {"temp_max": v})
    read("is_torque_enabled(poll_hardware=True)", lambda: servo.is_torque_enabled(True),
         lambda v: {"load": v})
    # pylx16a answers `is_led_power_on`: the spec's field is the wire's "off" flag.
    read("is_led_power_on(poll_hardware=True)", lambda: servo.is_led_power_on(True),
         lambda v: {"led_off": not v})
    read("get_led_error_triggers(poll_hardware=True)", lambda: servo.get_led_error_triggers(True),
         lambda v: {"over_temperature": v[0], "over_voltage": v[1], "locked_rotor": v[2],
                    "faults_reserved": 0})
    # The mode read: pylx16a's two readers of command 30, mode and speed, each one packet.
    read("is_motor_mode(poll_hardware=True)", lambda: servo.is_motor_mode(True),
         lambda v: mode_fields(v, port.answers[-1]))

    # move_stop sends the stop, then reads the position back (SERVO_POS_READ, recorded above).
    before = len(port.sent)
    servo.move_stop()
    assert len(port.sent) == before + 2 and port.sent[-1][4] == 28
    out.append(request(port.sent[-2], {}, {}, "move_stop()"))
    new_id = rng.randrange(254)
    write(f"set_id({new_id})", servo.set_id, new_id, fields={"id": new_id})
    offset = rng.randint(-30, 30)
    before = len(port.sent)
    servo.set_angle_offset(offset, permanent=True)
    assert len(port.sent) == before + 2
    raw_offset = round(offset * 25 / 6)
    out.append(request(port.sent[-2], {"offset": raw_offset * 0.24}, {"offset": 0.24},
                       f"set_angle_offset({offset}, permanent=True)"))
    out.append(request(port.sent[-1], {}, {}, f"set_angle_offset({offset}, permanent=True)"))
    low, high = sorted(rng.sample(range(1001), 2))
    write(f"set_angle_limits({low * 0.24}, {high * 0.24})", servo.set_angle_limits, low * 0.24, high * 0.24,
          fields={"min_angle": low * 0.24, "max_angle": high * 0.24},
          scales={"min_angle": 0.24, "max_angle": 0.24})
    low, high = sorted(rng.sample(range(4500, 12001), 2))
    write(f"set_vin_limits({low}, {high})", servo.set_vin_limits, low, high,
          fields={"min_vin": low, "max_vin": high})
    limit = rng.randrange(50, 101)
    write(f"set_temp_limit({limit})", servo.set_temp_limit, limit, fields={"temp_max": limit})
    write("enable_torque()", servo.enable_torque, fields={"load": True})
    speed = rng.randint(-1000, 1000)
    write(f"motor_mode({speed})", servo.motor_mode, speed, fields={"mode": "MOTOR", "speed": speed})
    write("servo_mode()", servo.servo_mode, fields={"mode": "SERVO", "speed": 0})
    write("disable_torque()", servo.disable_torque, fields={"load": False})
    write("led_power_off()", servo.led_power_off, fields={"led_off": True})
    write("led_power_on()", servo.led_power_on, fields={"led_off": False})
    bits = [rng.random() < 0.5 for _ in range(3)]
    write(f"set_led_error_triggers{tuple(bits)}", servo.set_led_error_triggers, *bits,
          fields={"over_temperature": bits[0], "over_voltage": bits[1], "locked_rotor": bits[2],
                  "faults_reserved": 0})
    return out


def mode_fields(motor: bool, answer: bytes) -> dict:
    """SERVO_OR_MOTOR_MODE_READ's values: the mode as pylx16a's `is_motor_mode` returns it, and
    the speed as its `get_motor_speed` computes it from the same bytes (a second read of
    command 30, which this call does not make)."""
    params = answer[5:-1]
    speed = params[2] + params[3] * 256
    return {"mode": "MOTOR" if motor else "SERVO", "speed": speed - 65536 if speed > 32767 else speed}


def main() -> None:
    rng = random.Random(0x4C58_3136)
    port = FakeServoPort(rng)
    LX16A._controller = port
    frames = []
    for r in range(ROUNDS):
        for i, f in enumerate(round_of(rng, port)):
            f["name"] = f"{f['command'].lower()}_{f['direction']}_{r}_{i}"
            frames.append(f)
    doc = {
        "protocol": "lx16a",
        "source": {
            "generator": "scripts/lx16a_pylx16a_vectors.py",
            "pylx16a": version("pylx16a"),
            "what": "the packets pylx16a writes to a fake port for random calls of its methods, and the "
            "answers to its read commands, random values of the protocol's ranges that pylx16a reads back",
            "payload": "the values pylx16a takes or returns, under the spec's names: angles in degrees "
            "(0.24° a unit), the LED's state as the wire's off flag",
        },
        "frames": frames,
    }
    OUT.write_text(json.dumps(doc, indent=1) + "\n")
    print(f"{len(frames)} frames -> {OUT.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
