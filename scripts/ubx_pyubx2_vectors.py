"""Golden UBX frames written and decoded by pyubx2, for every command of `specs/ubx.toml`.

Writes `tests/vectors/ubx_pyubx2.json`: for each command, random messages (random field values,
random group lengths) whose payload is laid out from pyubx2's own payload definitions, framed
by pyubx2 (`UBXMessage(..., payload=...).serialize()`) and decoded by pyubx2
(`UBXReader.parse`); CFG-VALSET, CFG-VALDEL and the CFG-VALGET poll are written by pyubx2's
`config_set`, `config_del` and `config_poll` from keys of its configuration database. Each
frame records pyubx2's decoded values under the spec's names and in the spec's shape (bit
members as booleans or integers, enumerations by their spec names, scaled fields in pyubx2's
scaled units), with the scale of every scaled field, so a test can check a decoder against
them within each scale's resolution.

Run with pyubx2 installed (the version is written into the file):

    python3 -m venv .venv && .venv/bin/pip install pyubx2==1.4.0
    .venv/bin/python scripts/ubx_pyubx2_vectors.py

The spec and pyubx2 are matched by name: a spec field is the snake_case of a pyubx2 field
(`hMSL` -> `h_msl`) unless `RENAMES` says otherwise, and every spec field must find its pyubx2
field, so a name that drifts from pyubx2's fails here rather than passing unchecked.
"""

from __future__ import annotations

import json
import random
import re
import struct
import tomllib
from pathlib import Path

import pyubx2
from pyubx2 import GET, POLL, SET, UBXMessage, UBXReader
from pyubx2.ubxtypes_configdb import UBX_CONFIG_DATABASE
from pyubx2.ubxtypes_get import UBX_PAYLOADS_GET
from pyubx2.ubxtypes_poll import UBX_PAYLOADS_POLL
from pyubx2.ubxtypes_set import UBX_PAYLOADS_SET

ROOT = Path(__file__).resolve().parents[1]
SPEC = tomllib.loads((ROOT / "specs" / "ubx.toml").read_text())
OUT = ROOT / "tests" / "vectors" / "ubx_pyubx2.json"
FRAMES_PER_COMMAND = 4

#: pyubx2 names whose snake_case is not the spec's (the u-blox names these follow).
RENAMES = {
    "iTOW": "itow",
    "second": "sec",
    "UARTmode": "uart_mode",
    "cnoThreshNumSVs": "cno_thresh_num_svs",
    "_HPlon": "lon_hp",
    "_HPlat": "lat_hp",
    "_HPheight": "height_hp",
    "_HPhMSL": "h_msl_hp",
    "_HPrelPosN": "rel_pos_hpn",
    "_HPrelPosE": "rel_pos_hpe",
    "_HPrelPosD": "rel_pos_hpd",
    "_HPrelPosLength": "rel_pos_hp_length",
}

#: Scales u-blox gives that pyubx2 leaves out (its value is the raw integer).
SCALES_BEYOND_PYUBX2 = {"mean_xhp": 0.1, "mean_yhp": 0.1, "mean_zhp": 0.1, "mean_acc": 0.1}

#: High-precision parts pyubx2 adds into their main field (its `lon` is `lon + lon_hp`): the
#: spec keeps both as on the wire, read here from the payload, and pyubx2's sum is recorded
#: for the test to check against the spec's two values.
COMBINED = {
    "lon": "lon_hp",
    "lat": "lat_hp",
    "height": "height_hp",
    "h_msl": "h_msl_hp",
    "rel_pos_n": "rel_pos_hpn",
    "rel_pos_e": "rel_pos_hpe",
    "rel_pos_d": "rel_pos_hpd",
    "rel_pos_length": "rel_pos_hp_length",
}
COMBINED_IN = {"NAV-HPPOSLLH", "NAV-RELPOSNED"}

