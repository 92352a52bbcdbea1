#!/usr/bin/env bash
# Footprint of the generated HFLink codec on firmware, against a hand-written equivalent.
#
# Builds the crates of benches/firmware (a workspace of its own: release profile with
# opt-level "s", lto, one codegen unit, panic = abort) for thumbv7em-none-eabihf and prints the
# .text and .rodata sizes of each binary, read from the ELF by the `elf-sizes` tool of
# protocol-benches (no binutils needed), with ratios to the hand-written one, raw and net of an
# empty firmware (vector table and reset handler).
#
# With --scaling, also builds the generated firmware from synthetic specs of 16, 64 and 256
# commands (written to a temporary directory, found by the macro through PROTOCOL_SPEC_DIR) and
# prints their sizes and the in-process expansion time of those specs.
#
# Usage: bash benches/footprint.sh [--scaling]
# The firmware is built in "${CARGO_TARGET_DIR:-target}/firmware".
set -euo pipefail
cd "$(dirname "$0")/.."

scaling=0
case "${1:-}" in
  --scaling) scaling=1 ;;
  "") ;;
  *) echo "usage: bash benches/footprint.sh [--scaling]" >&2; exit 2 ;;
esac

target=thumbv7em-none-eabihf
if ! rustup target list --installed 2>/dev/null | grep -q "^${target}\$"; then
  rustup target add "$target"
fi

host_target="${CARGO_TARGET_DIR:-$PWD/target}"
fw_target="$host_target/firmware"
out="$fw_target/$target/release"
manifest=benches/firmware/Cargo.toml

fw_build() {
  CARGO_TARGET_DIR="$fw_target" cargo build --quiet --manifest-path "$manifest" --release \
    --target "$target" "$@"
}
sizes() {
  CARGO_TARGET_DIR="$host_target" cargo run --quiet -p protocol-benches --bin elf-sizes -- "$@"
}
synth() {
  CARGO_TARGET_DIR="$host_target" cargo run --quiet -p protocol-benches --bin synth -- "$@"
}

echo "== HFLink firmware: encode and decode every command ($target, opt-level s, lto)"
fw_build -p footprint-empty -p footprint-hand -p footprint-generated
sizes --baseline "empty=$out/footprint-empty" "hand-written=$out/footprint-hand" \
  "generated=$out/footprint-generated"

if [ "$scaling" = 1 ]; then
  tmp="$(mktemp -d)"
  trap 'rm -rf "$tmp"' EXIT
  rows=()
  for n in 16 64 256; do
    synth spec "$n" > "$tmp/synth.toml"
    PROTOCOL_SPEC_DIR="$tmp" fw_build -p footprint-synth
    cp "$out/footprint-synth" "$tmp/synth-$n"
    rows+=("$n commands=$tmp/synth-$n")
  done
  echo
  echo "== generated firmware from synthetic specs"
  sizes --baseline "empty=$out/footprint-empty" "${rows[@]}"
  echo
  echo "== expansion time of the synthetic specs (compile + codegen::expand, in process, dev profile)"
  synth expand 16 64 256
fi
