#!/usr/bin/env bash
# Holds RoboRTS sessions with firmware under QEMU through a fault-injecting relay, and measures
# what the session machinery costs the firmware. Builds the two chassis binaries of
# examples/embassy for QEMU's mps2-an386 (`mps2-session`: answers through the runtime's
# session Responder; `mps2-by-hand`: the same firmware answering by hand) and the host harness
# (`cargo run -p protocol-tests --example qemu_session`), then:
#   1. runs `mps2-session` with its UART on a pseudo-terminal and the harness's Requester
#      talking to it through a relay that drops, duplicates, corrupts and delays frames on
#      seeded schedules: it fails unless every request has exactly one outcome and the
#      firmware delivered none twice, and prints the fault matrix and the instructions per
#      request (SysTick under `-icount shift=0`);
#   2. runs `mps2-by-hand` on the fault-free row alone (its duplicate deliveries counted);
#   3. prints the sections of both binaries.
#
# Needs `qemu-system-arm` (run.sh installs it) and `stty`.
#
# Usage: bash examples/embassy/session.sh
set -euo pipefail
cd "$(dirname "$0")/../.."

target=thumbv7em-none-eabihf
manifest=examples/embassy/Cargo.toml
embassy_target="${CARGO_TARGET_DIR:-$PWD/target}/embassy"
CARGO_TARGET_DIR="$embassy_target" cargo build --quiet --locked --manifest-path "$manifest" \
  --release --target "$target" --features mps2 --bin mps2-session --bin mps2-by-hand
bin="$embassy_target/$target/release"
cargo build --quiet -p protocol-tests --example qemu_session
harness="${CARGO_TARGET_DIR:-$PWD/target}/debug/examples/qemu_session"

echo "== mps2-session: the session through the fault-injecting relay"
"$harness" "$bin/mps2-session"
echo "== mps2-by-hand: the same firmware answering by hand, fault-free"
"$harness" "$bin/mps2-by-hand" --baseline
size -A "$bin/mps2-by-hand" "$bin/mps2-session" | grep -E '^(\S+ +:|\.text|\.data|\.bss|\.rodata)'
