"""Shared fixtures: the repository's root, the bundled specs and their registry
(`tests/catalogue.toml`), and the `protocol` command the package is compared with."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

try:
    import tomllib
except ModuleNotFoundError:  # Python before 3.11
    import tomli as tomllib

import protocol_link

ROOT = Path(__file__).resolve().parents[2]
SPECS = ROOT / "specs"
VECTORS = ROOT / "tests" / "vectors"
CAPTURES = ROOT / "examples" / "captures"
#: The registry of bundled specs: one `[[spec]]` table each (its header says what the keys mean).
CATALOGUE = tomllib.loads((ROOT / "tests" / "catalogue.toml").read_text())["spec"]

_loaded: dict = {}


def spec(name: str, direction: str | None = None) -> protocol_link.Spec:
    """The bundled spec `specs/NAME.toml` (loaded once)."""
    key = (name, direction)
    if key not in _loaded:
        _loaded[key] = protocol_link.Spec.load(SPECS / f"{name}.toml", direction=direction)
    return _loaded[key]


def _cli() -> str | None:
    given = os.environ.get("PROTOCOL_CLI")
    if given:
        return given
    for profile in ("debug", "release"):
        path = ROOT / "target" / profile / "protocol"
        if path.exists():
            return str(path)
    return shutil.which("protocol")


@pytest.fixture(scope="session")
def cli() -> str:
    """The `protocol` command: `$PROTOCOL_CLI`, else the workspace's build of it
    (`cargo build -p protocol-cli`). Without one these tests are skipped, unless
    `PROTOCOL_REQUIRE_CLI` is set (CI), where a missing command fails them."""
    path = _cli()
    if path is None:
        message = "no `protocol` command: build it with `cargo build -p protocol-cli` or set PROTOCOL_CLI"
        if os.environ.get("PROTOCOL_REQUIRE_CLI"):
            pytest.fail(message)
        pytest.skip(message)
    return path