#: Fields the F9 description names where pyubx2 has reserved bytes (RXM-RAWX's `version`, byte
#: 13): read from the payload, where pyubx2's frames hold 0.
FROM_PAYLOAD = {("RXM-RAWX", "version")}

#: The pyubx2 mode of each spec command: GET for what a receiver sends (and the CFG messages
#: whose GET and SET layouts are the same), SET for what only a host sends.
SET_ONLY = {"CFG_RST", "CFG_VALSET", "CFG_VALDEL"}

#: Fields pyubx2 reads to choose a payload definition: the value that selects the spec's.
FIXED = {"NAV-RELPOSNED": {"version": 1}}


def snake(name: str) -> str:
    if name in RENAMES:
        return RENAMES[name]
    s = re.sub(r"([a-z0-9])([A-Z])", r"\1_\2", name.lstrip("_"))
    s = re.sub(r"([A-Z]+)([A-Z][a-z])", r"\1_\2", s)
    return s.lower()


def pyubx2_names(defn: dict) -> dict:
    """Every field name of a pyubx2 definition (groups and bit members included), by the
    spec name it maps to."""
    out = {}
    for key, kind in defn.items():
        base = key.removesuffix("_bit")
        if isinstance(kind, tuple) and isinstance(kind[1], dict):
            if str(kind[0]).startswith("X"):
                out[snake(base)] = base
            out.update(pyubx2_names(kind[1]))
        else:
            out[snake(base)] = base
    return out


# ---- Random payloads, laid out by pyubx2's definitions ----


def size_of(kind: str) -> int:
    return int(kind[1:4])


def random_value(rng: random.Random, kind: str) -> bytes:
    size = size_of(kind)
    if kind[0] == "R":
        if size == 4:
            return struct.pack("<f", rng.uniform(-5e4, 5e4))
        # At most 14 significant digits: a JSON reader without exact float parsing (serde_json's
        # default) still reads the decimal back as the same double.
        return struct.pack("<d", round(rng.uniform(-3e7, 3e7), 6))
    if kind[0] == "C":
        text = bytes(rng.choice(b"ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789=.-") for _ in range(rng.randint(0, size)))
        return text.ljust(size, b"\0")
    return rng.getrandbits(8 * size).to_bytes(size, "little")


def random_bits(rng: random.Random, kind: str, members: dict) -> bytes:
    """A bit word: random named members, 0 in reserved runs and above the last member."""
    word, at = 0, 0
    for name, width in members.items():
        bits = size_of(width)
        if not name.startswith("reserved"):
            word |= rng.getrandbits(bits) << at
        at += bits
    return word.to_bytes(size_of(kind), "little")


def random_payload(rng: random.Random, defn: dict, fixed: dict) -> bytes:
    counts = {}
    for key, kind in defn.items():
        if isinstance(kind, tuple) and isinstance(kind[1], dict) and not str(kind[0]).startswith("X"):
            if isinstance(kind[0], int):
                counts[key] = kind[0]
            else:
                # At most 4: the spec's smallest group (MON-RF's RF blocks).
                counts[key] = rng.randint(0, 4)
    by_count_field = {kind[0]: counts[key] for key, kind in defn.items() if key in counts and isinstance(kind[0], str)}
    out = b""
    for key, kind in defn.items():
        if key in counts:
            for _ in range(counts[key]):
                out += random_payload(rng, kind[1], {})
        elif isinstance(kind, tuple) and isinstance(kind[1], dict):
            out += random_bits(rng, kind[0], kind[1])
        else:
            kind = kind[0] if isinstance(kind, tuple) else kind
            if key in by_count_field:
                out += by_count_field[key].to_bytes(size_of(kind), "little")
            elif key in fixed:
                out += fixed[key].to_bytes(size_of(kind), "little")
            elif key.startswith("reserved"):
                out += bytes(size_of(kind))
            elif kind == "CH":
                out += bytes(rng.choice(b"abcdefghij ANTSUPERV=") for _ in range(rng.randint(0, 40)))
            else:
                out += random_value(rng, kind)
    return out


