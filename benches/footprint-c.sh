#!/usr/bin/env bash
# Footprint of the generated HFLink and referee C codecs on firmware (benches/firmware-c: main.c
# and main_referee.c), beside the Rust firmware of benches/footprint.sh: arm-none-eabi-gcc
# (Debian `gcc-arm-none-eabi` and `libnewlib-arm-none-eabi`, for memcpy and friends) with -Os,
# LTO and unused sections dropped, for a Cortex-M4F; prints .text and .rodata of each firmware
# and of an empty one.
#
# Usage: bash benches/footprint-c.sh
set -euo pipefail
cd "$(dirname "$0")/.."
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
cargo run -q -p protocol-cli -- gen c specs/hflink.toml -o "$out" > /dev/null
cargo run -q -p protocol-cli -- gen c specs/referee.toml -o "$out" > /dev/null
flags=(-std=c99 -Wall -Wextra -Wpedantic -Werror -Os -flto -mcpu=cortex-m4 -mthumb
  -mfloat-abi=hard -mfpu=fpv4-sp-d16 -ffunction-sections -fdata-sections
  -nostartfiles --specs=nano.specs --specs=nosys.specs -Wl,--gc-sections
  -T benches/firmware-c/link.ld -I "$out")
arm-none-eabi-gcc "${flags[@]}" benches/firmware-c/vectors.c benches/firmware-c/empty.c -o "$out/empty.elf"
arm-none-eabi-gcc "${flags[@]}" benches/firmware-c/vectors.c benches/firmware-c/main.c "$out/hflink.c" -o "$out/hflink.elf"
arm-none-eabi-gcc "${flags[@]}" benches/firmware-c/vectors.c benches/firmware-c/main_referee.c "$out/referee.c" -o "$out/referee.elf"
echo "arm-none-eabi-gcc $(arm-none-eabi-gcc -dumpversion)"
printf '%-10s %8s %8s %8s\n' firmware .text .rodata total
for elf in empty hflink referee; do
  read -r text rodata < <(arm-none-eabi-size -A "$out/$elf.elf" |
    awk '$1 == ".text" { t = $2 } $1 == ".rodata" { r = $2 } END { print t + 0, r + 0 }')
  printf '%-10s %8d %8d %8d\n' "$elf" "$text" "$rodata" "$((text + rodata))"
done
