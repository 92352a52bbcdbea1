"""Golden DroneCAN frames written and decoded by pydronecan, for every command of `specs/dronecan.toml`.

Writes `tests/vectors/dronecan_pydronecan.json`: for each command, random messages (random
field values over each DSDL field's whole range), serialized and framed by pydronecan's own
transport (`dronecan.transport.Transfer(...).to_frames()`, which builds the 29-bit identifier
and the tail byte) with a random priority, source node and transfer id, then decoded again by
pydronecan (`Transfer.from_frames`, which checks the tail byte). Each frame records the CAN id,
the data, pydronecan's header values and its decoded message in the spec's shape (bit members
as the spec names them, enumerations by their spec names, float16 values as the floats they
are), so a test can check a decoder against them.

Run with pydronecan installed (the version is written into the file):

    python3 -m venv .venv && .venv/bin/pip install dronecan==1.0.27
    .venv/bin/python scripts/dronecan_pydronecan_vectors.py

Every DSDL field of a covered message must map to a spec field (a name that drifts from the
DSDL's fails here), and every command of the spec must have its DSDL type.
"""

from __future__ import annotations

import json
import random
import tomllib
from importlib.metadata import version
from pathlib import Path

import dronecan
from dronecan.transport import Transfer

ROOT = Path(__file__).resolve().parents[1]
SPEC = tomllib.loads((ROOT / "specs" / "dronecan.toml").read_text())
OUT = ROOT / "tests" / "vectors" / "dronecan_pydronecan.json"
FRAMES_PER_COMMAND = 6

#: The DSDL type of each command of the spec.
TYPES = {
    "GLOBAL_TIME_SYNC": "uavcan.protocol.GlobalTimeSync",
    "NODE_STATUS": "uavcan.protocol.NodeStatus",
    "TRUE_AIRSPEED": "uavcan.equipment.air_data.TrueAirspeed",
    "INDICATED_AIRSPEED": "uavcan.equipment.air_data.IndicatedAirspeed",
    "ANGLE_OF_ATTACK": "uavcan.equipment.air_data.AngleOfAttack",
    "SIDESLIP": "uavcan.equipment.air_data.Sideslip",
    "STATIC_PRESSURE": "uavcan.equipment.air_data.StaticPressure",
    "STATIC_TEMPERATURE": "uavcan.equipment.air_data.StaticTemperature",
    "HARDPOINT_COMMAND": "uavcan.equipment.hardpoint.Command",
    "HARDPOINT_STATUS": "uavcan.equipment.hardpoint.Status",
    "BEEP_COMMAND": "uavcan.equipment.indication.BeepCommand",
    "PRIMARY_POWER_SUPPLY_STATUS": "uavcan.equipment.power.PrimaryPowerSupplyStatus",
    "CIRCUIT_STATUS": "uavcan.equipment.power.CircuitStatus",
    "ARMING_STATUS": "uavcan.equipment.safety.ArmingStatus",
    "DEVICE_TEMPERATURE": "uavcan.equipment.device.Temperature",
}

#: DSDL integer fields the spec types with an enumeration, by (type, field).
ENUMS = {
    ("uavcan.protocol.NodeStatus", "health"): "Health",
    ("uavcan.protocol.NodeStatus", "mode"): "Mode",
    ("uavcan.equipment.safety.ArmingStatus", "status"): "ArmingState",
}

#: DSDL flag words the spec splits into one member per documented bit, by (type, field): the
#: members from bit 0 up, and the name of the member that keeps the bits above them.
FLAGS = {
    ("uavcan.equipment.power.CircuitStatus", "error_flags"): (
        [
            "error_flag_overvoltage",
            "error_flag_undervoltage",
            "error_flag_overcurrent",
            "error_flag_undercurrent",
        ],
        "error_flags_reserved",
    ),
    ("uavcan.equipment.device.Temperature", "error_flags"): (
        ["error_flag_overheating", "error_flag_overcooling"],
        "error_flags_reserved",
    ),
}

#: Members of the spec that no DSDL field names: the padding bit after the last field of a
#: message whose length is not a whole number of bytes (pydronecan writes it as zero).
PADDING = {"uavcan.equipment.power.PrimaryPowerSupplyStatus": {"padding": False}}


def dsdl_type(full_name: str):
    """The pydronecan class of a DSDL message."""
    obj = dronecan
    for part in full_name.split("."):
        obj = getattr(obj, part)
    return obj


