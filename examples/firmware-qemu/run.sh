#!/usr/bin/env bash
# Builds the QEMU firmware for thumbv7em-none-eabihf, runs it on QEMU's mps2-an386 (a
# Cortex-M4) with semihosting and instruction counting (`-icount shift=0`: the virtual clock
# advances one nanosecond per instruction), and checks its output against the golden vectors
# with `protocol-benches`' `qemu-check`, which also prints the instructions per decoded frame.
#
# Needs `qemu-system-arm` (Debian: `apt-get install -y qemu-system-arm`; installed here when
# missing and the script runs as root).
#
# Usage: bash examples/firmware-qemu/run.sh
set -euo pipefail
cd "$(dirname "$0")/../.."

target=thumbv7em-none-eabihf
if ! rustup target list --installed 2>/dev/null | grep -q "^${target}\$"; then
  rustup target add "$target"
fi
if ! command -v qemu-system-arm > /dev/null; then
  if [ "$(id -u)" = 0 ]; then
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq qemu-system-arm
  else
    echo "qemu-system-arm is missing: apt-get install -y qemu-system-arm" >&2
    exit 1
  fi
fi

host_target="${CARGO_TARGET_DIR:-$PWD/target}"
fw_target="$host_target/firmware"
CARGO_TARGET_DIR="$fw_target" cargo build --quiet --manifest-path examples/firmware-qemu/Cargo.toml \
  --release --target "$target"
elf="$fw_target/$target/release/firmware-qemu"

out="$(mktemp)"
trap 'rm -f "$out"' EXIT
timeout 300 qemu-system-arm -M mps2-an386 -cpu cortex-m4 -nographic -monitor none -serial none \
  -semihosting-config enable=on,target=native -icount shift=0 -kernel "$elf" > "$out"
echo "firmware printed $(wc -l < "$out") lines; first lines:"
head -n 4 "$out"
CARGO_TARGET_DIR="$host_target" cargo run --quiet -p protocol-benches --bin qemu-check -- "$out"
