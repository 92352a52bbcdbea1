#!/usr/bin/env bash
# Builds the QEMU firmware for thumbv7em-none-eabihf, and its C twin (`c/main.c` with the
# HFLink and referee codecs `protocol gen c` prints) with arm-none-eabi-gcc -Os, runs both on
# QEMU's mps2-an386 (a Cortex-M4) with semihosting and instruction counting (`-icount shift=0`:
# the virtual clock advances one nanosecond per instruction), and checks their output against
# the golden vectors with `protocol-benches`' `qemu-check`, which also prints the instructions
# per decoded frame of every decoder.
#
# Needs `qemu-system-arm`, `gcc-arm-none-eabi` and `libnewlib-arm-none-eabi` (Debian; installed
# here when missing and the script runs as root).
#
# Usage: bash examples/firmware-qemu/run.sh
set -euo pipefail
cd "$(dirname "$0")/../.."

target=thumbv7em-none-eabihf
if ! rustup target list --installed 2>/dev/null | grep -q "^${target}\$"; then
  rustup target add "$target"
fi
missing=()
command -v qemu-system-arm > /dev/null || missing+=(qemu-system-arm)
command -v arm-none-eabi-gcc > /dev/null || missing+=(gcc-arm-none-eabi)
# newlib-nano (memcpy, memset), found through its specs file.
[ -n "$(arm-none-eabi-gcc -print-file-name=nano.specs 2>/dev/null | grep /)" ] ||
  missing+=(libnewlib-arm-none-eabi)
if [ "${#missing[@]}" -gt 0 ]; then
  if [ "$(id -u)" = 0 ]; then
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}"
  else
    echo "missing: apt-get install -y ${missing[*]}" >&2
    exit 1
  fi
fi

host_target="${CARGO_TARGET_DIR:-$PWD/target}"
fw_target="$host_target/firmware"
CARGO_TARGET_DIR="$fw_target" cargo build --quiet --manifest-path examples/firmware-qemu/Cargo.toml \
  --release --target "$target"
elf="$fw_target/$target/release/firmware-qemu"

out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
# The C firmware: the generated codecs and the golden vectors as a C header, built with the
# flags of benches/footprint-c.sh (the Rust firmware's opt-level "s" and LTO, in gcc's words).
CARGO_TARGET_DIR="$host_target" cargo run --quiet -p protocol-cli -- gen c specs/hflink.toml -o "$out" > /dev/null
CARGO_TARGET_DIR="$host_target" cargo run --quiet -p protocol-cli -- gen c specs/referee.toml -o "$out" > /dev/null
CARGO_TARGET_DIR="$host_target" cargo run --quiet -p protocol-benches --bin qemu-check -- --c-vectors "$out/vectors.h"
arm-none-eabi-gcc -std=c99 -Wall -Wextra -Wpedantic -Werror -Os -flto -mcpu=cortex-m4 -mthumb \
  -mfloat-abi=hard -mfpu=fpv4-sp-d16 -ffunction-sections -fdata-sections -nostartfiles \
  --specs=nano.specs --specs=nosys.specs -Wl,--gc-sections -T examples/firmware-qemu/c/link.ld \
  -I "$out" examples/firmware-qemu/c/main.c "$out/hflink.c" "$out/referee.c" -o "$out/firmware-qemu-c"
echo "arm-none-eabi-gcc $(arm-none-eabi-gcc -dumpversion), $(qemu-system-arm --version | head -n 1)"

for fw in rust c; do
  kernel="$elf"
  [ "$fw" = c ] && kernel="$out/firmware-qemu-c"
  timeout 300 qemu-system-arm -M mps2-an386 -cpu cortex-m4 -nographic -monitor none -serial none \
    -semihosting-config enable=on,target=native -icount shift=0 -kernel "$kernel" > "$out/$fw.out"
  echo "$fw firmware printed $(wc -l < "$out/$fw.out") lines; first lines:"
  head -n 4 "$out/$fw.out"
done
CARGO_TARGET_DIR="$host_target" cargo run --quiet -p protocol-benches --bin qemu-check -- "$out/rust.out" "$out/c.out"