# ---- pyubx2's decoded values in the spec's shape ----


class Expect:
    """Reads pyubx2's decoded message into the spec's JSON shape, recording scales."""

    def __init__(self, parsed, defn: dict, payload: bytes):
        self.parsed = parsed
        self.names = pyubx2_names(defn)
        self.payload = payload
        self.scales: dict[str, float] = {}
        self.sums: dict[str, list] = {}

    def attr(self, spec_name: str, suffix: str):
        py = self.names.get(spec_name)
        assert py is not None, f"{self.parsed.identity}: no pyubx2 field for `{spec_name}`"
        if py.startswith("reserved"):
            # pyubx2 reads no reserved bits (a reserved byte field of the same name may be an
            # attribute, 0); the payloads hold 0 there.
            return 0
        return getattr(self.parsed, py + suffix)

    def has(self, spec_name: str, suffix: str) -> bool:
        py = self.names.get(spec_name)
        return py is not None and hasattr(self.parsed, py + suffix)

    def struct(self, name: str, suffix: str = "", path: str = "") -> dict:
        out = {}
        for field in SPEC["structs"][name]["fields"]:
            if "pad" in field:
                continue
            fname, ftype = field["name"], field.get("type")
            here = f"{path}{fname}"
            if "bits" in field:
                for m in field["bits"]:
                    out[m["name"]] = member(m, self.attr(m["name"], suffix))
                if sum(m["bits"] for m in field["bits"]) < 8 * fixed_size(field):
                    # The bits above the last member, kept by the spec: 0 in these payloads.
                    out[f"{fname}_reserved"] = 0
            elif ftype in SPEC["structs"] and field.get("repeat"):
                out[fname] = self.group(ftype, suffix, f"{here}.")
            elif ftype in SPEC["structs"]:
                out[fname] = self.struct(ftype, suffix, f"{here}.")
            elif field.get("repeat") or "count" in field:
                items, i = [], 1
                while self.has(fname, f"{suffix}_{i:02d}"):
                    items.append(self.scalar(field, self.attr(fname, f"{suffix}_{i:02d}"), here))
                    i += 1
                out[fname] = items
            elif ftype == "bytes":
                tail = self.payload[len(self.payload) - self.tail_len(name, fname) :]
                if self.has(fname, suffix):
                    # INF's text: pyubx2's string is the payload's bytes.
                    assert self.attr(fname, suffix) == tail.decode("ascii")
                out[fname] = tail.hex()
            elif (self.parsed.identity, fname) in FROM_PAYLOAD:
                out[fname] = self.raw_at(name, fname)
            elif self.parsed.identity in COMBINED_IN and (fname in COMBINED or fname in COMBINED.values()):
                out[fname] = self.scalar(field, self.raw_at(name, fname), here)
                if fname in COMBINED:
                    self.sums[here] = [self.attr(fname, suffix), [here, COMBINED[fname]]]
            else:
                out[fname] = self.scalar(field, self.attr(fname, suffix), here)
        return out

    def raw_at(self, struct_name: str, field_name: str):
        """A field's value as the payload holds it, scaled as pyubx2 scales the others."""
        at = 0
        for f in SPEC["structs"][struct_name]["fields"]:
            if f.get("name") == field_name:
                fmt = {"u8": "<B", "i8": "<b", "i32": "<i"}[f["type"]]
                raw = struct.unpack_from(fmt, self.payload, at)[0]
                return round(raw * f["scale"], 12) if "scale" in f else raw
            at += fixed_size(f)
        raise KeyError(field_name)

    def tail_len(self, struct_name: str, field_name: str) -> int:
        head = sum(fixed_size(f) for f in SPEC["structs"][struct_name]["fields"] if f.get("name") != field_name)
        return len(self.payload) - head

    def group(self, elem: str, suffix: str, path: str) -> list:
        first = next(f for f in SPEC["structs"][elem]["fields"] if "name" in f)
        probe = first["bits"][0]["name"] if "bits" in first else first["name"]
        items, i = [], 1
        while self.has(probe, f"{suffix}_{i:02d}"):
            items.append(self.struct(elem, f"{suffix}_{i:02d}", path))
            i += 1
        return items

    def scalar(self, field: dict, value, path: str):
        ftype = field["type"]
        if isinstance(value, bytes) and ftype.startswith("char["):
            return value.rstrip(b"\0").decode("ascii")
        if isinstance(value, bytes):
            value = int.from_bytes(value, "little")
        if ftype in SPEC.get("enums", {}):
            return enum_name(ftype, value)
        if "scale" in field:
            self.scales[path] = field["scale"]
            if field["name"] in SCALES_BEYOND_PYUBX2:
                assert SCALES_BEYOND_PYUBX2[field["name"]] == field["scale"]
                return round(value * field["scale"], 12)
        if ftype == "f32":
            return f32_text(value)
        return value


