"""The Python objects equal the `protocol` command's JSON: every golden vector of
`tests/vectors` and every bundled capture of `examples/captures`, decoded by `protocol decode
--format json` and by the package, line for line (frames, rejections, skipped bytes, frames
without message).

A message's `to_json()` is compared as it is; its `to_dict()` after writing bytes as hex and
non-finite floats as the command's strings (`inf`, `-inf`, `NaN`), the only two places where
the Python objects are not JSON."""

from __future__ import annotations

import json
import math
import subprocess
from pathlib import Path

import pytest

import protocol_link
from conftest import CAPTURES, CATALOGUE, VECTORS, spec

def takes(entry: dict, suite: str) -> bool:
    """Whether a registry entry (a spec's, or one of its vector files') does not skip `suite`."""
    return suite not in entry.get("skip", [])


def stem(entry: dict) -> str:
    """The spec's file name without `.toml`: what `spec()` loads."""
    return entry["file"].removesuffix(".toml")


def vector_specs() -> dict:
    """Vector file -> the specs (and directions) that decode it: the registry's `python` suite."""
    out: dict = {}
    for entry in CATALOGUE:
        for vectors in entry.get("vectors", []):
            if takes(entry, "python") and takes(vectors, "python"):
                directions = entry.get("directions") or [None]
                out.setdefault(vectors["file"], []).extend((stem(entry), d) for d in directions)
    return out


def capture_specs() -> dict:
    """Capture -> spec and the command's options (its frame format, and the first direction of a
    spec whose directions are given), as the registry lists them."""
    out = {}
    for entry in CATALOGUE:
        for capture in entry.get("captures", []):
            options = ["--frame", capture["frame"]] if "frame" in capture else []
            options += ["--direction", entry["directions"][0]] if entry.get("directions") else []
            out[capture["name"] + ".bin"] = (stem(entry), options)
    return out


#: Vector file -> the specs (and directions) that decode it.
VECTOR_SPECS = vector_specs()


def jsonable(value):
    """A Python value as the command's JSON writes it."""
    if isinstance(value, dict):
        return {k: jsonable(v) for k, v in value.items()}
    if isinstance(value, list):
        return [jsonable(v) for v in value]
    if isinstance(value, bytes):
        return value.hex()
    if isinstance(value, float) and not math.isfinite(value):
        return "NaN" if math.isnan(value) else ("inf" if value > 0 else "-inf")
    return value


def plain_nan(value):
    """The command's JSON with a NaN's bits (`NaN(0x...)`) left out, as `to_dict()` has none."""
    if isinstance(value, dict):
        return {k: plain_nan(v) for k, v in value.items()}
    if isinstance(value, list):
        return [plain_nan(v) for v in value]
    if isinstance(value, str) and value.startswith("NaN("):
        return "NaN"
    return value


def cli_lines(cli: str, args: list) -> list:
    out = subprocess.run([cli, "decode", *args, "--format", "json"], capture_output=True, text=True, check=True)
    return [json.loads(line) for line in out.stdout.splitlines() if line.strip()]


def assert_same(items: list, lines: list, where: str) -> int:
    """Compares the package's items with the command's lines; returns the messages compared."""
    assert len(items) == len(lines), (where, len(items), len(lines))
    messages = 0
    for item, line in zip(items, lines):
        if isinstance(item, protocol_link.Message):
            assert json.loads(item.to_json()) == line, (where, line)
            assert jsonable(item.to_dict()) == plain_nan(line), (where, line)
            messages += 1
        else:
            assert item.to_dict() == line, (where, line)
    return messages


def hex_strings(node) -> list:
    """Every `hex` text of a vector file (frames, their serial forms, streams, stream parts)."""
    found = []
    if isinstance(node, dict):
        for k, v in node.items():
            if k == "hex" and isinstance(v, str):
                found.append(v)
            else:
                found.extend(hex_strings(v))
    elif isinstance(node, list):
        for v in node:
            found.extend(hex_strings(v))
    return found


def can_frames(node) -> list:
    """Every CAN frame of a vector file: `(can_id, data hex)`."""
    found = []
    if isinstance(node, dict):
        if isinstance(node.get("can_id"), int) and isinstance(node.get("data_hex"), str):
            found.append((node["can_id"], node["data_hex"]))
        for v in node.values():
            found.extend(can_frames(v))
    elif isinstance(node, list):
        for v in node:
            found.extend(can_frames(v))
    return found


def direction_args(direction):
    return ["--direction", direction] if direction else []


@pytest.mark.parametrize("file", sorted(VECTOR_SPECS))
def test_every_golden_vector_decodes_as_the_command_decodes_it(cli, tmp_path: Path, file: str):
    vectors = json.loads((VECTORS / file).read_text())
    # Frames first, one after the other, then the streams (whose damaged frames must not
    # swallow a frame vector).
    data = b"".join(bytes.fromhex(h) for h in hex_strings(vectors))
    assert data, file
    (tmp_path / "in.hex").write_text(data.hex())
    messages = 0
    for name, direction in VECTOR_SPECS[file]:
        path = f"specs/{name}.toml"
        lines = cli_lines(cli, [str(Path(spec(name).path)), str(tmp_path / "in.hex"), "--hex", *direction_args(direction)])
        items = list(protocol_link.iter_bytes(spec(name, direction), data, events=True))
        messages += assert_same(items, lines, f"{file} with {path}")
        # One frame at a time: `Spec.decode` gives what the stream gives.
        for line in lines:
            if "command" in line and "event" not in line:
                single = spec(name, direction).decode(bytes.fromhex(line["hex"]), format=line["format"])
                assert json.loads(single.to_json()) == dict(line, offset=0), line
    assert messages > 0, file


@pytest.mark.parametrize("file", ["agilex_scout.json"])
def test_every_can_vector_decodes_as_the_command_decodes_it(cli, tmp_path: Path, file: str):
    frames = can_frames(json.loads((VECTORS / file).read_text()))
    assert frames, file
    log = "".join(f"({i}.000000) can0 {can_id:03X}#{data.upper()}\n" for i, (can_id, data) in enumerate(frames))
    (tmp_path / "in.log").write_text(log)
    lines = cli_lines(cli, [spec("scout").path, "--candump", str(tmp_path / "in.log")])
    items = list(protocol_link.iter_candump(spec("scout"), tmp_path / "in.log", events=True))
    assert assert_same(items, lines, file) > 0


#: Capture -> spec and the command's options (`examples/captures/README.md`).
CAPTURE_SPECS = capture_specs()


@pytest.mark.parametrize("file", sorted(CAPTURE_SPECS))
def test_every_capture_decodes_as_the_command_decodes_it(cli, file: str):
    name, options = CAPTURE_SPECS[file]
    direction = options[1] if options[:1] == ["--direction"] else None
    frame = options[1] if options[:1] == ["--frame"] else None
    # Read in 64 KiB chunks, as the command reads (a run of skipped bytes is reported per chunk).
    lines = cli_lines(cli, [spec(name).path, str(CAPTURES / file), *options])
    items = list(protocol_link.iter_file(spec(name, direction), CAPTURES / file, format=frame, events=True))
    assert assert_same(items, lines, file) > 0


def test_the_can_capture_decodes_as_the_command_decodes_it(cli):
    lines = cli_lines(cli, [spec("scout").path, "--candump", str(CAPTURES / "scout_can.log")])
    items = list(protocol_link.iter_candump(spec("scout"), CAPTURES / "scout_can.log", events=True))
    assert assert_same(items, lines, "scout_can.log") > 0
