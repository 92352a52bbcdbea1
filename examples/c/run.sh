#!/usr/bin/env bash
# Regenerates the vendored HFLink C codec (examples/c/generated/), builds the example with the
# strict flags the generated code is held to, and runs it. CI runs this; its final
# `git diff --exit-code` catches vendored files that no longer match the spec.
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo run -q -p protocol-cli -- gen c specs/hflink.toml -o examples/c/generated > /dev/null
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
cc -std=c99 -Wall -Wextra -Wpedantic -Werror -O2 -I examples/c/generated \
  examples/c/main.c examples/c/generated/hflink.c -o "$out/hflink-example"
"$out/hflink-example"