def member(m: dict, value):
    if "type" in m:
        return enum_name(m["type"], value)
    return bool(value) if m["bits"] == 1 else value


def enum_name(enum: str, value: int):
    for name, v in SPEC["enums"][enum]["values"].items():
        if (v["value"] if isinstance(v, dict) else v) == value:
            return name
    return value


def f32_text(value: float) -> float:
    """The shortest decimal that reads back as the same `f32`, as the codec prints it."""
    bits = struct.pack("<f", value)
    for digits in range(1, 18):
        shortest = float(f"{value:.{digits}g}")
        if struct.pack("<f", shortest) == bits:
            return shortest
    return value


PRIMITIVE_SIZES = {"u8": 1, "i8": 1, "u16": 2, "i16": 2, "u32": 4, "i32": 4, "f32": 4, "f64": 8}


def fixed_size(field: dict) -> int:
    if "pad" in field:
        return field["pad"]
    ftype = field["type"]
    if ftype in SPEC.get("enums", {}):
        ftype = SPEC["enums"][ftype]["type"]
    if ftype in PRIMITIVE_SIZES:
        return PRIMITIVE_SIZES[ftype] * field.get("count", 1)
    raise ValueError(f"not a fixed-size field: {field}")


# ---- The frames ----


def frame_record(name: str, command: str, msg: UBXMessage, mode: int, payload_expect) -> dict:
    raw = msg.serialize()
    parsed = UBXReader.parse(raw, msgmode=mode, validate=1)
    assert parsed.identity == command.replace("_", "-"), (parsed.identity, command)
    payload = raw[6:-2]
    expect = payload_expect(parsed, payload)
    return {
        "name": name,
        "message": command,
        "pyubx2_mode": {GET: "GET", SET: "SET", POLL: "POLL"}[mode],
        "hex": raw.hex(),
        "payload": expect[0],
        "scales": expect[1],
        **({"pyubx2_sums": expect[2]} if len(expect) > 2 and expect[2] else {}),
    }


def by_definition(command: str, defn: dict):
    def read(parsed, payload):
        e = Expect(parsed, defn, payload)
        return e.struct(SPEC["commands"][command]["payload"]), e.scales, e.sums

    return read


def cfg_msg(parsed, payload):
    rates = [parsed.rateUART1, parsed.rateUART2, parsed.rateUSB, parsed.rateSPI, parsed.reserved]
    return {"msg_class": parsed.msgClass, "msg_id": parsed.msgID, "rate": parsed.rateDDC, "ports": {"rate": rates}}, {}


def cfg_prt_poll(parsed, payload):
    return {"port_id": parsed.portID, "settings": None}, {}


def cfg_prt(defn):
    def read(parsed, payload):
        e = Expect(parsed, defn, payload)
        return {"port_id": parsed.portID, "settings": e.struct("CfgPrtSettings")}, e.scales

    return read


