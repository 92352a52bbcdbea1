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
# The Scout firmware (scaled fields) is measured alone, with the list of the double-precision
# soft-float helpers (`__aeabi_d*`) it links: none when every scaled field computes in `f32`.
#
# With --crc-tables, also builds the referee firmware (a CRC-8 header check and a CRC-16 frame
# check; the spec copied as the synthetic crate's `synth.toml`) with each table size written on
# both checks (`table = 0`, `1`, `16`) and prints their sizes.
#
# With --mavlink, also builds a MAVLink node that uses three messages (benches/firmware/mavlink:
# it answers HEARTBEAT and keeps ATTITUDE and GLOBAL_POSITION_INT) on the whole common dialect
# and on the twelve messages of specs/mavlink.toml, decoding every message (`Packet::from_frame`)
# or each of the three alone (`Packet::from_frame_as`), and through a `Handler`, and prints
# their sizes.
#
# Usage: bash benches/footprint.sh [--scaling | --crc-tables | --mavlink]
# The firmware is built in "${CARGO_TARGET_DIR:-target}/firmware".
set -euo pipefail
cd "$(dirname "$0")/.."

scaling=0
crc_tables=0
mavlink=0
case "${1:-}" in
  --scaling) scaling=1 ;;
  --crc-tables) crc_tables=1 ;;
  --mavlink) mavlink=1 ;;
  "") ;;
  *) echo "usage: bash benches/footprint.sh [--scaling | --crc-tables | --mavlink]" >&2; exit 2 ;;
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

echo
echo "== Scout firmware: scaled fields (f32 in Rust, 8- and 16-bit on the wire), UART echo"
fw_build -p footprint-scout
sizes --baseline "empty=$out/footprint-empty" "scout=$out/footprint-scout"
echo "double-precision soft-float helpers linked:"
sizes --symbols __aeabi_d "$out/footprint-scout"

if [ "$mavlink" = 1 ]; then
  fw_build -p footprint-mavlink
  echo
  echo "== MAVLink node using three messages: the common dialect (234 messages) and 12 messages"
  sizes --baseline "empty=$out/footprint-empty" "common=$out/footprint-mavlink-common" \
    "twelve=$out/footprint-mavlink-twelve" "common, from_frame_as=$out/footprint-mavlink-common-as" \
    "twelve, from_frame_as=$out/footprint-mavlink-twelve-as" \
    "common, Handler=$out/footprint-mavlink-common-handler"
fi

if [ "$crc_tables" = 1 ]; then
  tmp="$(mktemp -d)"
  trap 'rm -rf "$tmp"' EXIT
  rows=()
  for t in 0 1 16; do
    sed -e 's/^name = "referee"$/name = "synth"/' \
      -e "s/{ check = \([^,]*\),/{ check = \1, table = $t,/" specs/referee.toml > "$tmp/synth.toml"
    PROTOCOL_SPEC_DIR="$tmp" fw_build -p footprint-synth
    cp "$out/footprint-synth" "$tmp/referee-$t"
    rows+=("referee table $t=$tmp/referee-$t")
  done
  echo
  echo "== referee firmware (CRC-8 header check, CRC-16 frame check) by CRC table size"
  sizes --baseline "empty=$out/footprint-empty" "${rows[@]}"
fi

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