def random_value(ftype, rng: random.Random):
    """A random value over the whole range of a DSDL primitive type."""
    name = str(ftype)
    bits = ftype.bitlen
    if "float" in name:
        # Finite values that the type holds (float16 tops out at 65504).
        limit = 60000.0 if bits == 16 else 1.0e6
        return rng.uniform(-limit, limit) * rng.choice([1.0, 1e-3, 1e-2])
    if name.endswith("bool"):
        return rng.random() < 0.5
    return rng.randrange(0, 1 << bits)


def spec_value(type_name: str, field: str, value):
    """pydronecan's value of a DSDL field as the spec's fields: a dict of spec name -> value."""
    if (type_name, field) in FLAGS:
        members, reserved = FLAGS[(type_name, field)]
        out = {m: bool((value >> i) & 1) for i, m in enumerate(members)}
        out[reserved] = value >> len(members)
        return out
    if (type_name, field) in ENUMS:
        values = SPEC["enums"][ENUMS[(type_name, field)]]["values"]
        names = {v: k for k, v in values.items()}
        return {field: names.get(value, value)}
    return {field: value}


def spec_fields(struct_name: str) -> set[str]:
    """Every field of a spec struct as a decoder shows it: bit members flat, a kept reserved run."""
    out = set()
    for f in SPEC["structs"][struct_name]["fields"]:
        if "bits" in f:
            out.update(b["name"] for b in f["bits"])
            if sum(b["bits"] for b in f["bits"]) < 8 and f.get("reserved", "keep") == "keep":
                out.add(f"{f['name']}_reserved")
        else:
            out.add(f["name"])
    return out


def frame_of(command: str, rng: random.Random) -> dict:
    """One random message of `command`, framed and decoded by pydronecan."""
    type_name = TYPES[command]
    cls = dsdl_type(type_name)
    dtype = dronecan.get_dronecan_data_type(cls())
    values = {f.name: random_value(f.type, rng) for f in dtype.fields}
    sent = Transfer(
        transfer_id=rng.randrange(32),
        source_node_id=rng.randrange(1, 128),
        payload=cls(**values),
        transfer_priority=rng.randrange(32),
    )
    frames = sent.to_frames()
    assert len(frames) == 1, f"{type_name} is not a single-frame transfer"
    received = Transfer()
    received.from_frames(frames)
    message = received.payload
    payload = dict(PADDING.get(type_name, {}))
    for f in dtype.fields:
        value = getattr(message, f.name)
        payload.update(spec_value(type_name, f.name, value))
    struct = SPEC["commands"][command]["payload"]
    assert set(payload) == spec_fields(struct), f"{command}: {sorted(payload)} vs the spec"
    return {
        "name": f"{command} #{rng.randrange(1 << 16):04x}",
        "command": command,
        "dsdl": type_name,
        "can_id": frames[0].message_id,
        "extended": True,
        "data": bytes(frames[0].bytes).hex(),
        "header": {
            "source_node_id": received.source_node_id,
            "priority": received.transfer_priority,
            "transfer_id": received.transfer_id,
            # `from_frames` accepts a single frame only with these three tail bits.
            "toggle": False,
            "end_of_transfer": True,
            "start_of_transfer": True,
        },
        "payload": payload,
    }


def main() -> None:
    rng = random.Random(0xD20CA)
    assert set(TYPES) == set(SPEC["commands"]), "every command of the spec has its DSDL type"
    for command, type_name in TYPES.items():
        dtid = dronecan.get_dronecan_data_type(dsdl_type(type_name)()).default_dtid
        assert SPEC["commands"][command]["id"] == dtid, f"{command}: data type id {dtid}"
    frames = [frame_of(c, rng) for c in TYPES for _ in range(FRAMES_PER_COMMAND)]
    out = {
        "protocol": "dronecan",
        "source": (
            f"pydronecan (PyPI dronecan {version('dronecan')}): random messages of every command "
            "of specs/dronecan.toml, serialized and framed by dronecan.transport.Transfer.to_frames "
            "(29-bit id and tail byte) and decoded by Transfer.from_frames; written by "
            "scripts/dronecan_pydronecan_vectors.py"
        ),
        "frames": frames,
    }
    OUT.write_text(json.dumps(out, indent=1) + "\n")
    print(f"{len(frames)} frames -> {OUT.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