def cfg_cfg(parsed, payload):
    """pyubx2 keeps CFG-CFG's masks whole; the spec names their bits as u-blox does."""
    out = {}
    (mask_field,) = SPEC["structs"]["CfgCfgMask"]["fields"]
    for spec_name, py in [("clear_mask", "clearMask"), ("save_mask", "saveMask"), ("load_mask", "loadMask")]:
        word, at, members = int.from_bytes(getattr(parsed, py), "little"), 0, {}
        for m in mask_field["bits"]:
            members[m["name"]] = member(m, (word >> at) & ((1 << m["bits"]) - 1))
            at += m["bits"]
        members["mask_reserved"] = word >> at
        out[spec_name] = members
    device = {"dev_bbr": "devBBR", "dev_flash": "devFlash", "dev_eeprom": "devEEPROM", "reserved1": "reserved1", "dev_spi_flash": "devSpiFlash"}
    (dev,) = SPEC["structs"]["CfgCfgDevices"]["fields"]
    out["devices"] = {m["name"]: member(m, getattr(parsed, device[m["name"]], 0)) for m in dev["bits"]}
    out["devices"]["device_mask_reserved"] = 0
    return out, {}


def config_keys(rng: random.Random, n: int) -> list[tuple[str, int, str]]:
    """`n` keys of pyubx2's configuration database: name, key id, value type."""
    names = sorted(UBX_CONFIG_DATABASE)
    return [(k, *UBX_CONFIG_DATABASE[k]) for k in rng.sample(names, n)]


def config_value(rng: random.Random, kind: str):
    if kind[0] == "R":
        return round(rng.uniform(-1000, 1000), 9) if size_of(kind) == 8 else f32_text(rng.uniform(-1000, 1000))
    if kind == "L":
        return rng.randint(0, 1)
    bits = 8 * size_of(kind) if kind[0] != "L" else 1
    if kind[0] == "I":
        return rng.getrandbits(bits) - (1 << (bits - 1))
    if kind[0] == "X":
        return rng.getrandbits(bits).to_bytes(size_of(kind), "little")
    return rng.getrandbits(bits)


def config_frames(rng: random.Random, i: int) -> list[dict]:
    def header(parsed, payload, names):
        return {k: getattr(parsed, v) for k, v in names.items()}

    def valset(parsed, payload):
        bits = {"ram": bool(parsed.ram), "bbr": bool(parsed.bbr), "flash": bool(parsed.flash), "layers_reserved": payload[1] >> 3}
        bits |= {"action": parsed.action, "transaction_reserved": payload[2] >> 2}
        return {"version": parsed.version, **bits, "cfg_data": payload[4:].hex()}, {}

    def valdel(parsed, payload):
        keys, j = [], 1
        while hasattr(parsed, f"keys_{j:02d}"):
            keys.append(getattr(parsed, f"keys_{j:02d}"))
            j += 1
        bits = {"reserved1": bool(payload[1] & 1), "bbr": bool(parsed.bbr), "flash": bool(parsed.flash), "layers_reserved": payload[1] >> 3}
        bits |= {"action": parsed.action, "transaction_reserved": payload[2] >> 2}
        return {"version": parsed.version, **bits, "keys": keys}, {}

    def valget(parsed, payload):
        names = {"version": "version", "layer": "layer", "position": "position"}
        return {**header(parsed, payload, names), "cfg_data": payload[4:].hex()}, {}

    pairs = [(name, config_value(rng, kind)) for name, _, kind in config_keys(rng, rng.randint(1, 8))]
    layers, txn = rng.randint(1, 7), rng.randint(0, 3)
    keys = [name for name, _, _ in config_keys(rng, rng.randint(1, 8))]
    answer = b"".join(
        struct.pack("<I", key) + value_bytes(config_value(rng, kind), kind) for _, key, kind in config_keys(rng, rng.randint(0, 8))
    )
    answer_payload = bytes([1, rng.choice([0, 1, 2, 7])]) + rng.randint(0, 100).to_bytes(2, "little") + answer
    return [
        frame_record(f"cfg_valset_{i}", "CFG_VALSET", UBXMessage.config_set(layers, txn, pairs), SET, valset),
        frame_record(f"cfg_valdel_{i}", "CFG_VALDEL", UBXMessage.config_del(layers & 6, txn, keys), SET, valdel),
        frame_record(f"cfg_valget_poll_{i}", "CFG_VALGET", UBXMessage.config_poll(rng.choice([0, 1, 2, 7]), rng.randint(0, 100), keys), POLL, valget),
        frame_record(f"cfg_valget_{i}", "CFG_VALGET", UBXMessage("CFG", "CFG-VALGET", GET, payload=answer_payload), GET, valget),
    ]


