#!/usr/bin/env bash
# Builds the embassy example (examples/embassy) for thumbv7em-none-eabihf: the STM32F405
# board binary, linked and not run (QEMU's STM32F4 machines do not model the clock controller
# that `embassy_stm32::init` waits on), and the mps2-an386 binary, which runs on QEMU with
# its UART fed the golden conversation of `golden.py` (requests and noise built from
# tests/vectors/hflink.json). The bytes the UART sends back must be the expected answers,
# byte for byte, within the timeout; then the sizes of both binaries are printed.
#
# Needs `qemu-system-arm` (Debian; installed here when missing and the script runs as root)
# and python3.
#
# Usage: bash examples/embassy/run.sh
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
    echo "missing: apt-get install -y qemu-system-arm" >&2
    exit 1
  fi
fi

manifest=examples/embassy/Cargo.toml
# Its own target directory: another workspace, other features of the shared crates.
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$PWD/target}/embassy"
for board in stm32f4 mps2; do
  cargo build --quiet --locked --manifest-path "$manifest" --release --target "$target" \
    --features "$board" --bin "$board"
done
bin="$CARGO_TARGET_DIR/$target/release"

out="$(mktemp -d)"
qemu_pid=
reader_pid=
cleanup() {
  for pid in $qemu_pid $reader_pid; do kill "$pid" 2> /dev/null || true; done
  rm -rf "$out"
}
trap cleanup EXIT
python3 examples/embassy/golden.py tests/vectors/hflink.json "$out/input.bin" "$out/expected.bin"

# The UART is a pair of named pipes (QEMU's `pipe` character device opens NAME.in and
# NAME.out). QEMU takes a byte from NAME.in only when the UART's receive register is empty,
# so the whole input can be written at once and none is lost.
mkfifo "$out/uart.in" "$out/uart.out"
: > "$out/answers.bin"
cat "$out/uart.out" >> "$out/answers.bin" &
reader_pid=$!
qemu-system-arm -M mps2-an386 -cpu cortex-m4 -display none -monitor none \
  -semihosting-config enable=on,target=native -chardev "pipe,id=uart,path=$out/uart" \
  -serial chardev:uart -kernel "$bin/mps2" > "$out/semihosting.txt" 2>&1 &
qemu_pid=$!
# Opening a pipe blocks until its other end is open: bounded, in case QEMU did not start.
if ! timeout 60 dd if="$out/input.bin" of="$out/uart.in" status=none; then
  echo "QEMU did not take the input on its UART:"
  cat "$out/semihosting.txt"
  exit 1
fi

# The firmware never stops (a UART has no end): wait until the expected number of bytes came
# back (the last request's answer is the last expected), QEMU stopped (a panic), or 60 s.
want=$(stat -c %s "$out/expected.bin")
for _ in $(seq 600); do
  [ "$(stat -c %s "$out/answers.bin")" -ge "$want" ] && break
  kill -0 "$qemu_pid" 2> /dev/null || break
  sleep 0.1
done
kill "$qemu_pid" 2> /dev/null || true
wait "$qemu_pid" 2> /dev/null || true
qemu_pid=
# QEMU's end closes the pipe: the reader has every byte once it exits.
wait "$reader_pid" 2> /dev/null || true
reader_pid=
grep -v 'terminating on signal' "$out/semihosting.txt" || true
if ! cmp -s "$out/answers.bin" "$out/expected.bin"; then
  echo "the mps2 binary's answers differ from the expected ones (or came late):"
  echo "expected: $(od -An -tx1 -v "$out/expected.bin" | tr -d ' \n')"
  echo "answered: $(od -An -tx1 -v "$out/answers.bin" | tr -d ' \n')"
  exit 1
fi
echo "the mps2 binary answered the golden conversation: $want bytes, as expected"
size -A "$bin/stm32f4" "$bin/mps2" | grep -E '^(\S+ +:|\.text|\.data|\.bss|\.rodata)'
