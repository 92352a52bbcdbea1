#!/usr/bin/env bash
# Checks the criterion binary as the benchmark compiles it (fat LTO, every decoder in one
# program): no function of the runtime calls an iterator adapter out of line.
#
# In a caller this large the compiler may leave an adapter's `next` or `fold` out of line where
# a smaller program (the `count` tool, the firmware) inlines it; the decoder's hot loops then pay
# a call per byte or per chunk, and the loop's constants (the sync bytes, a CRC's table) become
# run-time values. Instruction counts taken with `count` do not show it, so this test reads the
# benchmark binary itself: `objdump -d`, every function whose name starts with
# `protocol_runtime::`, every `call` it makes into `core::iter`.
#
# Allowed: `slice::Iter::all`, the loop over a layout's checks, markers or constants
# (`all_hold!` in `layout.rs`, and the frame checks and markers in `decoder/mod.rs`): one call
# per candidate, holding a checksum verification. Where the layout is read through a reference
# at run time (the run-time codec's path) the loop stays; a layout known at compile time with a
# lone check matches it without a loop. The allowance is by callee name, so a compile-time
# layout's call to `Iter::all` passes too; read `objdump -d` for that.
#
# Usage: bash benches/hot-calls.sh [cargo bench options, e.g. --features runtime-crc-fast]
set -euo pipefail
cd "$(dirname "$0")/.."

command -v objdump >/dev/null || { echo "hot-calls.sh: objdump (binutils) is not installed" >&2; exit 1; }
# shellcheck source=benches/codec-exe.sh
. benches/codec-exe.sh
exe="$(codec_exe "$@")"
[ -x "$exe" ] || { echo "hot-calls.sh: no benchmark executable found" >&2; exit 1; }

listing="$(mktemp)"
trap 'rm -f "$listing"' EXIT
# "caller -> callee" for every call a runtime function makes into `core::iter`.
objdump -d -C --no-show-raw-insn "$exe" | awk '
  /^[0-9a-f]+ <.*>:$/ { name = $0; sub(/^[0-9a-f]+ </, "", name); sub(/>:$/, "", name); runtime = (name ~ /^protocol_runtime::/); next }
  runtime && /\tcall / && /core::iter::/ { callee = $0; sub(/.*call +[0-9a-f]+ </, "", callee); sub(/>$/, "", callee); print name " -> " callee }
' | sort | uniq -c > "$listing"

allowed='<core::slice::iter::Iter<T> as core::iter::traits::iterator::Iterator>::all$'
functions="$(objdump -t "$exe" | grep -c 'protocol_runtime' || true)"
calls="$(wc -l < "$listing")"
bad="$(grep -v -E -- "$allowed" "$listing" || true)"
echo "hot-calls: $(basename "$exe"): $functions runtime symbols, $calls distinct calls into core::iter from them (allowed: slice::Iter::all)"
if [ -n "$bad" ]; then
  echo "hot-calls: iterator adapters called out of line by the runtime in the benchmark binary:" >&2
  echo "$bad" >&2
  echo "hot-calls: write these loops over indices (see decoder::bytes_agree and search::block_may_start_sync)" >&2
  exit 1
fi