def value_bytes(value, kind: str) -> bytes:
    if kind == "L":
        return bytes([value])
    if kind[0] == "R":
        return struct.pack("<d" if size_of(kind) == 8 else "<f", value)
    if kind[0] == "X":
        return value
    return value.to_bytes(size_of(kind), "little", signed=kind[0] == "I")


def random_frames(rng: random.Random, per_command: int) -> list[dict]:
    """`per_command` random frames of every command (and a CFG-PRT poll), as the file records
    them. The Python package's tests call it for frames of their own."""
    frames = []
    for command in SPEC["commands"]:
        ubx_name = command.replace("_", "-")
        if command in ("CFG_VALSET", "CFG_VALGET", "CFG_VALDEL"):
            continue
        mode = SET if command in SET_ONLY else GET
        defn = (UBX_PAYLOADS_SET if mode == SET else UBX_PAYLOADS_GET)[ubx_name]
        if ubx_name == "NAV-RELPOSNED":
            defn = UBX_PAYLOADS_GET["NAV-RELPOSNED"]
        read = {"CFG_MSG": cfg_msg, "CFG_CFG": cfg_cfg, "CFG_PRT": cfg_prt(defn)}.get(command) or by_definition(command, defn)
        for i in range(per_command):
            payload = random_payload(rng, defn, FIXED.get(ubx_name, {}))
            msg = UBXMessage(ubx_name[:3], ubx_name, mode, payload=payload)
            frames.append(frame_record(f"{command.lower()}_{i}", command, msg, mode, read))
        if command == "CFG_PRT":
            poll = UBXMessage("CFG", "CFG-PRT", POLL, payload=bytes([rng.randint(0, 4)]))
            frames.append(frame_record("cfg_prt_poll", command, poll, POLL, cfg_prt_poll))
    for i in range(per_command):
        frames.extend(config_frames(rng, i))
    assert {f["message"] for f in frames} == set(SPEC["commands"]), "every command has frames"
    return frames


def main() -> None:
    frames = random_frames(random.Random(0x55_42_58_32), FRAMES_PER_COMMAND)
    doc = {
        "protocol": "ubx",
        "source": {
            "generator": "scripts/ubx_pyubx2_vectors.py",
            "pyubx2": pyubx2.version,
            "what": "random messages of every command of specs/ubx.toml, payloads laid out from pyubx2's payload "
            "definitions (CFG-VALSET, CFG-VALDEL and the CFG-VALGET poll from its config_set, config_del and "
            "config_poll), framed by UBXMessage.serialize and decoded by UBXReader.parse(validate=1)",
            "payload": "pyubx2's decoded values under the spec's names: bit members as booleans (one bit) or integers, "
            "enumerations by their spec name, scaled fields in pyubx2's scaled units (scales: the spec's scale of each, "
            "by path); bits above a word's last member are 0; reserved bytes are 0",
        },
        "frames": frames,
    }
    OUT.write_text(json.dumps(doc, indent=1) + "\n")
    print(f"{len(frames)} frames of {len(SPEC['commands'])} commands -> {OUT.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
